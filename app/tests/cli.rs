//! End-to-end tests at the process boundary: the `dmpscope` binary on the
//! bundled sample, its outputs parsed as a user's script would.

mod support;

use std::path::PathBuf;

use serde_json::Value;
use support::{dmpscope, repo, sorted_keys, text, tmp_path as tmp};

fn sample() -> PathBuf {
    support::sample_path()
}

fn landscape_json(extra: &[&str]) -> Value {
    let out = tmp(&format!(
        "landscape-{}.json",
        extra.join("_").replace(['/', '.'], "-")
    ));
    let sample = sample();
    let mut args = vec![
        "landscape",
        sample.to_str().expect("path"),
        "--grid",
        "12",
        "--out",
        out.to_str().expect("path"),
    ];
    args.extend_from_slice(extra);
    let result = dmpscope(&args);
    assert!(result.status.success(), "stderr: {}", text(&result.stderr));
    serde_json::from_str(&std::fs::read_to_string(&out).expect("json written")).expect("valid json")
}

#[test]
fn info_lists_the_ten_sample_demos() {
    let out = dmpscope(&["info", sample().to_str().expect("path")]);
    assert!(out.status.success());
    let stdout = text(&out.stdout);
    for i in 1..=10 {
        assert!(
            stdout.contains(&format!("reach10.mcap:/demo_{i:02}")),
            "{stdout}"
        );
    }
    let json = dmpscope(&["info", "--json", sample().to_str().expect("path")]);
    let list: Value = serde_json::from_slice(&json.stdout).expect("info --json");
    let demos = list.as_array().expect("array");
    assert_eq!(demos.len(), 10);
    for d in demos {
        let rate = d["median_rate_hz"].as_f64().expect("rate");
        let duration = d["duration_s"].as_f64().expect("duration");
        assert!((85.0..95.0).contains(&rate), "{rate}");
        assert!((1.0..=1.6).contains(&duration), "{duration}");
    }
}

/// The landscape JSON's top-level keys; no orientation error on the reach sample.
fn check_the_top_level_keys(doc: &Value) {
    assert_eq!(
        sorted_keys(doc),
        [
            "a_peak",
            "d_rot_sum",
            "d_sum",
            "demos",
            "dm",
            "e_sum",
            "j",
            "k",
            "km",
            "optimum",
            "s",
            "table"
        ]
    );
    // The reach sample's tracker sends no rotation: no orientation error.
    assert!(
        doc["d_rot_sum"]
            .as_array()
            .expect("rows")
            .iter()
            .all(|row| row.as_array().expect("row").iter().all(Value::is_null))
    );
}

/// The axes, k and the maps of an `n` x `n` grid, J = S + k sum d at every
/// point; returns the grid's least J.
fn check_the_grids(doc: &Value, n: usize) -> f64 {
    assert_eq!(doc["dm"].as_array().expect("dm").len(), n);
    assert_eq!(doc["km"].as_array().expect("km").len(), n);
    assert_eq!(doc["dm"][0].as_f64(), Some(0.1));
    assert_eq!(doc["km"][n - 1].as_f64(), Some(1000.0));
    let k = doc["k"].as_f64().expect("k");
    assert_eq!(k, 20.0);
    let mut grid_min = f64::INFINITY;
    for i in 0..n {
        for j in 0..n {
            let (d, s, jv) = (
                doc["d_sum"][i][j].as_f64().expect("d"),
                doc["s"][i][j].as_f64().expect("s"),
                doc["j"][i][j].as_f64().expect("j"),
            );
            assert!(d > 0.0 && s >= 0.0 && d.is_finite() && s.is_finite());
            assert_eq!(jv, s + k * d);
            grid_min = grid_min.min(jv);
        }
    }
    grid_min
}

/// The optimum's keys, and its J at most the grid's least.
fn check_the_optimum(doc: &Value, grid_min: f64) {
    let opt = &doc["optimum"];
    assert_eq!(
        sorted_keys(opt),
        [
            "converged",
            "d_sum",
            "dm",
            "edge",
            "grid_min_j",
            "iterations",
            "j",
            "km",
            "on_edge",
            "s",
            "zeta"
        ]
    );
    assert!(opt["j"].as_f64().expect("j") <= grid_min);
}

