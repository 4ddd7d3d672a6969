//! Every bad input gives an error, never a panic, and the error's text names
//! the file and, where it applies, the topic and the sample index
//! (method.md sections 2.1-2.3). Also: out-of-order and duplicated stamps and
//! the log-time fallback. A global allocator records the largest single
//! allocation per thread, so "declares a huge length" can be checked to fail
//! without allocating it.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::collections::BTreeMap;
use std::io::Cursor;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::time::Instant;

use dmpscope_core::io::ros2::{POSE_STAMPED_SCHEMA, encode_pose_stamped};
use dmpscope_core::io::write::{TopicSamples, write_pose_stamped};
use dmpscope_core::io::{Loaded, load_bytes};
use dmpscope_core::synth::Rng;
use dmpscope_core::{Error, PrepSettings, RawDemo, Result, TimeSource, prepare};
use mcap::records::MessageHeader;

// ------------------------------------------------------ allocation tracking

struct Tracking;

thread_local! {
    static LARGEST: Cell<usize> = const { Cell::new(0) };
}

fn note(size: usize) {
    let _ = LARGEST.try_with(|c| c.set(c.get().max(size)));
}

#[allow(unsafe_code)]
// SAFETY: every call is forwarded unchanged to the system allocator.
unsafe impl GlobalAlloc for Tracking {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        note(layout.size());
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        note(layout.size());
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        note(new_size);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Tracking = Tracking;

/// Runs `f` and returns its result with the largest single allocation it made
/// on this thread.
fn largest_allocation<T>(f: impl FnOnce() -> T) -> (T, usize) {
    LARGEST.with(|c| c.set(0));
    let out = f();
    (out, LARGEST.with(Cell::get))
}

// ---------------------------------------------------------------- helpers

/// A sample as the writer takes it: `(stamp_ns, position)`.
type Sample = (i64, [f64; 3]);

const EPOCH: i64 = 1_700_000_000_000_000_000;
const PERIOD: i64 = 10_000_000; // 100 Hz

/// `n` samples of a smooth reach at 100 Hz.
fn reach(n: usize) -> Vec<Sample> {
    (0..n)
        .map(|k| {
            let u = k as f64 / n as f64;
            (
                EPOCH + k as i64 * PERIOD,
                [0.3 * u, 0.1 * u * u, 0.9 - 0.05 * u],
            )
        })
        .collect()
}

fn mcap_of(topics: &[(&str, &[Sample])], compress: bool) -> Vec<u8> {
    let topics: Vec<TopicSamples<'_>> = topics
        .iter()
        .map(|&(topic, samples)| TopicSamples {
            topic,
            frame_id: "world",
            samples,
        })
        .collect();
    write_pose_stamped(Cursor::new(Vec::new()), &topics, compress)
        .expect("write")
        .into_inner()
}

/// One channel written with `mcap::Writer` directly: `(log_time, message bytes)`.
fn raw_mcap(
    schema: Option<(&str, &[u8])>,
    topic: &str,
    encoding: &str,
    messages: &[(u64, Vec<u8>)],
) -> Vec<u8> {
    let mut w = mcap::Writer::new(Cursor::new(Vec::new())).expect("writer");
    let schema_id = match schema {
        Some((name, text)) => w.add_schema(name, "ros2msg", text).expect("schema"),
        None => 0,
    };
    let channel_id = w
        .add_channel(schema_id, topic, encoding, &BTreeMap::new())
        .expect("channel");
    for (sequence, (time, data)) in messages.iter().enumerate() {
        let header = MessageHeader {
            channel_id,
            sequence: sequence as u32,
            log_time: *time,
            publish_time: *time,
        };
        w.write_to_known_channel(&header, data).expect("message");
    }
    w.finish().expect("finish");
    w.into_inner().into_inner()
}

fn pose_mcap(messages: &[(u64, Vec<u8>)]) -> Vec<u8> {
    let schema = (
        "geometry_msgs/msg/PoseStamped",
        POSE_STAMPED_SCHEMA.as_bytes(),
    );
    raw_mcap(Some(schema), "/pose", "cdr", messages)
}

/// Loads without letting a panic escape as anything but a clear failure.
#[track_caller]
fn load(label: &str, bytes: &[u8]) -> Result<Loaded> {
    match catch_unwind(AssertUnwindSafe(|| load_bytes(label, bytes))) {
        Ok(r) => r,
        Err(_) => panic!("{label}: the loader panicked on {} bytes", bytes.len()),
    }
}

/// The error of a load that must fail; its text must name the file.
#[track_caller]
fn load_err(label: &str, bytes: &[u8]) -> (Error, String) {
    let err = match load(label, bytes) {
        Ok(l) => panic!("{label}: loaded {} demos from bad input", l.demos.len()),
        Err(e) => e,
    };
    let text = err.to_string();
    assert!(
        text.contains(label),
        "{label}: error does not name the file: {text}"
    );
    (err, text)
}

/// Top-level records after the magic: `(offset, opcode, body start, body length)`.
fn records(bytes: &[u8]) -> Vec<(usize, u8, usize, usize)> {
    let mut out = Vec::new();
    let mut pos = 8;
    while pos + 9 <= bytes.len() - 8 {
        let op = bytes[pos];
        let len = u64::from_le_bytes(bytes[pos + 1..pos + 9].try_into().expect("8 bytes")) as usize;
        out.push((pos, op, pos + 9, len));
        pos += 9 + len;
    }
    out
}

const CHUNK: u8 = 0x06;

/// The first chunk: `(record offset, body start, offset of its records, their length)`.
fn first_chunk(bytes: &[u8]) -> (usize, usize, usize, usize) {
    let &(at, _, body, _) = records(bytes)
        .iter()
        .find(|r| r.1 == CHUNK)
        .expect("a chunk");
    let clen = u32::from_le_bytes(bytes[body + 28..body + 32].try_into().expect("4")) as usize;
    let len_at = body + 32 + clen;
    let len = u64::from_le_bytes(bytes[len_at..len_at + 8].try_into().expect("8")) as usize;
    (at, body, len_at + 8, len)
}

fn raw_demo(stamps: &[i64], positions: &[[f64; 3]]) -> RawDemo {
    RawDemo {
        name: "demo.mcap:/hand".into(),
        file: "demo.mcap".into(),
        topic: "/hand".into(),
        stamps_ns: stamps.to_vec(),
        positions: positions.to_vec(),
        time_source: TimeSource::HeaderStamp,
    }
}

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

#[test]
fn truncated_files_are_errors_at_every_cut() {
    let a = reach(40);
    let b = reach(25);
    for compress in [false, true] {
        let bytes = mcap_of(&[("/a", &a), ("/b", &b)], compress);
        assert_eq!(
            load("whole.mcap", &bytes).expect("whole file").demos.len(),
            2
        );
        for cut in 0..bytes.len() {
            let label = format!("cut-{cut}.mcap");
            let (err, _) = load_err(&label, &bytes[..cut]);
            assert!(matches!(err, Error::Mcap { .. }), "{label}: {err:?}");
        }
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
#[ignore = "bug: chunk CRCs are checked only after the chunk's messages were decoded \
            (validate_chunk_crcs, not prevalidate_chunk_crcs), so a corrupt chunk is reported \
            as a decode or non-finite error of one message instead of as a CRC failure"]
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

/// Loads `file` with `value` at `offset`: the result, the largest single
/// allocation and the time taken.
fn load_patched(
    name: &str,
    file: &[u8],
    offset: usize,
    value: u64,
) -> (Result<Loaded>, usize, f64) {
    let mut bad = file.to_vec();
    bad[offset..offset + 8].copy_from_slice(&value.to_le_bytes());
    let start = Instant::now();
    let (result, largest) = largest_allocation(|| load(name, &bad));
    (result, largest, start.elapsed().as_secs_f64())
}

#[test]
fn a_huge_declared_length_fails_fast_without_allocating_it() {
    let limit = dmpscope_core::io::mcap_file::RECORD_LENGTH_LIMIT as u64;
    for (name, file, offset) in length_fields() {
        for huge in [u64::MAX, 1 << 40, limit + 1] {
            if huge == limit + 1 && name.ends_with("chunk record") {
                continue; // see the ignored test below
            }
            let (result, largest, secs) = load_patched("huge.mcap", &file, offset, huge);
            assert!(secs < 1.0, "{name} = {huge}: took {secs} s");
            assert!(
                largest < 1 << 20,
                "{name} = {huge}: allocated {largest} bytes at once"
            );
            match result {
                Err(e) => assert!(e.to_string().contains("huge.mcap"), "{e}"),
                // The reader ignores the uncompressed size of an uncompressed
                // chunk (it equals the records' length); the data is intact.
                Ok(_) => assert_eq!(
                    name, "plain chunk uncompressed size",
                    "{name} = {huge}: loaded"
                ),
            }
        }
    }
}

#[test]
#[ignore = "bug: the loader hands every ReadRequest's full size to LinearReader::insert, which \
            zero-fills it before reading, so a 3 KB file declaring a record of up to \
            RECORD_LENGTH_LIMIT (or a chunk of limit + 1) allocates ~256 MiB before it reports \
            'truncated' (an abort, not an error, where memory is tight, e.g. wasm)"]
fn a_large_declared_length_in_a_small_file_is_not_allocated() {
    let limit = dmpscope_core::io::mcap_file::RECORD_LENGTH_LIMIT as u64;
    for (name, file, offset) in length_fields() {
        if name == "plain chunk uncompressed size" {
            continue; // ignored by the reader
        }
        for large in [limit + 1, limit - 1, 100 << 20] {
            let (result, largest, _) = load_patched("large.mcap", &file, offset, large);
            assert!(result.is_err(), "{name} = {large}: loaded");
            assert!(
                largest < 16 << 20,
                "{name} = {large}: {file_len}-byte file, {largest} bytes allocated at once",
                file_len = file.len()
            );
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
    assert_eq!(demo.sorted_unique(), (st.clone(), pos.clone()));
    let settings = PrepSettings::default();
    assert_eq!(
        prepare(demo, &settings).expect("prepare"),
        prepare(&raw_demo(&st, &pos), &settings).expect("prepare")
    );
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
