//! Helpers shared by the test binaries that build, corrupt and load MCAP
//! files (`bad_input`, `alloc_limits`) or read the bundled samples
//! (`report`, `recovery`, `golden_orientation_grid`, `kernel_dispatch`).
//! Each binary includes this module with `mod common;`; not every binary
//! uses every helper.

#![allow(dead_code)]

use std::collections::BTreeMap;
use std::io::Cursor;
use std::panic::{AssertUnwindSafe, catch_unwind};

use dmpscope_core::export::write::{TopicSamples, write_pose_stamped};
use dmpscope_core::load::collect::Loaded;
use dmpscope_core::load::decode::ros2::POSE_STAMPED_SCHEMA;
use dmpscope_core::load::mcap::load_bytes;
use dmpscope_core::{Error, RawDemo, Result, TimeSource};
use mcap::records::MessageHeader;

/// A sample as the writer takes it: `(stamp_ns, position)`.
pub type Sample = (i64, [f64; 3]);

/// The stamp of the first sample `reach` gives, in nanoseconds.
pub const EPOCH: i64 = 1_700_000_000_000_000_000;
/// The interval between samples `reach` gives: 10 ms, 100 Hz.
pub const PERIOD: i64 = 10_000_000;

/// The opcode of an MCAP chunk record.
pub const CHUNK: u8 = 0x06;

