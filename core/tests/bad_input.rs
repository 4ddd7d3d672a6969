//! Every bad input gives an error, never a panic, and the error's text names
//! the file and, where it applies, the topic and the sample index
//! (method.md sections 2.1-2.3). Also: out-of-order and duplicated stamps and
//! the log-time fallback. That a huge declared length fails without being
//! allocated is checked in `alloc_limits.rs`, which measures allocations.

mod common;

use std::panic::{AssertUnwindSafe, catch_unwind};

use common::{
    EPOCH, Sample, first_chunk, load, load_err, mcap_of, mcap_of_chunked, pose_mcap, raw_demo,
    raw_mcap, reach,
};
use dmpscope_core::load::decode::ros2::encode_pose_stamped;
use dmpscope_core::rng::Rng;
use dmpscope_core::{Error, PrepSettings, RawDemo, TimeSource, prepare};

// ---------------------------------------------------------------- helpers

/// The error of `prepare` on a demo that must fail, as text.
#[track_caller]
fn prepare_err(raw: &RawDemo) -> String {
    let r = catch_unwind(AssertUnwindSafe(|| prepare(raw, &PrepSettings::default())))
        .unwrap_or_else(|_| panic!("{}: prepare panicked", raw.name));
    r.expect_err("prepare must fail").to_string()
}

// ------------------------------------------------------------------ tests

#[test]
fn non_finite_positions_name_file_topic_and_sample() {
    let clean = reach(60);
    for (value, axis, field) in [
        (f64::NAN, 1, "position.y"),
        (f64::INFINITY, 0, "position.x"),
        (f64::NEG_INFINITY, 2, "position.z"),
    ] {
        let mut bad = reach(60);
        bad[17].1[axis] = value;
        for compress in [false, true] {
            let bytes = mcap_of(&[("/a_clean", &clean), ("/b_bad", &bad)], compress);
            let (err, text) = load_err("nonfinite.mcap", &bytes);
            assert!(matches!(err, Error::NonFinite { .. }), "{err:?}");
            for part in ["topic /b_bad", "sample 17", field] {
                assert!(text.contains(part), "{text:?} lacks {part:?}");
            }
        }
        // The same demo given directly, with stamps out of order: the index is in file order.
        let mut stamps: Vec<i64> = bad.iter().map(|s| s.0).collect();
        stamps.swap(3, 30);
        let positions: Vec<[f64; 3]> = bad.iter().map(|s| s.1).collect();
        let text = prepare_err(&raw_demo(&stamps, &positions));
        for part in ["demo.mcap", "topic /hand", "sample 17", field] {
            assert!(text.contains(part), "{text:?} lacks {part:?}");
        }
    }
}

#[test]
fn too_few_samples_name_the_demo() {
    // 15 samples at 100 Hz: n0 = 15 < 21.
    let bytes = mcap_of(&[("/short", &reach(15))], false);
    let loaded = load("short.mcap", &bytes).expect("loads");
    let text = prepare_err(&loaded.demos[0]);
    for part in ["short.mcap:/short", "n0 = 15", "21"] {
        assert!(text.contains(part), "{text:?} lacks {part:?}");
    }
    // The boundary: 20 samples give n0 = 20 (error), 21 give n0 = 21 (fine).
    let s20 = reach(20);
    let (st, pos): (Vec<i64>, Vec<[f64; 3]>) = s20.iter().copied().unzip();
    assert!(prepare_err(&raw_demo(&st, &pos)).contains("n0 = 20"));
    let s21 = reach(21);
    let (st, pos): (Vec<i64>, Vec<[f64; 3]>) = s21.iter().copied().unzip();
    assert_eq!(
        prepare(&raw_demo(&st, &pos), &PrepSettings::default())
            .expect("21 samples")
            .n0,
        21
    );
    // Degenerate demos: none, one sample, every stamp equal.
    let p = [[0.1, 0.2, 0.3]; 30];
    for (stamps, n) in [(vec![], 0), (vec![EPOCH], 1), (vec![EPOCH; 30], 30)] {
        let text = prepare_err(&raw_demo(&stamps, &p[..n]));
        assert!(text.contains("demo.mcap:/hand"), "{text}");
    }
    // A huge gap over a tiny median interval gives no usable grid.
    let mut stamps: Vec<i64> = (0..30).map(|k| EPOCH + k).collect();
    stamps[29] = EPOCH + 1_000_000_000;
    let text = prepare_err(&raw_demo(&stamps, &p));
    assert!(text.contains("demo.mcap:/hand: duration 1"), "{text}");
}

