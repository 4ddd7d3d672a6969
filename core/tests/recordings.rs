//! Recordings as users have them (issue 12): rosbag2 bags split into files,
//! folders of bags, compressed bags, TF bags with `/tf_static` and still
//! robot links, a topic declared on two channels, the same file name in two
//! folders, truncated files, and an export that loads back as the same
//! demos. Every file here is written by the project's own writers in the
//! shape the real recorders give.

use std::collections::BTreeMap;
use std::io::Cursor;
use std::path::{Path, PathBuf};

use dmpscope_core::arrange::streams::load_source;
use dmpscope_core::arrange::streams::{StreamStatus, unique_names};
use dmpscope_core::load::decode::ros2;
use dmpscope_core::load::decode::ros2::StampedTransform;
use dmpscope_core::load::options::LoadOptions;
use dmpscope_core::load::source::SourceData;
use dmpscope_core::{Level, RawDemo};
use mcap::records::MessageHeader;

const EPOCH: i64 = 1_700_000_000_000_000_000;
const PERIOD: i64 = 11_111_111;

/// One channel to write: topic, schema (name, text), and (stamp, message).
struct Chan {
    topic: String,
    schema: (&'static str, &'static str),
    messages: Vec<(i64, Vec<u8>)>,
}

fn write(channels: &[Chan]) -> Vec<u8> {
    let mut w = mcap::WriteOptions::new()
        .profile("ros2")
        .create(Cursor::new(Vec::new()))
        .expect("writer");
    for chan in channels {
        let schema = w
            .add_schema(chan.schema.0, "ros2msg", chan.schema.1.as_bytes())
            .expect("schema");
        let id = w
            .add_channel(schema, &chan.topic, "cdr", &BTreeMap::new())
            .expect("channel");
        for (sequence, (t, data)) in chan.messages.iter().enumerate() {
            let time = u64::try_from(*t).expect("stamp");
            let header = MessageHeader {
                channel_id: id,
                sequence: sequence as u32,
                log_time: time,
                publish_time: time,
            };
            w.write_to_known_channel(&header, data).expect("message");
        }
    }
    w.finish().expect("finish");
    w.into_inner().into_inner()
}

const POSE: (&str, &str) = ("geometry_msgs/msg/PoseStamped", ros2::POSE_STAMPED_SCHEMA);
const TF: (&str, &str) = ("tf2_msgs/msg/TFMessage", ros2::TF_MESSAGE_SCHEMA);

/// A 0.4 m minimum-jerk reach of `n` samples from `t0`.
fn reach(t0: i64, n: usize) -> Vec<(i64, [f64; 3])> {
    (0..n)
        .map(|k| {
            let s = k as f64 / (n - 1) as f64;
            let m = 10.0 * s.powi(3) - 15.0 * s.powi(4) + 6.0 * s.powi(5);
            (
                t0 + k as i64 * PERIOD,
                [0.3 + 0.4 * m, 0.1 * m, 1.0 + 0.05 * m],
            )
        })
        .collect()
}

fn pose_chan(topic: &str, samples: &[(i64, [f64; 3])]) -> Chan {
    Chan {
        topic: topic.to_owned(),
        schema: POSE,
        messages: samples
            .iter()
            .map(|&(t, p)| (t, ros2::encode_pose_stamped(t, "world", p)))
            .collect(),
    }
}

const IDENTITY: [f64; 4] = [0.0, 0.0, 0.0, 1.0];

/// One transform of `child` to `parent`.
fn tr<'a>(
    stamp_ns: i64,
    parent: &'a str,
    child: &'a str,
    translation: [f64; 3],
    rotation: [f64; 4],
) -> StampedTransform<'a> {
    StampedTransform {
        stamp_ns,
        frame_id: parent,
        child_frame_id: child,
        translation,
        rotation,
    }
}

