//! Fuzzes the MCAP reader's two paths over random access: the summary and
//! chunk indexes with reads of what the poses need (over the bytes), and
//! the walk of a stream read forward only (over the same bytes, as a
//! zstd-compressed file is read). Any bytes must give demos or an error,
//! never a panic, a hang or an abort.
#![no_main]

use dmpscope_core::load::access::{ForwardAt, SliceAt, block_on};
use dmpscope_core::load::mcap::read_mcap;
use dmpscope_core::load::options::LoadOptions;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let options = LoadOptions::default();
    let _ = block_on(read_mcap("fuzz.mcap", &mut SliceAt(data), &options));
    let _ = block_on(read_mcap("fuzz.mcap", &mut ForwardAt::new(data), &options));
});
