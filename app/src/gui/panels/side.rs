//! The side panel: the demos and messages, the gains, the diagnostics, RL,
//! and the Loading and Settings sections.

use eframe::egui;

use super::super::commands::Command;
use super::super::view_state::ViewState;
use super::{demos, diagnostics, gains, loading, recording, rl, settings};
use crate::session::{Session, Settings};

/// The side panel.
pub fn side_ui(
    ui: &mut egui::Ui,
    session: &Session,
    s: &mut Settings,
    view: &mut ViewState,
) -> Vec<Command> {
    let mut out = Vec::new();
    demos::demos_ui(ui, session, view, &mut out);
    ui.separator();
    ui.collapsing("Recording", |ui| {
        recording::recording_ui(ui, session, s, view, &mut out)
    });
    ui.separator();
    gains::gains_ui(ui, session, s);
    ui.separator();
    egui::CollapsingHeader::new("Diagnostics")
        .default_open(true)
        .show(ui, |ui| {
            diagnostics::diagnostics_ui(ui, session, s, view, &mut out)
        });
    ui.separator();
    ui.collapsing("RL with DMP", |ui| {
        rl::rl_ui(ui, session, s, view, &mut out)
    });
    ui.separator();
    ui.collapsing("Loading", |ui| loading::loading_ui(ui, s, view));
    ui.separator();
    ui.collapsing("Settings", |ui| settings::settings_ui(ui, s));
    out
}
