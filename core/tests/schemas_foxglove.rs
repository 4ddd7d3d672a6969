//! The Foxglove schemas (`foxglove.PoseInFrame`, `PosesInFrame`,
//! `FrameTransform`, `FrameTransforms`) in protobuf and JSON: the field
//! layout against Foxglove's published `.proto` files, that every schema and
//! encoding of the same demos loads to the same stamps and positions as a
//! ROS 2 `PoseStamped` file, the errors for unusable schemas and malformed
//! messages, and that no bytes make a decoder panic.

use std::collections::BTreeMap;
use std::io::Cursor;
use std::panic::{AssertUnwindSafe, catch_unwind};

use dmpscope_core::export::foxglove::EncodedTopic;
use dmpscope_core::export::foxglove::FoxgloveEncoding;
use dmpscope_core::export::foxglove::descriptor_set;
use dmpscope_core::export::foxglove::descriptor_set_bytes;
use dmpscope_core::export::foxglove::encode_frame_transform_proto;
use dmpscope_core::export::foxglove::encode_frame_transforms_proto;
use dmpscope_core::export::foxglove::encode_pose_in_frame_proto;
use dmpscope_core::export::foxglove::encode_poses_in_frame_proto;
use dmpscope_core::export::foxglove::write_encoded;
use dmpscope_core::export::foxglove::write_pose_in_frame_json;
use dmpscope_core::export::foxglove_json::Transform;
use dmpscope_core::export::foxglove_json::encode_frame_transform_json;
use dmpscope_core::export::foxglove_json::encode_frame_transforms_json;
use dmpscope_core::export::foxglove_json::encode_pose_in_frame_json;
use dmpscope_core::export::foxglove_json::encode_poses_in_frame_json;
use dmpscope_core::export::foxglove_json::json_schema;
use dmpscope_core::export::write::{TopicSamples, write_pose_stamped};
use dmpscope_core::load::collect::Loaded;
use dmpscope_core::load::decode::foxglove_schemas::FoxgloveSchema;
use dmpscope_core::load::decode::{ChannelSchema, MessageDecoder, PoseSample, decoder_for};
use dmpscope_core::load::mcap::{load_bytes, load_bytes_with};
use dmpscope_core::load::options::LoadOptions;
use dmpscope_core::rng::Rng;
use dmpscope_core::{Error, RawDemo, TimeSource};
use mcap::records::MessageHeader;
use prost_reflect::prost::Message as _;
use prost_reflect::{DescriptorPool, Kind};

use FoxgloveEncoding::{Json, Protobuf};
use FoxgloveSchema::{FrameTransform, FrameTransforms, PoseInFrame, PosesInFrame};

/// A sample as the writers take it: `(stamp_ns, position)`.
type Sample = (i64, [f64; 3]);
/// Encoded messages, each `(log_time_ns, bytes)`.
type Messages = Vec<(i64, Vec<u8>)>;
/// A decoded pose with its key owned: `(key, stamp_ns, position)`.
type Decoded = (Option<String>, Option<i64>, [f64; 3]);

/// The first stamp: seconds and a nanosecond part that needs all its digits.
const EPOCH: i64 = 1_700_000_000_123_456_789;
/// 10 ms between samples.
const PERIOD: i64 = 10_000_000;
/// The child frames of the transform files, one per demo.
const CHILDREN: [&str; 3] = ["hand", "head", "tool"];

// ---------------------------------------------------------------- helpers

/// Three demos sharing their stamps (a pose array holds all at once), with
/// values that do not print short in decimal.
fn demos() -> Vec<Vec<Sample>> {
    let mut rng = Rng::new(7);
    (0..3)
        .map(|d| {
            (0..40)
                .map(|k| {
                    let u = k as f64 / 39.0;
                    let p = [
                        0.1 * d as f64 + 0.3 * u + rng.range(-1e-3, 1e-3),
                        -0.2 + 0.1 * u * u + rng.range(-1e-3, 1e-3),
                        0.9 - 0.05 * u + 1e-9 * rng.normal(),
                    ];
                    (EPOCH + k as i64 * PERIOD, p)
                })
                .collect()
        })
        .collect()
}

