//! End-to-end tests of the recording paths at the process boundary:
//! export (MCAP that loads back; the DMP JSON is in cli_export.rs), segmentation of one take, the
//! axis convention, CSV input, streams split at clock jumps and
//! dropouts, and a TF bag's unusable streams skipped with their reasons.

mod support;

use serde_json::Value;
use support::{dmpscope, text};

fn sample() -> String {
    support::sample_path().display().to_string()
}

fn ok(args: &[&str]) -> String {
    let out = dmpscope(args);
    assert!(
        out.status.success(),
        "dmpscope {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn tmp(name: &str) -> String {
    support::tmp_path(name).display().to_string()
}

#[test]
fn regen_exports_an_mcap_that_loads_back_as_demos_and_paths() {
    let out = tmp("export.mcap");
    ok(&[
        "regen",
        &sample(),
        "--dm",
        "25",
        "--km",
        "156.25",
        "--out",
        &out,
    ]);
    let names_of = |args: &[&str]| -> Vec<String> {
        let info: Value = serde_json::from_str(&ok(args)).expect("json");
        info.as_array()
            .expect("list")
            .iter()
            .map(|d| d["name"].as_str().expect("name").to_owned())
            .collect()
    };
    // The demos come back under their own names; the regenerated paths are
    // not demonstrations unless asked for.
    let names = names_of(&["info", "--json", &out]);
    let original = names_of(&["info", "--json", &sample()]);
    assert_eq!(names, original);
    let regen = names_of(&["info", "--json", &out, "--topic", "/regen/*"]);
    assert_eq!(regen.len(), 10, "{regen:?}");
    assert!(
        regen.contains(&"reach10.mcap:/demo_10 (regenerated)".to_owned()),
        "{regen:?}"
    );
    let bytes = std::fs::read(&out).expect("export");
    let text = String::from_utf8_lossy(&bytes);
    for needle in ["foxglove.PoseInFrame", "jsonschema", "dmpscope", "156.25"] {
        assert!(text.contains(needle), "export lacks {needle}");
    }
}

#[test]
fn one_take_is_segmented_into_its_reaches() {
    // Ten demos written on one topic, back to back in time, make one take.
    let take = tmp("take.mcap");
    let csv = tmp("take.csv");
    ok(&[
        "regen",
        &sample(),
        "--dm",
        "25",
        "--km",
        "156.25",
        "--out",
        &csv,
    ]);
    // Build a CSV take from the regenerated paths of demo 1..3 with rests.
    let body = std::fs::read_to_string(&csv).expect("csv");
    let mut rows = vec!["t,x,y,z".to_owned()];
    let mut t = 0.0;
    for demo in [
        "reach10.mcap:/demo_01",
        "reach10.mcap:/demo_02",
        "reach10.mcap:/demo_03",
    ] {
        let path: Vec<Vec<f64>> = body
            .lines()
            .filter(|l| l.starts_with(demo))
            .map(|l| {
                l.split(',')
                    .skip(3)
                    .take(3)
                    .map(|v| v.parse().expect("number"))
                    .collect()
            })
            .step_by(10)
            .collect();
        let rest = |p: &Vec<f64>, t: &mut f64, rows: &mut Vec<String>| {
            for _ in 0..60 {
                rows.push(format!("{t:.6},{},{},{}", p[0], p[1], p[2]));
                *t += 0.011;
            }
        };
        rest(&path[0], &mut t, &mut rows);
        for p in &path {
            rows.push(format!("{t:.6},{},{},{}", p[0], p[1], p[2]));
            t += 0.011;
        }
        rest(&path[path.len() - 1], &mut t, &mut rows);
    }
    std::fs::write(&take, rows.join("\n")).expect("write take");
    let take_csv = take.replace(".mcap", "-take.csv");
    std::fs::rename(&take, &take_csv).expect("rename");
    let listing = ok(&["info", "--segment", &take_csv]);
    assert!(listing.contains("(3 segments)"), "{listing}");
    let demos: Value =
        serde_json::from_str(&ok(&["info", "--json", "--demos", "segment", &take_csv]))
            .expect("json");
    let names: Vec<&str> = demos
        .as_array()
        .expect("list")
        .iter()
        .map(|d| d["name"].as_str().expect("name"))
        .collect();
    assert_eq!(names.len(), 3, "{names:?}");
    assert!(names[2].ends_with("#3"), "{names:?}");
    // And the three segments are demos the method runs on.
    let extract = ok(&["extract", "--demos", "segment", &take_csv, "--grid", "8"]);
    assert!(extract.starts_with("(M:D:K) = 1 : "), "{extract}");
}

#[test]
fn y_up_recordings_are_turned_to_z_up() {
    let z_up: Value = serde_json::from_str(&ok(&["info", "--json", &sample()])).expect("json");
    let y_up: Value =
        serde_json::from_str(&ok(&["info", "--json", "--y-up", &sample()])).expect("json");
    let (a, b) = (&z_up[0]["start"], &y_up[0]["start"]);
    // (x, y, z) y-up -> (-z, -x, y) z-up.
    assert_eq!(b[0].as_f64(), a[2].as_f64().map(|v| -v));
    assert_eq!(b[1].as_f64(), a[0].as_f64().map(|v| -v));
    assert_eq!(b[2].as_f64(), a[1].as_f64());
}

#[test]
fn a_bad_csv_row_is_named() {
    let bad = tmp("bad.csv");
    std::fs::write(&bad, "t,x,y,z\n0,0,0,0\n0.01,0.1,oops,0\n").expect("write");
    let out = dmpscope(&["info", &bad]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("bad.csv") && err.contains("sample 1"), "{err}");
}

/// Two reaches of the sample generator written as one topic, the second's
/// clock `shift_ns` after (negative: before) the first's end.
fn two_reaches_on_one_topic(name: &str, shift_ns: i64) -> String {
    use dmpscope_core::export::write::{TopicSamples, write_pose_stamped};
    let demos = dmpscope_core::synth::vive::reach_demos(3, 2, 1_700_000_000_000_000_000);
    let first = &demos[0].samples;
    let end = first.last().expect("samples").0;
    let start = demos[1].samples[0].0;
    let mut samples = first.clone();
    samples.extend(
        demos[1]
            .samples
            .iter()
            .map(|&(t, p)| (t - start + end + shift_ns, p)),
    );
    let path = tmp(name);
    let out = std::fs::File::create(&path).expect("file");
    let topics = [TopicSamples {
        orientations: None,
        topic: "/hand",
        frame_id: "world",
        samples: &samples,
    }];
    write_pose_stamped(std::io::BufWriter::new(out), &topics, true).expect("write");
    path
}

#[test]
fn a_clock_jump_or_a_dropout_splits_the_stream_and_says_where() {
    // The clock jumps back an hour between the two reaches.
    let jump = two_reaches_on_one_topic("jump.mcap", -3_600_000_000_000);
    let result = dmpscope(&["info", &jump]);
    assert!(result.status.success(), "{}", text(&result.stderr));
    let (out, err) = (text(&result.stdout), text(&result.stderr));
    assert!(err.contains("/hand: the clock jumps back 3600."), "{err}");
    assert!(err.contains("split into 2 demos"), "{err}");
    assert!(
        out.contains("/hand part 1/2") && out.contains("/hand part 2/2"),
        "{out}"
    );
    // A 0.5 s dropout: split too, or bridged with a warning on request.
    let gap = two_reaches_on_one_topic("dropout.mcap", 500_000_000);
    let split = dmpscope(&["info", &gap]);
    assert!(
        text(&split.stderr).contains("a 0.5"),
        "{}",
        text(&split.stderr)
    );
    assert!(text(&split.stdout).contains("part 2/2"));
    let kept = dmpscope(&["info", &gap, "--gaps", "keep"]);
    assert!(
        text(&kept.stderr).contains("bridged"),
        "{}",
        text(&kept.stderr)
    );
    assert!(!text(&kept.stdout).contains("part 2/2"));
    // Each part is judged as a demo of its own: the landscape runs.
    let extracted = dmpscope(&["extract", &jump, "--grid", "8", "--no-diagnostics"]);
    assert!(extracted.status.success(), "{}", text(&extracted.stderr));
}

#[test]
fn a_tf_bag_recorded_with_everything_gives_its_moving_streams_and_says_why_not_the_rest() {
    let bag = tmp("tfbag.mcap");
    std::fs::write(&bag, support::tf_bag_bytes()).expect("write");
    let out = dmpscope(&["extract", &bag, "--grid", "8", "--no-diagnostics"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    for why in [
        "/tf_static:base_link: skipped: its stamp never advances",
        "/tf:shoulder_link: skipped: it does not move (its positions span 0.0 mm",
    ] {
        assert!(err.contains(why), "stderr names {why}: {err}");
    }
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("/tf:tracker") && stdout.contains("/hand"),
        "{stdout}"
    );
    // --topic and --exclude choose.
    let info: Value = serde_json::from_str(&ok(&[
        "info",
        "--json",
        &bag,
        "--topic",
        "/tf",
        "--exclude",
        "*shoulder*",
    ]))
    .expect("json");
    let names: Vec<&str> = info
        .as_array()
        .expect("list")
        .iter()
        .map(|d| d["name"].as_str().expect("name"))
        .collect();
    assert_eq!(names, ["tfbag.mcap:/tf:tracker"]);
    // Nothing usable left: the command fails and says what was skipped.
    let out = dmpscope(&["extract", &bag, "--exclude", "/tf", "--exclude", "/hand"]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("no demonstration found: every stream was skipped"),
        "{err}"
    );
    // --frame matching nothing names the frames there are.
    let out = dmpscope(&["info", &bag, "--frame", "elbow"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains(
            "--frame elbow matches no frame here; the frames are: base_link, shoulder_link, tracker"
        ),
        "{err}"
    );
}
