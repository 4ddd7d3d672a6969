//! Orientation is kept from the recording to the raw demo: every pose
//! schema that has one hands it on (ROS 2 and ROS 1 poses and transforms,
//! Foxglove in protobuf and JSON, CSV with `qx,qy,qz,qw`), a point has none,
//! the y-up conversion and `--fixed-frame` turn it as they turn positions,
//! and sorting, gap splits and segments keep it beside its sample.

use std::collections::BTreeMap;
use std::f64::consts::FRAC_PI_2;
use std::io::Cursor;

use dmpscope_core::geom::{Quat, Vec3, quat_from_xyzw, xyzw};
use dmpscope_core::load::csv::load_csv;
use dmpscope_core::load::decode::ros2::StampedTransform;
use dmpscope_core::load::decode::{ros1, ros2};
use dmpscope_core::load::mcap::{load_bytes, load_bytes_with};
use dmpscope_core::load::options::LoadOptions;
use dmpscope_core::load::options::UpAxis;
use dmpscope_core::{RawDemo, TimeSource};
use mcap::records::MessageHeader;

const EPOCH: i64 = 1_700_000_000_000_000_000;
const PERIOD: i64 = 10_000_000;
const N: usize = 30;

/// A turn of `angle` about the unit axis `axis`, as `[x, y, z, w]`.
fn turn(axis: [f64; 3], angle: f64) -> [f64; 4] {
    let s = (angle / 2.0).sin();
    [axis[0] * s, axis[1] * s, axis[2] * s, (angle / 2.0).cos()]
}

/// Sample `k`: stamp, position, and an orientation that turns about a
/// tilted axis as the demo goes.
fn sample(k: usize) -> (i64, [f64; 3], [f64; 4]) {
    let u = k as f64 / N as f64;
    let axis = [0.0, 0.6, 0.8];
    (
        EPOCH + k as i64 * PERIOD,
        [0.3 * u, 0.1 - 0.2 * u, 0.9],
        turn(axis, 0.1 + 2.0 * u),
    )
}

/// An MCAP file of one topic whose messages `encode` makes from the samples.
fn mcap(
    schema: (&str, &str, &str),
    topic: &str,
    encode: &dyn Fn(i64, [f64; 3], [f64; 4]) -> Vec<u8>,
) -> Vec<u8> {
    let (name, encoding, message_encoding) = schema;
    let mut w = mcap::WriteOptions::new()
        .create(Cursor::new(Vec::new()))
        .expect("writer");
    let text = match name {
        "geometry_msgs/msg/PoseStamped" => ros2::POSE_STAMPED_SCHEMA,
        "geometry_msgs/msg/PointStamped" => ros2::POINT_STAMPED_SCHEMA,
        "tf2_msgs/msg/TFMessage" => ros2::TF_MESSAGE_SCHEMA,
        "geometry_msgs/PoseStamped" => ros1::POSE_STAMPED_SCHEMA,
        _ => ros1::TF_MESSAGE_SCHEMA,
    };
    let schema = w
        .add_schema(name, encoding, text.as_bytes())
        .expect("schema");
    let channel_id = w
        .add_channel(schema, topic, message_encoding, &BTreeMap::new())
        .expect("channel");
    for k in 0..N {
        let (t, p, q) = sample(k);
        let header = MessageHeader {
            channel_id,
            sequence: k as u32,
            log_time: t as u64,
            publish_time: t as u64,
        };
        w.write_to_known_channel(&header, &encode(t, p, q))
            .expect("message");
    }
    w.finish().expect("finish");
    w.into_inner().into_inner()
}

fn transform<'a>(
    t: i64,
    parent: &'a str,
    child: &'a str,
    p: [f64; 3],
    q: [f64; 4],
) -> StampedTransform<'a> {
    StampedTransform {
        stamp_ns: t,
        frame_id: parent,
        child_frame_id: child,
        translation: p,
        rotation: q,
    }
}

/// The same rotation, up to the quaternion's sign.
fn same(a: &Quat, b: [f64; 4]) -> bool {
    let a = xyzw(a);
    let dot: f64 = (0..4).map(|k| a[k] * b[k]).sum();
    (dot.abs() - 1.0).abs() < 1e-12
}

