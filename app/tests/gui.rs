//! The app driven as a user would (egui_kittest, no renderer): the sample
//! loads, the landscape fills, a preset button moves the operating point, a
//! drag on the J map moves it again, changing k changes J and the optimum
//! without recomputing the landscape, a rosbag2 folder opens, a folder with
//! nothing usable says so, a folder of recordings counts its files, the
//! Recording panel lists skipped streams and a
//! tick there recomputes the landscape. Jobs run inline (`Runner::inline`), so every
//! frame finishes the work it starts and no test sleeps; one test runs the
//! real background threads.

mod support;

use dmpscope::gui::{Command, DmpApp};
use dmpscope::session::{self, Runner, Settings, Source, Status};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

fn harness_on(sources: Vec<Source>, runner: Runner) -> Harness<'static, DmpApp> {
    let settings = Settings::with_grid_points(16);
    let mut h = Harness::builder()
        .with_size([1280.0, 800.0])
        .build_eframe(move |_cc| DmpApp::with_runner(settings, sources, runner));
    h.run_steps(2);
    h
}

fn harness() -> Harness<'static, DmpApp> {
    harness_on(vec![Source::Path(support::sample_path())], Runner::inline())
}

fn operating_point_row(h: &Harness<'_, DmpApp>) -> dmpscope_core::TableRow {
    h.state()
        .session()
        .table_rows()
        .into_iter()
        .find(|r| r.name == "Operating point")
        .expect("an operating-point row")
}

/// Scrolls the side panel down until the node is in the window.
fn scroll_into_view<'h>(
    h: &mut Harness<'h, DmpApp>,
    node: impl for<'a> Fn(&'a Harness<'h, DmpApp>) -> egui_kittest::Node<'a>,
) {
    for _ in 0..20 {
        if node(h).rect().max.y < 780.0 {
            return;
        }
        node(h).scroll_down();
        // Until the scroll's animation ends.
        h.run_steps(10);
    }
    panic!("not scrolled into view: {:?}", node(h).rect());
}

fn add(h: &mut Harness<'_, DmpApp>, sources: Vec<Source>) {
    let ctx = h.ctx.clone();
    h.state_mut().apply(
        Command::Session(session::Command::AddSources(sources)),
        &ctx,
    );
    h.run_steps(2);
}

#[test]
fn the_sample_loads_and_the_optimum_is_extracted() {
    let h = harness();
    let session = h.state().session();
    assert_eq!(session.model().map(|m| m.demos().len()), Some(10));
    assert!(session.landscape_complete());
    let x = session
        .extraction()
        .expect("extracted once the landscape is complete");
    assert!(x.converged);
    let names: Vec<String> = session
        .table_rows()
        .iter()
        .map(|r| r.name.clone())
        .collect();
    assert_eq!(
        names,
        [
            "Extracted",
            "Picked (compliant)",
            "Ours",
            "Hrstc1",
            "Hrstc2",
            "Hrstc3",
            "Hrstc4",
            "Operating point"
        ]
    );
}

#[test]
fn a_flat_j_gives_a_pick_and_go_to_the_pick_moves_the_operating_point() {
    let mut h = harness();
    let (dm, km, why) = {
        let view = h.state().session().allowed().expect("the verdict");
        assert!(view.allowed.j_flat, "reach10's J is flat");
        let p = view.allowed.pick.as_ref().expect("a pick");
        (p.dm, p.km, p.why.clone())
    };
    assert!(why.contains("J is flat"), "{why}");
    h.get_by_label_contains("What the demos allow: compliant")
        .click();
    h.run_steps(2);
    // The side panel is taller than the window: scroll to the button.
    for _ in 0..3 {
        h.get_by_role_and_label(egui::accesskit::Role::Button, "Go to the pick")
            .scroll_down();
        // Until the scroll's animation ends.
        h.run_steps(10);
    }
    let button = h.get_by_role_and_label(egui::accesskit::Role::Button, "Go to the pick");
    assert!(button.rect().max.y < 800.0, "{:?}", button.rect());
    button.click();
    h.run_steps(3);
    assert_eq!(h.state().settings.op, (dm, km));
    let row = operating_point_row(&h);
    assert_eq!((row.dm, row.km), (dm, km));
}