#[test]
fn a_file_without_pose_topics_lists_what_it_skipped() {
    let string = raw_mcap(
        Some(("std_msgs/msg/String", b"string data")),
        "/chatter",
        "cdr",
        &[(1, vec![0, 1, 0, 0, 3, 0, 0, 0, b'h', b'i', 0])],
    );
    let (err, text) = load_err("strings.mcap", &string);
    match &err {
        Error::NoDemos { file, skipped } => {
            assert_eq!(file, "strings.mcap");
            assert_eq!(
                skipped,
                &[("/chatter".to_owned(), "std_msgs/msg/String".to_owned())]
            );
        }
        other => panic!("expected NoDemos, got {other:?}"),
    }
    assert!(text.contains("/chatter (std_msgs/msg/String)"), "{text}");

    let schemaless = raw_mcap(None, "/json", "json", &[(1, b"{}".to_vec())]);
    let (_, text) = load_err("schemaless.mcap", &schemaless);
    assert!(text.contains("/json (no schema, json)"), "{text}");
}

#[test]
fn a_file_that_is_not_mcap_is_an_error() {
    let mut rng = Rng::new(9);
    let random: Vec<u8> = (0..4096).map(|_| rng.next_u64() as u8).collect();
    let valid = mcap_of(&[("/a", &reach(30))], false);
    let mut magic_then_noise = valid[..8].to_vec();
    magic_then_noise.extend_from_slice(&random[..100]);
    let cases: [(&str, &[u8]); 5] = [
        ("random.bin", &random),
        ("empty.mcap", &[]),
        ("text.mcap", b"this is a CSV file,1,2,3\n"),
        ("magic-only.mcap", &valid[..8]),
        ("magic-then-noise.mcap", &magic_then_noise),
    ];
    for (label, bytes) in cases {
        let (err, _) = load_err(label, bytes);
        assert!(matches!(err, Error::Mcap { .. }), "{label}: {err:?}");
    }
    let (_, text) = load_err("random.bin", &random);
    assert!(text.contains("magic"), "{text}");
}

/// A file cut anywhere is an error naming it, or, once a complete chunk
/// precedes the cut, loads that chunk's messages with a warning naming the
/// file and saying it is truncated: never a panic, never more than was there.
#[test]
fn truncated_files_fail_or_keep_their_complete_chunks_at_every_cut() {
    let a = reach(40);
    let b = reach(25);
    for compress in [false, true] {
        // Small chunks, so that some cuts fall after complete ones.
        let bytes = mcap_of_chunked(&[("/a", &a), ("/b", &b)], compress, 512);
        assert_eq!(
            load("whole.mcap", &bytes).expect("whole file").demos.len(),
            2
        );
        let mut recovered = 0;
        for cut in 0..bytes.len() {
            let label = format!("cut-{cut}.mcap");
            match load(&label, &bytes[..cut]) {
                Err(err) => {
                    assert!(matches!(err, Error::Mcap { .. }), "{label}: {err:?}");
                    assert!(err.to_string().contains(&label), "{err}");
                }
                Ok(loaded) => {
                    recovered += 1;
                    assert!(
                        loaded
                            .warnings
                            .iter()
                            .any(|w| w.contains(&label) && w.contains("truncated")),
                        "{label}: loaded without a truncation warning"
                    );
                    let kept: usize = loaded.demos.iter().map(|d| d.positions.len()).sum();
                    assert!(
                        kept > 0 && kept <= a.len() + b.len(),
                        "{label}: kept {kept}"
                    );
                    for d in &loaded.demos {
                        let source = if d.topic == "/a" { &a } else { &b };
                        assert_eq!(
                            d.positions[..],
                            source
                                .iter()
                                .map(|s| s.1.into())
                                .collect::<Vec<dmpscope_core::geom::Vec3>>()[..d.positions.len()]
                        );
                    }
                }
            }
        }
        assert!(
            recovered > 0,
            "no cut kept a complete chunk (compress = {compress})"
        );
    }
}

