//! Fuzzes the ROS 1 bag reader (its index and its walk): any bytes must
//! give demos or an error, never a panic, a hang or an abort.
#![no_main]

use dmpscope_core::load::rosbag1::load_bag_bytes;
use dmpscope_core::load::options::LoadOptions;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = load_bag_bytes("fuzz.bag", data, &LoadOptions::default());
});