#[test]
fn a_preset_button_then_a_drag_move_the_operating_point() {
    let mut h = harness();
    h.get_by_role_and_label(egui::accesskit::Role::Button, "Hrstc3")
        .click();
    h.run_steps(2);
    assert_eq!(h.state().settings.op, (100.0, 20.0));
    let row = operating_point_row(&h);
    assert_eq!((row.dm, row.km), (100.0, 20.0));
    let before = row.d_mean.clone();

    // Drag on the J map: it starts 44 px right of its title's left edge,
    // just below the title.
    let title = h.get_by_label("J = S + k sum d").rect();
    let start = egui::pos2(title.left() + 60.0, title.bottom() + 20.0);
    support::drag_from(&mut h, start);
    let (dm, km) = h.state().settings.op;
    assert!((dm, km) != (100.0, 20.0), "the drag did not move the point");
    let row = operating_point_row(&h);
    assert_eq!((row.dm, row.km), (dm, km), "the table follows the point");
    assert_ne!(row.d_mean, before);
}

#[test]
fn changing_k_recombines_j_and_moves_the_optimum() {
    let mut h = harness();
    let j20 = h.state().session().extraction().expect("optimum").j;
    let landscapes = h.state().session().runs().landscapes;
    h.state_mut().settings.k = 200.0;
    h.run_steps(2);
    let session = h.state().session();
    let x = session.extraction().expect("re-extracted for the new k");
    assert_eq!(x.k, 200.0);
    assert!(x.j > j20, "J grows with k: {} vs {j20}", x.j);
    assert_eq!(session.runs().landscapes, landscapes, "no new landscape");
    let rows = session.table_rows();
    let ours = rows.iter().find(|r| r.name == "Ours").expect("Ours");
    assert_eq!(ours.j, ours.s + 200.0 * ours.d_sum);
}

#[test]
fn a_bad_file_is_reported_in_the_window_and_nothing_loaded_is_lost() {
    let mut h = harness();
    let landscapes = h.state().session().runs().landscapes;
    let bad = support::tmp_path("broken.mcap");
    std::fs::write(&bad, b"\x89MCAP0\r\nthis is not a recording").expect("write");
    add(&mut h, vec![Source::Path(bad)]);
    let session = h.state().session();
    assert!(!session.loading());
    assert_eq!(
        session.model().map(|m| m.demos().len()),
        Some(10),
        "the sample's demos stay"
    );
    assert_eq!(
        session.runs().landscapes,
        landscapes,
        "nothing to recompute"
    );
    // The message names the file (get_by_* panics when nothing matches).
    let _message = h.get_by_label_contains("broken.mcap");
}

#[test]
fn a_rosbag2_folder_opens_as_in_the_cli() {
    let bag = support::rosbag2_folder("gui-bag", &[(0, 2), (2, 4)], false);
    let mut h = harness_on(vec![Source::Path(bag.clone())], Runner::inline());
    h.run_steps(1);
    let session = h.state().session();
    let names: Vec<&str> = session
        .model()
        .expect("a model of the bag's demos")
        .demos()
        .iter()
        .map(|d| d.name.as_str())
        .collect();
    // A split bag is one recording, named by its folder.
    assert_eq!(
        names,
        [
            "gui-bag:/hand_01",
            "gui-bag:/hand_02",
            "gui-bag:/hand_03",
            "gui-bag:/hand_04"
        ]
    );
    assert_eq!(session.status(), Status::Ready);
    assert!(h.get_all_by_label_contains("gui-bag:/hand_04").count() >= 1);
    // Its metadata.yaml opens the same folder (what a file dialog picks).
    add(&mut h, vec![Source::Path(bag.join("metadata.yaml"))]);
    assert_eq!(h.state().session().demos().len(), 8);
}

