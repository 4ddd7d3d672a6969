//! The independent reference's files (`tests/golden/`) and what the
//! golden tests share: reading them, the demos and model they describe.
#![allow(dead_code)]

use dmpscope_core::fit::settings::DmpSettings;
use dmpscope_core::geom::Vec3;
use dmpscope_core::{Model, PrepSettings, RawDemo, TimeSource, prepare};
use serde_json::Value;

/// A file of `tests/golden/` as JSON.
pub fn golden(name: &str) -> Value {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../tests/golden")
        .join(name);
    let text = std::fs::read_to_string(&path).expect("golden file");
    serde_json::from_str(&text).expect("golden json")
}

/// A JSON number.
pub fn f(v: &Value) -> f64 {
    v.as_f64().expect("number")
}

/// A JSON array of numbers.
pub fn fs(v: &Value) -> Vec<f64> {
    v.as_array().expect("array").iter().map(f).collect()
}

/// Relative closeness with a floor for values near zero.
#[track_caller]
pub fn close(actual: f64, expected: f64, rel: f64, what: &str) {
    let scale = expected.abs().max(1e-9);
    assert!(
        (actual - expected).abs() <= rel * scale,
        "{what}: {actual} vs golden {expected} (rel {:.3e})",
        (actual - expected).abs() / scale
    );
}

/// One demo of a reference file: `name`, integer `stamps_ns`,
/// `positions` and, when present, `orientations` (`[x, y, z, w]`).
pub fn raw_demo(d: &Value, file: &str) -> RawDemo {
    let name = d["name"].as_str().unwrap_or("demo").to_owned();
    RawDemo {
        name: name.clone(),
        file: file.into(),
        topic: name,
        stamps_ns: d["stamps_ns"]
            .as_array()
            .expect("stamps")
            .iter()
            .map(|v| v.as_i64().expect("int stamp"))
            .collect(),
        positions: d["positions"]
            .as_array()
            .expect("positions")
            .iter()
            .map(|p| {
                let p = fs(p);
                Vec3::new(p[0], p[1], p[2])
            })
            .collect(),
        orientations: d["orientations"].as_array().map(|qs| {
            qs.iter()
                .map(|q| {
                    let q = fs(q);
                    dmpscope_core::geom::quat_from_xyzw([q[0], q[1], q[2], q[3]])
                        .expect("a unit quaternion")
                })
                .collect()
        }),
        time_source: TimeSource::HeaderStamp,
    }
}

/// The reference's demos as decoded.
pub fn raw_demos() -> Vec<RawDemo> {
    let input = golden("input.json");
    input["demos"]
        .as_array()
        .expect("demos")
        .iter()
        .map(|d| raw_demo(d, "input.json"))
        .collect()
}

/// The model of the reference's demos with the paper's settings.
pub fn model() -> Model {
    let prepared = raw_demos()
        .iter()
        .map(|r| prepare(r, &PrepSettings::default()).expect("prepare"))
        .collect();
    Model::new(prepared, DmpSettings::default()).expect("model")
}
