//! The gains taken to a robot, at the process boundary: `regen` at a new
//! start, goal and duration, the `dmpscope.dmp` JSON export run by the
//! reference runner `examples/run_dmp.py` and checked against its JSON
//! Schema, the ROS 2 trajectories in the MCAP export decoded back, and bad
//! targets refused by name.

mod support;

use std::process::Command;

use dmpscope_core::export::ros_traj::{MULTI_DOF_NAME, PATH_NAME, decode_multi_dof, decode_path};
use serde_json::Value;
use support::{dmpscope, repo, text};

fn tmp(name: &str) -> String {
    support::tmp_path(name).display().to_string()
}

fn sample() -> String {
    support::sample_path().display().to_string()
}

#[track_caller]
fn ok(args: &[&str]) -> String {
    let out = dmpscope(args);
    assert!(
        out.status.success(),
        "dmpscope {args:?} failed: {}",
        text(&out.stderr)
    );
    text(&out.stdout)
}

const GAINS: [&str; 4] = ["--dm", "25", "--km", "156.25"];

/// `regen` of the planted sample's demo 1 at CartesianDMP's gains to a new
/// goal orientation, written to `out`.
fn planted_to_a_goal_orientation(out: &str, extra: &[&str]) -> Vec<String> {
    let planted = repo().join("assets/planted8.mcap").display().to_string();
    let mut args: Vec<String> = [
        "regen",
        &planted,
        "--dm",
        "25",
        "--km",
        "156.25",
        "--demo",
        "1",
        "--goal-orientation",
        "0.3",
        "0.1",
        "0.2",
        "0.9",
        "--out",
        out,
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    args.extend(extra.iter().map(|s| s.to_string()));
    args
}

fn regen(extra: &[&str]) -> Vec<String> {
    let mut args: Vec<String> = vec!["regen".into(), sample()];
    args.extend(GAINS.iter().map(|s| s.to_string()));
    args.extend(extra.iter().map(|s| s.to_string()));
    args
}

fn run(args: &[String]) -> String {
    let refs: Vec<&str> = args.iter().map(String::as_str).collect();
    ok(&refs)
}

fn json(path: &str) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).expect("export")).expect("valid JSON")
}

fn triple(v: &Value) -> [f64; 3] {
    std::array::from_fn(|i| v[i].as_f64().expect("number"))
}

/// The Python that runs the reference runner: `DMPSCOPE_PYTHON`, else
/// `python3`. `None` (the test then says it did not run) only outside CI:
/// under CI a missing NumPy is a failure.
fn python_with(modules: &str) -> Option<String> {
    let python = std::env::var("DMPSCOPE_PYTHON").unwrap_or_else(|_| "python3".into());
    let works = Command::new(&python)
        .args(["-c", &format!("import {modules}")])
        .output()
        .is_ok_and(|o| o.status.success());
    if works {
        return Some(python);
    }
    assert!(
        std::env::var_os("CI").is_none(),
        "CI needs {python} with {modules} (apt: python3-numpy python3-jsonschema)"
    );
    eprintln!("NOT RUN here: {python} lacks {modules}");
    None
}

/// Writes demo 1's export to a new start, goal and duration, and the skill's to a new goal.
fn write_a_demo_and_a_skill_export(demo: &str, skill: &str) {
    run(&regen(&[
        "--demo",
        "1",
        "--start",
        "0.30",
        "-0.25",
        "0.95",
        "--goal",
        "0.45",
        "0.3",
        "0.9",
        "--duration",
        "2",
        "--out",
        demo,
    ]));
    run(&regen(&[
        "--skill",
        "--scaling",
        "frame",
        "--goal",
        "0.2",
        "0.3",
        "1.1",
        "--out",
        skill,
    ]));
}

/// Writes the oriented export and checks its rollout starts at the new orientation.
fn write_and_check_the_oriented_export(oriented: &str) {
    run(&planted_to_a_goal_orientation(oriented, &[]));
    let od = json(oriented);
    let q = od["rollout"]["q"].as_array().expect("rollout.q");
    assert_eq!(q.len(), 1001);
    assert_eq!(
        q[0], od["orientation"]["q0_new"],
        "starts exactly at q0_new"
    );
    assert!(od["gains"]["settling_time_s"].as_f64().expect("settling") > 0.0);
}