/// Table I's rows (Extracted, then the paper's gains) and the ten demos.
fn check_the_table_and_demos(doc: &Value) {
    let names: Vec<&str> = doc["table"]
        .as_array()
        .expect("table")
        .iter()
        .map(|p| p["name"].as_str().expect("name"))
        .collect();
    assert_eq!(
        names,
        ["Extracted", "Ours", "Hrstc1", "Hrstc2", "Hrstc3", "Hrstc4"]
    );
    for p in doc["table"].as_array().expect("table") {
        assert_eq!(p["d_mean"].as_array().expect("d_mean").len(), 10);
        assert_eq!(p["a_peak"].as_array().expect("a_peak").len(), 10);
    }
    let demos = doc["demos"].as_array().expect("demos");
    assert_eq!(demos.len(), 10);
    assert_eq!(demos[0]["name"], "reach10.mcap:/demo_01");
    assert_eq!(demos[0]["n_samples"].as_u64().map(|n| n > 50), Some(true));
}

#[test]
fn landscape_json_has_exactly_the_documented_shape() {
    let doc = landscape_json(&[]);
    check_the_top_level_keys(&doc);
    let n = 12;
    let grid_min = check_the_grids(&doc, n);
    check_the_optimum(&doc, grid_min);
    check_the_table_and_demos(&doc);
}