#[test]
fn the_recording_panel_shows_skipped_streams_and_a_tick_recomputes_the_landscape() {
    let source = Source::Bytes {
        name: "tf.mcap".into(),
        bytes: support::tf_bag_bytes().into(),
    };
    let mut h = harness_on(vec![source], Runner::inline());
    h.run_steps(2);
    let names = |h: &Harness<'_, DmpApp>| -> Vec<String> {
        let s = h.state().session();
        s.model_demos()
            .iter()
            .map(|&i| s.demos()[i].info.name.clone())
            .collect()
    };
    assert_eq!(names(&h), ["tf.mcap:/hand", "tf.mcap:/tf:tracker"]);
    h.get_by_label("Recording").click();
    h.run_steps(2);
    let _summary = h.get_by_label_contains("tf.mcap: 2 of 4 streams kept");
    let _static = h.get_by_label("/tf_static:base_link");
    let _why = h.get_by_label("skipped: its stamp never advances (no duration)");
    let _still =
        h.get_by_label("skipped: it does not move (its positions span 0.0 mm, less than 10.0 mm)");
    let before = h.state().session().runs();
    assert!(h.state().session().landscape_complete());
    h.get_by_label("/hand").click();
    h.run_steps(3);
    assert_eq!(names(&h), ["tf.mcap:/tf:tracker"]);
    let after = h.state().session().runs();
    assert_eq!(
        after.loads, before.loads,
        "a tick regroups, it does not read again"
    );
    assert_eq!(after.landscapes, before.landscapes + 1);
    assert!(h.state().session().landscape_complete());
    assert_eq!(
        h.state().session().model().map(|m| m.demos().len()),
        Some(1)
    );
    // Back to the filter's verdict.
    h.get_by_label("as filtered").click();
    h.run_steps(3);
    assert_eq!(names(&h), ["tf.mcap:/hand", "tf.mcap:/tf:tracker"]);
}

#[test]
fn a_continuous_take_shows_its_timeline_and_new_thresholds_recut_it() {
    // Three reaches with 0.8 s rests between, as CSV.
    let mut csv = String::from("t,x,y,z\n");
    let (mut t, mut x) = (0.0_f64, 0.3_f64);
    for r in 0..3 {
        for _ in 0..72 {
            csv.push_str(&format!("{t:.6},{x:.6},0,1\n"));
            t += 1.0 / 90.0;
        }
        let (a, b) = if r % 2 == 0 { (0.3, 0.7) } else { (0.7, 0.3) };
        for k in 0..108 {
            let s = k as f64 / 107.0;
            x = a + (b - a) * (10.0 * s.powi(3) - 15.0 * s.powi(4) + 6.0 * s.powi(5));
            csv.push_str(&format!("{t:.6},{x:.6},0,1\n"));
            t += 1.0 / 90.0;
        }
    }
    let source = Source::Bytes {
        name: "take.csv".into(),
        bytes: csv.into_bytes().into(),
    };
    let mut settings = Settings::with_grid_points(16);
    settings.load.demos = dmpscope_core::load::options::Grouping::Segmented(
        dmpscope_core::load::options::SegmentSettings::default(),
    );
    let mut h = Harness::builder()
        .with_size([1280.0, 800.0])
        .build_eframe(move |_cc| DmpApp::with_runner(settings, vec![source], Runner::inline()));
    h.run_steps(3);
    assert_eq!(h.state().session().demos().len(), 3);
    h.get_by_label("Recording").click();
    h.run_steps(2);
    let _timeline =
        h.get_by_label("speed [m/s] over time [s]: 3 segments (shaded), rest below the line");
    let _count = h.get_by_label_contains("spans 400 mm: 3 demos");
    // A shortest demo longer than each reach leaves none.
    if let dmpscope_core::load::options::Grouping::Segmented(seg) =
        &mut h.state_mut().settings.load.demos
    {
        seg.min_segment_s = 2.0;
    }
    h.run_steps(3);
    let _none =
        h.get_by_label("speed [m/s] over time [s]: 0 segments (shaded), rest below the line");
    assert!(h.state().session().demos().is_empty());
}

#[test]
fn a_folder_with_no_usable_demo_says_so_instead_of_a_spinner() {
    let short = support::rosbag2_folder("gui-short", &[(0, 0)], true);
    let mut h = harness_on(vec![Source::Path(short)], Runner::inline());
    h.run_steps(1);
    assert!(matches!(
        h.state().session().status(),
        Status::NoUsableDemo(_)
    ));
    let _said = h.get_by_label_contains("No demonstration can be used");
    assert!(
        h.query_by_label_contains("Computing the landscape")
            .is_none()
    );

    let empty = support::tmp_path("gui-empty");
    std::fs::create_dir_all(&empty).expect("folder");
    let mut h = harness_on(vec![Source::Path(empty)], Runner::inline());
    h.run_steps(1);
    assert_eq!(h.state().session().status(), Status::NoDemos);
    let _said = h.get_by_label_contains("No demonstration was found");
    let _why = h.get_by_label_contains("holds no .mcap file");
}

