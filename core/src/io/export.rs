//! The reverse path: demos and regenerated paths written so that Foxglove
//! and Rerun open them (`foxglove.PoseInFrame`, JSON encoding, one topic per
//! path, the gains as MCAP metadata), and the fitted DMP as JSON.

use std::collections::BTreeMap;
use std::io::{Seek, Write};

use mcap::records::{MessageHeader, Metadata};
use serde::Serialize;

use super::foxglove_json::{encode_pose_in_frame_json, json_schema};
use super::foxglove_schemas::FoxgloveSchema;
use crate::model::Model;

/// The channel metadata key holding a demo's name: loading an export gives
/// the demo back under it.
pub const NAME_KEY: &str = "dmpscope.name";
/// The channel metadata key saying what a path is (`demonstration`,
/// `regenerated`); a regenerated path is not loaded as a demo.
pub const ROLE_KEY: &str = "dmpscope.role";
/// The role of a regenerated path.
pub const ROLE_REGENERATED: &str = "regenerated";

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

/// Every demo's target path and its regeneration at `(dm, km)`, absolute
/// positions, stamped from the demo's first recorded stamp.
pub fn regenerated_paths(
    model: &Model,
    first_stamps_ns: &[i64],
    dm: f64,
    km: f64,
) -> Vec<ExportPath> {
    let mut out = Vec::new();
    let mut taken = std::collections::HashSet::new();
    for (i, demo) in model.demos().iter().enumerate() {
        let start = first_stamps_ns.get(i).copied().unwrap_or(0);
        let n = demo.len();
        let stamp =
            |k: usize| start + (demo.duration_s * k as f64 / (n - 1) as f64 * 1e9).round() as i64;
        let absolute = |p: [f64; 3]| std::array::from_fn(|ax| p[ax] + demo.p0[ax]);
        // Every demo on its own topic, whatever its name reduces to.
        let base = topic_safe(&demo.name);
        let mut short = base.clone();
        let mut n = 1;
        while !taken.insert(short.clone()) {
            n += 1;
            short = format!("{base}_{n}");
        }
        let rollout = model.rollout(i, dm, km);
        out.push(ExportPath {
            topic: format!("/demo/{short}"),
            name: demo.name.clone(),
            role: "demonstration",
            samples: demo
                .y_raw
                .iter()
                .enumerate()
                .map(|(k, p)| (stamp(k), absolute(*p)))
                .collect(),
        });
        out.push(ExportPath {
            topic: format!("/regen/{short}"),
            name: demo.name.clone(),
            role: ROLE_REGENERATED,
            samples: rollout
                .y
                .iter()
                .enumerate()
                .map(|(k, p)| (stamp(k), absolute(*p)))
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
    writer.write_metadata(&Metadata {
        name: "dmpscope".into(),
        metadata: metadata.clone(),
    })?;
    writer.finish()?;
    Ok(writer.into_inner())
}

/// The fitted DMP of one demo at given gains, for `--out F.json`.
#[derive(Clone, Debug, Serialize)]
pub struct DemoDmp {
    /// The demo's name.
    pub name: String,
    /// Duration T (the paper's M), seconds.
    pub duration_s: f64,
    /// Start (absolute), metres.
    pub start: [f64; 3],
    /// Goal (absolute), metres.
    pub goal: [f64; 3],
    /// LWR weights per axis (`x`, `y`, `z`).
    pub weights: [Vec<f64>; 3],
    /// d at these gains, metres.
    pub d: f64,
    /// a_peak at these gains.
    pub a_peak: f64,
}

/// The gains, the basis and every demo's weights at `(dm, km)`.
#[derive(Clone, Debug, Serialize)]
pub struct DmpExport {
    /// D/M.
    pub dm: f64,
    /// K/M.
    pub km: f64,
    /// Damping ratio.
    pub zeta: f64,
    /// `alpha_x` of the canonical system.
    pub alpha_x: f64,
    /// Basis centres `c_i`.
    pub centres: Vec<f64>,
    /// Basis widths `h_i`.
    pub widths: Vec<f64>,
    /// Per demo.
    pub demos: Vec<DemoDmp>,
}

/// The export of a model at `(dm, km)`.
pub fn dmp_export(model: &Model, dm: f64, km: f64) -> DmpExport {
    let eval = model.evaluate(dm, km);
    let demos = model
        .demos()
        .iter()
        .enumerate()
        .map(|(i, d)| DemoDmp {
            name: d.name.clone(),
            duration_s: d.duration_s,
            start: d.p0,
            goal: std::array::from_fn(|ax| d.goal[ax] + d.p0[ax]),
            weights: std::array::from_fn(|ax| model.projections(i).weights_at(ax, dm, km)),
            d: eval.d[i],
            a_peak: eval.a_peak[i],
        })
        .collect();
    DmpExport {
        dm,
        km,
        zeta: eval.zeta,
        alpha_x: model.settings().alpha_x,
        centres: model.basis().centres.clone(),
        widths: model.basis().widths.clone(),
        demos,
    }
}