/// `extract --json` on the sample at 12 points, without diagnostics.
fn extract_json() -> Value {
    let out = dmpscope(&[
        "extract",
        sample().to_str().expect("path"),
        "--grid",
        "12",
        "--json",
        "--no-diagnostics",
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    serde_json::from_slice(&out.stdout).expect("json")
}

/// The extract report's top-level keys.
fn check_the_report_keys(report: &Value) {
    let keys = sorted_keys(report);
    assert_eq!(
        keys,
        [
            "acceptable",
            "demos",
            "e_depth",
            "e_excess",
            "e_flat",
            "e_note",
            "e_range",
            "j_depth",
            "j_flat",
            "k",
            "loading",
            "optimum",
            "optimum_robot",
            "pick",
            "pick_failure",
            "skill_mode",
            "table"
        ]
    );
}

/// What the report shares with the landscape JSON; returns the pick's row of
/// Table I, the one it adds.
fn check_what_the_landscape_shares(report: &Value, doc: &Value) -> Value {
    for key in ["demos", "k", "optimum"] {
        assert_eq!(report[key], doc[key], "{key}");
    }
    // Table I: the landscape's rows with the pick's row after Extracted.
    let mut table = report["table"].as_array().expect("table").clone();
    let picked = table.remove(1);
    assert!(
        picked["name"]
            .as_str()
            .expect("name")
            .starts_with("Picked (")
    );
    assert_eq!(Value::Array(table), doc["table"]);
    picked
}

/// The pick's keys, its row of Table I, the skill mode, the tolerance, and
/// the pick's gains for the robot.
fn check_the_pick(report: &Value, picked: &Value) {
    // The pick: where, by which rule and why, and for the robot.
    let pick = &report["pick"];
    let mut pick_keys = sorted_keys(pick);
    pick_keys.retain(|k| *k != "robot");
    assert_eq!(
        pick_keys,
        [
            "a_peak_max",
            "d_sum",
            "dm",
            "e_sum",
            "edge",
            "j",
            "km",
            "on_edge",
            "rule",
            "s",
            "settling",
            "why",
            "zeta"
        ]
    );
    assert_eq!(picked["dm"], pick["dm"]);
    assert_eq!(report["skill_mode"], "frame");
    let acceptable = &report["acceptable"];
    assert_eq!(acceptable["eps"].as_f64(), Some(0.02));
    let robot = &pick["robot"];
    let km = pick["km"].as_f64().expect("km");
    let t = robot["duration_s"].as_f64().expect("T");
    let stiffness = robot["stiffness_per_mass"].as_f64().expect("K/M real");
    assert!((stiffness - km / (t * t)).abs() <= 1e-12 * stiffness);
}

/// The loading choices: the defaults.
fn check_the_loading_choices(report: &Value) {
    // The loading choices: the defaults, the method as written.
    assert_eq!(report["loading"]["units"], "m");
    assert_eq!(report["loading"]["trim_rest"], false);
    assert_eq!(report["loading"]["sg_window"], 21);
}

#[test]
fn extract_json_is_the_same_report_as_landscape_json() {
    let doc = landscape_json(&[]);
    let report = extract_json();
    check_the_report_keys(&report);
    let picked = check_what_the_landscape_shares(&report, &doc);
    check_the_pick(&report, &picked);
    check_the_loading_choices(&report);
}

#[test]
fn changing_k_recombines_the_same_grids() {
    let a = landscape_json(&["--k", "20"]);
    let b = landscape_json(&["--k", "5"]);
    assert_eq!(a["s"], b["s"]);
    assert_eq!(a["d_sum"], b["d_sum"]);
    assert_ne!(a["j"], b["j"]);
    assert_eq!(b["k"].as_f64(), Some(5.0));
}

#[test]
fn a_folder_means_every_mcap_in_it() {
    // The bundled samples, one after the other, and their folder.
    let planted = repo().join("assets/planted8.mcap");
    let out = dmpscope(&[
        "info",
        "--json",
        planted.to_str().expect("path"),
        sample().to_str().expect("path"),
    ]);
    let folder = dmpscope(&[
        "info",
        "--json",
        repo().join("assets").to_str().expect("path"),
    ]);
    assert!(out.status.success() && folder.status.success());
    let names = |o: &std::process::Output| -> Vec<String> {
        let v: Value = serde_json::from_slice(&o.stdout).expect("json");
        v.as_array()
            .expect("list")
            .iter()
            .map(|d| d["name"].as_str().expect("name").to_owned())
            .collect()
    };
    assert_eq!(names(&out), names(&folder));
    assert_eq!(names(&folder).len(), 18);
}

#[test]
fn extract_prints_gains_edge_flag_and_table() {
    let out = dmpscope(&[
        "extract",
        sample().to_str().expect("path"),
        "--grid",
        "16",
        "--bootstrap",
        "4",
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    // The sample's optimum is on the K/M edge: J is flat, and what the
    // data allow comes first, then J's least value (never a dead end).
    assert!(stdout.starts_with("the data allow D/M "), "{stdout}");
    assert!(
        stdout.contains("J is flat (depth ") && stdout.contains("J alone does not determine"),
        "{stdout}"
    );
    for needle in [
        "(M:D:K) = 1 : ",
        "depth   = ",
        "S minimum: D/M",
        "leave-one-out and bootstrap on a 16x16 grid",
        "bootstrap (4 resamples, seed 1)",
        "zeta",
        "J ",
        "on edge = ",
        "Table I: d_mean",
        "Table I: a_peak",
        "Extracted",
        "Hrstc4",
    ] {
        assert!(stdout.contains(needle), "missing {needle}: {stdout}");
    }
}

#[test]
fn extract_flags_an_optimum_on_the_box_edge() {
    // K/M capped at 1: on this sample J keeps falling with K/M, so the
    // optimum must sit on the K/M maximum and the user must be told.
    let out = dmpscope(&[
        "extract",
        sample().to_str().expect("path"),
        "--grid",
        "8",
        "--km-range",
        "0.1",
        "1",
    ]);
    assert!(out.status.success());
    assert!(
        text(&out.stdout).contains("on edge = yes: K/M at its maximum"),
        "{}",
        text(&out.stdout)
    );
    assert!(text(&out.stderr).contains("warning: the optimum lies on the edge"));
}

#[test]
fn regen_writes_every_path() {
    let csv = tmp("regen.csv");
    let out = dmpscope(&[
        "regen",
        sample().to_str().expect("path"),
        "--dm",
        "10.73",
        "--km",
        "20.71",
        "--out",
        csv.to_str().expect("path"),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let summary = text(&out.stdout);
    assert!(summary.contains("d_mean [mm]") && summary.contains("reach10.mcap:/demo_10"));
    let body = std::fs::read_to_string(&csv).expect("csv");
    let lines: Vec<&str> = body.lines().collect();
    assert_eq!(lines.len(), 1 + 10 * 1001);
    assert!(lines[0].starts_with("demo,s,t_s,x,y,z"));
    let first: Vec<&str> = lines[1].split(',').collect();
    // The path starts where the demo starts.
    for ax in 0..3 {
        assert_eq!(first[3 + ax], first[6 + ax]);
    }
}

#[test]
fn the_sample_generator_is_deterministic() {
    let out = tmp("reach10.mcap");
    let result = dmpscope(&["gen-sample", "--out", out.to_str().expect("path")]);
    assert!(result.status.success(), "{}", text(&result.stderr));
    let fresh = std::fs::read(&out).expect("written");
    let bundled = std::fs::read(sample()).expect("bundled");
    assert!(
        fresh == bundled,
        "assets/reach10.mcap differs from `dmpscope gen-sample`"
    );
    let out = tmp("planted8.mcap");
    let result = dmpscope(&[
        "gen-sample",
        "--planted",
        "10.73",
        "20.71",
        "--noise-mm",
        "0.1",
        "--demos",
        "8",
        "--out",
        out.to_str().expect("path"),
    ]);
    assert!(result.status.success(), "{}", text(&result.stderr));
    let fresh = std::fs::read(&out).expect("written");
    let bundled = std::fs::read(repo().join("assets/planted8.mcap")).expect("bundled");
    assert!(
        fresh == bundled,
        "assets/planted8.mcap differs from `dmpscope gen-sample --planted 10.73 20.71 --noise-mm 0.1 --demos 8`"
    );
}

#[test]
fn bad_files_get_an_error_naming_them() {
    let not_mcap = tmp("notes.mcap");
    std::fs::write(&not_mcap, b"these are not the bytes you are looking for").expect("write");
    let out = dmpscope(&["info", not_mcap.to_str().expect("path")]);
    assert!(!out.status.success());
    let err = text(&out.stderr);
    assert!(err.contains("notes.mcap") && err.contains("MCAP"), "{err}");

    let bytes = std::fs::read(sample()).expect("sample");
    let truncated = tmp("truncated.mcap");
    std::fs::write(&truncated, &bytes[..bytes.len() / 2]).expect("write");
    let out = dmpscope(&[
        "landscape",
        truncated.to_str().expect("path"),
        "--grid",
        "4",
    ]);
    assert!(!out.status.success());
    let err = text(&out.stderr);
    assert!(
        err.contains("truncated.mcap") && err.contains("truncated"),
        "{err}"
    );

    let out = dmpscope(&["info", "/nonexistent/file.mcap"]);
    assert!(!out.status.success());
    assert!(text(&out.stderr).contains("/nonexistent/file.mcap"));
}

#[test]
fn one_demo_is_told_that_s_needs_two() {
    // Regenerating from a single demo: S is 0 and a note says why.
    let one = tmp("one.mcap");
    let target_out = dmpscope(&[
        "gen-sample",
        "--demos",
        "1",
        "--out",
        one.to_str().expect("path"),
    ]);
    assert!(target_out.status.success());
    let out = dmpscope(&[
        "regen",
        one.to_str().expect("path"),
        "--dm",
        "25",
        "--km",
        "156.25",
    ]);
    assert!(out.status.success());
    assert!(text(&out.stderr).contains("S needs two or more"));
    assert!(text(&out.stdout).contains("S = 0.000000"));
}

#[test]
fn help_lists_the_app_and_the_subcommands() {
    let out = dmpscope(&["--help"]);
    assert!(out.status.success());
    let help = text(&out.stdout);
    assert!(
        help.contains("Usage: dmpscope [OPTIONS] [FILES]..."),
        "{help}"
    );
    for sub in [
        "info",
        "landscape",
        "extract",
        "regen",
        "bench",
        "gen-sample",
    ] {
        assert!(help.contains(sub), "{help}");
    }
}

#[test]
fn extract_json_has_exactly_the_documented_diagnostics() {
    let planted = repo().join("assets/planted8.mcap");
    let out = dmpscope(&[
        "extract",
        planted.to_str().expect("path"),
        "--grid",
        "24",
        "--bootstrap",
        "6",
        "--diag-grid",
        "12",
        "--json",
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let doc: Value = serde_json::from_slice(&out.stdout).expect("json");
    let d = &doc["diagnostics"];
    assert_eq!(
        sorted_keys(d),
        [
            "balanced_k",
            "bootstrap",
            "demos",
            "depth",
            "flat",
            "k_ratio",
            "s_minimum"
        ]
    );
    assert_eq!(sorted_keys(&d["s_minimum"]), ["dm", "km", "s"]);
    let demos = d["demos"].as_array().expect("demos");
    assert_eq!(demos.len(), 8);
    for (i, demo) in demos.iter().enumerate() {
        assert_eq!(sorted_keys(demo), ["loo", "name", "s_share"]);
        assert_eq!(sorted_keys(&demo["loo"]), ["dm", "j", "km", "on_edge"]);
        assert_eq!(demo["name"], format!("planted8.mcap:/demo_{:02}", i + 1));
    }
    let shares: f64 = demos
        .iter()
        .map(|x| x["s_share"].as_f64().expect("share"))
        .sum();
    assert!((shares - 1.0).abs() < 1e-12, "shares sum to one: {shares}");
    let b = &d["bootstrap"];
    assert_eq!(
        sorted_keys(b),
        ["dm", "km", "n", "on_edge_fraction", "seed"]
    );
    assert_eq!(b["n"], 6);
    assert_eq!(b["seed"], 1);
    let p = b["dm"].as_array().expect("percentiles");
    assert!(p[0].as_f64() <= p[1].as_f64() && p[1].as_f64() <= p[2].as_f64());
    // On the planted demos the optimum is interior and determined.
    assert_eq!(d["flat"], false);
    assert_eq!(doc["optimum"]["on_edge"], false);
    let about = &doc["diagnostics_about"];
    assert_eq!(about["grid"]["dm"]["n"], 12);
    assert_eq!(about["resamples"], 6);
}

#[test]
fn one_or_two_demos_say_what_the_diagnostics_cannot_do() {
    let csv = tmp("one-demo.csv");
    let rows: String = (0..60)
        .map(|k| {
            let t = k as f64 / 50.0;
            format!("{t},{},{},0\n", 0.3 * t * t, 0.1 * t)
        })
        .collect();
    std::fs::write(&csv, rows).expect("csv");
    let out = dmpscope(&[
        "extract",
        csv.to_str().expect("path"),
        "--grid",
        "8",
        "--json",
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let doc: Value = serde_json::from_slice(&out.stdout).expect("json");
    let d = &doc["diagnostics"];
    assert!(d["s_minimum"].is_null() && d["bootstrap"].is_null() && d["k_ratio"].is_null());
    assert!(d["demos"][0]["s_share"].is_null() && d["demos"][0]["loo"].is_null());
    assert!(d["depth"].as_f64().is_some(), "depth still works: {d}");
    let notes = doc["diagnostics_about"]["notes"].to_string();
    assert!(notes.contains("two or more"), "{notes}");
    let text_out = dmpscope(&["extract", csv.to_str().expect("path"), "--grid", "8"]);
    assert!(text(&text_out.stdout).contains("need two or more"));
}

#[test]
fn an_a_peak_limit_gives_the_constrained_optimum() {
    let planted = repo().join("assets/planted8.mcap");
    let run = |limit: &str| {
        let result = dmpscope(&[
            "extract",
            planted.to_str().expect("path"),
            "--grid",
            "16",
            "--no-diagnostics",
            &format!("--a-peak-limit={limit}"),
            "--json",
        ]);
        assert!(result.status.success(), "{}", text(&result.stderr));
        let report: Value = serde_json::from_slice(&result.stdout).expect("json");
        report["constrained"].clone()
    };
    let c = run("5.8");
    assert_eq!(sorted_keys(&c), ["a_peak_limit", "optimum"]);
    assert_eq!(
        sorted_keys(&c["optimum"]),
        ["a_peak", "dm", "j", "km", "on_edge"]
    );
    let peak = c["optimum"]["a_peak"].as_f64().expect("a_peak");
    assert!(peak <= 5.8, "{peak}");
    assert_eq!(
        run("0.1")["optimum"],
        Value::Null,
        "nothing within 0.1 m/s^2"
    );
    let bad = dmpscope(&[
        "extract",
        planted.to_str().expect("path"),
        "--grid",
        "8",
        "--a-peak-limit=-1",
    ]);
    assert!(!bad.status.success());
    assert!(text(&bad.stderr).contains("--a-peak-limit must be a positive"));
}