/// Checks the demo's export: its header, real-time gains, target and rollout.
fn check_the_demo_export(demo: &str) -> Value {
    let doc = json(demo);
    assert_eq!(doc["schema"], "dmpscope.dmp");
    assert_eq!(doc["version"], 2);
    assert_eq!(doc["source"], "demo");
    assert_eq!(doc["tau"].as_f64(), Some(2.0));
    assert_eq!(doc["gains"]["real_time"]["d"].as_f64(), Some(12.5));
    assert_eq!(doc["gains"]["real_time"]["k"].as_f64(), Some(156.25 / 4.0));
    assert_eq!(triple(&doc["y0_new"]), [0.30, -0.25, 0.95]);
    assert_eq!(triple(&doc["g_new"]), [0.45, 0.3, 0.9]);
    let y = doc["rollout"]["y"].as_array().expect("y");
    assert_eq!(y.len(), 1001);
    // Exactly at the new start.
    assert_eq!(triple(&y[0]), [0.30, -0.25, 0.95]);
    let t = doc["rollout"]["t"].as_array().expect("t");
    assert_eq!(t[0].as_f64(), Some(0.0));
    assert!((t[1000].as_f64().expect("t") - 2.0).abs() < 1e-12);
    doc
}

/// Checks the skill's export: its source, demos, scaling and band.
fn check_the_skill_export(skill: &str) {
    let sk = json(skill);
    assert_eq!(sk["source"], "skill");
    assert_eq!(sk["demos"].as_array().expect("demos").len(), 10);
    assert_eq!(sk["scaling"]["mode"], "frame");
    assert_eq!(sk["rollout_sd"].as_array().expect("band").len(), 1001);
}

/// The reference runner runs the three exports and says each is ok.
fn the_runner_accepts_the_exports(python: &str, runner: &std::path::Path, exports: [&str; 3]) {
    let out = Command::new(python)
        .arg(runner)
        .args(exports)
        .output()
        .expect("run the runner");
    assert!(
        out.status.success(),
        "run_dmp.py: {}{}",
        text(&out.stdout),
        text(&out.stderr)
    );
    assert!(
        text(&out.stdout).contains(" q="),
        "the runner checks rollout.q"
    );
    assert_eq!(
        text(&out.stdout).matches(" ok").count(),
        3,
        "{}",
        text(&out.stdout)
    );
}

/// The reference runner fails the demo's export with one rollout value perturbed.
fn the_runner_refuses_a_perturbed_rollout(python: &str, runner: &std::path::Path, doc: &Value) {
    // A runner that cannot tell a wrong rollout from a right one is no
    // check: a perturbed golden value must fail it.
    let mut bad = doc.clone();
    let v = bad["rollout"]["y"][500][1].as_f64().expect("y");
    bad["rollout"]["y"][500][1] = Value::from(v + 1e-6);
    let bad_path = tmp("perturbed.json");
    std::fs::write(&bad_path, bad.to_string()).expect("write");
    let out = Command::new(python)
        .arg(runner)
        .arg(&bad_path)
        .output()
        .expect("run the runner");
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stdout));
}

/// The three exports validate against the `dmpscope.dmp` JSON Schema.
fn the_exports_fit_the_schema(python: &str, exports: [&str; 3]) {
    let schema = repo().join("docs/dmpscope.dmp.schema.json");
    let check = "import json, sys, jsonschema\n\
         s = json.load(open(sys.argv[1]))\n\
         for f in sys.argv[2:]: jsonschema.validate(json.load(open(f)), s)\n";
    let out = Command::new(python)
        .args(["-c", check])
        .arg(&schema)
        .args(exports)
        .output()
        .expect("validate");
    assert!(out.status.success(), "schema: {}", text(&out.stderr));
}

#[test]
fn the_json_export_runs_in_the_reference_runner_and_fits_its_schema() {
    let demo = tmp("demo.json");
    let skill = tmp("skill.json");
    write_a_demo_and_a_skill_export(&demo, &skill);
    // A demo with orientation (the planted sample) to a new goal orientation.
    let oriented = tmp("oriented.json");
    write_and_check_the_oriented_export(&oriented);
    let doc = check_the_demo_export(&demo);
    check_the_skill_export(&skill);

    let Some(python) = python_with("numpy") else {
        return;
    };
    let runner = repo().join("examples/run_dmp.py");
    the_runner_accepts_the_exports(&python, &runner, [&demo, &skill, &oriented]);
    the_runner_refuses_a_perturbed_rollout(&python, &runner, &doc);

    let Some(python) = python_with("jsonschema") else {
        return;
    };
    the_exports_fit_the_schema(&python, [&demo, &skill, &oriented]);
}

