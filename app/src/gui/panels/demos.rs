//! The demos found (include or exclude each; the ones the model had to
//! leave out are marked) and the messages, coloured by level.

use dmpscope_core::Level;
use eframe::egui::{self, Color32};

use super::super::forcing::demo_colour;
use super::PanelCtx;
use crate::session;

/// The colour of a message of `level`.
pub fn level_colour(level: Level) -> Color32 {
    match level {
        Level::Detail | Level::Info => Color32::from_rgb(150, 180, 220),
        Level::Warning => Color32::from_rgb(240, 180, 80),
        Level::Error => Color32::from_rgb(240, 120, 100),
    }
}

/// The demos list and the messages.
pub fn demos_ui(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>) {
    let session = cx.session;
    ui.heading("Demos");
    let in_model = session.model_demos();
    let hovered = cx.view.hovered.and_then(|i| in_model.get(i).copied());
    egui::ScrollArea::vertical()
        .id_salt("demos")
        .max_height(220.0)
        .show(ui, |ui| {
            for (i, entry) in session.demos().iter().enumerate() {
                let info = &entry.info;
                let mut text = format!(
                    "{}  ({} samples, {:.2} s)",
                    info.name, info.n_samples, info.duration_s
                );
                let left_out =
                    entry.included && session.model().is_some() && !in_model.contains(&i);
                if left_out {
                    text.push_str("  left out: see the messages");
                }
                let mut included = entry.included;
                let label = egui::RichText::new(text);
                let model_index = in_model.iter().position(|&m| m == i);
                let label = if left_out {
                    label.color(level_colour(Level::Warning))
                } else if hovered == Some(i) {
                    label
                        .strong()
                        .color(model_index.map_or(Color32::WHITE, demo_colour))
                } else {
                    label
                };
                let prepared = model_index
                    .and_then(|m| session.model().and_then(|model| model.demos().get(m)));
                let response = ui
                    .checkbox(&mut included, label)
                    .on_hover_text(demo_details(prepared));
                if response.hovered() {
                    cx.view.hovering = model_index;
                }
                if response.changed() {
                    cx.push(session::Command::SetIncluded { demo: i, included });
                }
            }
        });
    if !session.messages().is_empty() {
        ui.separator();
        egui::ScrollArea::vertical()
            .id_salt("messages")
            .max_height(160.0)
            .show(ui, |ui| {
                for m in session.messages() {
                    ui.colored_label(level_colour(m.level), &m.text);
                }
            });
        if ui.small_button("Clear messages").clicked() {
            cx.push(session::Command::ClearMessages);
        }
    }
}

/// A demo's details on hover: its rate and how much of its smoothed
/// acceleration is noise (method.md section 2, "Noise").
fn demo_details(prepared: Option<&dmpscope_core::PreparedDemo>) -> String {
    let Some(p) = prepared else {
        return "not in the model".to_owned();
    };
    let rate = 1.0 / p.median_interval_s.max(1e-12);
    let noise = match (p.acc_noise, p.suggested_sg_seconds) {
        (None, _) => "acceleration noise: not measured (too few samples)".to_owned(),
        (Some(n), None) => format!("acceleration noise: {:.0} % of its RMS", 100.0 * n),
        (Some(n), Some(s)) => format!(
            "acceleration noise: {:.0} % of its RMS, mostly noise; an SG window of {s} s \
             (Settings) smooths it",
            100.0 * n
        ),
    };
    format!("{rate:.0} Hz, {} resampled points\n{noise}", p.n0)
}