/// The offset of sample `k`'s CDR message (as `reach` and `mcap_of` write it) in `bytes`.
fn message_offset(bytes: &[u8], samples: &[Sample], k: usize) -> usize {
    let (t, p) = samples[k];
    let message = encode_pose_stamped(t, "world", p);
    bytes
        .windows(message.len())
        .position(|w| w == message.as_slice())
        .expect("message in file")
}

/// Offset of `pose.position.x` inside an encoded message with frame id "world".
const POSITION_X: usize = 28;

#[test]
fn a_corrupt_chunk_fails_its_crc() {
    // Uncompressed chunk: one bit of a position changes; the message still
    // decodes, so only the CRC can tell.
    let samples = reach(40);
    let bytes = mcap_of(&[("/a", &samples)], false);
    let mut bad = bytes.clone();
    bad[message_offset(&bytes, &samples, 20) + POSITION_X] ^= 0x01;
    let (err, text) = load_err("crc.mcap", &bad);
    assert!(matches!(err, Error::Mcap { .. }), "{err:?}");
    assert!(text.contains("CRC"), "{text}");

    // Compressed chunk: a flip of any compressed byte is an error (never a
    // panic) or, where it leaves the output unchanged, the same data; flips
    // that still decompress to different bytes are caught by the CRC.
    let bytes = mcap_of(&[("/a", &samples)], true);
    let (_, body, data, len) = first_chunk(&bytes);
    assert_eq!(&bytes[body + 32..body + 36], b"zstd");
    let original = load("zstd.mcap", &bytes).expect("loads").demos;
    let mut crc_errors = 0;
    for at in data..data + len {
        let mut bad = bytes.clone();
        bad[at] ^= 0x10;
        match load("zstd.mcap", &bad) {
            Err(e) => {
                let text = e.to_string();
                assert!(text.contains("zstd.mcap"), "{text}");
                crc_errors += usize::from(text.contains("CRC"));
            }
            // A flip in a zstd header bit that does not change the output.
            Ok(l) => assert_eq!(l.demos, original, "flip at {at}: different data loaded"),
        }
    }
    assert!(crc_errors > 0, "no flip reached the CRC check");

    // The stored CRC itself changed.
    let mut bad = bytes.clone();
    bad[body + 24] ^= 0xff;
    let (_, text) = load_err("stored-crc.mcap", &bad);
    assert!(text.contains("CRC"), "{text}");
}

#[test]
fn a_corrupt_chunk_is_reported_as_corrupt_not_as_a_bad_message() {
    let samples = reach(40);
    let bytes = mcap_of(&[("/a", &samples)], false);
    let at = message_offset(&bytes, &samples, 16);
    // (a) The CDR encapsulation byte: "unsupported CDR encapsulation 01 01".
    let mut header = bytes.clone();
    header[at] ^= 0x01;
    // (b) The exponent of position.x: a NaN, "non-finite value in position.x".
    let mut exponent = bytes.clone();
    exponent[at + POSITION_X + 6] |= 0xf0;
    exponent[at + POSITION_X + 7] = 0x7f;
    for (label, bad) in [("header.mcap", header), ("exponent.mcap", exponent)] {
        let (err, text) = load_err(label, &bad);
        assert!(text.contains("CRC"), "{label}: {err:?}");
    }
}

