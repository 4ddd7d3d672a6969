//! The gains: k, the operating point (typed, or snapped to a preset or the
//! optimum), the extracted optimum and, on the box's edge, the warning with
//! a button that widens the box.

use dmpscope_core::report::presets::PAPER_PRESETS;
use eframe::egui::{self, Color32};

use super::PanelCtx;

/// The gains section.
pub fn gains_ui(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>) {
    let session = cx.session;
    let s = &mut *cx.settings;
    ui.heading("Gains");
    k_ui(ui, s);
    operating_point_ui(ui, s);
    snap_buttons_ui(ui, session, s, &mut cx.view.click_targets);
    let Some(x) = session.extraction() else {
        no_optimum_ui(ui, session);
        return;
    };
    extracted_ui(ui, session, x);
    super::allowed::allowed_ui(ui, cx);
    box_edge_ui(ui, x, &mut cx.settings.grid);
}

/// The k slider.
fn k_ui(ui: &mut egui::Ui, s: &mut crate::session::Settings) {
    ui.horizontal(|ui| {
        let label = ui.label("k");
        ui.add(egui::Slider::new(&mut s.k, 0.0..=200.0).logarithmic(true))
            .labelled_by(label.id);
    });
}

/// The operating point typed: D/M and K/M, within the grid's box.
fn operating_point_ui(ui: &mut egui::Ui, s: &mut crate::session::Settings) {
    let (dm_axis, km_axis) = (s.grid.dm, s.grid.km);
    ui.horizontal(|ui| {
        let label = ui.label("D/M");
        ui.add(
            egui::DragValue::new(&mut s.op.0)
                .speed(0.1)
                .range(dm_axis.lo..=dm_axis.hi),
        )
        .labelled_by(label.id);
        let label = ui.label("K/M");
        ui.add(
            egui::DragValue::new(&mut s.op.1)
                .speed(0.5)
                .range(km_axis.lo..=km_axis.hi),
        )
        .labelled_by(label.id);
    });
}

/// The buttons that snap the operating point to a preset or the optimum (their
/// rectangles kept for the tests).
fn snap_buttons_ui(
    ui: &mut egui::Ui,
    session: &crate::session::Session,
    s: &mut crate::session::Settings,
    click_targets: &mut std::collections::BTreeMap<&'static str, egui::Rect>,
) {
    ui.horizontal_wrapped(|ui| {
        for p in PAPER_PRESETS {
            let button = ui.button(p.name);
            click_targets.insert(p.name, button.rect);
            if button.clicked() {
                s.op = (p.dm, p.km);
            }
        }
        if let Some(x) = session.extraction()
            && ui.button("Extracted").clicked()
        {
            s.op = (x.eval.dm, x.eval.km);
        }
    });
}

/// Why there is no optimum yet: extracting, no demos, a failure, or waiting.
fn no_optimum_ui(ui: &mut egui::Ui, session: &crate::session::Session) {
    if session.extracting() {
        ui.horizontal(|ui| {
            crate::gui::busy::spinner(ui);
            ui.label("Extracting the optimum…");
        });
    } else if session.model().is_none() {
        ui.weak("Extracted: needs demonstrations");
    } else if let Some(e) = session.extraction_error() {
        ui.colored_label(
            Color32::from_rgb(240, 120, 100),
            format!("Extraction failed: {e}"),
        );
    } else {
        ui.label("Extracted: waiting for the full landscape");
    }
}

/// The extracted optimum, or where J is least when it is flat.
fn extracted_ui(
    ui: &mut egui::Ui,
    session: &crate::session::Session,
    x: &dmpscope_core::Extraction,
) {
    let flat = session.diagnostics().map(|d| d.diagnostics.flat);
    if flat == Some(true) {
        // No number is presented as extracted when J is flat.
        flat_ui(ui, session);
        ui.weak(format!(
            "J is least at (M:D:K) = 1 : {:.3} : {:.3}, J {:.4}, barely below the box's boundary",
            x.eval.dm, x.eval.km, x.j
        ));
    } else {
        ui.label(format!(
            "Extracted (M:D:K) = 1 : {:.3} : {:.3}, zeta {:.3}, J {:.4}",
            x.eval.dm, x.eval.km, x.eval.zeta, x.j
        ));
    }
}

/// On the box's edge: the warning and the button that widens the box that way.
fn box_edge_ui(
    ui: &mut egui::Ui,
    x: &dmpscope_core::Extraction,
    g: &mut dmpscope_core::landscape::grid::Grid,
) {
    if x.on_edge() {
        ui.colored_label(
            Color32::from_rgb(240, 180, 80),
            format!("On the box edge: {}", x.edges.describe()),
        );
        if ui.button("Widen the box 10x that way").clicked() {
            let e = x.edges;
            if e.dm_low {
                g.dm.lo /= 10.0;
            }
            if e.dm_high {
                g.dm.hi *= 10.0;
            }
            if e.km_low {
                g.km.lo /= 10.0;
            }
            if e.km_high {
                g.km.hi *= 10.0;
            }
        }
    }
}

/// What a flat J means: the region the data allow, the pick below in it.
fn flat_ui(ui: &mut egui::Ui, session: &crate::session::Session) {
    let allow = session.allowed().map_or(String::new(), |v| {
        format!(": {}", v.allowed.acceptable.text())
    });
    ui.colored_label(
        Color32::from_rgb(240, 180, 80),
        format!(
            "J is flat (see Diagnostics), so the data allow a region{allow}; the pick below is \
             in it."
        ),
    );
}
