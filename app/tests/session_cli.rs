//! The session against the CLI: for the same files and options both give
//! the same demos and bit-identical numbers (here, beside the binary; the
//! session's own tests are in `session/tests/`).

mod support;

use dmpscope::session::{Command, Runner, Session, Settings, Source, Status};
use dmpscope_core::load::options::UpAxis;
use serde_json::Value;
use support::{dmpscope, repo, rosbag2_folder, text, tmp_path};

fn session_on(sources: Vec<Source>, settings: &Settings) -> Session {
    let mut s = Session::new(Runner::inline());
    s.apply(Command::AddSources(sources));
    s.update(settings);
    s
}

#[test]
fn the_session_and_the_cli_give_the_same_demos_and_numbers() {
    // A split rosbag2 recording, y-up, with a topic too short for a demo,
    // and settings away from the defaults.
    let bag = rosbag2_folder("same", &[(0, 3), (3, 5)], true);
    let bag_arg = bag.to_str().expect("path");
    let out = tmp_path("same.json");
    let result = dmpscope(&[
        "landscape",
        bag_arg,
        "--y-up",
        "--sg-window",
        "23",
        "--basis",
        "60",
        "--grid",
        "8",
        "--km-range",
        "0.5",
        "800",
        "--unusable",
        "skip",
        "--out",
        out.to_str().expect("path"),
    ]);
    assert!(result.status.success(), "{}", text(&result.stderr));
    assert!(
        text(&result.stderr).contains("/aborted"),
        "the CLI names the skipped demo: {}",
        text(&result.stderr)
    );
    let cli: Value =
        serde_json::from_str(&std::fs::read_to_string(&out).expect("json")).expect("valid");

    let mut settings = Settings::with_grid_points(8);
    settings.load.up = UpAxis::YUp;
    settings.prep.sg_window = 23;
    settings.dmp.basis_functions = 60;
    settings.grid.km.lo = 0.5;
    settings.grid.km.hi = 800.0;
    let session = session_on(vec![Source::Path(bag.clone())], &settings);
    assert!(
        session
            .messages()
            .iter()
            .any(|m| m.text.contains("/aborted")),
        "the session names the skipped demo: {:?}",
        session.messages()
    );
    let model = session.model().expect("model");
    let names: Vec<&str> = model.demos().iter().map(|d| d.name.as_str()).collect();
    let cli_names: Vec<&str> = cli["demos"]
        .as_array()
        .expect("demos")
        .iter()
        .map(|d| d["name"].as_str().expect("name"))
        .collect();
    assert_eq!(names, cli_names);
    assert_eq!(names.len(), 5);
    let land = &session.shown().expect("landscape").snapshot.landscape;
    for (key, grid) in [("d_sum", land.d_sum()), ("s", land.s())] {
        let rows: Vec<Vec<f64>> = serde_json::from_value(cli[key].clone()).expect("rows");
        assert_eq!(rows.concat(), *grid, "{key} differs");
    }
    let x = session.extraction().expect("optimum");
    assert_eq!(cli["optimum"]["dm"].as_f64(), Some(x.eval.dm));
    assert_eq!(cli["optimum"]["km"].as_f64(), Some(x.eval.km));
    assert_eq!(cli["optimum"]["j"].as_f64(), Some(x.j));
}

#[test]
fn a_folder_without_usable_demos_says_so_and_what_to_do() {
    let empty = tmp_path("no-recordings");
    std::fs::create_dir_all(&empty).expect("folder");
    let session = session_on(vec![Source::Path(empty)], &Settings::with_grid_points(8));
    assert_eq!(session.status(), Status::NoDemos);
    assert!(
        session
            .messages()
            .iter()
            .any(|m| m.text.contains("holds no .mcap file")),
        "{:?}",
        session.messages()
    );
    assert!(session.status().describe().contains("Open a recording"));

    let short = rosbag2_folder("only-short", &[(0, 0)], true);
    let session = session_on(vec![Source::Path(short)], &Settings::with_grid_points(8));
    match session.status() {
        Status::NoUsableDemo(why) => assert!(why.contains("/aborted"), "{why}"),
        other => panic!("expected no usable demo, got {other:?}"),
    }
}

#[test]
fn the_diagnostics_match_the_cli_and_reach_the_report() {
    let planted = repo().join("assets/planted8.mcap");
    let result = dmpscope(&[
        "extract",
        planted.to_str().expect("path"),
        "--grid",
        "16",
        "--bootstrap",
        "12",
        "--diag-grid",
        "8",
        "--json",
    ]);
    assert!(result.status.success(), "{}", text(&result.stderr));
    let cli: Value = serde_json::from_slice(&result.stdout).expect("json");

    let mut settings = Settings::with_grid_points(16);
    settings.diagnostics.bootstrap = 12;
    settings.diagnostics.grid_points = 8;
    let session = session_on(vec![Source::planted_sample()], &settings);
    let d = session.diagnostics().expect("diagnostics");
    assert!(d.complete() && !session.busy());
    assert_eq!(
        serde_json::to_value(&d.diagnostics).expect("json"),
        cli["diagnostics"]
    );
    assert_eq!(d.cloud.len(), 12);
    let report = serde_json::to_value(session.report().expect("report")).expect("json");
    assert_eq!(report["diagnostics"], cli["diagnostics"]);
    // The shares at the operating point sum to one, one per demo.
    let shares = session.point_shares().expect("shares");
    assert_eq!(shares.len(), 8);
    assert!((shares.iter().sum::<f64>() - 1.0).abs() < 1e-12);
    let terms = session.forcing_terms().expect("forcing terms");
    assert_eq!(terms.f.len(), 8);
    assert!(terms.sigma.iter().all(|v| v.is_finite()));
}
