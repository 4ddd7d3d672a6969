//! The right panel: the demo shown, a time slider, and the time plots of
//! the demo against its regeneration at the operating point.

use eframe::egui;

use super::super::commands::Command;
use super::super::plots;
use super::super::view_state::ViewState;
use crate::session::{Session, Settings};

/// The plots panel.
pub fn plots_ui(
    ui: &mut egui::Ui,
    session: &Session,
    _s: &mut Settings,
    view: &mut ViewState,
) -> Vec<Command> {
    let Some(model) = session.model() else {
        return Vec::new();
    };
    let demos = model.demos();
    let Some(demo) = demos.get(view.selected) else {
        return Vec::new();
    };
    ui.horizontal(|ui| {
        egui::ComboBox::from_label("demo")
            .selected_text(demo.name.clone())
            .show_ui(ui, |ui| {
                for (i, d) in demos.iter().enumerate() {
                    ui.selectable_value(&mut view.selected, i, &d.name);
                }
            });
    });
    ui.horizontal(|ui| {
        let label = ui.label("time");
        let mut seconds = view.t * demo.duration_s;
        ui.add(
            egui::Slider::new(&mut seconds, 0.0..=demo.duration_s)
                .suffix(" s")
                .max_decimals(2),
        )
        .labelled_by(label.id);
        view.t = (seconds / demo.duration_s).clamp(0.0, 1.0);
    });
    if let Some(rollout) = session.paths().get(view.selected)
        && let Some(t) = plots::show(ui, demo, rollout, view.t)
    {
        view.t = t;
    }
    Vec::new()
}
