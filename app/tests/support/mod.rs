//! What the end-to-end tests share: the repository, the binary, temp files.
#![allow(dead_code)]

pub mod takes;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The repository root.
pub fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The bundled sample recording.
pub fn sample_path() -> PathBuf {
    repo().join("assets/reach10.mcap")
}

/// Runs `dmpscope` from the repository root.
pub fn dmpscope(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_dmpscope"))
        .args(args)
        .current_dir(repo())
        .output()
        .expect("run dmpscope")
}

/// The keys of a JSON object, sorted (empty for anything else).
pub fn sorted_keys(value: &serde_json::Value) -> Vec<&str> {
    let mut keys: Vec<&str> = value
        .as_object()
        .map(|o| o.keys().map(String::as_str).collect())
        .unwrap_or_default();
    keys.sort_unstable();
    keys
}

/// Bytes as text, lossily.
pub fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// A path in a temp folder of this test process.
pub fn tmp_path(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("dmpscope-e2e-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir.join(name)
}

/// Writes a rosbag2 folder `name` (a `metadata.yaml` and one MCAP file per
/// entry `(first, end)` of `splits`, each holding the synthetic reaches
/// `first..end` of the sample generator on topics `/hand_NN`) and returns
/// its path. `short` adds, to the first file, a topic of 5 samples no demo
/// can be made of.
pub fn rosbag2_folder(name: &str, splits: &[(usize, usize)], short: bool) -> PathBuf {
    use dmpscope_core::export::write::{TopicSamples, write_pose_stamped};
    let dir = tmp_path(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("bag folder");
    let demos = dmpscope_core::synth::vive::reach_demos(
        7,
        splits.iter().map(|r| r.1).max().unwrap_or(0),
        1_700_000_000_000_000_000,
    );
    let mut files = Vec::new();
    for (f, &(first, end)) in splits.iter().enumerate() {
        let range = first..end;
        let topics: Vec<String> = range
            .clone()
            .map(|i| format!("/hand_{:02}", i + 1))
            .collect();
        let stub: Vec<(i64, [f64; 3])> = (0..5)
            .map(|k| (k * 10_000_000, [0.0, 0.0, k as f64 * 0.01]))
            .collect();
        let mut samples: Vec<TopicSamples<'_>> = range
            .clone()
            .zip(&topics)
            .map(|(i, topic)| TopicSamples {
                orientations: None,
                topic,
                frame_id: "world",
                samples: &demos[i].samples,
            })
            .collect();
        if short && f == 0 {
            samples.push(TopicSamples {
                orientations: None,
                topic: "/aborted",
                frame_id: "world",
                samples: &stub,
            });
        }
        let file = format!("{name}_{f}.mcap");
        let out = std::fs::File::create(dir.join(&file)).expect("bag file");
        write_pose_stamped(std::io::BufWriter::new(out), &samples, true).expect("write bag");
        files.push(file);
    }
    let list: String = files.iter().map(|f| format!("  - {f}\n")).collect();
    let metadata = format!(
        "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: mcap\n  relative_file_paths:\n{list}"
    );
    std::fs::write(dir.join("metadata.yaml"), metadata).expect("metadata");
    dir
}

/// A TF bag as `ros2 bag record -a` writes it: `/tf` with a moving
/// `tracker` and a still `shoulder_link`, `/tf_static` with one message,
/// and a moving `/hand` PoseStamped topic (another reach, 1 s later).
pub fn tf_bag_bytes() -> Vec<u8> {
    use dmpscope_core::load::decode::ros2;
    let epoch: i64 = 1_700_000_000_000_000_000;
    let mut w = mcap::WriteOptions::new()
        .profile("ros2")
        .create(std::io::Cursor::new(Vec::new()))
        .expect("writer");
    let [tf_id, static_id, hand_id] = tf_bag_channels(&mut w);
    write_tf_messages(&mut w, tf_id, static_id, epoch);
    for (k, (t, p)) in tf_reach(epoch + 2_000_000_000, 0.8).into_iter().enumerate() {
        put_message(
            &mut w,
            hand_id,
            k,
            t,
            &ros2::encode_pose_stamped(t, "world", p),
        );
    }
    w.finish().expect("finish");
    w.into_inner().into_inner()
}

/// The MCAP writer of [`tf_bag_bytes`], in memory.
type BagWriter = mcap::Writer<std::io::Cursor<Vec<u8>>>;

/// A smooth reach of 160 samples at 90 Hz from `t0` (ns), its x and z
/// extent times `scale`.
fn tf_reach(t0: i64, scale: f64) -> Vec<(i64, [f64; 3])> {
    (0..160)
        .map(|k| {
            let s = k as f64 / 159.0;
            let m = 10.0 * s.powi(3) - 15.0 * s.powi(4) + 6.0 * s.powi(5);
            (
                t0 + k * 11_111_111,
                [0.3 + 0.4 * scale * m, 0.1 * m, 1.0 + 0.05 * m * scale],
            )
        })
        .collect()
}

/// The TF bag's schemas and its channels `/tf`, `/tf_static` and `/hand`, in
/// that order.
fn tf_bag_channels(w: &mut BagWriter) -> [u16; 3] {
    use dmpscope_core::load::decode::ros2;
    let tf = w
        .add_schema(
            "tf2_msgs/msg/TFMessage",
            "ros2msg",
            ros2::TF_MESSAGE_SCHEMA.as_bytes(),
        )
        .expect("schema");
    let pose = w
        .add_schema(
            "geometry_msgs/msg/PoseStamped",
            "ros2msg",
            ros2::POSE_STAMPED_SCHEMA.as_bytes(),
        )
        .expect("schema");
    let meta = std::collections::BTreeMap::new();
    let tf_id = w.add_channel(tf, "/tf", "cdr", &meta).expect("channel");
    let static_id = w
        .add_channel(tf, "/tf_static", "cdr", &meta)
        .expect("channel");
    let hand_id = w.add_channel(pose, "/hand", "cdr", &meta).expect("channel");
    [tf_id, static_id, hand_id]
}

/// Writes message `seq` of channel `id`, logged and published at `t` (ns).
fn put_message(w: &mut BagWriter, id: u16, seq: usize, t: i64, data: &[u8]) {
    use mcap::records::MessageHeader;
    let time = u64::try_from(t).expect("stamp");
    let header = MessageHeader {
        channel_id: id,
        sequence: seq as u32,
        log_time: time,
        publish_time: time,
    };
    w.write_to_known_channel(&header, data).expect("message");
}

/// `/tf_static`'s one message (`world` to `base_link`), then `/tf` with the
/// moving `tracker` and the still `shoulder_link`.
fn write_tf_messages(w: &mut BagWriter, tf_id: u16, static_id: u16, epoch: i64) {
    use dmpscope_core::load::decode::ros2;
    use dmpscope_core::load::decode::ros2::StampedTransform;
    let statics = [StampedTransform {
        stamp_ns: epoch,
        frame_id: "world",
        child_frame_id: "base_link",
        translation: [0.1, 0.0, 0.0],
        rotation: [0.0, 0.0, 0.0, 1.0],
    }];
    put_message(w, static_id, 0, epoch, &ros2::encode_tf_message(&statics));
    for (k, (t, p)) in tf_reach(epoch, 1.0).into_iter().enumerate() {
        let ts = [
            StampedTransform {
                stamp_ns: t,
                frame_id: "world",
                child_frame_id: "tracker",
                translation: p,
                rotation: [0.0, 0.0, 0.0, 1.0],
            },
            StampedTransform {
                stamp_ns: t,
                frame_id: "base_link",
                child_frame_id: "shoulder_link",
                translation: [0.0, 0.0, 0.3],
                rotation: [0.0, 0.0, 0.0, 1.0],
            },
        ];
        put_message(w, tf_id, k, t, &ros2::encode_tf_message(&ts));
    }
}

/// The run at a new target the app shows; panics when it is off or failed.
pub fn run_at_new_target<'a>(
    h: &'a egui_kittest::Harness<'_, dmpscope::gui::DmpApp>,
) -> &'a dmpscope::session::TargetView {
    h.state()
        .session()
        .generalised()
        .expect("the run at a new target is on")
        .expect("the run at a new target runs")
}

/// Drags the pointer from `start` by 25 points right and down, in five
/// moves a frame apart, as a person drags on a map.
pub fn drag_from(h: &mut egui_kittest::Harness<'_, dmpscope::gui::DmpApp>, start: egui::Pos2) {
    h.hover_at(start);
    h.run_steps(1);
    h.drag_at(start);
    h.run_steps(1);
    for step in 1..=5 {
        h.hover_at(start + egui::vec2(5.0 * step as f32, 5.0 * step as f32));
        h.run_steps(1);
    }
    h.drop_at(start + egui::vec2(25.0, 25.0));
    h.run_steps(2);
}
