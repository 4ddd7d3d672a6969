//! The side panel: the demos found (include or exclude each), messages,
//! the gains (k, the operating point, preset and optimum buttons, the edge
//! warning) and the persisted settings.

use dmpscope_core::presets::PAPER_PRESETS;
use eframe::egui::{self, Color32};

use super::app::DmpApp;

impl DmpApp {
    pub(super) fn side_panel(&mut self, ui: &mut egui::Ui, ctx: &egui::Context) {
        ui.heading("Demos");
        let mut changed = false;
        egui::ScrollArea::vertical()
            .max_height(220.0)
            .show(ui, |ui| {
                for entry in &mut self.demos {
                    let info = &entry.info;
                    let text = format!(
                        "{}  ({} samples, {:.2} s)",
                        info.name, info.n_samples, info.duration_s
                    );
                    changed |= ui.checkbox(&mut entry.included, text).changed();
                }
            });
        if changed {
            self.refresh(ctx);
        }
        if !self.messages.is_empty() {
            ui.separator();
            for m in &self.messages {
                ui.colored_label(Color32::from_rgb(240, 120, 100), m);
            }
            if ui.small_button("Clear messages").clicked() {
                self.messages.clear();
            }
        }
        ui.separator();
        ui.heading("Gains");
        let s = &mut self.settings;
        ui.horizontal(|ui| {
            let label = ui.label("k");
            ui.add(egui::Slider::new(&mut s.k, 0.0..=200.0).logarithmic(true))
                .labelled_by(label.id);
        });
        ui.horizontal(|ui| {
            let label = ui.label("D/M");
            ui.add(
                egui::DragValue::new(&mut s.op.0)
                    .speed(0.1)
                    .range(s.dm_range.0..=s.dm_range.1),
            )
            .labelled_by(label.id);
            let label = ui.label("K/M");
            ui.add(
                egui::DragValue::new(&mut s.op.1)
                    .speed(0.5)
                    .range(s.km_range.0..=s.km_range.1),
            )
            .labelled_by(label.id);
        });
        ui.horizontal_wrapped(|ui| {
            for p in PAPER_PRESETS {
                if ui.button(p.name).clicked() {
                    s.op = (p.dm, p.km);
                }
            }
            if let Some(x) = &self.extraction
                && ui.button("Extracted").clicked()
            {
                s.op = (x.eval.dm, x.eval.km);
            }
        });
        match &self.extraction {
            Some(x) => {
                ui.label(format!(
                    "Extracted (M:D:K) = 1 : {:.3} : {:.3}, zeta {:.3}, J {:.4}",
                    x.eval.dm, x.eval.km, x.eval.zeta, x.j
                ));
                if x.on_edge() {
                    ui.colored_label(
                        Color32::from_rgb(240, 180, 80),
                        format!("On the box edge: {}", x.edges.describe()),
                    );
                    if ui.button("Widen the box 10x that way").clicked() {
                        let e = x.edges;
                        let s = &mut self.settings;
                        if e.dm_low {
                            s.dm_range.0 /= 10.0;
                        }
                        if e.dm_high {
                            s.dm_range.1 *= 10.0;
                        }
                        if e.km_low {
                            s.km_range.0 /= 10.0;
                        }
                        if e.km_high {
                            s.km_range.1 *= 10.0;
                        }
                        self.restart_landscape(ctx);
                    }
                }
            }
            None => {
                if self.extracting() {
                    ui.horizontal(|ui| {
                        ui.spinner();
                        ui.label("Extracting the optimum…");
                    });
                } else {
                    ui.label("Extracted: waiting for the full landscape");
                }
            }
        }
        ui.separator();
        ui.collapsing("RL with DMP", |ui| self.rl_panel(ui, ctx));
        ui.separator();
        ui.collapsing("Settings", |ui| self.settings_ui(ui, ctx));
    }

    fn settings_ui(&mut self, ui: &mut egui::Ui, ctx: &egui::Context) {
        let before = self.settings.clone();
        let s = &mut self.settings;
        egui::Grid::new("settings").show(ui, |ui| {
            let l = ui.label("grid points");
            ui.add(egui::DragValue::new(&mut s.grid_n).range(8..=512))
                .labelled_by(l.id);
            ui.end_row();
            let l = ui.label("D/M range");
            ui.horizontal(|ui| {
                ui.add(
                    egui::DragValue::new(&mut s.dm_range.0)
                        .speed(0.01)
                        .range(1e-6..=1e6),
                )
                .labelled_by(l.id);
                ui.add(
                    egui::DragValue::new(&mut s.dm_range.1)
                        .speed(1.0)
                        .range(1e-6..=1e7),
                )
                .labelled_by(l.id);
            });
            ui.end_row();
            let l = ui.label("K/M range");
            ui.horizontal(|ui| {
                ui.add(
                    egui::DragValue::new(&mut s.km_range.0)
                        .speed(0.01)
                        .range(1e-6..=1e6),
                )
                .labelled_by(l.id);
                ui.add(
                    egui::DragValue::new(&mut s.km_range.1)
                        .speed(1.0)
                        .range(1e-6..=1e7),
                )
                .labelled_by(l.id);
            });
            ui.end_row();
            ui.label("axes");
            ui.checkbox(&mut s.log_axes, "log-spaced");
            ui.end_row();
            ui.label("colours");
            ui.checkbox(&mut s.log_colour, "log scale");
            ui.end_row();
            let l = ui.label("SG window / order");
            ui.horizontal(|ui| {
                ui.add(egui::DragValue::new(&mut s.sg_window).range(5..=101))
                    .labelled_by(l.id);
                ui.add(egui::DragValue::new(&mut s.sg_order).range(2..=6))
                    .labelled_by(l.id);
            });
            ui.end_row();
            let l = ui.label("basis functions");
            ui.add(egui::DragValue::new(&mut s.basis).range(2..=500))
                .labelled_by(l.id);
            ui.end_row();
        });
        if s.sg_window.is_multiple_of(2) {
            s.sg_window += 1;
        }
        let grid_changed = s.grid_n != before.grid_n
            || s.dm_range != before.dm_range
            || s.km_range != before.km_range
            || s.log_axes != before.log_axes;
        if grid_changed && self.settings.grid().validate().is_ok() {
            self.restart_landscape(ctx);
        }
    }
}