/// The demos as writer topics `/a`, `/b`, `/c` in frame "world".
fn topics(demos: &[Vec<Sample>]) -> Vec<TopicSamples<'_>> {
    let names = ["/a", "/b", "/c"];
    let each = |(topic, samples)| TopicSamples {
        orientations: None,
        topic,
        frame_id: "world",
        samples,
    };
    names
        .into_iter()
        .zip(demos.iter().map(Vec::as_slice))
        .map(each)
        .collect()
}

fn pose_in_frame(enc: FoxgloveEncoding, stamp: i64, p: [f64; 3]) -> Vec<u8> {
    match enc {
        Protobuf => encode_pose_in_frame_proto(stamp, "world", p).expect("encode"),
        Json => encode_pose_in_frame_json(stamp, "world", p),
    }
}

fn poses_in_frame(enc: FoxgloveEncoding, stamp: i64, ps: &[[f64; 3]]) -> Vec<u8> {
    match enc {
        Protobuf => encode_poses_in_frame_proto(stamp, "world", ps).expect("encode"),
        Json => encode_poses_in_frame_json(stamp, "world", ps),
    }
}

fn frame_transforms(enc: FoxgloveEncoding, ts: &[Transform<'_>]) -> Vec<u8> {
    match (enc, ts) {
        (Protobuf, [t]) => encode_frame_transform_proto(t).expect("encode"),
        (Json, [t]) => encode_frame_transform_json(t),
        (Protobuf, _) => encode_frame_transforms_proto(ts).expect("encode"),
        (Json, _) => encode_frame_transforms_json(ts),
    }
}

/// The demos written in one schema and encoding: PoseInFrame as topics
/// `/a`, `/b`, `/c`; PosesInFrame as `/poses` (indices 0, 1, 2); the
/// transforms as `/tf` (child frames [`CHILDREN`]).
fn foxglove_file(schema: FoxgloveSchema, enc: FoxgloveEncoding, demos: &[Vec<Sample>]) -> Vec<u8> {
    let n = demos[0].len();
    let transform = |j: usize, k: usize| Transform {
        stamp_ns: demos[j][k].0,
        parent_frame_id: "world",
        child_frame_id: CHILDREN[j],
        translation: demos[j][k].1,
    };
    let topics: Vec<(&str, Messages)> = match schema {
        PoseInFrame => ["/a", "/b", "/c"]
            .into_iter()
            .zip(demos)
            .map(|(topic, d)| {
                (
                    topic,
                    d.iter()
                        .map(|&(t, p)| (t, pose_in_frame(enc, t, p)))
                        .collect(),
                )
            })
            .collect(),
        PosesInFrame => {
            let msgs = (0..n)
                .map(|k| {
                    let ps: Vec<[f64; 3]> = demos.iter().map(|d| d[k].1).collect();
                    (demos[0][k].0, poses_in_frame(enc, demos[0][k].0, &ps))
                })
                .collect();
            vec![("/poses", msgs)]
        }
        FrameTransform => {
            let msgs = (0..n)
                .flat_map(|k| (0..demos.len()).map(move |j| (j, k)))
                .map(|(j, k)| (demos[j][k].0, frame_transforms(enc, &[transform(j, k)])))
                .collect();
            vec![("/tf", msgs)]
        }
        FrameTransforms => {
            let msgs = (0..n)
                .map(|k| {
                    let ts: Vec<Transform<'_>> =
                        (0..demos.len()).map(|j| transform(j, k)).collect();
                    (demos[0][k].0, frame_transforms(enc, &ts))
                })
                .collect();
            vec![("/tf", msgs)]
        }
    };
    let list: Vec<EncodedTopic<'_>> = topics
        .iter()
        .map(|(topic, messages)| EncodedTopic { topic, messages })
        .collect();
    write_encoded(Cursor::new(Vec::new()), schema, enc, &list, true)
        .expect("write foxglove")
        .into_inner()
}

/// An MCAP file with one topic `/hand` of the given schema record and
/// messages (log times 1, 2, ...).
fn raw_file(name: &str, s_enc: &str, schema: &[u8], m_enc: &str, msgs: &[Vec<u8>]) -> Vec<u8> {
    let mut w = mcap::WriteOptions::new()
        .compression(None)
        .create(Cursor::new(Vec::new()))
        .expect("writer");
    let schema_id = w.add_schema(name, s_enc, schema).expect("schema");
    let channel_id = w
        .add_channel(schema_id, "/hand", m_enc, &BTreeMap::new())
        .expect("channel");
    for (i, data) in msgs.iter().enumerate() {
        let header = MessageHeader {
            channel_id,
            sequence: i as u32,
            log_time: i as u64 + 1,
            publish_time: i as u64 + 1,
        };
        w.write_to_known_channel(&header, data).expect("message");
    }
    w.finish().expect("finish");
    w.into_inner().into_inner()
}

/// [`raw_file`] with the built-in schema record of `schema` in `enc`.
fn fox_file(schema: FoxgloveSchema, enc: FoxgloveEncoding, msgs: &[Vec<u8>]) -> Vec<u8> {
    let data = enc.schema_data(schema);
    let (schema_enc, msg_enc) = (enc.schema_encoding(), enc.message_encoding());
    raw_file(schema.name(), schema_enc, &data, msg_enc, msgs)
}

/// A valid message of each schema (two poses or transforms in the lists).
fn valid(schema: FoxgloveSchema, enc: FoxgloveEncoding) -> Vec<u8> {
    let t = Transform {
        stamp_ns: EPOCH,
        parent_frame_id: "world",
        child_frame_id: "hand",
        translation: [0.1, -0.2, 0.3],
    };
    let ps = [[0.1, 0.2, 0.3], [0.4, 0.5, 0.6]];
    match schema {
        PoseInFrame => pose_in_frame(enc, EPOCH, ps[0]),
        PosesInFrame => poses_in_frame(enc, EPOCH, &ps),
        FrameTransform => frame_transforms(enc, &[t]),
        FrameTransforms => frame_transforms(enc, &[t, t]),
    }
}

fn load(label: &str, bytes: &[u8]) -> Loaded {
    load_bytes(label, bytes).unwrap_or_else(|e| panic!("{label}: {e}"))
}

/// The error of a load that must fail, and its text.
#[track_caller]
fn load_err(label: &str, bytes: &[u8]) -> (Error, String) {
    let r = catch_unwind(AssertUnwindSafe(|| load_bytes(label, bytes)))
        .unwrap_or_else(|_| panic!("{label}: the loader panicked"));
    let err = r.expect_err("the load must fail");
    let text = err.to_string();
    (err, text)
}

/// The decoder of a channel of the built-in schema.
fn decoder(schema: FoxgloveSchema, enc: FoxgloveEncoding) -> Box<dyn MessageDecoder> {
    let data = enc.schema_data(schema);
    let channel = ChannelSchema {
        message_encoding: enc.message_encoding(),
        schema_name: schema.name(),
        schema_encoding: enc.schema_encoding(),
        schema_data: &data,
    };
    decoder_for(&channel)
        .expect("a decoder for the schema")
        .expect("a usable schema")
}

/// Everything one message decodes to, keys owned.
fn decode_all(d: &mut dyn MessageDecoder, data: &[u8]) -> Result<Vec<Decoded>, String> {
    let mut got = Vec::new();
    d.decode(data, &mut |s: PoseSample<'_>| {
        got.push((s.key.map(|k| k.into_owned()), s.stamp_ns, s.position));
    })?;
    Ok(got)
}

