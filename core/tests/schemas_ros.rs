//! The ROS message decoders (ROS 2 CDR and ROS 1): byte layouts checked
//! against hand-built messages, the same demos written in every supported
//! schema load to identical stamps and positions, TF keys become demos and
//! can be filtered, bad messages name topic and sample, and no byte string
//! makes a decoder panic. The CSV loader is tested in `schemas_csv.rs`.

use std::borrow::Cow;
use std::collections::BTreeMap;
use std::io::Cursor;
use std::panic::{AssertUnwindSafe, catch_unwind};

use dmpscope_core::error::Location;
use dmpscope_core::geom::Vec3;
use dmpscope_core::load::collect::Loaded;
use dmpscope_core::load::decode::ros2::StampedTransform;
use dmpscope_core::load::decode::{
    ChannelSchema, MessageDecoder, PoseSample, decoder_for, ros1, ros2,
};
use dmpscope_core::load::mcap::{load_bytes, load_bytes_with};
use dmpscope_core::load::options::LoadOptions;
use dmpscope_core::{Error, TimeSource};
use mcap::records::MessageHeader;

// ---------------------------------------------------------------- helpers

/// The first stamp of the test demos (not a whole second, so the
/// nanoseconds field is exercised).
const EPOCH: i64 = 1_700_000_000_123_456_789;
/// 100 Hz.
const PERIOD: i64 = 10_000_000;
/// The child frames (and topic suffixes) of the three test demos.
const FRAMES: [&str; 3] = ["hand_a", "hand_b", "hand_c"];

type Sample = (i64, [f64; 3]);

/// Three demos of `n` samples; demo `d`'s stamps are offset by `d` µs so
/// each TF transform carries its own stamp.
fn demos(n: usize) -> Vec<Vec<Sample>> {
    (0..3)
        .map(|d| {
            (0..n)
                .map(|k| {
                    let u = k as f64 / n as f64;
                    let s = d as f64;
                    let stamp = EPOCH + k as i64 * PERIOD + d as i64 * 1000;
                    let p = [0.3 * u + s, 0.1 * u * u - 0.2 * s, 0.9 - 0.05 * u];
                    (stamp, p)
                })
                .collect()
        })
        .collect()
}

/// A schema as the MCAP file names it.
#[derive(Clone, Copy)]
struct Schema {
    name: &'static str,
    encoding: &'static str,
    text: &'static str,
    message_encoding: &'static str,
}

/// A ROS 2 (CDR) schema.
const fn r2(name: &'static str, text: &'static str) -> Schema {
    Schema {
        name,
        encoding: "ros2msg",
        text,
        message_encoding: "cdr",
    }
}

/// A ROS 1 schema.
const fn r1(name: &'static str, text: &'static str) -> Schema {
    Schema {
        name,
        encoding: "ros1msg",
        text,
        message_encoding: "ros1",
    }
}

const R2_POSE: Schema = r2("geometry_msgs/msg/PoseStamped", ros2::POSE_STAMPED_SCHEMA);
const R2_POSE_COV: Schema = r2(
    "geometry_msgs/msg/PoseWithCovarianceStamped",
    ros2::POSE_WITH_COVARIANCE_STAMPED_SCHEMA,
);
const R2_POINT: Schema = r2("geometry_msgs/msg/PointStamped", ros2::POINT_STAMPED_SCHEMA);
const R2_TRANSFORM: Schema = r2(
    "geometry_msgs/msg/TransformStamped",
    ros2::TRANSFORM_STAMPED_SCHEMA,
);
const R2_TF: Schema = r2("tf2_msgs/msg/TFMessage", ros2::TF_MESSAGE_SCHEMA);
const R1_POSE: Schema = r1("geometry_msgs/PoseStamped", ros1::POSE_STAMPED_SCHEMA);
const R1_TF: Schema = r1("tf2_msgs/TFMessage", ros1::TF_MESSAGE_SCHEMA);

/// One channel to write: its topic, schema and `(log_time, bytes)` messages.
#[derive(Clone)]
struct Chan {
    topic: String,
    schema: Schema,
    messages: Vec<(u64, Vec<u8>)>,
}

