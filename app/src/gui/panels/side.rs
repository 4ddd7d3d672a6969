//! The side panel: the demos and messages, the gains, the pinned gain sets,
//! the diagnostics, RL, and the Loading and Settings sections.

use eframe::egui;

use super::{PanelCtx, compare, demos, diagnostics, gains, loading, recording, rl, settings};

/// The side panel.
pub fn side_ui(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>) {
    demos::demos_ui(ui, cx);
    ui.separator();
    ui.collapsing("Recording", |ui| recording::recording_ui(ui, cx));
    ui.separator();
    gains::gains_ui(ui, cx);
    ui.separator();
    let pinned = cx.view.pins.list().len();
    let title = if pinned == 0 {
        "Compare gain sets".to_owned()
    } else {
        format!("Compare gain sets ({pinned} pinned)")
    };
    egui::CollapsingHeader::new(title)
        .id_salt("compare gain sets")
        .show(ui, |ui| compare::compare_ui(ui, cx));
    ui.separator();
    egui::CollapsingHeader::new("Diagnostics")
        .default_open(true)
        .show(ui, |ui| diagnostics::diagnostics_ui(ui, cx));
    ui.separator();
    ui.collapsing("RL with DMP", |ui| rl::rl_ui(ui, cx));
    ui.separator();
    ui.collapsing("Loading", |ui| loading::loading_ui(ui, cx));
    ui.separator();
    ui.collapsing("Settings", |ui| settings::settings_ui(ui, cx));
}
