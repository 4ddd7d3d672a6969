//! A file that declares a huge or large length (of a record, a chunk or its
//! records) fails fast and without allocating what it declares (method.md
//! section 2.1). The global allocator counts every byte allocated; since it
//! counts on all threads, everything that measures runs in the single test of
//! this binary, so nothing else runs in the process meanwhile.

mod common;

use std::alloc::System;
use std::time::Instant;

use common::{first_chunk, load, mcap_of, raw_mcap, reach, records};
use dmpscope_core::Result;
use dmpscope_core::load::collect::Loaded;
use dmpscope_core::load::mcap::RECORD_LENGTH_LIMIT;
use stats_alloc::{INSTRUMENTED_SYSTEM, Region, StatsAlloc};

#[global_allocator]
static GLOBAL: &StatsAlloc<System> = &INSTRUMENTED_SYSTEM;

/// The most bytes a load of a few-kilobyte file may allocate in all.
const ALLOWANCE: usize = 16 << 20;

/// Length fields to patch: `(name, file, offset of the u64)`.
fn length_fields() -> Vec<(&'static str, Vec<u8>, usize)> {
    let unchunked = raw_mcap(None, "/x", "json", &[(1, b"{}".to_vec())]);
    let plain = mcap_of(&[("/a", &reach(40))], false);
    let zstd = mcap_of(&[("/a", &reach(40))], true);
    let (p, z) = (first_chunk(&plain), first_chunk(&zstd));
    vec![
        ("header record", unchunked, 9),
        ("header record", plain.clone(), 9),
        ("plain chunk record", plain.clone(), p.0 + 1),
        ("plain chunk uncompressed size", plain.clone(), p.1 + 16),
        ("plain chunk records length", plain.clone(), p.2 - 8),
        ("record inside a chunk", plain, p.2 + 1),
        ("zstd chunk record", zstd.clone(), z.0 + 1),
        ("zstd chunk uncompressed size", zstd.clone(), z.1 + 16),
        ("zstd chunk records length", zstd, z.2 - 8),
    ]
}

/// Loads `file` with `value` at `offset`: the result, the bytes allocated in
/// all during the load and the time it took.
fn load_patched(
    name: &str,
    file: &[u8],
    offset: usize,
    value: u64,
) -> (Result<Loaded>, usize, f64) {
    let mut bad = file.to_vec();
    bad[offset..offset + 8].copy_from_slice(&value.to_le_bytes());
    let start = Instant::now();
    let region = Region::new(GLOBAL);
    let result = load(name, &bad);
    let allocated = region.change().bytes_allocated;
    (result, allocated, start.elapsed().as_secs_f64())
}

/// Lengths no input could hold (`u64::MAX`, 1 TiB) or just over the limit
/// are errors that name the file, found without allocating them.
fn huge_declared_lengths() {
    let limit = RECORD_LENGTH_LIMIT as u64;
    for (name, file, offset) in length_fields() {
        for huge in [u64::MAX, 1 << 40, limit + 1] {
            let (result, allocated, secs) = load_patched("huge.mcap", &file, offset, huge);
            assert!(secs < 1.0, "{name} = {huge}: took {secs} s");
            assert!(
                allocated < ALLOWANCE,
                "{name} = {huge}: {file_len}-byte file, {allocated} bytes allocated",
                file_len = file.len()
            );
            match result {
                Err(e) => assert!(e.to_string().contains("huge.mcap"), "{e}"),
                // The reader ignores the uncompressed size of an uncompressed
                // chunk (it equals the records' length); the data is intact.
                Ok(_) if name == "plain chunk uncompressed size" => {}
                // A chunk that claims to run past the end of the file
                // reads as a truncated file: its complete records are kept,
                // with a warning naming the file.
                Ok(loaded) => assert!(
                    name.ends_with("chunk record")
                        && loaded
                            .warnings
                            .iter()
                            .any(|w| w.contains("huge.mcap") && w.contains("truncated")),
                    "{name} = {huge}: loaded without a truncation warning"
                ),
            }
        }
    }
}

/// Lengths about the limit (just over it, just under it, 100 MiB) in a
/// few-kilobyte file: the file ends first, and what it declares is never
/// allocated ahead of the bytes that should fill it.
fn large_declared_lengths() {
    let limit = RECORD_LENGTH_LIMIT as u64;
    for (name, file, offset) in length_fields() {
        if name == "plain chunk uncompressed size" {
            continue; // ignored by the reader
        }
        for large in [limit + 1, limit - 1, 100 << 20] {
            let (result, allocated, secs) = load_patched("large.mcap", &file, offset, large);
            assert!(secs < 1.0, "{name} = {large}: took {secs} s");
            assert!(
                allocated < ALLOWANCE,
                "{name} = {large}: {file_len}-byte file, {allocated} bytes allocated",
                file_len = file.len()
            );
            match result {
                Err(e) => assert!(e.to_string().contains("large.mcap"), "{e}"),
                // As above: read as a truncated file, with a warning.
                Ok(loaded) => assert!(
                    name.ends_with("chunk record")
                        && loaded
                            .warnings
                            .iter()
                            .any(|w| w.contains("large.mcap") && w.contains("truncated")),
                    "{name} = {large}: loaded without a truncation warning"
                ),
            }
        }
    }
}

/// Found by the fuzzer: a string length inside a schema or channel record
/// (a u32) that claims nearly 4 GiB made mcap's parser reserve it. Every
/// length-prefixed field of those records is checked against the record.
fn huge_string_lengths() {
    let file = raw_mcap(Some(("x", b"{}")), "/x", "json", &[(1, b"{}".to_vec())]);
    let mut patched = 0;
    for (_, opcode, body, _) in records(&file) {
        // The first length-prefixed field: schema name, channel topic.
        let field = match opcode {
            3 => body + 2,
            4 => body + 4,
            _ => continue,
        };
        let mut bad = file.clone();
        bad[field..field + 4].copy_from_slice(&0xFFFF_FFF0u32.to_le_bytes());
        let region = Region::new(GLOBAL);
        let result = load("strings.mcap", &bad);
        let allocated = region.change().bytes_allocated;
        assert!(
            allocated < ALLOWANCE,
            "opcode {opcode}: {allocated} bytes allocated"
        );
        let err = result.expect_err("a record whose string runs past it loads");
        assert!(
            err.to_string().contains("strings.mcap") && err.to_string().contains("malformed"),
            "{err}"
        );
        patched += 1;
    }
    assert_eq!(patched, 2, "a schema and a channel record");
    // The same in a chunk's header: its compression name.
    for compress in [false, true] {
        let file = mcap_of(&[("/a", &reach(40))], compress);
        let (_, body, _, _) = first_chunk(&file);
        let mut bad = file.clone();
        bad[body + 28..body + 32].copy_from_slice(&0xFFFF_FFF0u32.to_le_bytes());
        let region = Region::new(GLOBAL);
        let result = load("chunk-name.mcap", &bad);
        let allocated = region.change().bytes_allocated;
        assert!(allocated < ALLOWANCE, "{allocated} bytes allocated");
        let err = result.expect_err("a chunk whose compression name runs past it loads");
        assert!(err.to_string().contains("malformed"), "{err}");
    }
}

/// The one test of this binary: nothing else allocates while it measures.
#[test]
fn declared_lengths_fail_fast_without_being_allocated() {
    huge_declared_lengths();
    large_declared_lengths();
    huge_string_lengths();
}