#[track_caller]
fn assert_demos(label: &str, got: &[RawDemo], want: &[Vec<Sample>], suffixes: &[&str]) {
    assert_eq!(got.len(), want.len(), "{label}: demo count");
    for ((g, w), suffix) in got.iter().zip(want).zip(suffixes) {
        let name = &g.name;
        assert!(name.ends_with(suffix), "{label}: {name} is not *{suffix}");
        assert_eq!(g.time_source, TimeSource::HeaderStamp, "{label}: {name}");
        let (stamps, positions): (Vec<i64>, Vec<[f64; 3]>) = w.iter().copied().unzip();
        assert_eq!(g.stamps_ns, stamps, "{label}: stamps of {name}");
        assert_eq!(xyz(&g.positions), positions, "{label}: positions of {name}");
    }
}

/// Little-endian fixed64 of a double, after its tag byte.
fn double(tag: u8, v: f64) -> Vec<u8> {
    let mut b = vec![tag];
    b.extend(v.to_le_bytes());
    b
}

fn varint(mut v: u64) -> Vec<u8> {
    let mut b = Vec::new();
    loop {
        let byte = (v & 0x7f) as u8;
        v >>= 7;
        if v == 0 {
            b.push(byte);
            return b;
        }
        b.push(byte | 0x80);
    }
}