#[test]
fn a_folder_of_recordings_counts_its_files() {
    // Two CSV recordings in one folder: one source, two files, two demos.
    let folder = support::tmp_path("gui-two-csvs");
    std::fs::create_dir_all(&folder).expect("folder");
    for (i, reach) in [0.3, 0.25].into_iter().enumerate() {
        let mut csv = String::from("t,x,y,z\n");
        for k in 0..200 {
            let s = f64::from(k) / 199.0;
            let x = reach * s * s * (3.0 - 2.0 * s);
            csv.push_str(&format!("{},{x},{},0.9\n", f64::from(k) * 0.01, 0.1 * x));
        }
        std::fs::write(folder.join(format!("trial_{i}.csv")), csv).expect("csv");
    }
    let h = harness_on(vec![Source::Path(folder)], Runner::inline());
    assert_eq!(h.state().session().demos().len(), 2);
    let _count = h.get_by_label("2 file(s), 2 demos");
}

#[test]
fn open_without_a_system_dialog_picks_files_in_the_apps_own_browser() {
    let assets = support::repo().join("assets");
    let settings = Settings::with_grid_points(16);
    let sample = support::sample_path();
    let mut h = Harness::builder()
        .with_size([1280.0, 800.0])
        .build_eframe(move |_cc| {
            DmpApp::with_runner(settings, vec![Source::Path(sample)], Runner::inline())
                .with_app_browser(Some(assets))
        });
    h.run_steps(2);
    h.get_by_role_and_label(egui::accesskit::Role::Button, "Open…")
        .click();
    // The command, the dialog's answer, the browser's first (sizing) frame.
    h.run_steps(5);
    let _said = h.get_by_label_contains("dmpscope's own file browser");
    let _window = h.get_by_label_contains("Open recordings");
    // The browser starts in the folder given; pick the sample again.
    h.get_by_label("🗋 reach10.mcap").click();
    h.run_steps(2);
    h.get_by_role_and_label(egui::accesskit::Role::Button, "Open")
        .click();
    h.run_steps(3);
    assert!(
        h.query_by_label_contains("Open recordings").is_none(),
        "closed"
    );
    assert_eq!(h.state().session().demos().len(), 20);
}

#[test]
fn the_rl_panel_trains_and_shows_the_learned_path() {
    let mut h = harness();
    h.state_mut().view.rl.steps = 800;
    // Fold the diagnostics away and clear the messages so the RL section
    // fits the side panel.
    h.get_by_label("Diagnostics").click();
    h.run_steps(2);
    h.get_by_role_and_label(egui::accesskit::Role::Button, "Clear messages")
        .click();
    h.run_steps(2);
    h.get_by_label("RL with DMP").click();
    h.run_steps(2);
    h.get_by_role_and_label(egui::accesskit::Role::Button, "Train")
        .click();
    h.run_steps(3);
    let (_, p) = h.state().session().rl().expect("a run started");
    assert!(p.done, "training finished");
    assert_eq!(p.decisions, (800, 800));
    assert_eq!(p.returns.len(), 2, "two iterations of 4 episodes");
    let greedy = p.greedy.as_ref().expect("a learned path");
    assert_eq!(greedy.path.len(), 1001);
    assert!(greedy.final_error.is_finite() && p.d.is_finite());
    // The result line names the goal error.
    let _line = h.get_by_label_contains("goal error");
}

