//! The app driven as a user would (egui_kittest, no renderer): the sample
//! loads, the landscape fills, a preset button moves the operating point, a
//! drag on the J map moves it again, and changing k changes J and the
//! optimum without recomputing the landscape.

use dmpscope::gui::{DmpApp, Settings};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

fn harness() -> Harness<'static, DmpApp> {
    let settings = Settings {
        grid_n: 16,
        ..Settings::default()
    };
    let sample = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/reach10.mcap");
    let mut h = Harness::builder()
        .with_size([1280.0, 800.0])
        .build_eframe(move |_cc| DmpApp::with_settings(settings, vec![sample]));
    h.run_steps(2);
    let ctx = h.ctx.clone();
    h.state_mut().wait_for_landscape(&ctx);
    h.run_steps(2);
    h
}

fn operating_point_row(h: &Harness<'_, DmpApp>) -> dmpscope_core::TableRow {
    h.state()
        .table_rows()
        .into_iter()
        .find(|r| r.name == "Operating point")
        .expect("an operating-point row")
}

#[test]
fn the_sample_loads_and_the_optimum_is_extracted() {
    let h = harness();
    let app = h.state();
    assert_eq!(app.demo_names().len(), 10);
    assert!(app.landscape_complete());
    let x = app
        .extraction
        .as_ref()
        .expect("extracted once the landscape is complete");
    assert!(x.converged);
    let names: Vec<String> = app.table_rows().iter().map(|r| r.name.clone()).collect();
    assert_eq!(
        names,
        [
            "Extracted",
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
    h.hover_at(start);
    h.run_steps(1);
    h.drag_at(start);
    h.run_steps(1);
    for step in 1..=5 {
        h.hover_at(start + egui::vec2(5.0 * step as f32, 5.0 * step as f32));
        h.run_steps(1);
    }
    h.drop_at(start + egui::vec2(25.0, 25.0));
    h.run_steps(2);
    let (dm, km) = h.state().settings.op;
    assert!((dm, km) != (100.0, 20.0), "the drag did not move the point");
    let row = operating_point_row(&h);
    assert_eq!((row.dm, row.km), (dm, km), "the table follows the point");
    assert_ne!(row.d_mean, before);
}

#[test]
fn changing_k_recombines_j_and_moves_the_optimum() {
    let mut h = harness();
    let j20 = h.state().extraction.as_ref().expect("optimum").j;
    h.state_mut().settings.k = 200.0;
    h.run_steps(1);
    let ctx = h.ctx.clone();
    h.state_mut().wait_for_landscape(&ctx);
    h.run_steps(1);
    let x = h
        .state()
        .extraction
        .as_ref()
        .expect("re-extracted for the new k");
    assert_eq!(x.k, 200.0);
    assert!(x.j > j20, "J grows with k: {} vs {j20}", x.j);
    let rows = h.state().table_rows();
    let ours = rows.iter().find(|r| r.name == "Ours").expect("Ours");
    assert_eq!(ours.j, ours.s + 200.0 * ours.d_sum);
}

#[test]
fn a_bad_file_is_reported_in_the_window_and_nothing_loaded_is_lost() {
    let mut h = harness();
    let dir = std::env::temp_dir().join(format!("dmpscope-gui-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let bad = dir.join("broken.mcap");
    std::fs::write(&bad, b"\x89MCAP0\r\nthis is not a recording").expect("write");
    let ctx = h.ctx.clone();
    h.state_mut().add_files(vec![bad], &ctx);
    for _ in 0..500 {
        if !h.state().loading() {
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(5));
        h.run_steps(1);
    }
    h.run_steps(2);
    assert!(!h.state().loading());
    assert_eq!(h.state().demo_names().len(), 10, "the sample's demos stay");
    // The message names the file (get_by_* panics when nothing matches).
    let _message = h.get_by_label_contains("broken.mcap");
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn the_rl_panel_trains_in_the_background_and_shows_the_learned_path() {
    let mut h = harness();
    h.state_mut().rl_choices.steps = 800;
    h.get_by_label("RL with DMP").click();
    h.run_steps(2);
    h.get_by_role_and_label(egui::accesskit::Role::Button, "Train")
        .click();
    h.run_steps(1);
    for _ in 0..2000 {
        if h.state().rl_progress().is_some_and(|p| p.done) {
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(5));
        h.run_steps(1);
    }
    let p = h.state().rl_progress().expect("a run started");
    assert!(p.done, "training finished");
    assert_eq!(p.decisions, (800, 800));
    assert_eq!(p.returns.len(), 2, "two iterations of 4 episodes");
    let greedy = p.greedy.expect("a learned path");
    assert_eq!(greedy.path.len(), 1001);
    assert!(greedy.final_error.is_finite() && p.d.is_finite());
    h.run_steps(2);
    // The result line names the goal error.
    let _line = h.get_by_label_contains("goal error");
}