/// A length-delimited field: tag, length, content.
fn len_field(tag: u8, content: &[u8]) -> Vec<u8> {
    let mut b = vec![tag];
    b.extend(varint(content.len() as u64));
    b.extend(content);
    b
}

// ------------------------------------------------------------------ tests

#[test]
fn descriptor_sets_have_foxgloves_field_numbers() {
    // Foxglove's published .proto files: message, then field=number:type.
    const LAYOUT: &str = "
        google.protobuf.Timestamp seconds=1:int64 nanos=2:int32
        foxglove.Vector3 x=1:double y=2:double z=3:double
        foxglove.Quaternion x=1:double y=2:double z=3:double w=4:double
        foxglove.Pose position=1:foxglove.Vector3 orientation=2:foxglove.Quaternion
        foxglove.PoseInFrame timestamp=1:google.protobuf.Timestamp frame_id=2:string
            pose=3:foxglove.Pose
        foxglove.PosesInFrame timestamp=1:google.protobuf.Timestamp frame_id=2:string
            poses=3:repeated.foxglove.Pose
        foxglove.FrameTransform timestamp=1:google.protobuf.Timestamp parent_frame_id=2:string
            child_frame_id=3:string translation=4:foxglove.Vector3 rotation=5:foxglove.Quaternion
        foxglove.FrameTransforms transforms=1:repeated.foxglove.FrameTransform";
    let mut expected: BTreeMap<&str, Vec<&str>> = BTreeMap::new();
    let mut message = "";
    for word in LAYOUT.split_whitespace() {
        if word.contains('=') {
            expected.entry(message).or_default().push(word);
        } else {
            message = word;
        }
    }
    assert_eq!(expected.len(), 8);
    for schema in FoxgloveSchema::ALL {
        let pool = DescriptorPool::decode(descriptor_set_bytes(schema).as_slice())
            .unwrap_or_else(|e| panic!("{schema:?}: {e}"));
        assert!(pool.get_message_by_name(schema.name()).is_some());
        let mut seen = 0;
        for desc in pool.all_messages() {
            let want = &expected[desc.full_name()];
            let got: Vec<String> = desc
                .fields()
                .map(|f| {
                    let kind = match f.kind() {
                        Kind::Message(m) => m.full_name().to_owned(),
                        other => format!("{other:?}").to_lowercase(),
                    };
                    let list = if f.is_list() { "repeated." } else { "" };
                    format!("{}={}:{list}{kind}", f.name(), f.number())
                })
                .collect();
            assert_eq!(&got, want, "{schema:?}: {}", desc.full_name());
            seen += 1;
        }
        let files = if schema == FrameTransform { 4 } else { 5 };
        assert_eq!(seen, files, "{schema:?}");
    }
    let json: serde_json::Value =
        serde_json::from_str(&json_schema(PosesInFrame)).expect("JSON Schema is JSON");
    assert_eq!(json["title"], "foxglove.PosesInFrame");
    let items = &json["properties"]["poses"]["items"];
    assert_eq!(items["properties"]["position"]["title"], "foxglove.Vector3");
}