#[test]
fn background_threads_load_compute_and_extract() {
    let ctx_runner = |ctx: &egui::Context| {
        let ctx = ctx.clone();
        Runner::background(move || ctx.request_repaint())
    };
    let settings = Settings::with_grid_points(16);
    let sample = support::sample_path();
    let mut h = Harness::builder()
        .with_size([1280.0, 800.0])
        .build_eframe(move |cc| {
            DmpApp::with_runner(
                settings,
                vec![Source::Path(sample)],
                ctx_runner(&cc.egui_ctx),
            )
        });
    for _ in 0..2000 {
        h.run_steps(1);
        let s = h.state().session();
        if s.extraction().is_some() && !s.busy() {
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    let session = h.state().session();
    assert!(
        session.extraction().is_some(),
        "status {:?}",
        session.status()
    );
    assert_eq!(session.model().map(|m| m.demos().len()), Some(10));
}

#[test]
fn the_new_target_tab_runs_a_demo_or_the_skill_and_exports_it_for_a_robot() {
    use dmpscope::gui::Export;
    use dmpscope::session::{GeneraliseSpec, TargetSource};
    let mut h = harness();
    h.get_by_role_and_label(egui::accesskit::Role::Button, "New target")
        .click();
    h.run_steps(2);
    assert!(h.state().session().generalised().is_none());
    assert!(
        h.state().export(Export::Dmp).is_err(),
        "nothing to export yet"
    );
    h.get_by_label("Run the DMP at a new target").click();
    h.run_steps(2);
    let _readout = h.get_by_label_contains("peak speed");
    // A goal moved towards the start: the per-axis factors shrink and the
    // run still ends at the new goal.
    let (start, goal) = {
        let g = support::run_at_new_target(&h);
        (g.out.start, g.out.goal)
    };
    let closer: [f64; 3] = std::array::from_fn(|a| start[a] + 0.5 * (goal[a] - start[a]));
    let mut spec = *h.state().session().generalise_spec().expect("on");
    spec.target.goal = Some(closer.into());
    spec.target.duration_s = Some(2.5);
    let ctx = h.ctx.clone();
    h.state_mut().apply(
        Command::Session(session::Command::SetGeneralise(Some(spec))),
        &ctx,
    );
    h.run_steps(2);
    let (name, bytes) = h.state().export(Export::Dmp).expect("export");
    assert_eq!(name, "dmpscope-dmp.json");
    let doc: serde_json::Value = serde_json::from_slice(&bytes).expect("json");
    assert_eq!(doc["schema"], "dmpscope.dmp");
    assert_eq!(doc["source"], "demo");
    assert_eq!(doc["tau"].as_f64(), Some(2.5));
    let g_new: Vec<f64> = doc["g_new"]
        .as_array()
        .expect("g_new")
        .iter()
        .map(|v| v.as_f64().expect("number"))
        .collect();
    assert_eq!(g_new, closer);
    // The skill, by its button.
    h.get_by_label("the skill of all demos").click();
    h.run_steps(2);
    let spec = *h.state().session().generalise_spec().expect("on");
    assert_eq!(spec.source, TargetSource::Skill);
    assert_eq!(
        spec,
        GeneraliseSpec {
            source: TargetSource::Skill,
            ..spec.reset()
        },
        "a new source starts at its own target"
    );
    let (_, bytes) = h.state().export(Export::Dmp).expect("export");
    let doc: serde_json::Value = serde_json::from_slice(&bytes).expect("json");
    assert_eq!(doc["source"], "skill");
    assert_eq!(doc["demos"].as_array().map(Vec::len), Some(10));
    // Off again.
    h.get_by_label("Run the DMP at a new target").click();
    h.run_steps(2);
    assert!(h.state().session().generalised().is_none());
}

/// The area egui's meshes cover in the last frame, in windows (each pixel
/// once per triangle over it).
fn painted_windows(h: &Harness<'_, DmpApp>) -> f64 {
    let out = h.output();
    let window = f64::from(h.ctx.content_rect().area());
    let primitives = h.ctx.tessellate(out.shapes.clone(), out.pixels_per_point);
    let mut area = 0.0;
    for p in &primitives {
        if let egui::epaint::Primitive::Mesh(m) = &p.primitive {
            for t in m.indices.chunks_exact(3) {
                let [a, b, c] = [t[0], t[1], t[2]].map(|i| m.vertices[i as usize].pos);
                area += f64::from(((b - a).x * (c - a).y - (b - a).y * (c - a).x).abs()) * 0.5;
            }
        }
    }
    area / window
}

/// Under software rasterisers (SwiftShader in a browser without a GPU,
/// lavapipe) every pixel egui fills costs its shader in full, so the app
/// run by eframe leaves the panels' background to the renderer's clear:
/// its meshes then cover less than the window once, against twice when
/// every panel fills its own rect (as a harness, whose renderer clears to
/// transparent, still draws it).
#[test]
fn the_clear_paints_the_background_and_the_panels_fill_less_than_the_window() {
    let harness = |from_clear: bool| {
        let settings = Settings::with_grid_points(16);
        let source = Source::Path(support::sample_path());
        let mut h = Harness::builder()
            .with_size([1280.0, 800.0])
            .build_eframe(move |_cc| {
                let app = DmpApp::with_runner(settings, vec![source], Runner::inline());
                if from_clear {
                    app.with_background_from_clear()
                } else {
                    app
                }
            });
        h.run_steps(3);
        h
    };
    let (filled, cleared) = (harness(false), harness(true));
    // The clear is the panels' colour, in either theme.
    for visuals in [egui::Visuals::dark(), egui::Visuals::light()] {
        assert_eq!(
            eframe::App::clear_color(cleared.state(), &visuals),
            visuals.panel_fill.to_normalized_gamma_f32()
        );
    }
    let (filled, cleared) = (painted_windows(&filled), painted_windows(&cleared));
    assert!(cleared < 1.0, "{cleared:.2} windows painted");
    assert!(
        filled - cleared > 0.9,
        "the panels' fills: {filled:.2} windows against {cleared:.2}"
    );
}

/// Table I lays out only the cells in sight (it is three columns per demo
/// wide); scrolling it brings the others in, at the width they had.
#[test]
fn table_i_lays_out_the_cells_in_sight_and_scrolls_to_the_rest() {
    let mut h = harness();
    let last = "e demo_10 [mm]";
    assert_eq!(h.query_all_by_label(last).count(), 0, "out of sight");
    let csv = h.state().session().report().expect("report").csv();
    assert!(csv.contains("demo_10"), "the copy has every column: {csv}");
    let at = h.get_by_label("Operating point").rect().center();
    for _ in 0..40 {
        h.hover_at(at);
        h.event(egui::Event::MouseWheel {
            unit: egui::MouseWheelUnit::Point,
            delta: egui::vec2(-200.0, 0.0),
            phase: egui::TouchPhase::Move,
            source: egui::MouseWheelSource::Wheel,
            modifiers: egui::Modifiers::default(),
        });
        h.run_steps(2);
        if h.query_all_by_label(last).count() > 0 {
            break;
        }
    }
    assert_eq!(h.query_all_by_label(last).count(), 1, "scrolled in");
    assert_eq!(
        h.query_all_by_label("Operating point").count(),
        0,
        "the first column scrolled out"
    );
}

#[test]
fn loading_cuts_out_and_back_trials_at_their_farthest_point() {
    use dmpscope_core::load::options::{Cut, Grouping, SegmentPick, SegmentSettings};
    let path = support::takes::trials("gui-trials.mcap");
    let mut h = harness_on(vec![Source::Path(path.into())], Runner::inline());
    h.state_mut().settings.load.demos = Grouping::Segmented(SegmentSettings {
        keep: SegmentPick::First,
        ..SegmentSettings::default()
    });
    h.run_steps(3);
    let said = |h: &Harness<'_, DmpApp>, what: &str| {
        h.state()
            .session()
            .messages()
            .iter()
            .any(|m| m.text.contains(what))
    };
    assert_eq!(h.state().session().demos().len(), 6);
    assert!(said(&h, "/trial_3#1: ends"), "the loop is said");
    scroll_into_view(&mut h, |h| h.get_by_label("Loading"));
    h.get_by_label("Loading").click();
    h.run_steps(2);
    let label = "each demo at its farthest point";
    let role = egui::accesskit::Role::CheckBox;
    scroll_into_view(&mut h, |h| h.get_by_role_and_label(role, label));
    h.get_by_role_and_label(role, label).click();
    h.run_steps(4);
    assert_eq!(h.state().settings.load.cut, Cut::Farthest);
    assert!(said(&h, "/trial_3#1: cut at its farthest point"));
    assert!(said(&h, "/trial_6#1: cut at its farthest point"));
    let reaches: Vec<f64> = h
        .state()
        .session()
        .demos()
        .iter()
        .map(|d| (d.info.goal[0] - d.info.start[0]).hypot(d.info.goal[1] - d.info.start[1]))
        .collect();
    assert_eq!(reaches.len(), 6);
    assert!(
        reaches.iter().all(|r| (r - 0.35).abs() < 0.01),
        "{reaches:?}"
    );
}
