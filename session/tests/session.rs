//! The session driven headless and synchronously (no egui, no sleeps): each
//! setting recomputes exactly its stages. (Its agreement with the CLI is
//! tested beside the binary, `app/tests/session_cli.rs`.)

use std::path::{Path, PathBuf};

use dmpscope_core::geom::Vec3;
use dmpscope_core::load::options::Grouping;
use dmpscope_core::load::options::UpAxis;
use dmpscope_session::{Command, Runner, Session, Settings, Source, StageRuns, Status};

/// The repository root.
fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn session_on(sources: Vec<Source>, settings: &Settings) -> Session {
    let mut s = Session::new(Runner::inline());
    s.apply(Command::AddSources(sources));
    s.update(settings);
    s
}

/// What changed in the stage counters between two readings.
fn delta(before: StageRuns, after: StageRuns) -> [usize; 8] {
    [
        after.loads - before.loads,
        after.groupings - before.groupings,
        after.models - before.models,
        after.landscapes - before.landscapes,
        after.extractions - before.extractions,
        after.diagnostics - before.diagnostics,
        after.tables - before.tables,
        after.points - before.points,
    ]
}

/// Updates the session to `settings` and checks which stages ran, by name.
fn check(session: &mut Session, settings: &Settings, expect: [usize; 8], what: &str) {
    let before = session.runs();
    session.update(settings);
    assert_eq!(delta(before, session.runs()), expect, "{what}");
    assert!(!session.busy(), "{what}: inline jobs finish in the update");
}

/// The sample's session on `settings`, checked ready with its ten demos.
fn a_ready_sample_session(settings: &Settings) -> Session {
    let session = session_on(vec![Source::sample()], settings);
    assert_eq!(session.status(), Status::Ready);
    assert!(session.extraction().is_some());
    assert_eq!(session.model().map(|m| m.demos().len()), Some(10));
    session
}

/// The settings after the landscape: the operating point, k, the bootstrap, the limit.
fn the_settings_after_the_landscape(session: &mut Session, settings: &mut Settings) {
    //                                  loads group model land  extr diag table point
    check(
        session,
        settings,
        [0, 0, 0, 0, 0, 0, 0, 0],
        "nothing changed",
    );
    settings.op = (12.0, 34.0);
    check(
        session,
        settings,
        [0, 0, 0, 0, 0, 0, 0, 1],
        "the operating point",
    );
    settings.k = 5.0;
    check(session, settings, [0, 0, 0, 0, 1, 1, 0, 0], "k");
    settings.diagnostics.bootstrap = 12;
    check(session, settings, [0, 0, 0, 0, 0, 1, 0, 0], "the bootstrap");
    settings.a_peak_limit = Some(50.0);
    check(
        session,
        settings,
        [0, 0, 0, 0, 0, 0, 0, 0],
        "an a_peak limit",
    );
    assert!(session.constrained().is_some());
}

/// The landscape's grid and the model's settings: the grid, the SG window, the basis, a demo.
fn the_grid_and_model_settings(session: &mut Session, settings: &mut Settings) {
    //                                  loads group model land  extr diag table point
    settings.set_grid_points(9);
    check(session, settings, [0, 0, 0, 1, 1, 1, 0, 0], "the grid");
    settings.grid.km.hi = 2000.0;
    check(session, settings, [0, 0, 0, 1, 1, 1, 0, 0], "the K/M range");
    settings.prep.sg_window = 23;
    check(session, settings, [0, 0, 1, 1, 1, 1, 1, 1], "the SG window");
    settings.dmp.basis_functions = 60;
    check(session, settings, [0, 0, 1, 1, 1, 1, 1, 1], "the basis");
    session.apply(Command::SetIncluded {
        demo: 3,
        included: false,
    });
    check(
        session,
        settings,
        [0, 0, 1, 1, 1, 1, 1, 1],
        "an excluded demo",
    );
    assert_eq!(session.model().map(|m| m.demos().len()), Some(9));
}