#[test]
fn bad_targets_are_refused_naming_the_argument_and_nothing_is_written() {
    let out_path = tmp("never.json");
    let cases: [(&[&str], &str); 7] = [
        (
            &[
                "--demo", "1", "--start", "0.3", "0.2", "1", "--goal", "0.3", "0.2", "1",
            ],
            "the goal (--goal) equals the start (--start)",
        ),
        (&["--demo", "1", "--duration", "0"], "--duration"),
        (&["--demo", "1", "--duration", "-2"], "--duration"),
        (&["--demo", "1", "--duration", "nan"], "--duration"),
        (&["--demo", "0"], "--demo must be between 1 and 10"),
        (&["--demo", "11"], "--demo must be between 1 and 10, got 11"),
        (&[], "pass --demo N (1-based) or --skill"),
    ];
    for (extra, message) in cases {
        let mut args = regen(extra);
        args.extend(["--out".to_owned(), out_path.clone()]);
        let refs: Vec<&str> = args.iter().map(String::as_str).collect();
        let out = dmpscope(&refs);
        assert!(!out.status.success(), "{extra:?} was accepted");
        let err = text(&out.stderr);
        assert!(err.contains(message), "{extra:?}: {err}");
        assert!(!err.contains("panicked"), "{err}");
        assert!(!std::path::Path::new(&out_path).exists());
    }
}

/// The generalised rollout of the JSON export: times, positions, velocities, accelerations.
struct Rollout {
    t: Vec<f64>,
    y: Vec<[f64; 3]>,
    v: Vec<[f64; 3]>,
    a: Vec<[f64; 3]>,
}

/// Writes the same target's export to the MCAP and to the JSON path.
fn export_one_target_twice(target: &[&str], mcap_path: &str, json_path: &str) {
    let mut args = regen(target);
    args.extend(["--out".into(), mcap_path.to_owned()]);
    run(&args);
    let mut args = regen(target);
    args.extend(["--out".into(), json_path.to_owned()]);
    run(&args);
}

/// Reads the rollout of the JSON export at `json_path`.
fn read_the_json_rollout(json_path: &str) -> Rollout {
    let doc = json(json_path);
    let rows = |key: &str| -> Vec<[f64; 3]> {
        doc["rollout"][key]
            .as_array()
            .expect("rows")
            .iter()
            .map(triple)
            .collect()
    };
    let (y, v, a) = (rows("y"), rows("v"), rows("a"));
    let t: Vec<f64> = doc["rollout"]["t"]
        .as_array()
        .expect("t")
        .iter()
        .map(|v| v.as_f64().expect("t"))
        .collect();
    Rollout { t, y, v, a }
}

/// Checks the nav_msgs/Path message against the rollout and returns its topic.
fn check_the_path_message(
    message: &mcap::Message<'_>,
    schema: &mcap::Schema<'_>,
    rollout: &Rollout,
) -> String {
    let (t, y) = (&rollout.t, &rollout.y);
    let topic = message.channel.topic.clone();
    assert_eq!(topic, "/dmp/reach10_demo_03/path");
    assert_eq!(message.channel.message_encoding, "cdr");
    assert_eq!(schema.encoding, "ros2msg");
    let (stamp, frame, poses) = decode_path(&message.data).expect("Path");
    assert_eq!(frame, "world");
    assert_eq!(poses.len(), 1001);
    for (k, (s, p, q)) in poses.iter().enumerate() {
        assert_eq!(*p, y[k], "pose {k}");
        assert_eq!(*q, [0.0, 0.0, 0.0, 1.0], "no orientation: the identity");
        assert_eq!(*s, stamp + (t[k] * 1e9).round() as i64);
    }
    topic
}

/// Checks the MultiDOFJointTrajectory message against the rollout and returns its topic.
fn check_the_trajectory_message(message: &mcap::Message<'_>, rollout: &Rollout) -> String {
    let Rollout { t, y, v, a } = rollout;
    let topic = message.channel.topic.clone();
    assert_eq!(topic, "/dmp/reach10_demo_03/trajectory");
    let traj = decode_multi_dof(&message.data).expect("trajectory");
    assert_eq!(traj.joint, "end_effector");
    assert_eq!(
        (traj.y.len(), traj.v.len(), traj.a.len()),
        (1001, 1001, 1001)
    );
    assert_eq!(
        (traj.y.clone(), traj.v.clone(), traj.a.clone()),
        (y.clone(), v.clone(), a.clone())
    );
    for (k, tk) in traj.t.iter().enumerate() {
        assert!((tk - t[k]).abs() <= 1e-9, "time_from_start {k}");
    }
    assert!(traj.orientation.is_none(), "reach10 has no orientation");
    topic
}

/// Checks the MCAP's two trajectory messages against the rollout.
fn check_the_mcap_messages(mcap_path: &str, rollout: &Rollout) {
    let bytes = std::fs::read(mcap_path).expect("mcap");
    let mut seen = Vec::new();
    for message in mcap::MessageStream::new(&bytes).expect("mcap") {
        let message = message.expect("message");
        let schema = message.channel.schema.as_ref().expect("schema");
        match schema.name.as_str() {
            PATH_NAME => seen.push(check_the_path_message(&message, schema, rollout)),
            MULTI_DOF_NAME => seen.push(check_the_trajectory_message(&message, rollout)),
            _ => {}
        }
    }
    assert_eq!(seen.len(), 2, "{seen:?}");
}