/// An MCAP file of the channels, written with `mcap::Writer`.
fn write_mcap(channels: &[Chan]) -> Vec<u8> {
    let mut w = mcap::WriteOptions::new()
        .create(Cursor::new(Vec::new()))
        .expect("writer");
    for chan in channels {
        let s = chan.schema;
        let schema = w
            .add_schema(s.name, s.encoding, s.text.as_bytes())
            .expect("schema");
        let channel_id = w
            .add_channel(schema, &chan.topic, s.message_encoding, &BTreeMap::new())
            .expect("channel");
        for (sequence, (time, data)) in chan.messages.iter().enumerate() {
            let header = MessageHeader {
                channel_id,
                sequence: sequence as u32,
                log_time: *time,
                publish_time: *time,
            };
            w.write_to_known_channel(&header, data).expect("message");
        }
    }
    w.finish().expect("finish");
    w.into_inner().into_inner()
}

/// The log time of a sample: 5 ms after its stamp, so a loader that used
/// log time instead of the header stamp would be caught.
fn log_time(stamp: i64) -> u64 {
    u64::try_from(stamp + 5_000_000).expect("positive")
}

/// A transform to encode, from `frame` to `child`.
fn tr<'a>(stamp_ns: i64, frame: &'a str, child: &'a str, p: [f64; 3]) -> StampedTransform<'a> {
    StampedTransform {
        stamp_ns,
        frame_id: frame,
        child_frame_id: child,
        translation: p,
        rotation: [0.0, 0.0, 0.0, 1.0],
    }
}

fn r2_pose((t, p): Sample) -> Vec<u8> {
    ros2::encode_pose_stamped(t, "world", p)
}

fn r2_cov((t, p): Sample) -> Vec<u8> {
    ros2::encode_pose_with_covariance_stamped(t, "world", p)
}

fn r2_point((t, p): Sample) -> Vec<u8> {
    ros2::encode_point_stamped(t, "world", p)
}

fn r1_pose((t, p): Sample) -> Vec<u8> {
    ros1::encode_pose_stamped(t, "world", p)
}

/// One topic per demo (`/hand_a`, ...), each message made by `encode`.
fn per_topic(schema: Schema, demos: &[Vec<Sample>], encode: fn(Sample) -> Vec<u8>) -> Vec<Chan> {
    demos
        .iter()
        .zip(FRAMES)
        .map(|(demo, frame)| Chan {
            topic: format!("/{frame}"),
            schema,
            messages: demo.iter().map(|&s| (log_time(s.0), encode(s))).collect(),
        })
        .collect()
}