/// The load settings: what a demo is, a break in time, the up axis, the frame filter.
fn the_load_settings(session: &mut Session, settings: &mut Settings) {
    //                                  loads group model land  extr diag table point
    settings.load.demos = Grouping::PerFile;
    check(
        session,
        settings,
        [0, 1, 1, 1, 1, 1, 1, 1],
        "what a demo is",
    );
    settings.load.demos = Grouping::PerTopic;
    check(
        session,
        settings,
        [0, 1, 1, 1, 1, 1, 1, 1],
        "back to topics",
    );
    // The sample has no break in time: bridging instead of splitting
    // regroups, and the same demos recompute nothing.
    settings.load.gaps = dmpscope_core::load::options::GapPolicy::Keep;
    check(
        session,
        settings,
        [0, 1, 0, 0, 0, 0, 0, 0],
        "what a break in time does",
    );
    // The excluded demo stays excluded across the regrouping.
    assert_eq!(session.model().map(|m| m.demos().len()), Some(9));
    settings.load.up = UpAxis::YUp;
    check(session, settings, [1, 1, 1, 1, 1, 1, 1, 1], "the up axis");
    // The sample has no TF frames: the filter reads the file again, but
    // the same demos recompute nothing after them.
    settings.load.frames = vec!["hand".into()];
    check(
        session,
        settings,
        [1, 1, 0, 0, 0, 0, 0, 0],
        "the frame filter",
    );
}

/// A whole new settings value, then the same values again.
fn a_whole_new_settings_value(session: &mut Session) {
    // Whatever set them: a whole new settings value (an imported file, a
    // reset) is compared the same way.
    let reset = Settings::with_grid_points(9);
    check(session, &reset, [1, 1, 1, 1, 1, 1, 1, 1], "a reset");
    check(
        session,
        &reset.clone(),
        [0, 0, 0, 0, 0, 0, 0, 0],
        "the same values again",
    );
}

#[test]
fn each_setting_recomputes_exactly_its_stages() {
    let mut settings = Settings::with_grid_points(8);
    let mut session = a_ready_sample_session(&settings);
    the_settings_after_the_landscape(&mut session, &mut settings);
    the_grid_and_model_settings(&mut session, &mut settings);
    the_load_settings(&mut session, &mut settings);
    a_whole_new_settings_value(&mut session);
}

#[test]
fn a_peak_limit_gives_a_constrained_optimum_or_says_none_is_within() {
    let mut settings = Settings::with_grid_points(12);
    settings.diagnostics.bootstrap = 4;
    let mut session = session_on(vec![Source::planted_sample()], &settings);
    let x = session.extraction().expect("optimum").clone();
    let free_peak = x.eval.a_peak.iter().copied().fold(0.0, f64::max);
    let land = &session.shown().expect("landscape").snapshot.landscape;
    let lowest = land.a_peak().iter().copied().fold(f64::INFINITY, f64::min);
    assert!(
        lowest < free_peak,
        "the limit must bind: {lowest} vs {free_peak}"
    );
    let limit = 0.5 * (lowest + free_peak);
    settings.a_peak_limit = Some(limit);
    session.update(&settings);
    let c = session.constrained().expect("computed").expect("within");
    let model = session.model().expect("model");
    let e = model.evaluate(c.dm, c.km);
    let peak = e.a_peak.iter().copied().fold(0.0, f64::max);
    assert!(peak <= limit, "{peak} > {limit}");
    assert!(c.value >= x.j, "a constraint cannot lower J");
    settings.a_peak_limit = Some(1e-9);
    session.update(&settings);
    assert_eq!(session.constrained(), Some(None));
    settings.a_peak_limit = None;
    session.update(&settings);
    assert_eq!(session.constrained(), None);
}

