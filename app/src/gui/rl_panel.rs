//! The RL panel: pick the gains (operating point, extracted, a paper
//! preset), train a PPO agent whose action is the forcing term on the
//! selected demo in the background, watch the reward curve and cancel; the
//! learned path is drawn in the 3D view beside the demo and its LfD
//! regeneration.

use dmpscope_core::presets::PAPER_PRESETS;
use dmpscope_core::rl::REACHED_M;
use eframe::egui::{self, Color32};
use egui_plot::{Line, Plot, PlotPoints};

use super::app::DmpApp;
use super::rl_run::RlRun;

/// The panel's choices.
#[derive(Clone, Debug)]
pub struct RlChoices {
    /// 0: the operating point, 1: the extracted gains, 2 + i: preset i.
    pub gains: usize,
    /// Decisions to train.
    pub steps: usize,
    /// The seed.
    pub seed: u64,
}

impl Default for RlChoices {
    fn default() -> Self {
        Self {
            gains: 1,
            steps: 100_000,
            seed: 1,
        }
    }
}

impl DmpApp {
    fn rl_gains(&self) -> Option<(String, f64, f64)> {
        match self.rl_choices.gains {
            0 => Some((
                "operating point".into(),
                self.settings.op.0,
                self.settings.op.1,
            )),
            1 => self
                .extraction
                .as_ref()
                .map(|x| ("extracted".into(), x.eval.dm, x.eval.km)),
            i => PAPER_PRESETS
                .get(i - 2)
                .map(|p| (p.name.to_owned(), p.dm, p.km)),
        }
    }

    /// The learned path to draw: (model demo index, path in demo
    /// coordinates).
    pub(super) fn rl_path(&self) -> Option<(usize, Vec<[f64; 3]>)> {
        let run = self.rl.as_ref()?;
        Some((run.what.0, run.progress().greedy?.path))
    }

    pub(super) fn rl_panel(&mut self, ui: &mut egui::Ui, ctx: &egui::Context) {
        let names: Vec<String> = std::iter::once("operating point".to_owned())
            .chain(std::iter::once("extracted".to_owned()))
            .chain(PAPER_PRESETS.iter().map(|p| p.name.to_owned()))
            .collect();
        let c = &mut self.rl_choices;
        egui::ComboBox::from_label("gains")
            .selected_text(names.get(c.gains).cloned().unwrap_or_default())
            .show_ui(ui, |ui| {
                for (i, n) in names.iter().enumerate() {
                    ui.selectable_value(&mut c.gains, i, n);
                }
            });
        ui.horizontal(|ui| {
            let l = ui.label("decisions");
            ui.add(
                egui::DragValue::new(&mut c.steps)
                    .range(400..=2_000_000)
                    .speed(1000),
            )
            .labelled_by(l.id);
            let l = ui.label("seed");
            ui.add(egui::DragValue::new(&mut c.seed)).labelled_by(l.id);
        });
        let running = self.rl.as_ref().is_some_and(|r| !r.progress().done);
        ui.horizontal(|ui| {
            let gains = self.rl_gains();
            let can = self.model.is_some() && gains.is_some() && !running;
            if ui
                .add_enabled(can, egui::Button::new("Train"))
                .on_disabled_hover_text("needs demos and the chosen gains (the extracted ones once the landscape is done)")
                .clicked()
                && let (Some(model), Some(gains)) = (&self.model, gains)
            {
                let wake = {
                    let ctx = ctx.clone();
                    move || ctx.request_repaint()
                };
                let (steps, seed) = (self.rl_choices.steps, self.rl_choices.seed);
                match RlRun::start(model.clone(), self.selected, gains, steps, seed, wake) {
                    Ok(run) => self.rl = Some(run),
                    Err(e) => self.messages.push(format!("RL: {e}")),
                }
            }
            if running
                && ui.button("Cancel").clicked()
                && let Some(run) = &self.rl
            {
                run.cancel();
            }
        });
        let Some(run) = &self.rl else {
            ui.weak("Trains on the demo shown in the plots.");
            return;
        };
        let p = run.progress();
        let (demo, dm, km, name) = &run.what;
        ui.label(format!(
            "demo {} · {name} (D/M {dm:.3}, K/M {km:.3})",
            demo + 1
        ));
        let (done, total) = p.decisions;
        ui.add(
            egui::ProgressBar::new(done as f32 / total.max(1) as f32)
                .text(format!("{done}/{total} decisions, {:.1} s", p.seconds)),
        );
        if let Some(g) = &p.greedy {
            let reached = g.final_error <= REACHED_M;
            ui.colored_label(
                if reached {
                    Color32::from_rgb(120, 210, 120)
                } else {
                    Color32::from_rgb(240, 160, 90)
                },
                format!(
                    "goal error {:.2} mm ({}), d {:.1} mm, a_peak {:.1}",
                    g.final_error * 1e3,
                    if reached { "reached" } else { "not reached" },
                    p.d * 1e3,
                    g.a_peak()
                ),
            );
        }
        let points: PlotPoints<'_> = p
            .returns
            .iter()
            .enumerate()
            .map(|(i, r)| [i as f64, *r])
            .collect();
        Plot::new("rl returns")
            .height(110.0)
            .y_axis_label("mean return")
            .x_axis_label("iteration")
            .allow_scroll(false)
            .show(ui, |plot| plot.line(Line::new("return", points)));
    }
}
