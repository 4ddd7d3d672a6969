//! What the demos allow, at the process boundary (docs/method.md section
//! 11): a flat J is never a dead end (the region, a pick and why, the
//! robot's gains, E's verdict); one demo and a rule without a point are
//! said plainly; the planted sample's pick is its optimum.

mod support;

use serde_json::Value;
use support::{dmpscope, repo, sample_path, text};

fn extract(args: &[&str]) -> (String, String) {
    let out = dmpscope(&[&["extract", "--grid", "32", "--no-diagnostics"], args].concat());
    assert!(out.status.success(), "{}", text(&out.stderr));
    (text(&out.stdout), text(&out.stderr))
}

#[test]
fn a_flat_j_says_what_the_demos_allow_and_picks_compliant_gains() {
    let sample = sample_path();
    let (stdout, _) = extract(&[sample.to_str().expect("path")]);
    for needle in [
        "the data allow D/M",
        "picked by compliant",
        "why: J is flat",
        "for the robot: K/M",
        "2 % settling time",
        "identifiability (frame skill",
        "Picked (compliant)",
        "E[m]",
    ] {
        assert!(stdout.contains(needle), "{needle}:\n{stdout}");
    }
}

#[test]
fn the_planted_sample_picks_its_optimum_and_says_why() {
    let planted = repo().join("assets/planted8.mcap");
    let out = dmpscope(&[
        "extract",
        planted.to_str().expect("path"),
        "--grid",
        "32",
        "--no-diagnostics",
        "--json",
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let r: Value = serde_json::from_slice(&out.stdout).expect("json");
    assert_eq!(r["j_flat"], false);
    assert_eq!(r["pick"]["rule"], "optimum");
    assert_eq!(r["pick"]["dm"], r["optimum"]["dm"]);
    assert!(r["pick"]["why"].as_str().expect("why").contains("not flat"));
    let zeta = r["pick"]["zeta"].as_f64().expect("zeta");
    assert_eq!(r["pick"]["robot"]["zeta"].as_f64(), Some(zeta));
    // Each mode is named; mode none finds structure the frame skill does not.
    let none = dmpscope(&[
        "extract",
        planted.to_str().expect("path"),
        "--grid",
        "24",
        "--no-diagnostics",
        "--json",
        "--skill-mode",
        "none",
    ]);
    let r: Value = serde_json::from_slice(&none.stdout).expect("json");
    assert_eq!(r["skill_mode"], "none");
    assert!(
        r["e_depth"].as_f64().expect("depth") > 1.0,
        "{}",
        r["e_depth"]
    );
}

#[test]
fn one_demo_and_a_rule_without_a_point_are_said_plainly() {
    let sample = sample_path();
    let path = sample.to_str().expect("path");
    let (stdout, _) = extract(&[path, "--topic", "/demo_01"]);
    assert!(stdout.contains("E needs two demos"), "{stdout}");
    let (stdout, stderr) = extract(&[path, "--pick", "compliant", "--accept-eps", "0.005"]);
    assert!(
        stderr
            .contains("no gains in the acceptable region have zeta in [0.7, 1.5]; the nearest is"),
        "{stderr}"
    );
    assert!(stdout.contains("no pick"), "{stdout}");
    let bad = dmpscope(&["extract", path, "--pick", "stiff"]);
    assert!(!bad.status.success());
    assert!(text(&bad.stderr).contains("optimum, compliant, critical or smooth"));
}