/// `n` samples of a smooth reach at 100 Hz.
pub fn reach(n: usize) -> Vec<Sample> {
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

/// An MCAP file of `geometry_msgs/msg/PoseStamped` topics `(topic, samples)`
/// with frame id "world", as the crate's writer gives it; `compress` chooses
/// zstd chunks over plain ones.
pub fn mcap_of(topics: &[(&str, &[Sample])], compress: bool) -> Vec<u8> {
    let topics: Vec<TopicSamples<'_>> = topics
        .iter()
        .map(|&(topic, samples)| TopicSamples {
            orientations: None,
            topic,
            frame_id: "world",
            samples,
        })
        .collect();
    write_pose_stamped(Cursor::new(Vec::new()), &topics, compress)
        .expect("write")
        .into_inner()
}

/// Like [`mcap_of`], with chunks closed after about `chunk_size` bytes.
pub fn mcap_of_chunked(topics: &[(&str, &[Sample])], compress: bool, chunk_size: u64) -> Vec<u8> {
    let compression = compress.then_some(mcap::Compression::Zstd);
    let mut w = mcap::WriteOptions::new()
        .compression(compression)
        .chunk_size(Some(chunk_size))
        .create(Cursor::new(Vec::new()))
        .expect("writer");
    let schema = w
        .add_schema(
            "geometry_msgs/msg/PoseStamped",
            "ros2msg",
            POSE_STAMPED_SCHEMA.as_bytes(),
        )
        .expect("schema");
    for (topic, samples) in topics {
        let channel_id = w
            .add_channel(schema, topic, "cdr", &BTreeMap::new())
            .expect("channel");
        for (sequence, (stamp, p)) in samples.iter().enumerate() {
            let header = MessageHeader {
                channel_id,
                sequence: sequence as u32,
                log_time: *stamp as u64,
                publish_time: *stamp as u64,
            };
            let data = dmpscope_core::load::decode::ros2::encode_pose_stamped(*stamp, "world", *p);
            w.write_to_known_channel(&header, &data).expect("message");
        }
    }
    w.finish().expect("finish");
    w.into_inner().into_inner()
}

/// One channel written with `mcap::Writer` directly: `(log_time, message bytes)`.
pub fn raw_mcap(
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

/// One `/pose` channel of CDR-encoded `geometry_msgs/msg/PoseStamped`
/// messages `(log_time, message bytes)`, written with `raw_mcap`.
pub fn pose_mcap(messages: &[(u64, Vec<u8>)]) -> Vec<u8> {
    let schema = (
        "geometry_msgs/msg/PoseStamped",
        POSE_STAMPED_SCHEMA.as_bytes(),
    );
    raw_mcap(Some(schema), "/pose", "cdr", messages)
}

/// Loads without letting a panic escape as anything but a clear failure.
#[track_caller]
pub fn load(label: &str, bytes: &[u8]) -> Result<Loaded> {
    match catch_unwind(AssertUnwindSafe(|| load_bytes(label, bytes))) {
        Ok(r) => r,
        Err(_) => panic!("{label}: the loader panicked on {} bytes", bytes.len()),
    }
}

/// The error of a load that must fail; its text must name the file.
#[track_caller]
pub fn load_err(label: &str, bytes: &[u8]) -> (Error, String) {
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
pub fn records(bytes: &[u8]) -> Vec<(usize, u8, usize, usize)> {
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

/// The first chunk: `(record offset, body start, offset of its records, their length)`.
pub fn first_chunk(bytes: &[u8]) -> (usize, usize, usize, usize) {
    let &(at, _, body, _) = records(bytes)
        .iter()
        .find(|r| r.1 == CHUNK)
        .expect("a chunk");
    let clen = u32::from_le_bytes(bytes[body + 28..body + 32].try_into().expect("4")) as usize;
    let len_at = body + 32 + clen;
    let len = u64::from_le_bytes(bytes[len_at..len_at + 8].try_into().expect("8")) as usize;
    (at, body, len_at + 8, len)
}

/// A demo "demo.mcap:/hand" with header stamps, given directly rather than
/// loaded from a file.
pub fn raw_demo(stamps: &[i64], positions: &[[f64; 3]]) -> RawDemo {
    RawDemo {
        name: "demo.mcap:/hand".into(),
        file: "demo.mcap".into(),
        topic: "/hand".into(),
        stamps_ns: stamps.to_vec(),
        positions: positions.iter().map(|&p| p.into()).collect(),
        orientations: None,
        time_source: TimeSource::HeaderStamp,
    }
}

/// The largest absolute value.
pub fn max_abs(v: impl IntoIterator<Item = f64>) -> f64 {
    v.into_iter().fold(0.0, |a, x| a.max(x.abs()))
}

/// `|actual - expected| <= tol`, naming `what` when not.
#[track_caller]
pub fn close(actual: f64, expected: f64, tol: f64, what: impl std::fmt::Display) {
    let diff = (actual - expected).abs();
    assert!(
        diff <= tol,
        "{what}: {actual} vs {expected} (off by {diff:e}, tolerance {tol:e})"
    );
}

/// The bundled reach sample's demos (`assets/reach10.mcap`), read as the
/// app and the CLI read it.
pub fn sample_demos() -> Vec<RawDemo> {
    bundled(
        "reach10.mcap",
        include_bytes!("../../../assets/reach10.mcap"),
    )
}

/// The bundled planted sample's demos (`assets/planted8.mcap`: eight
/// demos with orientations), read as the app and the CLI read it.
pub fn planted8_demos() -> Vec<RawDemo> {
    bundled(
        "planted8.mcap",
        include_bytes!("../../../assets/planted8.mcap"),
    )
}

/// The demos of the bundled recording `name` (its bytes), loaded with the
/// default options.
fn bundled(name: &str, bytes: &[u8]) -> Vec<RawDemo> {
    dmpscope_core::arrange::streams::load_source(
        name,
        dmpscope_core::load::source::SourceData::Bytes(bytes),
        &dmpscope_core::load::options::LoadOptions::default(),
    )
    .unwrap_or_else(|e| panic!("the bundled {name} loads: {e}"))
    .demos
}

/// Planted demos (`dmpscope_core::planted`) as raw demos named
/// `planted:i` on topics `/demo_ii`, orientations included.
pub fn planted_raw(spec: &dmpscope_core::synth::planted_forcing::PlantedSpec) -> Vec<RawDemo> {
    dmpscope_core::synth::planted::planted_demos(spec, EPOCH)
        .iter()
        .enumerate()
        .map(|(i, d)| RawDemo {
            name: format!("planted:{i}"),
            file: "planted".into(),
            topic: format!("/demo_{i:02}"),
            stamps_ns: d.samples.iter().map(|s| s.0).collect(),
            positions: d.samples.iter().map(|s| s.1.into()).collect(),
            orientations: d.orientations.as_ref().map(|qs| {
                qs.iter()
                    .map(|q| dmpscope_core::geom::quat_from_xyzw(*q).expect("a unit quaternion"))
                    .collect()
            }),
            time_source: TimeSource::HeaderStamp,
        })
        .collect()
}