#[test]
fn a_sample_replaces_samples_but_never_the_users_recordings() {
    let settings = Settings::with_grid_points(6);
    let mut session = session_on(vec![Source::sample()], &settings);
    assert_eq!(session.demos().len(), 10);
    session.apply(Command::OpenSample(Source::planted_sample()));
    session.update(&settings);
    assert_eq!(session.sources().count(), 1);
    assert_eq!(session.demos().len(), 8);
    let user = repo().join("assets/reach10.mcap");
    let mut session = session_on(vec![Source::Path(user)], &settings);
    session.apply(Command::OpenSample(Source::planted_sample()));
    session.update(&settings);
    assert_eq!(session.sources().count(), 2);
    assert_eq!(session.demos().len(), 18);
}

#[test]
fn one_demo_says_what_the_diagnostics_need_and_the_rest_works() {
    let mut settings = Settings::with_grid_points(8);
    settings.diagnostics.bootstrap = 5;
    let mut session = session_on(vec![Source::sample()], &settings);
    for demo in 1..10 {
        session.apply(Command::SetIncluded {
            demo,
            included: false,
        });
    }
    session.update(&settings);
    assert_eq!(session.model().map(|m| m.demos().len()), Some(1));
    let d = session.diagnostics().expect("diagnostics");
    assert!(d.complete() && d.cloud.is_empty());
    assert!(
        d.about.notes.iter().any(|n| n.contains("need two or more")),
        "{:?}",
        d.about.notes
    );
    let v = &d.diagnostics;
    assert!(v.s_minimum.is_none() && v.bootstrap.is_none());
    assert!(
        v.demos
            .iter()
            .all(|x| x.s_share.is_none() && x.loo.is_none())
    );
    // depth and sum d still work; nothing is NaN.
    assert!(v.depth.is_some_and(f64::is_finite));
    assert!(session.point_shares().is_none());
    let terms = session.forcing_terms().expect("terms");
    assert!(terms.sigma.iter().all(|&s| s == 0.0));
    assert!(terms.f.iter().flatten().flatten().all(|v| v.is_finite()));
    let report = serde_json::to_string(&session.report().expect("report")).expect("json");
    assert!(!report.contains("NaN"), "{report}");

    // Two demos: leave-one-out and the bootstrap say what they cannot do.
    session.apply(Command::SetIncluded {
        demo: 1,
        included: true,
    });
    session.update(&settings);
    let d = session.diagnostics().expect("diagnostics");
    assert!(d.complete());
    assert!(
        d.about
            .notes
            .iter()
            .any(|n| n.contains("two demonstrations")),
        "{:?}",
        d.about.notes
    );
    assert!(d.diagnostics.bootstrap.is_some());
}