#[test]
fn hand_assembled_protobuf_decodes_by_field_number() {
    let (x, y, z) = (0.125, -2.5, 1e-3);
    // PoseInFrame: 1 timestamp {1 seconds varint, 2 nanos varint}, 2 frame_id,
    // 3 pose {1 position {1 x, 2 y, 3 z fixed64}, 2 orientation {4 w}}.
    let mut time = vec![0x08];
    time.extend(varint(1_700_000_000));
    time.push(0x10);
    time.extend(varint(123_456_789));
    let position = [double(0x09, x), double(0x11, y), double(0x19, z)].concat();
    let orientation = double(0x21, 1.0);
    let pose = [len_field(0x0A, &position), len_field(0x12, &orientation)].concat();
    let frame = len_field(0x12, b"world");
    let message = [
        len_field(0x0A, &time),
        frame.clone(),
        len_field(0x1A, &pose),
    ]
    .concat();
    let want = vec![(None, Some(1_700_000_000_123_456_789), [x, y, z])];
    let mut d = decoder(PoseInFrame, Protobuf);
    assert_eq!(decode_all(d.as_mut(), &message), Ok(want.clone()));
    // The encoder writes exactly these bytes (fields in number order, zeros left out).
    let encoded = encode_pose_in_frame_proto(1_700_000_000_123_456_789, "world", [x, y, z]);
    assert_eq!(encoded.expect("encode"), message);
    // Fields in another order, an unknown field (15) and a missing orientation.
    let reordered = [
        len_field(0x1A, &len_field(0x0A, &position)),
        vec![0x78, 0x05],
        len_field(0x0A, &time),
    ]
    .concat();
    assert_eq!(decode_all(d.as_mut(), &reordered), Ok(want));

    // FrameTransform: 3 child_frame_id, 4 translation, 2 parent; no timestamp.
    let translation = len_field(0x22, &[double(0x09, x), double(0x19, z)].concat());
    let child = len_field(0x1A, b"hand");
    let transform = [frame, child, translation, len_field(0x2A, &orientation)].concat();
    let mut d = decoder(FrameTransform, Protobuf);
    let got = decode_all(d.as_mut(), &transform);
    assert_eq!(got, Ok(vec![(Some("hand".into()), None, [x, 0.0, z])]));
    // FrameTransforms: 1 transforms (repeated).
    let list = [len_field(0x0A, &transform), len_field(0x0A, &transform)].concat();
    let mut d = decoder(FrameTransforms, Protobuf);
    assert_eq!(decode_all(d.as_mut(), &list).map(|v| v.len()), Ok(2));
    // PosesInFrame: 3 poses (repeated); keys are the indices.
    let poses = [&pose[..], &[], &pose].map(|p| len_field(0x1A, p)).concat();
    let mut d = decoder(PosesInFrame, Protobuf);
    let got = decode_all(d.as_mut(), &poses).expect("decode");
    let keys: Vec<_> = got.iter().map(|s| s.0.clone().expect("key")).collect();
    assert_eq!(keys, ["0", "1", "2"]);
    assert_eq!(got[1].2, [0.0; 3]);
    assert_eq!(got[2].2, [x, y, z]);

    // JSON by field name, with missing fields as zero and nulls as missing.
    let text = br#"{"timestamp":{"sec":1700000000,"nsec":123456789},"frame_id":"world",
        "pose":{"position":{"x":0.125,"y":null},"orientation":{"w":1}}}"#;
    let mut d = decoder(PoseInFrame, Json);
    let want = vec![(None, Some(1_700_000_000_123_456_789), [x, 0.0, 0.0])];
    assert_eq!(decode_all(d.as_mut(), text), Ok(want));
}

#[test]
fn every_schema_and_encoding_loads_like_ros2_pose_stamped() {
    let demos = demos();
    let abc = [":/a", ":/b", ":/c"];
    let ros2 = write_pose_stamped(Cursor::new(Vec::new()), &topics(&demos), true);
    let ros2 = load("ros2.mcap", &ros2.expect("write ros2").into_inner());
    assert_demos("ros2", &ros2.demos, &demos, &abc);
    for schema in FoxgloveSchema::ALL {
        for enc in [Protobuf, Json] {
            let label = format!("{schema:?}-{enc:?}.mcap");
            let loaded = load(&label, &foxglove_file(schema, enc, &demos));
            let clean = loaded.skipped.is_empty() && loaded.warnings.is_empty();
            assert!(clean, "{label}: {loaded:?}");
            let suffixes: &[&str] = match schema {
                PoseInFrame => &abc,
                PosesInFrame => &[":/poses:0", ":/poses:1", ":/poses:2"],
                _ => &[":/tf:hand", ":/tf:head", ":/tf:tool"],
            };
            assert_demos(&label, &loaded.demos, &demos, suffixes);
            for (g, r) in loaded.demos.iter().zip(&ros2.demos) {
                let same = g.stamps_ns == r.stamps_ns && g.positions == r.positions;
                assert!(same, "{label}: {} differs from {}", g.name, r.name);
            }
        }
    }
    // The JSON PoseInFrame writer the app exports with.
    let bytes = write_pose_in_frame_json(Cursor::new(Vec::new()), &topics(&demos), false);
    let export = load("export.mcap", &bytes.expect("write").into_inner());
    assert_demos("export", &export.demos, &demos, &abc);
}

