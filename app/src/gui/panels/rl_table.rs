//! The RL panel's table of finished runs (the CLI's `rl --compare` table):
//! per run the gains, seed, whether and how closely the policy's mean
//! reaches the goal, d against the demo, a_peak, when it first reached,
//! how steadily it stayed reached and whether training stayed stable; then
//! one line per gain set.

use dmpscope_core::rl::run::{RunReport, summarise};
use eframe::egui::{self, Color32};

/// The table of `runs`.
pub fn runs_table(ui: &mut egui::Ui, runs: &[RunReport]) {
    egui::ScrollArea::horizontal()
        .id_salt("rl runs")
        .show(ui, |ui| {
            egui::Grid::new("rl runs table")
                .striped(true)
                .num_columns(10)
                .show(ui, |ui| {
                    for h in [
                        "gains",
                        "seed",
                        "reached",
                        "error mm",
                        "d mm",
                        "a_peak",
                        "1st reach",
                        "at s",
                        "held",
                        "stable",
                    ] {
                        ui.strong(h);
                    }
                    ui.end_row();
                    for r in runs {
                        ui.label(&r.name);
                        ui.label(r.seed.to_string());
                        let (text, colour) = if r.reached {
                            ("yes", Color32::from_rgb(120, 210, 120))
                        } else {
                            ("no", Color32::from_rgb(240, 160, 90))
                        };
                        ui.colored_label(colour, text);
                        ui.label(format!("{:.2}", r.greedy.final_error * 1e3));
                        ui.label(format!("{:.1}", r.d * 1e3));
                        ui.label(format!("{:.1}", r.greedy.a_peak()));
                        match r.first_reach {
                            Some(f) => {
                                ui.label(f.decisions.to_string());
                                ui.label(format!("{:.1}", f.seconds));
                            }
                            None => {
                                ui.label("-");
                                ui.label("-");
                            }
                        }
                        ui.label(
                            r.held
                                .map_or("-".to_owned(), |h| format!("{:.0}%", 100.0 * h)),
                        );
                        ui.label(if r.diverged { "no" } else { "yes" });
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