/// A TF channel: one `TFMessage` per entry, logged at its stamp.
fn tf_chan(topic: &str, messages: &[(i64, Vec<StampedTransform<'_>>)]) -> Chan {
    Chan {
        topic: topic.to_owned(),
        schema: TF,
        messages: messages
            .iter()
            .map(|(t, ts)| (*t, ros2::encode_tf_message(ts)))
            .collect(),
    }
}

/// `/tf` with `child` moving under `parent` along `samples`.
fn moving(parent: &str, child: &str, samples: &[(i64, [f64; 3])]) -> Chan {
    let messages: Vec<_> = samples
        .iter()
        .map(|&(t, p)| (t, vec![tr(t, parent, child, p, IDENTITY)]))
        .collect();
    tf_chan("/tf", &messages)
}

fn tmp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir()
        .join(format!("dmpscope-recordings-{}", std::process::id()))
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

fn load(path: &Path) -> dmpscope_core::arrange::streams::SourceDemos {
    let name = path.display().to_string();
    load_source(&name, SourceData::Path(path), &LoadOptions::default()).expect("loads")
}

fn metadata(files: &[&str]) -> String {
    let list: String = files.iter().map(|f| format!("    - {f}\n")).collect();
    format!(
        "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: mcap\n  \
         relative_file_paths:\n{list}  duration:\n    nanoseconds: 0\n"
    )
}

#[test]
fn a_split_bag_is_one_recording_with_or_without_its_metadata() {
    let whole = reach(EPOCH, 200);
    for with_metadata in [true, false] {
        let bag = tmp(&format!("split{with_metadata}"));
        let name = bag
            .file_name()
            .expect("name")
            .to_string_lossy()
            .into_owned();
        // The reach crosses the split at sample 120.
        let files = [format!("{name}_0.mcap"), format!("{name}_1.mcap")];
        std::fs::write(
            bag.join(&files[0]),
            write(&[pose_chan("/hand", &whole[..120])]),
        )
        .expect("write");
        std::fs::write(
            bag.join(&files[1]),
            write(&[pose_chan("/hand", &whole[120..])]),
        )
        .expect("write");
        if with_metadata {
            std::fs::write(
                bag.join("metadata.yaml"),
                metadata(&[files[0].as_str(), files[1].as_str()]),
            )
            .expect("metadata");
        }
        let loaded = load(&bag);
        assert_eq!(loaded.demos.len(), 1, "{:?}", loaded.notices);
        let demo = &loaded.demos[0];
        assert_eq!(demo.name, format!("{name}:/hand"));
        assert_eq!(demo.stamps_ns.len(), 200);
        assert_eq!(demo.stamps_ns[119] + PERIOD, demo.stamps_ns[120]);
        assert!(
            loaded
                .notices
                .iter()
                .any(|n| n.text.contains("split into 2 files, read as one recording")),
            "{:?}",
            loaded.notices
        );
    }
}

#[test]
fn a_folder_of_bags_is_walked_and_compressed_bags_load() {
    let root = tmp("bags");
    let one = root.join("run_a");
    let two = root.join("run_b");
    std::fs::create_dir_all(&one).expect("dir");
    std::fs::create_dir_all(&two).expect("dir");
    let bytes = write(&[pose_chan("/hand", &reach(EPOCH, 150))]);
    // A file-compressed bag (`compression_mode: FILE`).
    let packed = zstd::stream::encode_all(&bytes[..], 3).expect("zstd");
    std::fs::write(one.join("run_a_0.mcap.zstd"), packed).expect("write");
    std::fs::write(one.join("metadata.yaml"), metadata(&["run_a_0.mcap.zstd"])).expect("meta");
    // A message-compressed bag: each CDR message zstd-compressed.
    let mut chan = pose_chan("/hand", &reach(EPOCH + 5 * 1_000_000_000, 150));
    for (_, data) in &mut chan.messages {
        *data = zstd::stream::encode_all(&data[..], 3).expect("zstd");
    }
    std::fs::write(two.join("run_b_0.mcap"), write(&[chan])).expect("write");
    let loaded = load(&root);
    let names: Vec<&str> = loaded.demos.iter().map(|d| d.name.as_str()).collect();
    assert_eq!(names, ["run_a:/hand", "run_b:/hand"]);
    assert!(loaded.demos.iter().all(|d| d.stamps_ns.len() == 150));
    assert!(
        loaded
            .notices
            .iter()
            .any(|n| n.text.contains("150 messages were zstd-compressed")),
        "{:?}",
        loaded.notices
    );
    // A compressed file that is not zstd says so and how to decompress.
    let bad = tmp("badzstd").join("x.mcap.zstd");
    std::fs::write(&bad, b"not zstd at all").expect("write");
    let name = bad.display().to_string();
    let err =
        load_source(&name, SourceData::Path(&bad), &LoadOptions::default()).expect_err("not zstd");
    assert!(err.to_string().contains("zstd"), "{err}");
}

/// A TF bag as `ros2 bag record -a` gives it: `/tf` with a moving tracker
/// and still robot links, `/tf_static` with one message, an RViz
/// `/goal_pose` (one message), and an aborted 19-sample reach.
fn tf_bag() -> Vec<u8> {
    let hand = reach(EPOCH, 180);
    let messages: Vec<_> = hand
        .iter()
        .map(|&(t, p)| {
            let link = [0.0, 0.0, 0.3 + 1e-5 * (t % 3) as f64];
            let ts = vec![
                tr(t, "world", "tracker", p, IDENTITY),
                tr(t, "base_link", "shoulder_link", link, IDENTITY),
            ];
            (t, ts)
        })
        .collect();
    let tf = tf_chan("/tf", &messages);
    let base = [0.1, 0.0, 0.0];
    let tf_static = tf_chan(
        "/tf_static",
        &[(EPOCH, vec![tr(EPOCH, "world", "base_link", base, IDENTITY)])],
    );
    write(&[
        tf,
        tf_static,
        pose_chan("/goal_pose", &reach(EPOCH, 2)[1..]),
        pose_chan("/aborted", &reach(EPOCH, 19)),
    ])
}

#[test]
fn a_tf_bag_keeps_the_tracker_and_says_why_each_other_stream_is_skipped() {
    let loaded = load_source(
        "tf.mcap",
        SourceData::Bytes(&tf_bag()),
        &LoadOptions::default(),
    )
    .expect("loads");
    let topics: Vec<&str> = loaded.demos.iter().map(|d| d.topic.as_str()).collect();
    // The 19-sample reach moves and has time: it is a stream, and
    // preparation leaves it out later (too few samples).
    assert_eq!(topics, ["/aborted", "/tf:tracker"]);
    let status: BTreeMap<&str, &StreamStatus> = loaded
        .streams
        .iter()
        .map(|s| (s.topic.as_str(), &s.status))
        .collect();
    assert_eq!(status["/goal_pose"], &StreamStatus::NoTime);
    assert_eq!(status["/tf_static:base_link"], &StreamStatus::NoTime);
    assert!(matches!(
        status["/tf:shoulder_link"],
        StreamStatus::Still(_)
    ));
    let warned = |what: &str| {
        loaded
            .notices
            .iter()
            .any(|n| n.level == Level::Warning && n.text.contains(what))
    };
    assert!(warned(
        "tf.mcap: /tf_static:base_link: skipped: its stamp never advances"
    ));
    assert!(warned(
        "tf.mcap: /tf:shoulder_link: skipped: it does not move"
    ));
    // The model skips the aborted reach with a reason and keeps the tracker.
    let built = dmpscope_core::build_model(
        &loaded.demos,
        &Default::default(),
        Default::default(),
        dmpscope_core::pipeline::Unusable::Skip,
    )
    .expect("one usable demo");
    assert_eq!(built.model.demos().len(), 1);
    assert!(
        built
            .notices
            .iter()
            .any(|n| n.text.contains("/aborted") && n.text.contains("too few samples")),
        "{:?}",
        built.notices
    );
    // --topic / --exclude choose; per file takes the stream that moves most.
    let options = LoadOptions {
        streams: dmpscope_core::load::options::StreamFilter {
            exclude: vec!["/abort*".into()],
            ..Default::default()
        },
        demos: dmpscope_core::load::options::Grouping::PerFile,
        ..Default::default()
    };
    let loaded = load_source("tf.mcap", SourceData::Bytes(&tf_bag()), &options).expect("loads");
    assert_eq!(loaded.demos.len(), 1);
    assert_eq!(loaded.demos[0].topic, "/tf:tracker");
}

#[test]
fn a_topic_on_two_channels_is_one_stream() {
    let whole = reach(EPOCH, 200);
    let bytes = write(&[
        pose_chan("/hand", &whole[..90]),
        pose_chan("/hand", &whole[90..]),
    ]);
    let loaded = load_source(
        "merged.mcap",
        SourceData::Bytes(&bytes),
        &LoadOptions::default(),
    )
    .expect("loads");
    assert_eq!(loaded.demos.len(), 1);
    assert_eq!(loaded.demos[0].stamps_ns.len(), 200);
}

#[test]
fn the_same_file_name_in_two_folders_gives_two_names() {
    let root = tmp("names");
    let mut demos: Vec<RawDemo> = Vec::new();
    for day in ["monday", "tuesday"] {
        let dir = root.join(day);
        std::fs::create_dir_all(&dir).expect("dir");
        let file = dir.join("reach.mcap");
        std::fs::write(&file, write(&[pose_chan("/hand", &reach(EPOCH, 150))])).expect("write");
        demos.extend(load(&file).demos);
    }
    unique_names(&mut demos);
    let names: Vec<&str> = demos.iter().map(|d| d.name.as_str()).collect();
    assert_eq!(
        names,
        ["monday/reach.mcap:/hand", "tuesday/reach.mcap:/hand"]
    );
}

#[test]
fn a_truncated_file_names_the_streams_it_cut_short() {
    let mut w = mcap::WriteOptions::new()
        .profile("ros2")
        .chunk_size(Some(4096))
        .create(Cursor::new(Vec::new()))
        .expect("writer");
    let schema = w
        .add_schema(POSE.0, "ros2msg", POSE.1.as_bytes())
        .expect("schema");
    let hand = w
        .add_channel(schema, "/hand", "cdr", &BTreeMap::new())
        .expect("channel");
    let early = w
        .add_channel(schema, "/early", "cdr", &BTreeMap::new())
        .expect("channel");
    let samples = reach(EPOCH, 400);
    for (k, &(t, p)) in samples.iter().enumerate() {
        let time = u64::try_from(t).expect("stamp");
        for (id, on) in [(hand, true), (early, k < 100)] {
            if on {
                let header = MessageHeader {
                    channel_id: id,
                    sequence: k as u32,
                    log_time: time,
                    publish_time: time,
                };
                w.write_to_known_channel(&header, &ros2::encode_pose_stamped(t, "w", p))
                    .expect("message");
            }
        }
    }
    w.finish().expect("finish");
    let bytes = w.into_inner().into_inner();
    let cut = &bytes[..bytes.len() * 2 / 3];
    let loaded = load_source("cut.mcap", SourceData::Bytes(cut), &LoadOptions::default())
        .expect("the complete chunks load");
    let warning = loaded
        .notices
        .iter()
        .find(|n| n.text.contains("truncated"))
        .expect("a truncation warning");
    assert!(
        warning.text.contains("cut short: /hand ("),
        "{}",
        warning.text
    );
    assert!(!warning.text.contains("/early"), "{}", warning.text);
}

#[test]
fn an_export_loads_back_as_the_same_demos_names_included() {
    use dmpscope_core::export::recording::{regenerated_paths, write_pose_in_frame_json};
    // Non-ASCII topics, and two names that reduce to one topic segment.
    let topics = ["/左手", "/右手", "/hand.1", "/hand_1"];
    let channels: Vec<Chan> = topics
        .iter()
        .enumerate()
        .map(|(i, t)| pose_chan(t, &reach(EPOCH + i as i64 * 3_000_000_000, 150)))
        .collect();
    let bytes = write(&channels);
    let loaded = load_source(
        "händе.mcap",
        SourceData::Bytes(&bytes),
        &LoadOptions::default(),
    )
    .expect("loads");
    let built = dmpscope_core::build_model(
        &loaded.demos,
        &Default::default(),
        Default::default(),
        dmpscope_core::pipeline::Unusable::Fail,
    )
    .expect("model");
    let firsts: Vec<i64> = loaded.demos.iter().map(|d| d.stamps_ns[0]).collect();
    let paths = regenerated_paths(&built.model, &firsts, 20.0, 100.0);
    let mut export_topics: Vec<&str> = paths.iter().map(|p| p.topic.as_str()).collect();
    export_topics.sort();
    export_topics.dedup();
    assert_eq!(
        export_topics.len(),
        8,
        "every path on its own topic: {export_topics:?}"
    );
    assert!(export_topics.iter().any(|t| t.contains("左手")));
    let file = write_pose_in_frame_json(Cursor::new(Vec::new()), &paths, "world", &BTreeMap::new())
        .expect("export")
        .into_inner();
    let back = load_source(
        "export.mcap",
        SourceData::Bytes(&file),
        &LoadOptions::default(),
    )
    .expect("the export loads");
    let names = |d: &[RawDemo]| {
        let mut n: Vec<String> = d.iter().map(|d| d.name.clone()).collect();
        n.sort();
        n
    };
    assert_eq!(names(&back.demos), names(&loaded.demos));
    assert!(
        back.notices
            .iter()
            .any(|n| n.text.contains("a path dmpscope regenerated")),
        "{:?}",
        back.notices
    );
    // The positions are the exported target paths, on the unit-time grid.
    let model_demo = &built.model.demos()[0];
    let again = back
        .demos
        .iter()
        .find(|d| d.name == model_demo.name)
        .expect("same name");
    assert_eq!(again.positions.len(), model_demo.y_raw.len());
    for (p, q) in again.positions.iter().zip(&model_demo.y_raw) {
        for a in 0..3 {
            assert!((p[a] - (q[a] + model_demo.p0[a])).abs() < 1e-9);
        }
    }
}

#[test]
fn a_fixed_frame_composes_tf_and_tf_static_into_one_frame() {
    // world -> base (static: 1 m along x, turned 90 degrees about z),
    // base -> tracker (dynamic, at 90 Hz).
    let q = [
        0.0,
        0.0,
        (std::f64::consts::FRAC_PI_4).sin(),
        (std::f64::consts::FRAC_PI_4).cos(),
    ];
    let base = tr(EPOCH, "world", "base", [1.0, 0.0, 0.0], q);
    let statics = tf_chan("/tf_static", &[(EPOCH, vec![base])]);
    let hand = reach(EPOCH, 150);
    let tf = moving("base", "tracker", &hand);
    let bytes = write(&[statics, tf]);
    let tracker = |fixed: Option<&str>| {
        let options = LoadOptions {
            fixed_frame: fixed.map(str::to_owned),
            ..LoadOptions::default()
        };
        let loaded = load_source("chain.mcap", SourceData::Bytes(&bytes), &options).expect("loads");
        loaded
            .demos
            .into_iter()
            .find(|d| d.topic == "/tf:tracker")
            .expect("the tracker")
    };
    // By default the tracker is relative to its parent, base.
    let own = tracker(None);
    for (p, (_, q)) in own.positions.iter().zip(&hand) {
        assert_eq!(<[f64; 3]>::from(*p), *q);
    }
    // In world: turned 90 degrees and shifted, (x, y, z) -> (1 - y, x, z).
    let world = tracker(Some("world"));
    for (p, (_, q)) in world.positions.iter().zip(&hand) {
        let expect = [1.0 - q[1], q[0], q[2]];
        assert!(
            (0..3).all(|a| (p[a] - expect[a]).abs() < 1e-12),
            "{p:?} vs {expect:?}"
        );
    }
    // A fixed frame the tree does not hold skips the stream and says why.
    let options = LoadOptions {
        fixed_frame: Some("map".into()),
        ..LoadOptions::default()
    };
    let err = load_source("chain.mcap", SourceData::Bytes(&bytes), &options)
        .expect_err("nothing is expressible in map");
    assert!(
        err.to_string()
            .starts_with("chain.mcap: /tf:tracker: not expressed in map: no transform chain joins"),
        "{err}"
    );
    let channels = vec![pose_chan("/hand", &hand), moving("base", "tracker", &hand)];
    let loaded = load_source("mixed.mcap", SourceData::Bytes(&write(&channels)), &options)
        .expect("the PoseStamped stream stays");
    assert!(
        loaded.notices.iter().any(|n| n
            .text
            .contains("/tf:tracker: not expressed in map: no transform chain joins tracker (under base) and map (under map): skipped")),
        "{:?}",
        loaded.notices
    );
}

#[test]
fn a_fixed_frame_composes_foxglove_frame_transforms_too() {
    use dmpscope_core::export::foxglove_json::Transform;
    use dmpscope_core::export::foxglove_json::encode_frame_transforms_json;
    use dmpscope_core::export::foxglove_json::json_schema;
    use dmpscope_core::load::decode::foxglove_schemas::FoxgloveSchema;
    let mut w = mcap::WriteOptions::new()
        .create(Cursor::new(Vec::new()))
        .expect("writer");
    let schema = w
        .add_schema(
            FoxgloveSchema::FrameTransforms.name(),
            "jsonschema",
            json_schema(FoxgloveSchema::FrameTransforms).as_bytes(),
        )
        .expect("schema");
    let id = w
        .add_channel(schema, "/transforms", "json", &BTreeMap::new())
        .expect("channel");
    let hand = reach(EPOCH, 150);
    for (k, &(t, p)) in hand.iter().enumerate() {
        let ts = [
            Transform {
                stamp_ns: t,
                parent_frame_id: "world",
                child_frame_id: "base",
                translation: [1.0, 0.0, 0.0],
            },
            Transform {
                stamp_ns: t,
                parent_frame_id: "base",
                child_frame_id: "tracker",
                translation: p,
            },
        ];
        let time = u64::try_from(t).expect("stamp");
        let header = MessageHeader {
            channel_id: id,
            sequence: k as u32,
            log_time: time,
            publish_time: time,
        };
        w.write_to_known_channel(&header, &encode_frame_transforms_json(&ts))
            .expect("message");
    }
    w.finish().expect("finish");
    let bytes = w.into_inner().into_inner();
    let options = LoadOptions {
        fixed_frame: Some("world".into()),
        ..LoadOptions::default()
    };
    let loaded = load_source("fox.mcap", SourceData::Bytes(&bytes), &options).expect("loads");
    let tracker = loaded
        .demos
        .iter()
        .find(|d| d.topic == "/transforms:tracker")
        .expect("the tracker");
    for (p, (_, q)) in tracker.positions.iter().zip(&hand) {
        assert!((p[0] - (q[0] + 1.0)).abs() < 1e-12 && (p[1] - q[1]).abs() < 1e-12);
    }
}
