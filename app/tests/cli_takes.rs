//! Demos as people record them (issue 44): reach-and-return trials whose
//! hand did not pause at the far end (the loop notice, `--cut farthest`),
//! and one continuous take of reaches to several goals and returns home
//! (`--segments out|back`).

mod support;

use serde_json::Value;
use support::takes::{HOME, Take, goal, trials, write};
use support::{dmpscope, text};

fn distance(a: &Value, b: &Value) -> f64 {
    (0..3)
        .map(|ax| (a[ax].as_f64().expect("x") - b[ax].as_f64().expect("x")).powi(2))
        .sum::<f64>()
        .sqrt()
}

fn info(args: &[&str]) -> (Vec<Value>, String) {
    let out = dmpscope(&[&["info", "--json"], args].concat());
    assert!(out.status.success(), "{}", text(&out.stderr));
    let demos: Vec<Value> = serde_json::from_slice(&out.stdout).expect("json");
    (demos, text(&out.stderr))
}

#[test]
fn out_and_back_trials_without_a_pause_are_said_and_cut_at_their_farthest_point() {
    // Six reach-to-grasp trials; in trials 3 and 6 the hand did not pause
    // at the object.
    let path = trials("trials.mcap");
    let first = ["--demos", "segment", "--segments", "first"];
    let (demos, notes) = info(&[&[path.as_str()][..], &first].concat());
    assert_eq!(demos.len(), 6);
    assert!(notes.contains("trials.mcap:/trial_3"), "{notes}");
    assert!(notes.contains("trials.mcap:/trial_6"), "{notes}");
    assert!(notes.contains("--cut farthest"), "{notes}");
    assert!(!notes.contains("trials.mcap:/trial_1 "), "{notes}");
    // Cut at the farthest point, every trial is its reach: from home to
    // the object, 0.35 m.
    let (cut, notes) = info(&[&[path.as_str()][..], &first, &["--cut", "farthest"]].concat());
    for (i, d) in cut.iter().enumerate() {
        let reach = distance(&d["start"], &d["goal"]);
        assert!((reach - 0.35).abs() < 0.01, "{d}");
        // Only the loops are cut (and said); the reaches that rested at the
        // object already end at their farthest point.
        let said = notes.contains(&format!("/trial_{}#1: cut at its farthest point", i + 1));
        assert_eq!(said, i == 2 || i == 5, "{notes}");
    }
}

#[test]
fn a_take_of_reaches_and_returns_gives_the_reaches_out_and_the_returns_back() {
    let mut take = Take::new(9);
    take.rest(1.0, HOME);
    for i in 0..8 {
        take.mv(HOME, goal(i), 1.0);
        take.rest(0.5, goal(i));
        take.mv(goal(i), HOME, 1.0);
        take.rest(0.8, HOME);
    }
    let path = write("take.mcap", &[("/tracker".to_owned(), take.samples)]);
    let segment = |which: &str| info(&[path.as_str(), "--demos", "segment", "--segments", which]).0;
    assert_eq!(segment("all").len(), 16);
    let out = segment("out");
    assert_eq!(out.len(), 8);
    for (i, d) in out.iter().enumerate() {
        let g = Value::from(goal(i).to_vec());
        let h = Value::from(HOME.to_vec());
        assert!(distance(&d["start"], &h) < 0.02, "{d}");
        assert!(distance(&d["goal"], &g) < 0.02, "{d}");
    }
    let back = segment("back");
    assert_eq!(back.len(), 8);
    for (i, d) in back.iter().enumerate() {
        let g = Value::from(goal(i).to_vec());
        let h = Value::from(HOME.to_vec());
        assert!(distance(&d["start"], &g) < 0.02, "{d}");
        assert!(distance(&d["goal"], &h) < 0.02, "{d}");
    }
}
