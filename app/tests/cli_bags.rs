//! ROS 1 bags at the process boundary: `info` and `extract` on a folder of
//! bags give the demos, samples and numbers of the same bags converted to
//! ROS 2 MCAP by `rosbags-convert` (fixtures: core/tests/bags/make_bags.py).

mod support;

use std::path::PathBuf;

use serde_json::Value;
use support::{dmpscope, text};

fn bags(sub: &str) -> String {
    let path: PathBuf = [
        env!("CARGO_MANIFEST_DIR"),
        "..",
        "core",
        "tests",
        "bags",
        sub,
    ]
    .iter()
    .collect();
    path.display().to_string()
}

fn json(args: &[&str]) -> Value {
    let out = dmpscope(args);
    assert!(out.status.success(), "{args:?}: {}", text(&out.stderr));
    serde_json::from_slice(&out.stdout).expect("json")
}

#[test]
fn info_on_bags_equals_info_on_their_conversions() {
    let (bag, mcap) = (bags("reach"), bags("converted"));
    let a = json(&["info", "--json", &bag]);
    let b = json(&["info", "--json", &mcap]);
    let (a, b) = (a.as_array().expect("list"), b.as_array().expect("list"));
    assert_eq!(a.len(), 6);
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(b) {
        for key in [
            "n_samples",
            "duration_s",
            "median_rate_hz",
            "start",
            "goal",
            "orientation",
        ] {
            assert_eq!(x[key], y[key], "{key} of {} and {}", x["name"], y["name"]);
        }
    }
    // The skipped custom type is named on stderr, once per bag.
    let out = dmpscope(&["info", &bag]);
    assert_eq!(text(&out.stderr).matches("my_msgs/Button").count(), 3);
}

#[test]
fn extract_on_bags_equals_extract_on_their_conversions() {
    let (bag, mcap) = (bags("reach"), bags("converted"));
    let args = |src: &str| {
        json(&[
            "extract",
            src,
            "--topic",
            "/vive/controller",
            "--grid",
            "16",
            "--json",
        ])
    };
    let (a, b) = (args(&bag), args(&mcap));
    for key in ["dm", "km", "j", "s", "d_sum"] {
        let (x, y) = (&a["optimum"][key], &b["optimum"][key]);
        assert!(x.is_number(), "{key}: {a}");
        assert_eq!(x, y, "{key}");
    }
}
