//! Gain sets compared in the app (issue 45, egui_kittest): three sets
//! pinned through the Compare section give three overlays in the 3D view
//! (every demo regenerated at each) and in the Demo tab's position and
//! orientation plots, the
//! comparison's numbers are Table I's for the same gains, a set removed
//! takes its overlays with it, and the figure of what is on screen is an
//! SVG with a path per set and demo.

mod support;

use dmpscope::gui::DmpApp;
use dmpscope::session::{Runner, Settings, Source};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

fn harness() -> Harness<'static, DmpApp> {
    harness_of(support::sample_path())
}

fn harness_of(path: std::path::PathBuf) -> Harness<'static, DmpApp> {
    let settings = Settings::with_grid_points(16);
    let sources = vec![Source::Path(path)];
    let mut h = Harness::builder()
        .with_size([1280.0, 800.0])
        .build_eframe(move |_cc| DmpApp::with_runner(settings, sources, Runner::inline()));
    h.run_steps(2);
    h
}

#[test]
fn three_pinned_sets_are_drawn_compared_and_removed() {
    let mut h = harness();
    h.get_by_label("Compare gain sets").click();
    h.run_steps(2);
    let field = h.get_by_role(egui::accesskit::Role::TextInput);
    field.click();
    h.run_steps(1);
    h.get_by_role(egui::accesskit::Role::TextInput)
        .type_text("extracted, Hrstc1, 40:400");
    h.run_steps(1);
    h.get_by_role_and_label(egui::accesskit::Role::Button, "Pin")
        .click();
    h.run_steps(3);
    let app = h.state();
    let names: Vec<&str> = app
        .view()
        .pins
        .list()
        .iter()
        .map(|p| p.name.as_str())
        .collect();
    assert_eq!(
        names,
        ["Extracted", "Hrstc1", "40:400"],
        "{:?}",
        app.view().pin_error
    );
    let demos = app.session().model().expect("model").demos().len();
    // Every demo regenerated at each set in the 3D view, each set in the
    // Demo tab's plots.
    assert_eq!(app.view().view3d.pin_paths, vec![demos; 3]);
    assert_eq!(app.view().plot_pin_lines, 3);
    // The comparison's numbers are Table I's for the same gains.
    let table = app.session().table_rows();
    let rows = app.view().pins.rows();
    assert_eq!(rows.len(), 3);
    for name in ["Extracted", "Hrstc1"] {
        let compared = rows.iter().find(|r| r.row.name == name).expect("compared");
        let row = table.iter().find(|r| r.name == name).expect("Table I");
        // As JSON, where a NaN (no orientation) is null and equal to itself.
        let json = |r| serde_json::to_value(r).expect("json");
        assert_eq!(json(&compared.row), json(row), "{name}");
    }
    assert!(rows[2].settling.unit > 0.0 && rows[2].settling.unit.is_finite());
    // The figure of what is on screen: a path per set and demo in 3D.
    let svg = h
        .state()
        .figure()
        .and_then(|f| dmpscope::figure::svg(&f).map_err(|e| e.to_string()));
    let svg = svg.expect("figure");
    for p in h.state().view().pins.list() {
        let stroke = format!(
            "stroke=\"#{:02X}{:02X}{:02X}\"",
            p.colour[0], p.colour[1], p.colour[2]
        );
        let paths = svg.matches(&stroke).count();
        assert!(paths > demos, "{} paths in {stroke}", paths);
    }
    // Removing the second set removes its overlays.
    let remove: Vec<_> = h.get_all_by_label("remove").collect();
    assert_eq!(remove.len(), 3);
    remove[1].click();
    h.run_steps(3);
    let names: Vec<&str> = h
        .state()
        .view()
        .pins
        .list()
        .iter()
        .map(|p| p.name.as_str())
        .collect();
    assert_eq!(names, ["Extracted", "40:400"]);
    assert_eq!(h.state().view().view3d.pin_paths, vec![demos; 2]);
    assert_eq!(h.state().view().plot_pin_lines, 2);
}

/// Pins `text` (comma-separated gains) through the Compare section.
fn pin(h: &mut Harness<'static, DmpApp>, text: &str) {
    h.get_by_label("Compare gain sets").click();
    h.run_steps(2);
    h.get_by_role(egui::accesskit::Role::TextInput).click();
    h.run_steps(1);
    h.get_by_role(egui::accesskit::Role::TextInput)
        .type_text(text);
    h.run_steps(1);
    h.get_by_role_and_label(egui::accesskit::Role::Button, "Pin")
        .click();
    h.run_steps(3);
}

#[test]
fn the_orientation_plots_overlay_the_pins_too() {
    let mut h = harness_of(support::repo().join("assets/planted8.mcap"));
    pin(&mut h, "Hrstc1, 40:400");
    assert_eq!(h.state().view().pins.list().len(), 2);
    assert_eq!(h.state().view().plot_pin_lines, 2, "position overlays");
    h.get_by_role_and_label(egui::accesskit::Role::Button, "orientation")
        .click();
    h.run_steps(2);
    assert!(h.state().view().orientation_plots);
    assert_eq!(h.state().view().plot_pin_lines, 2, "orientation overlays");
    // A set removed leaves the orientation plots too.
    let remove: Vec<_> = h.get_all_by_label("remove").collect();
    remove[0].click();
    h.run_steps(3);
    assert_eq!(h.state().view().plot_pin_lines, 1);
}

#[test]
fn pins_are_at_most_six_and_typed_gains_are_checked() {
    let mut h = harness();
    h.get_by_label("Compare gain sets").click();
    h.run_steps(2);
    h.get_by_role(egui::accesskit::Role::TextInput).click();
    h.run_steps(1);
    h.get_by_role(egui::accesskit::Role::TextInput)
        .type_text("1:1,2:2,3:3,4:4,5:5,6:6");
    h.get_by_role_and_label(egui::accesskit::Role::Button, "Pin")
        .click();
    h.run_steps(3);
    assert_eq!(h.state().view().pins.list().len(), 6);
    h.get_by_label("operating point").click();
    h.run_steps(2);
    assert_eq!(h.state().view().pins.list().len(), 6);
    let error = h.state().view().pin_error.clone().expect("refused");
    assert!(error.contains("at most 6"), "{error}");
}
