//! `dmpscope rl` at the process boundary: the JSON it writes, the same
//! numbers for the same seed, clear errors for bad arguments.

mod support;

use support::{dmpscope, text};

fn run_json(dir: &std::path::Path, name: &str, seed: &str) -> serde_json::Value {
    let out = dir.join(name);
    let o = dmpscope(&[
        "rl",
        "assets/reach10.mcap",
        "--demo",
        "2",
        "--preset",
        "hrstc1",
        "--steps",
        "800",
        "--seed",
        seed,
        "--out",
        out.to_str().expect("utf-8 path"),
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    assert!(text(&o.stdout).contains("Hrstc1"), "{}", text(&o.stdout));
    serde_json::from_slice(&std::fs::read(out).expect("json written")).expect("json")
}

#[test]
fn rl_writes_its_results_and_repeats_them_for_a_seed() {
    let dir = std::env::temp_dir().join(format!("dmpscope-cli-rl-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let a = run_json(&dir, "a.json", "5");
    for key in ["final_error_m", "d_m", "a_peak", "train_seconds"] {
        assert!(
            a[key].as_f64().is_some_and(f64::is_finite),
            "{key}: {}",
            a[key]
        );
    }
    assert!(a["reached"].is_boolean());
    let reached = a["final_error_m"].as_f64().is_some_and(|e| e <= 0.005);
    assert_eq!(a["reached"].as_bool(), Some(reached));
    let returns = a["returns"].as_array().expect("returns");
    assert_eq!(
        returns.len(),
        2,
        "800 decisions = 2 iterations of 4 episodes"
    );
    let path = a["path"].as_array().expect("path");
    assert_eq!(path.len(), 1001, "the learned path on the demo's grid");
    let b = run_json(&dir, "b.json", "5");
    for key in ["final_error_m", "d_m", "a_peak", "returns", "path"] {
        assert_eq!(a[key], b[key], "{key} repeats for the same seed");
    }
    let c = run_json(&dir, "c.json", "6");
    assert_ne!(
        a["returns"], c["returns"],
        "another seed learns differently"
    );
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn rl_options_residual_mode_a_thousand_decisions_forcing_exploration_and_the_saved_policy() {
    let dir = std::env::temp_dir().join(format!("dmpscope-cli-rl-opt-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let (out, policy) = (dir.join("r.json"), dir.join("policy.json"));
    let o = dmpscope(&[
        "rl",
        "assets/reach10.mcap",
        "--preset",
        "Ours",
        "--mode",
        "residual",
        "--decisions",
        "1000",
        "--explore",
        "forcing",
        "--steps",
        "4000",
        "--out",
        out.to_str().expect("utf-8 path"),
        "--save-policy",
        policy.to_str().expect("utf-8 path"),
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let stdout = text(&o.stdout);
    assert!(
        stdout.contains("1000 decisions per episode, action: residual, exploration: forcing"),
        "{stdout}"
    );
    let r: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&out).expect("json")).expect("json");
    assert_eq!(
        r["returns"].as_array().map(Vec::len),
        Some(1),
        "4 episodes of 1000"
    );
    assert!(r["diverged"].is_boolean());
    let p: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&policy).expect("policy")).expect("json");
    assert_eq!(p["format"], "dmpscope.policy");
    assert_eq!(p["mode"], "residual");
    assert_eq!(p["integration_steps_per_decision"], 1);
    let sizes = p["policy"]["actor"]["sizes"].as_array().expect("sizes");
    assert_eq!(sizes.len(), 4, "7-64-64-3");
    let mean = p["policy"]["obs_norm"]["mean"]
        .as_array()
        .expect("normaliser");
    assert_eq!(mean.len(), 7);
    assert!(
        p["policy"]["obs_norm"]["count"]
            .as_f64()
            .is_some_and(|c| c > 4000.0)
    );
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn rl_compare_reports_each_gain_set() {
    let o = dmpscope(&[
        "rl",
        "assets/reach10.mcap",
        "--compare",
        "--grid",
        "16",
        "--steps",
        "400",
        "--seeds",
        "2",
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let stdout = text(&o.stdout);
    for name in ["Extracted", "Ours", "Hrstc1", "Hrstc2", "Hrstc3", "Hrstc4"] {
        assert!(
            stdout
                .lines()
                .any(|l| l.starts_with(name) && l.contains("reached") && l.contains("/2, stable")),
            "{name}: {stdout}"
        );
    }
    assert!(
        stdout.contains("1st reach") && stdout.contains("stable"),
        "{stdout}"
    );
}

#[test]
fn rl_rejects_bad_arguments_clearly() {
    let cases: [(&[&str], &str); 5] = [
        (
            &["--demo", "99", "--preset", "Ours"],
            "--demo must be between 1 and 10",
        ),
        (&["--preset", "Nope"], "no preset \"Nope\""),
        (
            &["--dm", "0", "--km", "5"],
            "--dm must be a positive number",
        ),
        (&[], "choose the gains"),
        (
            &["--preset", "Ours", "--decisions", "0"],
            "decisions per episode must be 1 to 1000",
        ),
    ];
    for (args, message) in cases {
        let mut all = vec!["rl", "assets/reach10.mcap", "--steps", "100"];
        all.extend_from_slice(args);
        let o = dmpscope(&all);
        assert!(!o.status.success(), "{args:?} should fail");
        let err = text(&o.stderr);
        assert!(err.contains(message), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{err}");
    }
}