#[test]
fn a_new_target_recomputes_only_the_generalised_run() {
    use dmpscope_core::Scaling;
    use dmpscope_session::{GeneraliseSpec, TargetSource};
    let mut settings = Settings::with_grid_points(8);
    let mut session = session_on(vec![Source::sample()], &settings);
    let step = |session: &mut Session, settings: &Settings| {
        let before = session.runs();
        session.update(settings);
        let after = session.runs();
        (after.generalised - before.generalised, delta(before, after))
    };
    assert!(session.generalised().is_none(), "off until asked for");
    let mut spec = GeneraliseSpec::demo(2);
    session.apply(Command::SetGeneralise(Some(spec)));
    assert_eq!(step(&mut session, &settings), (1, [0; 8]));
    {
        // At its own target: the operating point's path, to the bit.
        let model = session.model().expect("model").clone();
        let g = session.generalised().expect("on").expect("runs");
        let own = &session.paths()[2];
        let p0 = model.demos()[2].p0;
        for (a, b) in g.out.unit.y.iter().zip(&own.y) {
            assert_eq!(*a, b + p0);
        }
    }
    assert_eq!(
        step(&mut session, &settings),
        (0, [0; 8]),
        "nothing changed"
    );
    // A dragged goal: the run only, every frame.
    let goal = session.generalised().expect("on").expect("runs").out.goal;
    spec.target.goal = Some(Vec3::new(goal[0] - 0.1, goal[1], goal[2]));
    session.apply(Command::SetGeneralise(Some(spec)));
    assert_eq!(step(&mut session, &settings), (1, [0; 8]), "a new goal");
    let g = session.generalised().expect("on").expect("runs");
    assert_eq!(g.out.goal, Vec3::new(goal[0] - 0.1, goal[1], goal[2]));
    // New gains: the point and the run.
    settings.op = (12.0, 34.0);
    assert_eq!(
        step(&mut session, &settings),
        (1, [0, 0, 0, 0, 0, 0, 0, 1]),
        "the operating point"
    );
    // A goal on the start is refused in words, not NaN.
    let start = session.generalised().expect("on").expect("runs").out.start;
    spec.target.goal = Some(start);
    session.apply(Command::SetGeneralise(Some(spec)));
    step(&mut session, &settings);
    let err = session.generalised().expect("on").expect_err("refused");
    assert!(err.contains("equals the start"), "{err}");
    // The skill of all demos, frame-independent, with its band.
    spec = GeneraliseSpec {
        source: TargetSource::Skill,
        ..spec.reset()
    };
    spec.target.scaling = Scaling::Frame;
    session.apply(Command::SetGeneralise(Some(spec)));
    step(&mut session, &settings);
    let g = session.generalised().expect("on").expect("runs");
    assert_eq!(g.out.band.len(), 1001);
    assert_eq!(g.forcing_sd.as_ref().map(|sd| sd.len()), Some(1001));
    assert!(g.primitive.name.contains("10 demos"));
    // A new model keeps the target and runs it again.
    session.apply(Command::SetIncluded {
        demo: 0,
        included: false,
    });
    let (runs, _) = step(&mut session, &settings);
    assert_eq!(runs, 1);
    let g = session.generalised().expect("on").expect("runs");
    assert!(g.primitive.name.contains("9 demos"));
    session.apply(Command::SetGeneralise(None));
    step(&mut session, &settings);
    assert!(session.generalised().is_none());
}

#[test]
fn paced_by_frames_the_landscape_starts_a_frame_after_its_model_is_shown() {
    let settings = Settings::default();
    let mut session = Session::new(Runner::inline());
    session.pace_by_frames(true);
    session.apply(Command::AddSources(vec![Source::planted_sample()]));
    session.update(&settings);
    // The model is built (a job of a demo per step: at once, inline); its
    // landscape waits for a frame that shows it.
    let version = session.model_version();
    assert!(version.is_some(), "the model is built");
    assert_eq!(session.runs().landscapes, 0);
    assert!(!session.landscape_running() && session.shown().is_none());
    assert_eq!(
        session.status(),
        Status::Computing(0, 0),
        "it says it computes"
    );
    assert!(session.busy());
    // A frame that drew no model, or another one, does not start it.
    assert!(
        session.frame_shown(None),
        "the caller asks for the next frame"
    );
    session.update(&settings);
    assert_eq!(session.runs().landscapes, 0);
    // The frame that drew it does.
    assert!(session.frame_shown(version));
    session.update(&settings);
    assert_eq!(session.runs().landscapes, 1);
    assert!(
        session.landscape_complete(),
        "inline, the landscape is done"
    );
    assert!(!session.frame_shown(version), "nothing waits any more");
    // A new model's landscape waits again, and the old one is not shown.
    let mut refit = settings.clone();
    refit.dmp.basis_functions += 5;
    session.update(&refit);
    assert_ne!(session.model_version(), version);
    assert!(session.shown().is_none(), "no landscape of the old model");
    assert_eq!(session.runs().landscapes, 1);
    assert!(session.frame_shown(session.model_version()));
    session.update(&refit);
    assert_eq!(session.runs().landscapes, 2);
}

#[test]
fn without_pacing_the_landscape_starts_with_its_model() {
    let session = a_ready_sample_session(&Settings::default());
    assert_eq!(session.runs().landscapes, 1);
    assert!(session.landscape_complete());
}
