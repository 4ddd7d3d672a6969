//! The reverse path: demos and regenerated paths written so that Foxglove
//! and Rerun open them (`foxglove.PoseInFrame`, JSON encoding, one topic per
//! path, the gains as MCAP metadata), and ROS 2 trajectories beside them.
//! The DMP itself is exported by [`crate::export::dmp_doc`].

use std::collections::BTreeMap;
use std::io::{Seek, Write};

use mcap::records::{MessageHeader, Metadata};

use crate::export::foxglove_json::encode_pose_in_frame_json;
use crate::export::foxglove_json::json_schema;
use crate::export::ros_traj::{
    MULTI_DOF_NAME, PATH_NAME, TimedPath, encode_multi_dof, encode_path, multi_dof_schema,
    path_schema,
};
use crate::landscape::model::Model;
use crate::load::decode::foxglove_schemas::FoxgloveSchema;
use crate::load::formats::{NAME_KEY, ROLE_KEY, ROLE_REGENERATED, ROLE_TRAJECTORY};

/// A path to export: its topic and `(stamp_ns, position)` samples.
pub struct ExportPath {
    /// The topic, e.g. `/demo/demo_01`.
    pub topic: String,
    /// The demo's name, kept as channel metadata ([`NAME_KEY`]).
    pub name: String,
    /// `demonstration` or `regenerated` ([`ROLE_KEY`]).
    pub role: &'static str,
    /// Samples in time order.
    pub samples: Vec<(i64, [f64; 3])>,
}

/// Hands out topic segments for names, each different from the ones
/// before (`name`, `name_2`, ...), whatever the names reduce to.
#[derive(Debug, Default)]
pub struct TopicNames(std::collections::HashSet<String>);

impl TopicNames {
    /// A segment for `name` that no earlier call returned.
    pub fn unique(&mut self, name: &str) -> String {
        let base = topic_safe(name);
        let mut short = base.clone();
        let mut n = 1;
        while !self.0.insert(short.clone()) {
            n += 1;
            short = format!("{base}_{n}");
        }
        short
    }
}

/// The stamp of sample `k` of `n` over `duration_s` from `start_ns`.
fn stamp_of(start_ns: i64, duration_s: f64, k: usize, n: usize) -> i64 {
    start_ns + (duration_s * k as f64 / (n.max(2) - 1) as f64 * 1e9).round() as i64
}

/// Every demo's target path on `/demo/<segment>`, absolute positions,
/// stamped from the demo's first recorded stamp; with each demo's topic
/// segment (from `names`).
pub fn demo_paths(
    model: &Model,
    first_stamps_ns: &[i64],
    names: &mut TopicNames,
) -> (Vec<ExportPath>, Vec<String>) {
    let mut out = Vec::new();
    let mut shorts = Vec::new();
    for (i, demo) in model.demos().iter().enumerate() {
        let start = first_stamps_ns.get(i).copied().unwrap_or(0);
        let n = demo.len();
        let short = names.unique(&demo.name);
        out.push(ExportPath {
            topic: format!("/demo/{short}"),
            name: demo.name.clone(),
            role: "demonstration",
            samples: demo
                .y_raw
                .iter()
                .enumerate()
                .map(|(k, p)| {
                    let p = std::array::from_fn(|ax| p[ax] + demo.p0[ax]);
                    (stamp_of(start, demo.duration_s, k, n), p)
                })
                .collect(),
        });
        shorts.push(short);
    }
    (out, shorts)
}

/// Every demo's target path and its regeneration at `(dm, km)` on
/// `/regen/<segment>`, absolute positions, stamped from the demo's first
/// recorded stamp.
pub fn regenerated_paths(
    model: &Model,
    first_stamps_ns: &[i64],
    dm: f64,
    km: f64,
) -> Vec<ExportPath> {
    let (mut out, shorts) = demo_paths(model, first_stamps_ns, &mut TopicNames::default());
    for (i, (demo, short)) in model.demos().iter().zip(shorts).enumerate() {
        let start = first_stamps_ns.get(i).copied().unwrap_or(0);
        let n = demo.len();
        let rollout = model.rollout(i, dm, km);
        out.push(ExportPath {
            topic: format!("/regen/{short}"),
            name: demo.name.clone(),
            role: ROLE_REGENERATED,
            samples: rollout
                .y
                .iter()
                .enumerate()
                .map(|(k, p)| {
                    let p = std::array::from_fn(|ax| p[ax] + demo.p0[ax]);
                    (stamp_of(start, demo.duration_s, k, n), p)
                })
                .collect(),
        });
    }
    out
}

