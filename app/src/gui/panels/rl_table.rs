//! The RL panel's table of finished runs: the CLI's `rl --compare` table,
//! its columns from [`dmpscope_core::rl::table`]; then one line per gain
//! set.

use dmpscope_core::rl::run::{RunReport, summarise};
use dmpscope_core::rl::table::RUN_COLUMNS;
use eframe::egui::{self, Color32};

/// The table of `runs`.
pub fn runs_table(ui: &mut egui::Ui, runs: &[RunReport]) {
    egui::ScrollArea::horizontal()
        .id_salt("rl runs")
        .show(ui, |ui| {
            egui::Grid::new("rl runs table")
                .striped(true)
                .num_columns(RUN_COLUMNS.len())
                .show(ui, |ui| {
                    for c in &RUN_COLUMNS {
                        ui.strong(c.title);
                    }
                    ui.end_row();
                    for r in runs {
                        for c in &RUN_COLUMNS {
                            let cell = (c.cell)(r);
                            match (c.title, cell.as_str()) {
                                ("reached", "yes") => {
                                    ui.colored_label(Color32::from_rgb(120, 210, 120), cell)
                                }
                                ("reached", _) => {
                                    ui.colored_label(Color32::from_rgb(240, 160, 90), cell)
                                }
                                _ => ui.label(cell),
                            };
                        }
                        ui.end_row();
                    }
                });
        });
    for set in summarise(runs) {
        ui.label(format!(
            "{}: reached {}/{}",
            set.name, set.reached, set.runs
        ));
    }
}
