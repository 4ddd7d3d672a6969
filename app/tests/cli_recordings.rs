//! Recordings from other labs at the process boundary: motion-capture
//! trials exported in millimetres, reach-and-return trials of which only
//! the reach is wanted, arm demos with rests at the ends, and a robot arm
//! logged at 1 kHz. Each choice is made by a flag and said in a notice;
//! without the flag the user is warned.

mod support;

use std::path::PathBuf;

use serde_json::Value;
use support::{dmpscope, text, tmp_path};

/// Minimum jerk from 0 to 1.
fn mj(u: f64) -> f64 {
    let u = u.clamp(0.0, 1.0);
    u * u * u * (10.0 - 15.0 * u + 6.0 * u * u)
}

/// A folder of CSV trials: `rows(k)` gives trial k's `(t, [x, y, z])`.
fn folder(name: &str, trials: usize, rows: impl Fn(usize) -> Vec<(f64, [f64; 3])>) -> PathBuf {
    let dir = tmp_path(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("folder");
    for k in 0..trials {
        let mut csv = String::from("t,x,y,z\n");
        for (t, p) in rows(k) {
            csv += &format!("{t:.6},{:.4},{:.4},{:.4}\n", p[0], p[1], p[2]);
        }
        std::fs::write(dir.join(format!("trial_{k:02}.csv")), csv).expect("write");
    }
    dir
}

/// Reach-and-return trials in millimetres at 120 Hz: 0.5 s still, a reach
/// of `reach_mm(k)` over 1 s, 0.5 s holding, the return over 1 s, 0.5 s still.
fn reach_and_return_mm(k: usize) -> Vec<(f64, [f64; 3])> {
    let reach = 300.0 + 20.0 * k as f64;
    let start = [193.184 + 5.0 * k as f64, -402.32, 168.017];
    (0..=420)
        .map(|i| {
            let t = i as f64 / 120.0;
            let s = mj(t - 0.5) - mj(t - 2.0);
            let wiggle = 0.3 * ((i * 7 + k) as f64).sin();
            (
                t,
                [
                    start[0] + reach * s + wiggle,
                    start[1] + 0.6 * reach * s,
                    start[2] + 0.2 * reach * s,
                ],
            )
        })
        .collect()
}

fn run(args: &[&str]) -> (String, String) {
    let out = dmpscope(args);
    assert!(out.status.success(), "{args:?}: {}", text(&out.stderr));
    (text(&out.stdout), text(&out.stderr))
}

#[test]
fn millimetre_trials_give_their_reaches_in_metres() {
    let dir = folder("mm-trials", 5, reach_and_return_mm);
    // A table beside the trials is not a demo: skipped, said.
    std::fs::write(dir.join("gains.csv"), "gains,dm,km\nExtracted,1,2\n").expect("write");
    let dir = dir.to_str().expect("path");
    let seg = ["--demos", "segment", "--segments", "first"];
    // Without --units: a warning naming file and topic and the flag.
    let (_, err) = run(&[&["info", dir][..], &seg].concat());
    assert!(
        err.contains("trial_00.csv: csv") && err.contains("--units mm"),
        "{err}"
    );
    assert!(
        err.contains("gains.csv") && err.contains("skipped (not a t,x,y,z"),
        "{err}"
    );
    let (out, err) = run(&[&["info", "--json", "--units", "mm", dir][..], &seg].concat());
    assert!(!err.contains("--units mm"), "{err}");
    assert!(
        err.contains("2 segments, kept 1 (--segments first)"),
        "{err}"
    );
    let demos: Value = serde_json::from_str(&out).expect("json");
    let demos = demos.as_array().expect("list");
    assert_eq!(demos.len(), 5, "one demo per trial");
    for (k, d) in demos.iter().enumerate() {
        let (s, g) = (&d["start"], &d["goal"]);
        let reach: f64 = (0..3)
            .map(|a| (g[a].as_f64().unwrap_or(0.0) - s[a].as_f64().unwrap_or(0.0)).powi(2))
            .sum::<f64>()
            .sqrt();
        let want = (300.0 + 20.0 * k as f64) * 1e-3 * (1.0f64 + 0.36 + 0.04).sqrt();
        assert!(
            (reach - want).abs() < 0.01 * want,
            "trial {k}: {reach} m, want {want}"
        );
    }
    // extract says which choices it made.
    let (out, _) = run(&[
        &[
            "extract",
            "--json",
            "--grid",
            "12",
            "--no-diagnostics",
            "--units",
            "mm",
            dir,
        ][..],
        &seg,
    ]
    .concat());
    let report: Value = serde_json::from_str(&out).expect("json");
    assert_eq!(report["demos"].as_array().map(Vec::len), Some(5));
    let loading = &report["loading"];
    assert_eq!(loading["units"], "mm");
    assert_eq!(loading["demos"], "segment");
    assert_eq!(loading["segments"], "first");
    assert_eq!(loading["trim_rest"], false);
}

/// An arm moved by hand, logged at 500 Hz: 0.4 s still, a 1.2 s move, 0.3 s still.
fn arm_with_rests(k: usize) -> Vec<(f64, [f64; 3])> {
    (0..=950)
        .map(|i| {
            let t = i as f64 / 500.0;
            let s = mj((t - 0.4) / 1.2);
            let wiggle = 2e-5 * ((i * 13 + k) as f64).sin();
            (
                t,
                [0.4 + 0.3 * s + wiggle, 0.1 * s, 0.5 + 0.05 * k as f64 * s],
            )
        })
        .collect()
}

#[test]
fn rests_at_the_ends_are_reported_and_trimmed_on_request() {
    let dir = folder("arm-rests", 3, arm_with_rests);
    let dir = dir.to_str().expect("path");
    let duration = |out: &str| -> Vec<f64> {
        let v: Value = serde_json::from_str(out).expect("json");
        v.as_array()
            .expect("list")
            .iter()
            .map(|d| d["duration_s"].as_f64().expect("duration"))
            .collect()
    };
    let (out, err) = run(&["info", "--json", dir]);
    assert!(
        err.contains("at rest at its start (") && err.contains("--trim-rest"),
        "{err}"
    );
    let whole = duration(&out);
    let (out, err) = run(&["info", "--json", "--trim-rest", dir]);
    assert!(err.contains("trimmed (--trim-rest)"), "{err}");
    let trimmed = duration(&out);
    for (w, t) in whole.iter().zip(&trimmed) {
        assert!((w - 1.9).abs() < 1e-6, "{w}");
        // The 0.4 + 0.3 s still go, and the move's first and last 0.1 s,
        // below the rest speed too (minimum jerk starts and ends gently).
        assert!((0.95..1.25).contains(t), "{t}");
    }
}

#[test]
fn a_short_smoothing_window_is_flagged_and_a_window_in_seconds_fixes_it() {
    // A robot arm at 1 kHz: 21 samples are 20 ms.
    let dir = folder("arm-1khz", 3, |k| {
        (0..=1500)
            .map(|i| {
                let t = i as f64 / 1000.0;
                (
                    t,
                    [
                        0.3 * mj(t / 1.5) + 1e-5 * ((i + k) as f64).cos(),
                        0.05 * k as f64 * mj(t / 1.5),
                        0.4,
                    ],
                )
            })
            .collect()
    });
    let dir = dir.to_str().expect("path");
    let (_, err) = run(&["extract", "--grid", "8", "--no-diagnostics", dir]);
    assert!(
        err.contains("21-sample Savitzky-Golay window spans 20 ms"),
        "{err}"
    );
    let (out, err) = run(&[
        "extract",
        "--json",
        "--grid",
        "8",
        "--no-diagnostics",
        "--sg-seconds",
        "0.1",
        dir,
    ]);
    assert!(!err.contains("Savitzky-Golay window spans"), "{err}");
    let report: Value = serde_json::from_str(&out).expect("json");
    assert_eq!(report["loading"]["sg_seconds"], 0.1);
    // The wider window smooths: S at the paper's gains changes.
    let (plain, _) = run(&["extract", "--json", "--grid", "8", "--no-diagnostics", dir]);
    let plain: Value = serde_json::from_str(&plain).expect("json");
    let s = |r: &Value| r["table"][1]["s"].as_f64().expect("S");
    assert!(
        (s(&report) - s(&plain)).abs() > 1e-6 * s(&plain),
        "{} {}",
        s(&report),
        s(&plain)
    );
    // A window of no duration is refused.
    let out = dmpscope(&["extract", "--sg-seconds", "0", dir]);
    assert!(!out.status.success() && text(&out.stderr).contains("above 0"));
}

/// An OptiTrack Motive export (format 1.22, as Motive writes it) in
/// millimetres, y up: two hands reaching 300 mm forward (-z in Motive's
/// frame) and 150 mm up at 120 Hz for 2 s, a marker beside them, and the
/// left hand not tracked at frame 10.
fn motive_export() -> String {
    let mut text = String::from(
        "Format Version,1.22,Take Name,Take 1,Capture Frame Rate,120.000000,\
         Rotation Type,Quaternion,Length Units,Millimeters,Coordinate Space,Global\n\n",
    );
    let row = |cells: Vec<String>| format!(",,{}\n", cells.join(","));
    let mut types = vec!["Rigid Body".to_owned(); 14];
    types.extend(vec!["Marker".to_owned(); 3]);
    let mut names = vec!["left_hand".to_owned(); 7];
    names.extend(vec!["right_hand".to_owned(); 7]);
    names.extend(vec!["wrist".to_owned(); 3]);
    let group = |g: &str, n: usize| vec![g.to_owned(); n];
    let groups = [
        group("Rotation", 4),
        group("Position", 3),
        group("Rotation", 4),
        group("Position", 3),
        group("Position", 3),
    ]
    .concat();
    text += &row(types);
    text += &row(names);
    text += &row(vec!["\"1\"".to_owned(); 17]);
    text += &row(groups);
    text += "Frame,Time (Seconds),X,Y,Z,W,X,Y,Z,X,Y,Z,W,X,Y,Z,X,Y,Z\n";
    for i in 0..=240 {
        let t = i as f64 / 120.0;
        let s = mj(t / 2.0);
        let hand = |x: f64| format!("0,0,0,1,{x:.3},{:.3},{:.3}", 1000.0 + 150.0 * s, -300.0 * s);
        let left = if i == 10 {
            ",,,,,,".to_owned()
        } else {
            hand(-200.0)
        };
        text += &format!("{i},{t:.6},{left},{},5,5,5\n", hand(200.0));
    }
    text
}

#[test]
fn a_motive_export_gives_a_demo_per_rigid_body_in_metres() {
    let dir = tmp_path("motive");
    std::fs::create_dir_all(&dir).expect("folder");
    let file = dir.join("take.csv");
    std::fs::write(&file, motive_export()).expect("write");
    let file = file.to_str().expect("path");
    let (out, err) = run(&["info", "--json", "--y-up", file]);
    for said in [
        "a Motive export (format 1.22): rigid bodies left_hand, right_hand \
         (lengths in Millimeters as it declares, read as metres)",
        "skipped 1 asset(s) that are not rigid bodies: wrist",
        "left_hand: 1 of 241 frames without it (not tracked): left out",
    ] {
        assert!(err.contains(said), "{said}: {err}");
    }
    assert!(!err.contains("--y-up (the app's Loading"), "{err}");
    let demos: Value = serde_json::from_str(&out).expect("json");
    let demos = demos.as_array().expect("list");
    let names: Vec<&str> = demos.iter().filter_map(|d| d["name"].as_str()).collect();
    assert_eq!(names, ["take.csv:left_hand", "take.csv:right_hand"]);
    // y up to z up: (x, y, z) -> (-z, -x, y), in metres: 0.3 m forward, 0.15 m up.
    let right = &demos[1];
    let (s, g) = (&right["start"], &right["goal"]);
    let d: Vec<f64> = (0..3)
        .map(|a| g[a].as_f64().unwrap_or(f64::NAN) - s[a].as_f64().unwrap_or(f64::NAN))
        .collect();
    assert!(
        (d[0] - 0.3).abs() < 1e-6 && d[1].abs() < 1e-9 && (d[2] - 0.15).abs() < 1e-6,
        "{d:?}"
    );
    assert_eq!(demos[0]["n_samples"], 240);
    // Without --y-up it is read z-up, and said.
    let (_, err) = run(&["info", file]);
    assert!(
        err.contains("Motive exports y-up unless set otherwise: --y-up"),
        "{err}"
    );
}