/// A demo name as a topic segment: `reach10.mcap:/demo_01` ->
/// `reach10_demo_01`; letters of any script are kept (`/händ_links`).
pub fn topic_safe(name: &str) -> String {
    let name = name.strip_suffix(".mcap").unwrap_or(name);
    let mut out = String::with_capacity(name.len());
    for c in name.replace(".mcap:", "_").chars() {
        let keep = c.is_alphanumeric() || c == '_' || c == '-';
        if keep {
            out.push(c);
        } else if !out.ends_with('_') {
            out.push('_');
        }
    }
    out.trim_matches('_').to_owned()
}

/// Writes the paths as `foxglove.PoseInFrame` (JSON) in frame `frame_id`,
/// with `metadata` (e.g. the gains) as one MCAP metadata record `dmpscope`.
pub fn write_pose_in_frame_json<W: Write + Seek>(
    out: W,
    paths: &[ExportPath],
    frame_id: &str,
    metadata: &BTreeMap<String, String>,
) -> mcap::McapResult<W> {
    write_export_mcap(out, paths, &[], frame_id, metadata)
}

/// A path to export as ROS 2 trajectories.
pub struct TrajectoryExport {
    /// Topic prefix: the messages go to `<prefix>/path` and
    /// `<prefix>/trajectory`.
    pub prefix: String,
    /// The path's name, kept as channel metadata ([`NAME_KEY`]).
    pub name: String,
    /// The path in real time.
    pub path: TimedPath,
}

/// [`write_pose_in_frame_json`] plus each of `trajectories` as one ROS 2
/// `nav_msgs/msg/Path` on `<prefix>/path` and one
/// `trajectory_msgs/msg/MultiDOFJointTrajectory` on `<prefix>/trajectory`
/// (CDR), both with the role [`ROLE_TRAJECTORY`] so loading the file skips
/// them.
pub fn write_export_mcap<W: Write + Seek>(
    out: W,
    paths: &[ExportPath],
    trajectories: &[TrajectoryExport],
    frame_id: &str,
    metadata: &BTreeMap<String, String>,
) -> mcap::McapResult<W> {
    let mut writer = mcap::WriteOptions::new()
        .library(concat!("dmpscope/", env!("CARGO_PKG_VERSION")))
        .create(out)?;
    let schema = writer.add_schema(
        FoxgloveSchema::PoseInFrame.name(),
        "jsonschema",
        json_schema(FoxgloveSchema::PoseInFrame).as_bytes(),
    )?;
    let mut messages = Vec::new();
    for path in paths {
        let meta = BTreeMap::from([
            (NAME_KEY.to_owned(), path.name.clone()),
            (ROLE_KEY.to_owned(), path.role.to_owned()),
        ]);
        let channel_id = writer.add_channel(schema, &path.topic, "json", &meta)?;
        for (sequence, &(stamp, position)) in path.samples.iter().enumerate() {
            messages.push((stamp, channel_id, sequence as u32, position));
        }
    }
    // Log-time order, so players replay the paths side by side.
    messages.sort_by_key(|m| (m.0, m.1));
    for (stamp, channel_id, sequence, position) in messages {
        let time = u64::try_from(stamp).unwrap_or(0);
        writer.write_to_known_channel(
            &MessageHeader {
                channel_id,
                sequence,
                log_time: time,
                publish_time: time,
            },
            &encode_pose_in_frame_json(stamp, frame_id, position),
        )?;
    }
    if !trajectories.is_empty() {
        let path_schema = writer.add_schema(PATH_NAME, "ros2msg", path_schema().as_bytes())?;
        let dof_schema =
            writer.add_schema(MULTI_DOF_NAME, "ros2msg", multi_dof_schema().as_bytes())?;
        for t in trajectories {
            let (traj, prefix) = (&t.path, &t.prefix);
            let meta = BTreeMap::from([
                (NAME_KEY.to_owned(), t.name.clone()),
                (ROLE_KEY.to_owned(), ROLE_TRAJECTORY.to_owned()),
            ]);
            let time = u64::try_from(traj.stamp_ns).unwrap_or(0);
            let header = |channel_id| MessageHeader {
                channel_id,
                sequence: 0,
                log_time: time,
                publish_time: time,
            };
            let ch = writer.add_channel(path_schema, &format!("{prefix}/path"), "cdr", &meta)?;
            writer.write_to_known_channel(&header(ch), &encode_path(traj))?;
            let ch =
                writer.add_channel(dof_schema, &format!("{prefix}/trajectory"), "cdr", &meta)?;
            writer.write_to_known_channel(&header(ch), &encode_multi_dof(traj))?;
        }
    }
    writer.write_metadata(&Metadata {
        name: "dmpscope".into(),
        metadata: metadata.clone(),
    })?;
    writer.finish()?;
    Ok(writer.into_inner())
}