/// `info` reads the MCAP export back as demonstrations.
fn info_reads_the_export_back(mcap_path: &str) {
    // Loading the export gives back the ten demos and says what it skipped.
    let out = dmpscope(&["info", mcap_path]);
    assert!(out.status.success());
    let said = format!("{}{}", text(&out.stdout), text(&out.stderr));
    assert!(said.contains("10 demonstrations"), "{said}");
    assert!(text(&out.stderr).contains("a trajectory dmpscope exported"));
}

#[test]
fn the_mcap_export_holds_ros_trajectories_that_decode_back() {
    let mcap_path = tmp("robot.mcap");
    let json_path = tmp("robot.json");
    let target = [
        "--demo",
        "3",
        "--goal",
        "0.5",
        "0.1",
        "1.2",
        "--duration",
        "1.5",
    ];
    export_one_target_twice(&target, &mcap_path, &json_path);
    let rollout = read_the_json_rollout(&json_path);
    check_the_mcap_messages(&mcap_path, &rollout);
    info_reads_the_export_back(&mcap_path);
}

#[test]
fn the_csv_of_a_generalised_path_is_in_real_time() {
    let csv = tmp("moved.csv");
    let summary = run(&regen(&[
        "--demo",
        "2",
        "--start",
        "0.1",
        "0.2",
        "0.3",
        "--goal",
        "0.4",
        "0.6",
        "0.1",
        "--duration",
        "4",
        "--scaling",
        "frame",
        "--out",
        &csv,
    ]));
    assert!(summary.contains("v_max [m/s]"), "{summary}");
    let body = std::fs::read_to_string(&csv).expect("csv");
    let lines: Vec<&str> = body.lines().collect();
    assert_eq!(lines.len(), 1 + 1001);
    assert!(lines[0].starts_with("demo,s,t_s,x,y,z,demo_x,demo_y,demo_z,vx,vy,vz,ax,ay,az"));
    let first: Vec<&str> = lines[1].split(',').collect();
    assert_eq!(&first[3..6], ["0.1", "0.2", "0.3"]);
    // Moved paths have no demo to compare with.
    assert_eq!(&first[6..9], ["", "", ""]);
    let last: Vec<&str> = lines[1001].split(',').collect();
    assert!((last[2].parse::<f64>().expect("t") - 4.0).abs() < 1e-12);
}

#[test]
fn the_ros_trajectories_of_an_oriented_path_carry_its_orientation() {
    // The planted sample's demos have orientations: the Path's poses and
    // the MultiDOFJointTrajectory's rotations are the DMP's, its angular
    // velocity and acceleration the unit-time ones over the duration.
    let (mcap_path, json_path) = (tmp("oriented_ros.mcap"), tmp("oriented_ros.json"));
    let args = |out: &str| planted_to_a_goal_orientation(out, &["--duration", "2.0"]);
    run(&args(&mcap_path));
    run(&args(&json_path));
    let doc = json(&json_path);
    let q_doc: Vec<Vec<f64>> = doc["rollout"]["q"]
        .as_array()
        .expect("rollout.q")
        .iter()
        .map(|q| {
            q.as_array()
                .expect("q")
                .iter()
                .map(|c| c.as_f64().expect("c"))
                .collect()
        })
        .collect();
    let bytes = std::fs::read(&mcap_path).expect("mcap");
    let mut seen = 0;
    for message in mcap::MessageStream::new(&bytes).expect("mcap") {
        let message = message.expect("message");
        let schema = message.channel.schema.as_ref().expect("schema");
        match schema.name.as_str() {
            PATH_NAME => {
                let (_, _, poses) = decode_path(&message.data).expect("Path");
                for (k, (_, _, q)) in poses.iter().enumerate() {
                    assert_eq!(q.to_vec(), q_doc[k], "pose {k}'s orientation");
                }
                seen += 1;
            }
            MULTI_DOF_NAME => {
                let traj = decode_multi_dof(&message.data).expect("trajectory");
                let o = traj.orientation.expect("an orientation");
                for (k, q) in o.q.iter().enumerate() {
                    assert_eq!(q.to_vec(), q_doc[k], "rotation {k}");
                }
                let speed = |w: &[f64; 3]| w.iter().map(|c| c * c).sum::<f64>().sqrt();
                let fastest = o.w.iter().map(speed).fold(0.0, f64::max);
                assert!(fastest > 0.1, "the angular velocity is there: {fastest}");
                let norm = |q: &[f64; 4]| q.iter().map(|c| c * c).sum::<f64>().sqrt();
                assert!(o.q.iter().all(|q| (norm(q) - 1.0).abs() < 1e-12));
                seen += 1;
            }
            _ => {}
        }
    }
    assert_eq!(seen, 2);
}
