//! Hostile files (`dmpscope_core::synth::hostile`): decompression bombs in
//! zstd, lz4 and bz2, sizes that lie, floods of chunk indexes and channels.
//! Each ends within a second, in a clear error naming the file or, where
//! its lie is harmless, in its demos.

use std::time::Instant;

use dmpscope_core::load::options::LoadOptions;
use dmpscope_core::load::source::{SourceData, load_streams};
use dmpscope_core::synth::hostile::hostile_files;

#[test]
fn every_hostile_file_ends_within_a_second_in_an_error_naming_it_or_its_demos() {
    for h in hostile_files() {
        let start = Instant::now();
        let result = load_streams(h.name, SourceData::Bytes(&h.bytes), &LoadOptions::default());
        let secs = start.elapsed().as_secs_f64();
        println!(
            "{} ({} bytes, {}): {secs:.3} s: {}",
            h.name,
            h.bytes.len(),
            h.what,
            match &result {
                Ok(l) => format!("{} demos", l.demos.len()),
                Err(e) => e.to_string(),
            }
        );
        assert!(secs < 1.0, "{}: took {secs:.3} s", h.name);
        match result {
            Ok(loaded) => {
                assert!(h.loads, "{}: loaded {} demos", h.name, loaded.demos.len());
                assert_eq!(loaded.demos.len(), 1, "{}", h.name);
                assert_eq!(loaded.demos[0].positions.len(), 50, "{}", h.name);
            }
            Err(e) => {
                assert!(!h.loads, "{}: {e}", h.name);
                assert!(e.to_string().contains(h.name), "{}: {e}", h.name);
            }
        }
    }
}

#[test]
fn the_zstd_bomb_is_about_a_hundred_kilobytes() {
    let bomb = hostile_files()
        .into_iter()
        .find(|h| h.name == "zstd_bomb.mcap")
        .expect("the bomb");
    assert!(bomb.bytes.len() < 200_000, "{} bytes", bomb.bytes.len());
}