#[test]
fn poses_in_frame_with_three_poses_gives_three_demos() {
    let ps = [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0], [7.0, 8.0, 9.5]];
    for enc in [Protobuf, Json] {
        let msgs: Vec<Vec<u8>> = (0..10)
            .map(|k| {
                let shifted: Vec<[f64; 3]> =
                    ps.iter().map(|p| [p[0] + k as f64, p[1], p[2]]).collect();
                poses_in_frame(enc, EPOCH + k * PERIOD, &shifted)
            })
            .collect();
        let bytes = fox_file(PosesInFrame, enc, &msgs);
        let loaded = load("poses.mcap", &bytes);
        let names: Vec<&str> = loaded.demos.iter().map(|d| d.name.as_str()).collect();
        let want = [
            "poses.mcap:/hand:0",
            "poses.mcap:/hand:1",
            "poses.mcap:/hand:2",
        ];
        assert_eq!(names, want, "{enc:?}");
        for (d, p) in loaded.demos.iter().zip(ps) {
            assert_eq!(d.positions.len(), 10);
            assert_eq!(xyz(&d.positions)[9], [p[0] + 9.0, p[1], p[2]]);
            assert_eq!(d.stamps_ns[9], EPOCH + 9 * PERIOD);
        }
        // The frames option picks indices.
        let options = LoadOptions {
            frames: vec!["1".into()],
            ..LoadOptions::default()
        };
        let one = load_bytes_with("poses.mcap", &bytes, &options).expect("load");
        assert_eq!(one.demos.len(), 1);
        assert_eq!(xyz(&one.demos[0].positions)[0], ps[1]);
    }
}

#[test]
fn zero_or_missing_timestamp_falls_back_to_log_time() {
    for enc in [Protobuf, Json] {
        let empty = match enc {
            Protobuf => Vec::new(),
            Json => b"{}".to_vec(),
        };
        let msgs = [pose_in_frame(enc, 0, [1.0, 0.0, 0.0]), empty];
        let d = &load("zero.mcap", &fox_file(PoseInFrame, enc, &msgs)).demos[0];
        assert_eq!(d.time_source, TimeSource::LogTime, "{enc:?}");
        assert_eq!(d.stamps_ns, [1, 2]);
        assert_eq!(xyz(&d.positions), [[1.0, 0.0, 0.0], [0.0; 3]]);
    }
}