#[test]
fn a_short_or_malformed_message_names_topic_and_sample() {
    let mut messages: Vec<(u64, Vec<u8>)> = reach(30)
        .iter()
        .map(|&(t, p)| (t as u64, encode_pose_stamped(t, "world", p)))
        .collect();
    let full = messages[4].1.clone();
    let cases: [(&str, Vec<u8>, &str); 4] = [
        (
            "cut-in-position",
            full[..40].to_vec(),
            "message ends before pose.position",
        ),
        (
            "cut-in-orientation",
            full[..full.len() - 3].to_vec(),
            "pose.orientation.w",
        ),
        ("shorter-than-header", vec![0, 1], "encapsulation header"),
        (
            "huge-frame-id",
            {
                let mut m = full.clone();
                m[12..16].copy_from_slice(&u32::MAX.to_le_bytes());
                m
            },
            "runs past the message",
        ),
    ];
    for (label, data, words) in cases {
        messages[4].1 = data;
        let label = format!("{label}.mcap");
        let (err, text) = load_err(&label, &pose_mcap(&messages));
        assert!(matches!(err, Error::Decode { .. }), "{err:?}");
        for part in ["topic /pose", "sample 4", words] {
            assert!(text.contains(part), "{text:?} lacks {part:?}");
        }
    }
}

#[test]
fn out_of_order_and_duplicated_stamps_sort_stably_keeping_the_first() {
    let stamps = [30, 10, 20, 10, 30, 5, 20];
    let positions: Vec<[f64; 3]> = (0..stamps.len()).map(|i| [i as f64, 0.0, 0.0]).collect();
    let raw = raw_demo(&stamps, &positions);
    let (s, p) = raw.sorted_unique();
    assert_eq!(s, [5, 10, 20, 30]);
    let kept: Vec<f64> = p.iter().map(|q| q[0]).collect();
    assert_eq!(
        kept,
        [5.0, 1.0, 2.0, 0.0],
        "first in file order of each stamp"
    );

    // Through a file: the demo keeps file order; preparing it equals preparing
    // the sorted, de-duplicated demo.
    let mut samples = reach(60);
    samples.swap(10, 11);
    samples.swap(40, 20);
    let dup = (samples[30].0, [9.0, 9.0, 9.0]); // a later duplicate: dropped
    samples.insert(45, dup);
    let bytes = mcap_of(&[("/hand", &samples)], false);
    let loaded = load("demo.mcap", &bytes).expect("loads");
    let demo = &loaded.demos[0];
    assert_eq!(demo.name, "demo.mcap:/hand");
    assert_eq!(demo.time_source, TimeSource::HeaderStamp);
    let stamps: Vec<i64> = samples.iter().map(|s| s.0).collect();
    assert_eq!(demo.stamps_ns, stamps, "file order kept");
    let clean = reach(60);
    let (st, pos): (Vec<i64>, Vec<[f64; 3]>) = clean.iter().copied().unzip();
    let vecs: Vec<dmpscope_core::geom::Vec3> = pos.iter().map(|&p| p.into()).collect();
    assert_eq!(demo.sorted_unique(), (st.clone(), vecs));
    let settings = PrepSettings::default();
    let mut from_file = prepare(demo, &settings).expect("prepare");
    let sorted = prepare(&raw_demo(&st, &pos), &settings).expect("prepare");
    assert_eq!(from_file.n_samples, 61, "the samples as recorded");
    from_file.n_samples = sorted.n_samples;
    assert_eq!(from_file, sorted);
}