fn only(bytes: &[u8], label: &str, options: &LoadOptions) -> RawDemo {
    let mut loaded = load_bytes_with(label, bytes, options).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(loaded.demos.len(), 1, "{label}");
    loaded.demos.remove(0)
}

#[test]
fn every_pose_schema_keeps_its_orientation_and_a_point_has_none() {
    let r2_pose = mcap(
        ("geometry_msgs/msg/PoseStamped", "ros2msg", "cdr"),
        "/hand",
        &|t, p, q| ros2::encode_oriented_pose_stamped(t, "world", p, q),
    );
    let r1_pose = mcap(
        ("geometry_msgs/PoseStamped", "ros1msg", "ros1"),
        "/hand",
        &|t, p, q| ros1::encode_oriented_pose_stamped(t, "world", p, q),
    );
    let r2_tf = mcap(
        ("tf2_msgs/msg/TFMessage", "ros2msg", "cdr"),
        "/tf",
        &|t, p, q| ros2::encode_tf_message(&[transform(t, "world", "hand", p, q)]),
    );
    let r1_tf = mcap(
        ("tf2_msgs/TFMessage", "ros1msg", "ros1"),
        "/tf",
        &|t, p, q| ros1::encode_tf_message(&[transform(t, "world", "hand", p, q)]),
    );
    let r2_odometry = mcap(
        ("nav_msgs/msg/Odometry", "ros2msg", "cdr"),
        "/odom",
        &|t, p, q| ros2::encode_odometry(t, "odom", p, q),
    );
    for (label, bytes) in [
        ("r2_pose.mcap", r2_pose),
        ("r2_odometry.mcap", r2_odometry),
        ("r1_pose.mcap", r1_pose),
        ("r2_tf.mcap", r2_tf),
        ("r1_tf.mcap", r1_tf),
    ] {
        let demo = only(&bytes, label, &LoadOptions::default());
        let q = demo
            .orientations
            .as_ref()
            .unwrap_or_else(|| panic!("{label}: no orientation"));
        assert_eq!(q.len(), N, "{label}");
        for (k, q) in q.iter().enumerate() {
            assert!(same(q, sample(k).2), "{label} sample {k}: {q:?}");
        }
        assert!(demo.info().orientation, "{label}");
    }
    let point = mcap(
        ("geometry_msgs/msg/PointStamped", "ros2msg", "cdr"),
        "/hand",
        &|t, p, _| ros2::encode_point_stamped(t, "world", p),
    );
    let demo = only(&point, "point.mcap", &LoadOptions::default());
    assert!(demo.orientations.is_none() && !demo.info().orientation);
}

#[test]
fn an_unusable_quaternion_is_an_error_naming_the_sample() {
    // method.md section 12: a zero or non-finite quaternion is an error like
    // a non-finite position, naming file, topic and sample.
    let with_zero_at = |bad: i64, q_bad: [f64; 4]| {
        mcap(
            ("geometry_msgs/msg/PoseStamped", "ros2msg", "cdr"),
            "/hand",
            &move |t, p, q| {
                let q = if t == EPOCH + bad * PERIOD { q_bad } else { q };
                ros2::encode_oriented_pose_stamped(t, "world", p, q)
            },
        )
    };
    let bytes = with_zero_at(3, [0.0; 4]);
    let err = load_bytes("zero.mcap", &bytes).expect_err("a zero quaternion");
    let said = err.to_string();
    assert!(
        said.contains("zero.mcap") && said.contains("/hand") && said.contains("sample 3"),
        "{said}"
    );
    assert!(said.contains("--drop-bad-orientation"), "{said}");
    let nan = with_zero_at(5, [f64::NAN, 0.0, 0.0, 1.0]);
    let said = load_bytes("nan.mcap", &nan).expect_err("NaN").to_string();
    assert!(
        said.contains("sample 5") && said.contains("orientation"),
        "{said}"
    );
    // The option beyond the method: the positions load without orientation
    // and the user is told.
    let options = LoadOptions {
        drop_bad_orientation: true,
        ..LoadOptions::default()
    };
    let loaded = load_bytes_with("zero.mcap", &bytes, &options).expect("loads");
    let demo = &loaded.demos[0];
    assert_eq!(demo.positions.len(), N);
    assert!(demo.orientations.is_none());
    assert!(
        loaded
            .warnings
            .iter()
            .any(|w| w.contains("zero.mcap: /hand: 1 of 30 samples have no usable orientation")),
        "{:?}",
        loaded.warnings
    );
}

