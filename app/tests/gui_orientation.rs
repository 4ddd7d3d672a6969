//! Orientation in the app (method.md section 12), driven as a user would
//! (egui_kittest, no renderer, jobs inline): on the planted sample, whose
//! demos turn, the 3D view offers its orientation triads, the Demo tab
//! plots the orientation against the DMP's, the d_rot map is offered, Table
//! I has the orientation's columns, and the New target tab takes a goal
//! orientation typed as roll, pitch and yaw and reaches it.

mod support;

use dmpscope::gui::{Command, DmpApp};
use dmpscope::session::{self, Runner, Settings, Source};
use dmpscope_core::rotation;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

fn planted() -> Harness<'static, DmpApp> {
    let settings = Settings::with_grid_points(12);
    let sources = vec![Source::Path(support::repo().join("assets/planted8.mcap"))];
    let mut h = Harness::builder()
        .with_size([1280.0, 800.0])
        .build_eframe(move |_cc| DmpApp::with_runner(settings, sources, Runner::inline()));
    h.run_steps(3);
    h
}

#[test]
fn the_orientation_is_drawn_plotted_mapped_and_tabled() {
    let mut h = planted();
    let session = h.state().session();
    let model = session.model().expect("model");
    assert!(model.has_orientation());
    assert!(
        session.turns().iter().all(Option::is_some),
        "every demo turns"
    );
    // The 3D view's toggle and the map of d_rot.
    let _triads = h.get_by_role_and_label(egui::accesskit::Role::CheckBox, "orientation");
    // The d_rot map is computed when first shown (it costs about twice the
    // position's kernel).
    let nan_map = |h: &Harness<'_, DmpApp>| {
        let shown = h.state().session().shown().expect("landscape");
        shown
            .values(dmpscope_core::landscape::quantity::Quantity::DRotSum)
            .iter()
            .all(|v| v.is_nan())
    };
    assert!(nan_map(&h), "not computed until shown");
    h.get_by_label("d_rot").click();
    h.run_steps(4);
    assert!(!nan_map(&h), "computed once chosen");
    // Table I's orientation columns.
    let report = h.state().session().report().expect("report");
    assert!(report.oriented());
    assert!(
        h.query_all_by_label("sum d_rot [deg]").count() >= 1,
        "the column"
    );
    // The Demo tab plots the orientation.
    assert!(!h.state().view().orientation_plots);
    h.get_by_role_and_label(egui::accesskit::Role::Button, "orientation")
        .click();
    h.run_steps(2);
    assert!(h.state().view().orientation_plots, "the orientation plots");
}

#[test]
fn a_goal_orientation_typed_in_new_target_is_reached() {
    let mut h = planted();
    h.get_by_role_and_label(egui::accesskit::Role::Button, "New target")
        .click();
    h.run_steps(2);
    h.get_by_label("Run the DMP at a new target").click();
    h.run_steps(2);
    // The rows are there, with the demo's own as defaults.
    // Each row: roll, pitch and yaw, labelled by the row.
    assert_eq!(h.query_all_by_label("goal orientation").count(), 3);
    assert_eq!(h.query_all_by_label("start orientation").count(), 3);
    let _readout = h.get_by_label_contains("orientation ends");
    // At CartesianDMP's gains a goal turned 30 degrees in yaw from the
    // demo's own is reached within a fraction of a degree.
    h.state_mut().settings.op = (25.0, 156.25);
    h.run_steps(2);
    let own = {
        let s = h.state().session();
        let model = s.model().expect("model");
        model.demos()[0].orientation.as_ref().expect("turns").goal
    };
    let goal = rotation::mul(rotation::exp([0.0, 0.0, 15f64.to_radians()]), own);
    let mut spec = *h.state().session().generalise_spec().expect("on");
    spec.target.goal_orientation = Some(goal);
    let ctx = h.ctx.clone();
    h.state_mut().apply(
        Command::Session(session::Command::SetGeneralise(Some(spec))),
        &ctx,
    );
    h.run_steps(2);
    let g = support::run_at_new_target(&h);
    let path = g.out.orientation.as_ref().expect("an orientation path");
    let end = rotation::angle(*path.q.last().expect("end"), goal).to_degrees();
    assert!(end < 0.1, "ends {end} degrees from the new goal");
    let _readout = h.get_by_label_contains("orientation ends 0.0");
}