#[test]
fn zero_or_missing_stamps_fall_back_to_log_time() {
    let samples = reach(40);
    let log: Vec<u64> = (0..40).map(|k| 5_000_000_000 + k * 12_000_000).collect();
    let message =
        |k: usize, stamp: i64| (log[k], encode_pose_stamped(stamp, "world", samples[k].1));
    let expect_log: Vec<i64> = log.iter().map(|&t| t as i64).collect();

    // All header stamps zero.
    let zeros: Vec<_> = (0..40).map(|k| message(k, 0)).collect();
    let demo = &load("zero.mcap", &pose_mcap(&zeros)).expect("loads").demos[0];
    assert_eq!(demo.time_source, TimeSource::LogTime);
    assert_eq!(demo.stamps_ns, expect_log);
    let prepared = prepare(demo, &PrepSettings::default()).expect("prepare");
    assert!((prepared.duration_s - 39.0 * 0.012).abs() < 1e-12);

    // One message without a stamp: the whole demo uses log time.
    let one_missing: Vec<_> = (0..40)
        .map(|k| message(k, if k == 7 { 0 } else { samples[k].0 }))
        .collect();
    let demo = &load("one.mcap", &pose_mcap(&one_missing))
        .expect("loads")
        .demos[0];
    assert_eq!(demo.time_source, TimeSource::LogTime);
    assert_eq!(demo.stamps_ns, expect_log);

    // All stamped: the header stamps, not the log time.
    let stamped: Vec<_> = (0..40).map(|k| message(k, samples[k].0)).collect();
    let demo = &load("stamped.mcap", &pose_mcap(&stamped))
        .expect("loads")
        .demos[0];
    assert_eq!(demo.time_source, TimeSource::HeaderStamp);
    assert_eq!(
        demo.stamps_ns,
        samples.iter().map(|s| s.0).collect::<Vec<_>>()
    );
}

/// Found by the fuzzer: a record inside an uncompressed chunk that declares
/// more bytes than the chunk has left (but less than the record limit) made
/// mcap's reader underflow. It is an error naming the file, for every record
/// of the chunk and every overrun.
#[test]
fn a_record_overrunning_its_chunk_is_an_error() {
    let bytes = mcap_of(&[("/a", &reach(30))], false);
    let (_, body, records_at, records_len) = first_chunk(&bytes);
    let mut offset = records_at;
    let mut patched = 0;
    while offset + 9 <= records_at + records_len {
        let len = u64::from_le_bytes(bytes[offset + 1..offset + 9].try_into().expect("8")) as usize;
        let left = records_at + records_len - offset - 9;
        for declared in [left + 1, left + 100, left + 4096] {
            let mut bad = bytes.clone();
            bad[offset + 1..offset + 9].copy_from_slice(&(declared as u64).to_le_bytes());
            let label = format!("overrun-{offset}-{declared}.mcap");
            let (err, text) = load_err(&label, &bad);
            assert!(matches!(err, Error::Mcap { .. }), "{err:?}");
            assert!(text.contains("CRC"), "{text}");
            // With the chunk's CRC unset (0), the walk itself must catch it.
            bad[body + 24..body + 28].copy_from_slice(&[0; 4]);
            let (err, text) = load_err(&label, &bad);
            assert!(matches!(err, Error::Mcap { .. }), "{err:?}");
            assert!(text.contains("inside a chunk declares"), "{text}");
            patched += 1;
        }
        offset += 9 + len;
    }
    assert!(patched > 30, "only {patched} records patched");
}

/// Found by the fuzzer: stamps 1 us apart with one 10 s gap asked for 1e7
/// resampled points (seconds of work). Past `MAX_RESAMPLED` it is an error,
/// at once.
#[test]
fn a_gap_far_longer_than_the_sampling_interval_is_an_error_not_a_hang() {
    let mut stamps: Vec<i64> = (0..40).map(|k| k * 1_000).collect();
    stamps.push(10_000_000_000);
    let positions = vec![[0.0; 3]; stamps.len()];
    let raw = raw_demo(&stamps, &positions);
    let start = std::time::Instant::now();
    let text = prepare_err(&raw);
    assert!(
        start.elapsed().as_secs_f64() < 0.5,
        "took {:?}",
        start.elapsed()
    );
    assert!(text.contains("gaps") && text.contains(&raw.name), "{text}");
}