/// One `/tf` topic, each message holding the k-th sample of every demo.
fn tf_topic(
    schema: Schema,
    demos: &[Vec<Sample>],
    encode: fn(&[StampedTransform<'_>]) -> Vec<u8>,
) -> Vec<Chan> {
    let messages = (0..demos[0].len())
        .map(|k| {
            let ts: Vec<_> = (0..3)
                .map(|d| tr(demos[d][k].0, "world", FRAMES[d], demos[d][k].1))
                .collect();
            (log_time(demos[0][k].0), encode(&ts))
        })
        .collect();
    vec![Chan {
        topic: "/tf".to_owned(),
        schema,
        messages,
    }]
}

/// One `/tf` topic of single `TransformStamped`s, the demos interleaved.
fn transform_topic(demos: &[Vec<Sample>]) -> Vec<Chan> {
    let mut messages = Vec::new();
    for k in 0..demos[0].len() {
        for d in 0..3 {
            let (stamp, p) = demos[d][k];
            let t = tr(stamp, "world", FRAMES[d], p);
            messages.push((log_time(stamp), ros2::encode_transform_stamped(&t)));
        }
    }
    vec![Chan {
        topic: "/tf".to_owned(),
        schema: R2_TRANSFORM,
        messages,
    }]
}

/// Every supported format: (label, channels, expected demo names).
fn all_formats(demos: &[Vec<Sample>]) -> Vec<(&'static str, Vec<Chan>, Vec<String>)> {
    let formats = [
        ("r2_pose.mcap", per_topic(R2_POSE, demos, r2_pose)),
        ("r2_cov.mcap", per_topic(R2_POSE_COV, demos, r2_cov)),
        ("r2_point.mcap", per_topic(R2_POINT, demos, r2_point)),
        ("r2_transform.mcap", transform_topic(demos)),
        (
            "r2_tf.mcap",
            tf_topic(R2_TF, demos, ros2::encode_tf_message),
        ),
        ("r1_pose.mcap", per_topic(R1_POSE, demos, r1_pose)),
        (
            "r1_tf.mcap",
            tf_topic(R1_TF, demos, ros1::encode_tf_message),
        ),
    ];
    formats
        .into_iter()
        .map(|(label, channels)| {
            let tf = channels.len() == 1;
            let names = FRAMES
                .iter()
                .map(|f| match tf {
                    true => format!("{label}:/tf:{f}"),
                    false => format!("{label}:/{f}"),
                })
                .collect();
            (label, channels, names)
        })
        .collect()
}

fn load_ok(label: &str, bytes: &[u8]) -> Loaded {
    load_bytes(label, bytes).unwrap_or_else(|e| panic!("{label}: {e}"))
}

/// A decoded sample, owned: (key, stamp, position).
type Got = (Option<String>, Option<i64>, [f64; 3]);

/// Decodes one message with `decoder`, returning the samples and whether
/// every key was borrowed from the message.
fn decode_all(decoder: &mut dyn MessageDecoder, data: &[u8]) -> Result<(Vec<Got>, bool), String> {
    let mut out = Vec::new();
    let mut borrowed = true;
    decoder.decode(data, &mut |s: PoseSample<'_>| {
        borrowed &= !matches!(s.key, Some(Cow::Owned(_)));
        out.push((s.key.map(Cow::into_owned), s.stamp_ns, s.position));
    })?;
    Ok((out, borrowed))
}

fn key(k: &str) -> Option<String> {
    Some(k.to_owned())
}

/// The registry's decoder for a schema.
fn registry(schema: Schema) -> Box<dyn MessageDecoder> {
    let channel = ChannelSchema {
        message_encoding: schema.message_encoding,
        schema_name: schema.name,
        schema_encoding: schema.encoding,
        schema_data: schema.text.as_bytes(),
    };
    decoder_for(&channel)
        .unwrap_or_else(|| panic!("no decoder for {}", schema.name))
        .expect("usable schema")
}

fn le32(v: u32) -> [u8; 4] {
    v.to_le_bytes()
}

fn le64(v: f64) -> [u8; 8] {
    v.to_le_bytes()
}

// ------------------------------------------------- hand-built byte layouts

#[test]
fn ros2_pose_stamped_layout_with_odd_frame_id() {
    let stamp = 1_700_000_000_123_456_789;
    let p = [1.5, -2.25, 3.0];
    for frame in ["world", "", "a", "ab", "abc", "abcd", "abcdefg", "abcdefgh"] {
        let mut m = vec![0x00, 0x01, 0x00, 0x00]; // little-endian CDR
        m.extend(1_700_000_000i32.to_le_bytes()); // body 0: sec
        m.extend(le32(123_456_789)); // body 4: nanosec
        m.extend(le32(frame.len() as u32 + 1)); // body 8: length with the NUL
        m.extend(frame.as_bytes()); // body 12..
        m.push(0);
        let body = m.len() - 4;
        m.resize(4 + body.next_multiple_of(8), 0); // float64 alignment
        for v in [p[0], p[1], p[2], 0.0, 0.0, 0.0, 1.0] {
            m.extend(le64(v));
        }
        if frame == "world" {
            // "world\0" ends at body 18: 6 bytes of padding, x at body 24.
            assert_eq!(m.len(), 4 + 24 + 56);
            assert_eq!(
                (&m[4 + 12..4 + 18], &m[4 + 18..4 + 24]),
                (&b"world\0"[..], &[0; 6][..])
            );
        }
        let s = ros2::decode_pose_stamped(&m).expect("decode");
        assert_eq!(
            (s.key, s.stamp_ns, s.position),
            (None, Some(stamp), p),
            "{frame:?}"
        );
        assert_eq!(ros2::encode_pose_stamped(stamp, frame, p), m, "{frame:?}");
    }
}

#[test]
fn ros2_point_and_covariance_layouts() {
    // Big-endian CDR (`00 00`), frame "ab" (length 3, 1 byte of padding).
    let mut m = vec![0x00, 0x00, 0x00, 0x00];
    m.extend(5i32.to_be_bytes());
    m.extend(6u32.to_be_bytes());
    m.extend(3u32.to_be_bytes());
    m.extend(b"ab\0");
    m.push(0); // body 15..16
    for v in [1.0f64, 2.0, 3.0] {
        m.extend(v.to_be_bytes());
    }
    let s = ros2::decode_point_stamped(&m).expect("decode");
    assert_eq!(
        (s.stamp_ns, s.position),
        (Some(5_000_000_006), [1.0, 2.0, 3.0])
    );

    // PoseWithCovarianceStamped: the pose, then 36 float64 without a length.
    let m = ros2::encode_pose_with_covariance_stamped(5_000_000_006, "map", [4.0, 5.0, 6.0]);
    assert_eq!(m.len(), 4 + 16 + 7 * 8 + 36 * 8); // "map\0" ends at body 16, aligned
    let s = ros2::decode_pose_with_covariance_stamped(&m).expect("decode");
    assert_eq!(
        (s.stamp_ns, s.position),
        (Some(5_000_000_006), [4.0, 5.0, 6.0])
    );
    let err = ros2::decode_pose_with_covariance_stamped(&m[..m.len() - 8]).expect_err("short");
    assert!(err.contains("covariance"), "{err}");
    // The zero stamp is "no stamp".
    let s =
        ros2::decode_point_stamped(&ros2::encode_point_stamped(0, "", [0.0; 3])).expect("decode");
    assert_eq!(s.stamp_ns, None);
}

#[test]
fn ros2_tf_message_layout_with_two_transforms() {
    let mut m = vec![0x00, 0x01, 0x00, 0x00];
    m.extend(le32(2)); // body 0: sequence length
    // transforms[0]
    m.extend(le32(100)); // 4: sec
    m.extend(le32(5)); // 8: nanosec
    m.extend(le32(4)); // 12: frame_id length
    m.extend(b"map\0"); // 16..20
    m.extend(le32(3)); // 20: child_frame_id length
    m.extend(b"h1\0"); // 24..27
    m.extend([0; 5]); // 27..32: padding
    for v in [0.1, 0.2, 0.3, 0.0, 0.0, 0.0, 1.0] {
        m.extend(le64(v)); // 32..88
    }
    // transforms[1]
    m.extend(le32(101)); // 88
    m.extend(le32(6)); // 92
    m.extend(le32(4)); // 96
    m.extend(b"map\0"); // 100..104
    m.extend(le32(6)); // 104
    m.extend(b"hand2\0"); // 108..114
    m.extend([0; 6]); // 114..120
    for v in [-1.0, -2.0, -3.0, 0.0, 0.0, 0.0, 1.0] {
        m.extend(le64(v)); // 120..176
    }
    assert_eq!(m.len(), 4 + 176);
    let (got, borrowed) = decode_all(registry(R2_TF).as_mut(), &m).expect("decode");
    assert_eq!(
        got,
        [
            (key("h1"), Some(100_000_000_005), [0.1, 0.2, 0.3]),
            (key("hand2"), Some(101_000_000_006), [-1.0, -2.0, -3.0]),
        ]
    );
    assert!(borrowed, "TF keys must borrow from the message");
    let ts = [
        tr(100_000_000_005, "map", "h1", [0.1, 0.2, 0.3]),
        tr(101_000_000_006, "map", "hand2", [-1.0, -2.0, -3.0]),
    ];
    assert_eq!(ros2::encode_tf_message(&ts), m);
    // Alone, the same TransformStamped starts at body offset 0, so "h1\0"
    // ends at 23 and one byte of padding (not five) precedes the translation.
    let one = ros2::encode_transform_stamped(&ts[0]);
    assert_eq!(one.len(), 4 + 24 + 56);
    assert_eq!((&one[4..27], one[27]), (&m[8..31], 0));
    assert_eq!(one[28..], m[36..92]);
    let (got, borrowed) = decode_all(registry(R2_TRANSFORM).as_mut(), &one).expect("decode");
    assert_eq!(got, [(key("h1"), Some(100_000_000_005), [0.1, 0.2, 0.3])]);
    assert!(borrowed);
    // A message bad in its second transform hands out nothing.
    let mut n = 0;
    let err = registry(R2_TF)
        .decode(&m[..m.len() - 1], &mut |_| n += 1)
        .expect_err("short");
    assert!(err.contains("transforms[1]"), "{err}");
    assert_eq!(n, 0);
}

#[test]
fn ros1_layouts() {
    // PoseStamped: seq, secs, nsecs, frame_id without NUL, no padding.
    let mut m = Vec::new();
    m.extend(le32(7)); // 0: seq
    m.extend(le32(1_700_000_000)); // 4: secs
    m.extend(le32(42)); // 8: nsecs
    m.extend(le32(5)); // 12: frame_id length (no NUL)
    m.extend(b"world"); // 16..21
    for v in [1.0, 2.0, 3.5, 0.0, 0.0, 0.0, 1.0] {
        m.extend(le64(v)); // 21..77, unaligned
    }
    assert_eq!(m.len(), 77);
    let s = ros1::decode_pose_stamped(&m).expect("decode");
    assert_eq!(
        (s.key, s.stamp_ns, s.position),
        (None, Some(1_700_000_000_000_000_042), [1.0, 2.0, 3.5])
    );
    let mut encoded =
        ros1::encode_pose_stamped(1_700_000_000_000_000_042, "world", [1.0, 2.0, 3.5]);
    encoded[0] = 7; // the encoder writes seq 0
    assert_eq!(encoded, m);

    // TFMessage with two transforms.
    let mut m = Vec::new();
    m.extend(le32(2));
    for (secs, child, x) in [(100u32, "h1", 0.5), (101, "hand2", -0.5)] {
        m.extend(le32(0));
        m.extend(le32(secs));
        m.extend(le32(9));
        m.extend(le32(3));
        m.extend(b"map");
        m.extend(le32(child.len() as u32));
        m.extend(child.as_bytes());
        for v in [x, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0] {
            m.extend(le64(v));
        }
    }
    let (got, borrowed) = decode_all(registry(R1_TF).as_mut(), &m).expect("decode");
    assert_eq!(
        got,
        [
            (key("h1"), Some(100_000_000_009), [0.5, 0.0, 0.0]),
            (key("hand2"), Some(101_000_000_009), [-0.5, 0.0, 0.0]),
        ]
    );
    assert!(borrowed);
    let ts = [
        tr(100_000_000_009, "map", "h1", [0.5, 0.0, 0.0]),
        tr(101_000_000_009, "map", "hand2", [-0.5, 0.0, 0.0]),
    ];
    assert_eq!(ros1::encode_tf_message(&ts), m);
}

// ------------------------------------------------------- whole-file loads

#[test]
fn every_format_loads_to_the_same_demos() {
    let demos = demos(40);
    for (label, channels, names) in all_formats(&demos) {
        let loaded = load_ok(label, &write_mcap(&channels));
        assert!(loaded.skipped.is_empty(), "{label}: {:?}", loaded.skipped);
        let got: Vec<&str> = loaded.demos.iter().map(|d| d.name.as_str()).collect();
        assert_eq!(got, names, "{label}");
        for (demo, want) in loaded.demos.iter().zip(&demos) {
            assert_eq!(demo.time_source, TimeSource::HeaderStamp, "{}", demo.name);
            let stamps: Vec<i64> = want.iter().map(|s| s.0).collect();
            let positions: Vec<[f64; 3]> = want.iter().map(|s| s.1).collect();
            assert_eq!(demo.stamps_ns, stamps, "{}", demo.name);
            assert_eq!(
                demo.positions,
                positions.iter().map(|&p| p.into()).collect::<Vec<Vec3>>(),
                "{}",
                demo.name
            );
        }
    }
}

#[test]
fn tf_frames_become_demos_and_can_be_filtered() {
    let demos = demos(12);
    for (label, bytes) in [
        (
            "tf.mcap",
            write_mcap(&tf_topic(R2_TF, &demos, ros2::encode_tf_message)),
        ),
        ("tf.mcap", write_mcap(&transform_topic(&demos))),
        (
            "tf.mcap",
            write_mcap(&tf_topic(R1_TF, &demos, ros1::encode_tf_message)),
        ),
    ] {
        let loaded = load_ok(label, &bytes);
        let names: Vec<&str> = loaded.demos.iter().map(|d| d.name.as_str()).collect();
        assert_eq!(
            names,
            [
                "tf.mcap:/tf:hand_a",
                "tf.mcap:/tf:hand_b",
                "tf.mcap:/tf:hand_c"
            ]
        );
        assert!(loaded.demos.iter().all(|d| d.positions.len() == 12));

        let only = |frames: &[&str]| {
            let options = LoadOptions {
                frames: frames.iter().map(|f| f.to_string()).collect(),
                ..Default::default()
            };
            load_bytes_with(label, &bytes, &options)
                .map(|l| l.demos.into_iter().map(|d| d.topic).collect::<Vec<_>>())
        };
        assert_eq!(only(&["hand_b"]).expect("load"), ["/tf:hand_b"]);
        assert_eq!(
            only(&["hand_c", "hand_a"]).expect("load"),
            ["/tf:hand_a", "/tf:hand_c"]
        );
        let err = only(&["elbow"]).expect_err("no frame matches");
        assert!(
            err.to_string().ends_with(
                "--frame elbow matches no frame here; the frames are: hand_a, hand_b, hand_c"
            ),
            "the error lists the frames that exist: {err}"
        );
    }
    // Keys filter multi-pose topics only: a PoseStamped topic stays.
    let mut channels = per_topic(R2_POSE, &demos[..1], r2_pose);
    channels.extend(tf_topic(R2_TF, &demos, ros2::encode_tf_message));
    let bytes = write_mcap(&channels);
    let options = LoadOptions {
        frames: vec!["hand_b".to_owned()],
        ..Default::default()
    };
    let loaded = load_bytes_with("mixed.mcap", &bytes, &options).expect("load");
    let topics: Vec<&str> = loaded.demos.iter().map(|d| d.topic.as_str()).collect();
    assert_eq!(topics, ["/hand_a", "/tf:hand_b"]);
}

#[test]
fn bad_messages_name_topic_and_sample() {
    let demos = demos(8);
    for (label, channels, _) in all_formats(&demos) {
        let topic = channels[0].topic.clone();
        // Message 5 of the first topic cut short by one byte, or to 3 bytes.
        for keep in [None, Some(3)] {
            let mut bad = channels.clone();
            let data = &mut bad[0].messages[5].1;
            data.truncate(keep.unwrap_or(data.len() - 1));
            let err = load_bytes(label, &write_mcap(&bad)).expect_err("bad message must fail");
            let Error::Decode { at, reason } = &err else {
                panic!("{label}: expected a decode error, got {err:?}");
            };
            let want = Location::file(label).topic(topic.as_str()).sample(5);
            assert_eq!(at, &want, "{label}: {reason}");
            let text = err.to_string();
            for part in [label, &format!("topic {topic}"), "sample 5"] {
                assert!(text.contains(part), "{text:?} lacks {part:?}");
            }
        }
    }
}

// ------------------------------------------------------------- robustness

#[test]
fn decoders_never_panic() {
    let t = |c| tr(EPOCH, "world", c, [0.1, 0.2, 0.3]);
    let s = (EPOCH, [1.0, 2.0, 3.0]);
    let tf = [t("a"), t("bb"), t("ccc")];
    let cases: [(Schema, Vec<u8>, usize); 7] = [
        (R2_POSE, r2_pose(s), 1),
        (R2_POSE_COV, r2_cov(s), 1),
        (R2_POINT, r2_point(s), 1),
        (R2_TRANSFORM, ros2::encode_transform_stamped(&t("hand")), 1),
        (R2_TF, ros2::encode_tf_message(&tf), 3),
        (R1_POSE, r1_pose(s), 1),
        (R1_TF, ros1::encode_tf_message(&tf), 3),
    ];
    let mut rng = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = move || {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        rng
    };
    for (schema, valid, count) in cases {
        // Where the first field starts: after the CDR encapsulation header.
        let at = if schema.message_encoding == "cdr" {
            4
        } else {
            0
        };
        let mut decoder = registry(schema);
        let mut run = |data: &[u8]| {
            catch_unwind(AssertUnwindSafe(|| decode_all(decoder.as_mut(), data)))
                .unwrap_or_else(|_| panic!("{} panicked on {data:02x?}", schema.name))
        };
        let (samples, _) = run(&valid).expect("the valid message decodes");
        assert_eq!(samples.len(), count, "{}", schema.name);
        for len in 0..valid.len() {
            let err = run(&valid[..len]).expect_err("a prefix is not a message");
            assert!(!err.is_empty());
        }
        for _ in 0..3000 {
            // Random bytes, half of them behind a valid CDR header or a
            // small TF count, so the decoders get past the first field.
            let len = (next() % 160) as usize;
            let mut data: Vec<u8> = (0..len).map(|_| next() as u8).collect();
            if next() % 2 == 0 && data.len() >= 8 {
                data[..4].copy_from_slice(&[0, 1, 0, 0]);
                data[at..at + 4].copy_from_slice(&le32((next() % 4) as u32));
            }
            let _ = run(&data);
            // The valid message with a few bytes changed.
            let mut mutated = valid.clone();
            for _ in 0..1 + next() % 4 {
                let i = (next() as usize) % mutated.len();
                mutated[i] = next() as u8;
            }
            let _ = run(&mutated);
        }
        // Huge declared counts and lengths fail without a panic.
        let mut huge = valid.clone();
        huge[at..at + 4].copy_from_slice(&le32(u32::MAX));
        let _ = run(&huge);
        huge[at + 8..at + 12].copy_from_slice(&le32(u32::MAX));
        let _ = run(&huge);
    }
}
