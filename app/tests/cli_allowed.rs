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

/// `settle_unit` as method.md section 11 ("Settling") defines it.
fn settle_unit(dm: f64, km: f64) -> f64 {
    let disc = dm * dm - 4.0 * km;
    let sigma = if disc < 0.0 {
        dm / 2.0
    } else {
        (dm - disc.sqrt()) / 2.0
    };
    50f64.ln() / sigma
}

#[test]
fn settle_within_keeps_the_compliant_pick_to_gains_that_settle_in_time() {
    let sample = sample_path();
    let path = sample.to_str().expect("path");
    let run = |extra: &[&str]| -> Value {
        let out = dmpscope(
            &[
                &[
                    "extract",
                    path,
                    "--grid",
                    "32",
                    "--no-diagnostics",
                    "--json",
                    "--pick",
                    "compliant",
                ],
                extra,
            ]
            .concat(),
        );
        assert!(out.status.success(), "{}", text(&out.stderr));
        serde_json::from_slice(&out.stdout).expect("json")
    };
    // In a box whose least K/M is inside the region the compliant pick sits
    // on that edge, and says so (the rule would go further).
    let narrow = run(&["--dm-range", "5", "60", "--km-range", "900", "1000"]);
    let pick = &narrow["pick"];
    assert_eq!(pick["on_edge"], true, "{pick}");
    assert!(
        pick["edge"].as_str().expect("edge").contains("least K/M"),
        "{pick}"
    );
    let free = run(&[]);
    assert_eq!(free["pick"]["on_edge"], false, "{}", free["pick"]);
    // With it: the least-K/M point (then D/M) of the rule among the
    // region's points that settle within 1 unit time.
    let kept = run(&["--settle-within", "1"]);
    let pick = &kept["pick"];
    let (dm, km) = (
        pick["dm"].as_f64().expect("dm"),
        pick["km"].as_f64().expect("km"),
    );
    let t = pick["settling"]["unit"].as_f64().expect("settling");
    assert!(
        t <= 1.0 && (t - settle_unit(dm, km)).abs() <= 1e-12 * t,
        "{pick}"
    );
    let secs = pick["settling"]["seconds"].as_f64().expect("seconds");
    let duration = pick["robot"]["duration_s"].as_f64().expect("T");
    assert!((secs - t * duration).abs() <= 1e-12 * secs);
    let out = dmpscope(&["landscape", path, "--grid", "32"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let land: Value = serde_json::from_slice(&out.stdout).expect("json");
    let axis = |k: &str| -> Vec<f64> {
        land[k]
            .as_array()
            .expect(k)
            .iter()
            .map(|v| v.as_f64().expect("f64"))
            .collect()
    };
    let (dms, kms) = (axis("dm"), axis("km"));
    let j_star = kept["optimum"]["j"].as_f64().expect("J*");
    let eps = kept["acceptable"]["eps"].as_f64().expect("eps");
    let mut best: Option<(f64, f64)> = None;
    for (i, &d) in dms.iter().enumerate() {
        for (k, &q) in kms.iter().enumerate() {
            let j = land["j"][i][k].as_f64().unwrap_or(f64::INFINITY);
            let zeta = d / (2.0 * q.sqrt());
            if j <= (1.0 + eps) * j_star && (0.7..=1.5).contains(&zeta) && settle_unit(d, q) <= 1.0
            {
                let better = best.is_none_or(|(bd, bk)| q < bk || (q == bk && d < bd));
                if better {
                    best = Some((d, q));
                }
            }
        }
    }
    assert_eq!(
        best,
        Some((dm, km)),
        "the grid's least-K/M point that settles in time"
    );
    assert!(
        pick["why"]
            .as_str()
            .expect("why")
            .contains("settle within 1"),
        "{pick}"
    );
}
