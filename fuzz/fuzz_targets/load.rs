//! Fuzzes the MCAP loader and the preparation of whatever it loads: any
//! bytes must give demos or an error, never a panic, a hang or an abort.
#![no_main]

use dmpscope_core::load::mcap::load_bytes;
use dmpscope_core::{PrepSettings, prepare};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(loaded) = load_bytes("fuzz.mcap", data) {
        for demo in &loaded.demos {
            let _ = prepare(demo, &PrepSettings::default());
        }
    }
});