#[test]
fn a_stream_of_zero_quaternions_has_no_orientation_and_says_so() {
    // A source that sends no rotation (ROS 1's default quaternion is all
    // zero): no orientation, said, the positions loaded.
    let bytes = mcap(
        ("geometry_msgs/msg/PoseStamped", "ros2msg", "cdr"),
        "/hand",
        &|t, p, _| ros2::encode_oriented_pose_stamped(t, "world", p, [0.0; 4]),
    );
    let loaded = load_bytes("unset.mcap", &bytes).expect("loads");
    assert!(loaded.demos[0].orientations.is_none());
    assert!(
        loaded
            .warnings
            .iter()
            .any(|w| w.contains("every orientation is the zero quaternion")),
        "{:?}",
        loaded.warnings
    );
}

#[test]
fn y_up_turns_orientations_as_it_turns_positions() {
    let bytes = mcap(
        ("geometry_msgs/msg/PoseStamped", "ros2msg", "cdr"),
        "/hand",
        &|t, p, q| ros2::encode_oriented_pose_stamped(t, "world", p, q),
    );
    let options = LoadOptions {
        up: UpAxis::YUp,
        ..LoadOptions::default()
    };
    let demo = only(&bytes, "yup.mcap", &options);
    let q = demo.orientations.expect("orientation");
    for (k, q) in q.iter().enumerate() {
        let stored = quat_from_xyzw(sample(k).2).expect("unit");
        // A body axis seen in the recording's frame, then converted like a
        // position, is the converted orientation's axis.
        for axis in [Vec3::x(), Vec3::y(), Vec3::z()] {
            let recorded: [f64; 3] = (stored * axis).into();
            let want = Vec3::from(UpAxis::YUp.to_z_up(recorded));
            assert!((q * axis - want).norm() < 1e-12, "sample {k}");
        }
    }
}

#[test]
fn a_fixed_frame_composes_the_orientation_through_the_tree() {
    // world -> base: static, a quarter turn about z; base -> hand: the
    // samples. In world the hand's orientation is the quarter turn, then
    // its own.
    let base = turn([0.0, 0.0, 1.0], FRAC_PI_2);
    let bytes = mcap(
        ("tf2_msgs/msg/TFMessage", "ros2msg", "cdr"),
        "/tf",
        &|t, p, q| {
            ros2::encode_tf_message(&[
                transform(t, "world", "base", [1.0, 0.0, 0.0], base),
                transform(t, "base", "hand", p, q),
            ])
        },
    );
    let options = LoadOptions {
        frames: vec!["hand".into()],
        fixed_frame: Some("world".into()),
        ..LoadOptions::default()
    };
    let demo = only(&bytes, "fixed.mcap", &options);
    let q = demo.orientations.expect("orientation");
    let base = quat_from_xyzw(base).expect("unit");
    for (k, q) in q.iter().enumerate() {
        let want = base * quat_from_xyzw(sample(k).2).expect("unit");
        assert!(same(q, xyzw(&want)), "sample {k}");
    }
}

#[test]
fn csv_reads_an_optional_quaternion() {
    let mut text = String::from("t,x,y,z,qx,qy,qz,qw\n");
    for k in 0..N {
        let (t, p, q) = sample(k);
        let t = (t - EPOCH) as f64 * 1e-9;
        text += &format!(
            "{t},{},{},{},{},{},{},{}\n",
            p[0], p[1], p[2], q[0], q[1], q[2], q[3]
        );
    }
    let demo = load_csv("oriented.csv", &text).expect("csv");
    let q = demo.orientations.expect("orientation");
    assert!(q.iter().enumerate().all(|(k, q)| same(q, sample(k).2)));
    let plain = load_csv("plain.csv", "t,x,y,z\n0,0,0,0\n0.1,1,0,0\n").expect("csv");
    assert!(plain.orientations.is_none());
    let err = load_csv("short.csv", "0,0,0,0,0,0,0,1\n0.1,1,0,0\n").expect_err("short row");
    assert!(err.to_string().contains("expected 8"), "{err}");
}

