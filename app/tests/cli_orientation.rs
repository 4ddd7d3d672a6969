//! The orientation's options on the command line (method.md section 12):
//! `--k-rot` weighs d_rot in J and is refused without an orientation;
//! `--orientation-gains` runs the orientation at its own gains, so d_rot is
//! the same for every row of Table I; a bad pair is refused by name.

mod support;

use serde_json::Value;
use support::{dmpscope, repo, text};

fn extract(args: &[&str]) -> Result<Value, String> {
    let planted = repo().join("assets/planted8.mcap").display().to_string();
    let mut all = vec![
        "extract",
        planted.as_str(),
        "--grid",
        "16",
        "--no-diagnostics",
    ];
    all.extend(args);
    all.push("--json");
    let out = dmpscope(&all);
    if out.status.success() {
        serde_json::from_slice(&out.stdout).map_err(|e| e.to_string())
    } else {
        Err(text(&out.stderr))
    }
}

fn d_rot_sums(report: &Value) -> Vec<f64> {
    report["table"]
        .as_array()
        .expect("rows")
        .iter()
        .map(|r| r["d_rot_sum"].as_f64().expect("d_rot_sum"))
        .collect()
}

#[test]
fn k_rot_weighs_the_orientation_and_needs_one() {
    let plain = extract(&[]).expect("extract");
    let weighed = extract(&["--k-rot", "0.5"]).expect("extract with k_rot");
    let (a, b) = (&plain["optimum"], &weighed["optimum"]);
    assert_ne!(a["dm"], b["dm"], "the orientation moves the optimum");
    // J = S + k sum d + k_rot sum d_rot at the optimum.
    let row = &weighed["table"][0];
    let j = row["s"].as_f64().expect("s")
        + 20.0 * row["d_sum"].as_f64().expect("d_sum")
        + 0.5 * row["d_rot_sum"].as_f64().expect("d_rot_sum");
    let said = row["j"].as_f64().expect("j");
    assert!((j - said).abs() <= 1e-12 * said.abs(), "{j} vs {said}");
    let reach = repo().join("assets/reach10.mcap").display().to_string();
    let out = dmpscope(&["extract", &reach, "--grid", "8", "--k-rot", "1"]);
    assert!(!out.status.success());
    assert!(text(&out.stderr).contains("no demo has an orientation"));
}

#[test]
fn separate_orientation_gains_make_d_rot_the_same_at_every_gain_pair() {
    let report = extract(&["--orientation-gains", "25", "156.25"]).expect("extract");
    let sums = d_rot_sums(&report);
    assert!(sums.len() >= 6);
    assert!(sums.windows(2).all(|w| w[0] == w[1]), "{sums:?}");
    let plain = d_rot_sums(&extract(&[]).expect("extract"));
    assert!(plain.windows(2).any(|w| w[0] != w[1]), "{plain:?}");
    let said = extract(&["--orientation-gains", "-1", "5"]).expect_err("refused");
    assert!(
        said.contains("orientation gains must be positive"),
        "{said}"
    );
}