#[test]
fn other_foxglove_schemas_are_skipped() {
    let bytes = raw_file("foxglove.Log", "protobuf", b"", "protobuf", &[vec![1, 2]]);
    match load_err("log.mcap", &bytes).0 {
        Error::NoDemos { skipped, .. } => {
            assert_eq!(skipped, [("/hand".to_owned(), "foxglove.Log".to_owned())]);
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn unusable_descriptor_set_names_the_topic() {
    let msg = pose_in_frame(Protobuf, EPOCH, [1.0, 2.0, 3.0]);
    // Without foxglove/Pose.proto, which PoseInFrame.proto imports.
    let mut missing = descriptor_set(PoseInFrame);
    missing.file.retain(|f| f.name() != "foxglove/Pose.proto");
    // Vector3.x as a string (type 9).
    let mut retyped = descriptor_set(PoseInFrame);
    for m in retyped.file.iter_mut().flat_map(|f| &mut f.message_type) {
        if m.name() == "Vector3" {
            m.field[0].r#type = Some(9);
        }
    }
    let unusable = "not a usable FileDescriptorSet";
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        ("protobuf", b"\x0a\xff\xff\xff".to_vec(), unusable),
        ("protobuf", missing.encode_to_vec(), unusable),
        (
            "protobuf",
            retyped.encode_to_vec(),
            "foxglove.Vector3.x is string, expected a double",
        ),
        (
            "protobuf",
            descriptor_set_bytes(FrameTransform),
            "does not define foxglove.PoseInFrame",
        ),
        (
            "jsonschema",
            json_schema(PoseInFrame).into_bytes(),
            "expected \"protobuf\"",
        ),
    ];
    for (schema_enc, data, reason) in cases {
        let msgs = [msg.clone()];
        let bytes = raw_file("foxglove.PoseInFrame", schema_enc, &data, "protobuf", &msgs);
        let (err, text) = load_err("fds.mcap", &bytes);
        assert!(matches!(err, Error::Decode { .. }), "{err:?}");
        let schema = "unusable schema foxglove.PoseInFrame";
        for part in ["fds.mcap", "topic /hand", schema, reason] {
            assert!(text.contains(part), "{text:?} lacks {part:?}");
        }
    }
}

#[test]
fn malformed_messages_name_topic_and_sample() {
    let good = valid(PoseInFrame, Protobuf);
    let truncated = good[..good.len() - 3].to_vec();
    let mut huge_time = vec![0x08];
    huge_time.extend(varint(i64::MAX as u64));
    let invalid = "not a valid protobuf";
    let mut cases: Vec<(FoxgloveSchema, FoxgloveEncoding, Vec<u8>, &str)> = vec![
        (PoseInFrame, Protobuf, truncated, invalid),
        // Field 3 (pose) with the varint wire type.
        (PoseInFrame, Protobuf, vec![0x18, 0x01], invalid),
        (
            PoseInFrame,
            Protobuf,
            len_field(0x0A, &huge_time),
            "out of range",
        ),
        (
            FrameTransforms,
            Protobuf,
            vec![0x0A, 0x05, 0x1A, 0x09],
            invalid,
        ),
    ];
    let json_cases: [(FoxgloveSchema, &str, &str); 7] = [
        (PoseInFrame, r#"{"pose": {"#, "not valid JSON"),
        (PoseInFrame, "[1, 2]", "must be a JSON object"),
        (PoseInFrame, r#"{"pose": 5}"#, "pose is not an object"),
        (
            PoseInFrame,
            r#"{"pose": {"position": {"y": "2"}}}"#,
            "pose.position.y is not a number",
        ),
        (
            PoseInFrame,
            r#"{"timestamp": {"sec": 1.5}}"#,
            "timestamp.sec is not an integer",
        ),
        (
            PosesInFrame,
            r#"{"poses": [{}, 3]}"#,
            "poses[1] is not an object",
        ),
        (
            FrameTransforms,
            r#"{"transforms": [{}, {"child_frame_id": 4}]}"#,
            "transforms[1].child_frame_id is not a string",
        ),
    ];
    for (schema, text, reason) in json_cases {
        cases.push((schema, Json, text.as_bytes().to_vec(), reason));
    }
    for (schema, enc, bad, reason) in cases {
        let mut msgs = vec![valid(schema, enc); 7];
        msgs.push(bad);
        let (err, text) = load_err("bad.mcap", &fox_file(schema, enc, &msgs));
        assert!(matches!(err, Error::Decode { .. }), "{reason}: {err:?}");
        for part in ["bad.mcap", "topic /hand", "sample 7", reason] {
            assert!(text.contains(part), "{text:?} lacks {part:?}");
        }
    }
}

#[test]
fn no_bytes_make_a_decoder_panic() {
    let mut rng = Rng::new(99);
    for schema in FoxgloveSchema::ALL {
        for enc in [Protobuf, Json] {
            let valid = valid(schema, enc);
            let mut d = decoder(schema, enc);
            assert!(decode_all(d.as_mut(), &valid).is_ok(), "{schema:?} {enc:?}");
            let mut inputs: Vec<Vec<u8>> = (0..valid.len()).map(|n| valid[..n].to_vec()).collect();
            for _ in 0..500 {
                let len = (rng.next_u64() % 96) as usize;
                inputs.push((0..len).map(|_| rng.next_u64() as u8).collect());
                let mut flipped = valid.clone();
                for _ in 0..1 + rng.next_u64() % 4 {
                    let i = (rng.next_u64() as usize) % flipped.len();
                    flipped[i] = rng.next_u64() as u8;
                }
                inputs.push(flipped);
            }
            for input in &inputs {
                let _ = catch_unwind(AssertUnwindSafe(|| decode_all(d.as_mut(), input)))
                    .unwrap_or_else(|_| panic!("{schema:?} {enc:?} panicked on {input:?}"));
            }
        }
        // Every prefix of the FileDescriptorSet builds a decoder or gives a reason.
        let fds = descriptor_set_bytes(schema);
        for n in 0..fds.len() {
            let channel = ChannelSchema {
                message_encoding: "protobuf",
                schema_name: schema.name(),
                schema_encoding: "protobuf",
                schema_data: &fds[..n],
            };
            let r = catch_unwind(|| decoder_for(&channel).map(|r| r.map(|_| ())))
                .unwrap_or_else(|_| panic!("{schema:?}: panicked on a {n}-byte prefix"));
            assert!(r.is_some(), "{schema:?}");
        }
    }
}

/// Positions as plain arrays, to compare with literals.
fn xyz(v: &[dmpscope_core::geom::Vec3]) -> Vec<[f64; 3]> {
    v.iter().map(|p| (*p).into()).collect()
}