#[test]
fn sorting_and_cutting_keep_each_orientation_with_its_sample() {
    // Out of order, with a repeated stamp (the first in file order stays).
    let order = [2usize, 0, 1, 1, 3];
    let demo = RawDemo {
        name: "d".into(),
        file: "d.mcap".into(),
        topic: "/d".into(),
        stamps_ns: order.iter().map(|&k| sample(k).0).collect(),
        positions: order.iter().map(|&k| sample(k).1.into()).collect(),
        orientations: Some(
            order
                .iter()
                .enumerate()
                .map(|(i, &k)| {
                    // The duplicate carries another rotation, which must go.
                    let q = if i == 3 {
                        turn([1.0, 0.0, 0.0], 1.0)
                    } else {
                        sample(k).2
                    };
                    quat_from_xyzw(q).expect("unit")
                })
                .collect(),
        ),
        time_source: TimeSource::HeaderStamp,
    };
    let sorted = demo.sorted();
    assert_eq!(
        sorted.stamps_ns,
        (0..4).map(|k| sample(k).0).collect::<Vec<_>>()
    );
    let q = sorted.orientations.as_ref().expect("orientation");
    assert!((0..4).all(|k| same(&q[k], sample(k).2)));
    let part = sorted.part(1..3, "p".into(), "/p".into());
    assert_eq!(part.stamps_ns, vec![sample(1).0, sample(2).0]);
    let q = part.orientations.expect("orientation");
    assert!(same(&q[0], sample(1).2) && same(&q[1], sample(2).2));
    // A recording joined from a file without orientation has none.
    let mut joined = sorted.clone();
    joined.extend(RawDemo {
        orientations: None,
        ..sorted.part(3..4, "q".into(), "/q".into())
    });
    assert_eq!(joined.stamps_ns.len(), 5);
    assert!(joined.orientations.is_none());
    // Plain loading of our own writer's files gives identity orientations.
    let bytes = mcap(
        ("geometry_msgs/msg/PoseStamped", "ros2msg", "cdr"),
        "/hand",
        &|t, p, _| ros2::encode_pose_stamped(t, "world", p),
    );
    let loaded = load_bytes("plain.mcap", &bytes).expect("load");
    let q = loaded.demos[0].orientations.as_ref().expect("orientation");
    assert!(q.iter().all(|q| q.angle() == 0.0));
}

#[test]
fn foxglove_poses_hand_on_their_orientation() {
    use dmpscope_core::export::foxglove::EncodedTopic;
    use dmpscope_core::export::foxglove::FoxgloveEncoding;
    use dmpscope_core::export::foxglove::encode_pose_in_frame_proto;
    use dmpscope_core::export::foxglove::write_encoded;
    use dmpscope_core::export::foxglove_json::encode_pose_in_frame_json;
    use dmpscope_core::load::decode::foxglove_schemas::FoxgloveSchema;
    for encoding in [FoxgloveEncoding::Protobuf, FoxgloveEncoding::Json] {
        let messages: Vec<(i64, Vec<u8>)> = (0..N)
            .map(|k| {
                let (t, p, _) = sample(k);
                let bytes = match encoding {
                    FoxgloveEncoding::Protobuf => {
                        encode_pose_in_frame_proto(t, "world", p).expect("encode")
                    }
                    FoxgloveEncoding::Json => encode_pose_in_frame_json(t, "world", p),
                };
                (t, bytes)
            })
            .collect();
        let topics = [EncodedTopic {
            topic: "/hand",
            messages: &messages,
        }];
        let bytes = write_encoded(
            Cursor::new(Vec::new()),
            FoxgloveSchema::PoseInFrame,
            encoding,
            &topics,
            false,
        )
        .expect("write")
        .into_inner();
        let demo = only(&bytes, "fox.mcap", &LoadOptions::default());
        let q = demo.orientations.expect("orientation");
        assert_eq!(q.len(), N);
        assert!(
            q.iter().all(|q| same(q, [0.0, 0.0, 0.0, 1.0])),
            "{encoding:?}"
        );
    }
}
