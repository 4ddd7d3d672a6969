//! Fuzzes the CSV readers: a plain `t,x,y,z[,qx,qy,qz,qw]` file and
//! OptiTrack Motive's export (its metadata, header rows and frames). Any
//! text must give demos or an error, never a panic, a hang or an abort.
#![no_main]

use dmpscope_core::load::csv::load_csv;
use dmpscope_core::load::motive::load_motive;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        let _ = load_csv("fuzz.csv", text);
        let _ = load_motive("fuzz.csv", text);
    }
});
