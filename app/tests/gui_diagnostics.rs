//! "Can I trust these gains?" as a user meets it (egui_kittest, jobs
//! inline): the Samples menu, the verdict on a determined and on a flat
//! optimum, the balanced-k button, excluding a flagged demo in one click,
//! a hovered demo named in the forcing-term view, a click on the Pareto
//! front, and the a_peak limit's constrained optimum.

mod support;

use dmpscope::gui::DmpApp;
use dmpscope::session::{Runner, Settings, Source};
use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

fn harness_on(source: Source) -> Harness<'static, DmpApp> {
    let mut settings = Settings::with_grid_points(16);
    settings.diagnostics.bootstrap = 20;
    let mut h = Harness::builder()
        .with_size([1280.0, 800.0])
        .build_eframe(move |_cc| DmpApp::with_runner(settings, vec![source], Runner::inline()));
    h.run_steps(3);
    h
}

#[test]
fn the_samples_menu_replaces_the_sample_and_the_verdict_follows() {
    let mut h = harness_on(Source::sample());
    // The reach sample's optimum is on the box edge and flat.
    let d = h.state().session().diagnostics().expect("diagnostics");
    assert!(d.complete() && d.diagnostics.flat);
    let _gains = h.get_by_label_contains("J is flat (see Diagnostics), so the data allow a region");
    let _verdict = h.get_by_label_contains("The data do not determine the gains: J's optimum");
    assert!(h.query_by_label_contains("Extracted (M:D:K)").is_none());

    h.get_by_role_and_label(Role::Button, "Samples").click();
    h.run_steps(2);
    h.get_by_role_and_label(Role::Button, "planted8.mcap")
        .click();
    h.run_steps(3);
    let session = h.state().session();
    assert_eq!(session.sources().count(), 1, "the sample was replaced");
    assert_eq!(session.model().map(|m| m.demos().len()), Some(8));
    let d = session.diagnostics().expect("diagnostics");
    assert!(d.complete() && !d.diagnostics.flat);
    let _verdict = h.get_by_label_contains("the data determine it");
    let _extracted = h.get_by_label_contains("Extracted (M:D:K)");
    let _bootstrap = h.get_by_label_contains("Bootstrap (20 resamples, seed 1)");
}

#[test]
fn use_it_sets_the_balanced_k() {
    let mut h = harness_on(Source::planted_sample());
    let balanced = h
        .state()
        .session()
        .diagnostics()
        .and_then(|d| d.diagnostics.balanced_k)
        .expect("balanced k");
    h.get_by_role_and_label(Role::Button, "Use it").click();
    h.run_steps(3);
    assert_eq!(h.state().settings.k, balanced);
    let x = h.state().session().extraction().expect("re-extracted");
    assert_eq!(x.k, balanced);
    let d = h.state().session().diagnostics().expect("re-diagnosed");
    assert!(d.complete());
}

#[test]
fn a_flagged_demo_is_excluded_in_one_click() {
    let mut h = harness_on(Source::planted_sample());
    let session = h.state().session();
    let d = &session.diagnostics().expect("diagnostics").diagnostics;
    let flagged = d.inconsistent();
    assert!(!flagged.is_empty(), "planted8 at 0.1 mm flags a demo");
    let name = d.demos[flagged[0]].name.clone();
    h.get_by_role_and_label(Role::Button, "Exclude").click();
    h.run_steps(3);
    let session = h.state().session();
    let model = session.model().expect("model");
    assert_eq!(model.demos().len(), 7);
    assert!(model.demos().iter().all(|m| m.name != name), "{name} left");
    let entry = session
        .demos()
        .iter()
        .find(|e| e.raw.name == name)
        .expect("still listed");
    assert!(!entry.included, "unticked in the demos list");
}

#[test]
fn a_demo_hovered_in_the_list_is_named_in_the_forcing_terms() {
    let mut h = harness_on(Source::planted_sample());
    h.get_by_role_and_label(Role::Button, "Forcing terms")
        .click();
    h.run_steps(2);
    let _hint = h.get_by_label_contains("hover a curve");
    let row = h.get_by_label_contains("planted8.mcap:/demo_03  (").rect();
    h.hover_at(row.center());
    h.run_steps(3);
    assert_eq!(h.state().view.hovered, Some(2));
    let _named = h.get_by_label_contains("planted8.mcap:/demo_03, ");
    let _share = h.get_by_label_contains("% of S here");
}

#[test]
fn a_click_on_the_pareto_front_moves_the_operating_point_onto_it() {
    let mut h = harness_on(Source::planted_sample());
    h.get_by_role_and_label(Role::Button, "Trade-off").click();
    h.run_steps(2);
    let caption = h.get_by_label_contains("Pareto-optimal").rect();
    let before = h.state().settings.op;
    let at = egui::pos2(caption.center().x, caption.bottom() + 200.0);
    h.hover_at(at);
    h.run_steps(1);
    // A press and a release in place: a click.
    h.drag_at(at);
    h.run_steps(1);
    h.drop_at(at);
    h.run_steps(3);
    let op = h.state().settings.op;
    assert_ne!(op, before, "the click moved the operating point");
    let shown = h.state().session().shown().expect("landscape");
    let l = &shown.snapshot.landscape;
    let front = dmpscope_core::extract::diagnostics::pareto::pareto_front(
        shown.values(dmpscope_core::landscape::quantity::Quantity::DSum),
        shown.values(dmpscope_core::landscape::quantity::Quantity::S),
    );
    let n_km = shown.grid().km.n;
    assert!(
        front
            .iter()
            .any(|&i| (l.dm[i / n_km], l.km[i % n_km]) == op),
        "{op:?} is a point of the front"
    );
}

#[test]
fn an_a_peak_limit_gives_the_constrained_optimum() {
    let mut h = harness_on(Source::planted_sample());
    // The limit's rows are near the side panel's foot at 800 px: a taller
    // window keeps its Go there button on screen (a user scrolls to it).
    h.set_size(egui::vec2(1280.0, 1000.0));
    h.run_steps(2);
    h.get_by_label("Limit a_peak to").click();
    h.run_steps(3);
    let limit = h.state().settings.a_peak_limit.expect("a limit");
    let c = *h
        .state()
        .session()
        .constrained()
        .expect("computed")
        .expect("gains within the limit");
    let _line = h.get_by_label_contains("Constrained optimum: D/M");
    // The J map's title, and the map itself (its accessible label).
    assert_eq!(h.query_all_by_label_contains("(grey: a_peak >").count(), 2);
    let before = h.state().settings.op;
    // The Go there buttons: the S minimum's, then the constrained one's.
    let buttons = h.get_all_by_role_and_label(Role::Button, "Go there");
    let last = buttons.last().expect("a Go there button");
    last.click();
    h.run_steps(2);
    assert_ne!(h.state().settings.op, before);
    assert_eq!(h.state().settings.op, (c.dm, c.km));
    let e = h.state().session().point().expect("evaluated");
    assert!(e.a_peak.iter().all(|&a| a <= limit));
}
