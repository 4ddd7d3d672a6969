//! The RL panel: pick the gains (operating point, extracted, a paper
//! preset, or the gains picked in What the demos allow), the action mode and the decisions per episode, train a PPO
//! agent on the demo shown in the plots, or compare the extracted gains
//! with every preset over three seeds; watch the reward curves and cancel.
//! The learned path is drawn in the 3D view beside the demo and its LfD
//! regeneration; finished runs are listed in a table (`rl_table.rs`).

use dmpscope_core::report::presets::PAPER_PRESETS;
use dmpscope_core::rl::REACHED_M;
use dmpscope_core::rl::env::{ActionMode, ExploreScale};
use eframe::egui::{self, Color32};
use egui_plot::{Line, Plot, PlotPoints};

use super::super::view_state::{RlChoices, ViewState};
use super::PanelCtx;
use super::rl_table::runs_table;
use crate::session::{self, RlProgress, RlRequest, RlRun, Session, Settings};

/// Seeds per gain set in a comparison.
const COMPARE_SEEDS: u64 = 3;

fn chosen_gains(session: &Session, s: &Settings, choice: usize) -> Option<(String, f64, f64)> {
    match choice {
        0 => Some(("operating point".into(), s.op.0, s.op.1)),
        1 => session
            .extraction()
            .map(|x| ("extracted".into(), x.eval.dm, x.eval.km)),
        i if i == PICKED => session
            .allowed()
            .and_then(|v| v.allowed.pick.as_ref())
            .map(|p| (format!("picked ({})", p.rule.name()), p.dm, p.km)),
        i => PAPER_PRESETS
            .get(i - 2)
            .map(|p| (p.name.to_owned(), p.dm, p.km)),
    }
}

/// The gains combo's entry of the picked gains (after the presets).
const PICKED: usize = 2 + PAPER_PRESETS.len();

/// The RL section.
pub fn rl_ui(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>) {
    let session = cx.session;
    rl_gains_ui(ui, &mut cx.view.rl);
    rl_options_ui(ui, &mut cx.view.rl);
    let run = session.rl();
    let running = run.is_some_and(|(_, p)| !p.done);
    rl_buttons_ui(ui, cx, running);
    let Some((request, p)) = run else {
        ui.weak(
            "Trains on the demo shown in the plots: its positions (an orientation, where \
             recorded, is not part of RL).",
        );
        return;
    };
    let Some(current) = request.runs.get(p.run) else {
        return;
    };
    rl_progress_ui(ui, request, current, p);
    rl_outcome_ui(ui, p);
    rl_returns_ui(ui, request, p);
}

/// The gains combo, the decisions to train and the seed.
fn rl_gains_ui(ui: &mut egui::Ui, c: &mut RlChoices) {
    let names: Vec<String> = ["operating point", "extracted"]
        .into_iter()
        .map(str::to_owned)
        .chain(PAPER_PRESETS.iter().map(|p| p.name.to_owned()))
        .chain(["picked (What the demos allow)".to_owned()])
        .collect();
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
}

/// The environment's options: action mode, decisions per episode, exploration.
fn rl_options_ui(ui: &mut egui::Ui, c: &mut RlChoices) {
    // Wrapped: the two combos are wider than the side panel's default.
    ui.horizontal_wrapped(|ui| {
        egui::ComboBox::from_label("action")
            .selected_text(c.options.mode.name())
            .show_ui(ui, |ui| {
                for m in ActionMode::ALL {
                    ui.selectable_value(&mut c.options.mode, m, m.name());
                }
            })
            .response
            .on_hover_text(
                "forcing: the action is the whole forcing term (the paper); \
                 residual: it is added to the demo's fitted forcing term",
            );
        egui::ComboBox::from_label("per episode")
            .selected_text(format!("{} decisions", c.options.decisions))
            .show_ui(ui, |ui| {
                for n in [100, 1000] {
                    ui.selectable_value(&mut c.options.decisions, n, format!("{n} decisions"));
                }
            });
        egui::ComboBox::from_label("explore")
            .selected_text(c.options.explore.name())
            .show_ui(ui, |ui| {
                for e in ExploreScale::ALL {
                    ui.selectable_value(&mut c.options.explore, e, e.name());
                }
            })
            .response
            .on_hover_text(
                "the policy's initial deviation: half the RMS of the demo's acceleration \
                 (default), or of its fitted forcing term (which grows with K/M)",
            );
    });
}

/// The Train, Compare and Cancel buttons.
fn rl_buttons_ui(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>, running: bool) {
    let session = cx.session;
    ui.horizontal(|ui| {
        let gains = chosen_gains(session, cx.settings, cx.view.rl.gains);
        let can = session.model().is_some() && gains.is_some() && !running;
        if ui
            .add_enabled(can, egui::Button::new("Train"))
            .on_disabled_hover_text(
                "needs demos and the chosen gains (the extracted ones once the landscape is done)",
            )
            .clicked()
            && let Some((gains_name, dm, km)) = gains
        {
            let runs = vec![RlRun {
                gains_name,
                dm,
                km,
                seed: cx.view.rl.seed,
            }];
            let train = request(cx.view, runs);
            cx.push(session::Command::StartRl(train));
        }
        let extracted = session.extraction().map(|x| (x.eval.dm, x.eval.km));
        let can = session.model().is_some() && extracted.is_some() && !running;
        if ui
            .add_enabled(can, egui::Button::new("Compare"))
            .on_hover_text(
                "trains the extracted gains and every paper preset, 3 seeds each, one after the other",
            )
            .on_disabled_hover_text("needs demos and the extracted gains")
            .clicked()
            && let Some((dm, km)) = extracted
        {
            let sets = std::iter::once(("Extracted".to_owned(), dm, km))
                .chain(PAPER_PRESETS.iter().map(|p| (p.name.to_owned(), p.dm, p.km)));
            let seed = cx.view.rl.seed;
            let runs = sets
                .flat_map(|(name, dm, km)| {
                    (0..COMPARE_SEEDS).map(move |i| RlRun {
                        gains_name: name.clone(),
                        dm,
                        km,
                        seed: seed + i,
                    })
                })
                .collect();
            let compare = request(cx.view, runs);
            cx.push(session::Command::StartRl(compare));
        }
        if running && ui.button("Cancel").clicked() {
            cx.push(session::Command::CancelRl);
        }
    });
}

/// The run under way (`current` of `request`) and the progress bar.
fn rl_progress_ui(ui: &mut egui::Ui, request: &RlRequest, current: &RlRun, p: &RlProgress) {
    let of = if request.runs.len() > 1 {
        format!("run {}/{} · ", p.run + 1, request.runs.len())
    } else {
        String::new()
    };
    ui.label(format!(
        "{of}demo {} · {} seed {} (D/M {:.3}, K/M {:.3}) · {} · {} per episode · explore {}",
        request.demo + 1,
        current.gains_name,
        current.seed,
        current.dm,
        current.km,
        request.options.mode.name(),
        request.options.decisions,
        request.options.explore.name()
    ));
    let (done, total) = p.decisions;
    let state = if p.cancelled { ", cancelled" } else { "" };
    ui.add(
        egui::ProgressBar::new(done as f32 / total.max(1) as f32).text(format!(
            "{done}/{total} decisions, {:.1} s{state}",
            p.seconds
        )),
    );
}

/// The policy's goal error, its first reach, divergence and why training stopped.
fn rl_outcome_ui(ui: &mut egui::Ui, p: &RlProgress) {
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
    ui.label(match p.first_reach {
        Some(f) => format!(
            "first reached after {} decisions ({:.1} s)",
            f.decisions, f.seconds
        ),
        None => "not reached yet".to_owned(),
    });
    if p.diverged {
        ui.colored_label(
            Color32::from_rgb(240, 160, 90),
            "diverging: the last tenth's mean return is more than 10 % below the best tenth's",
        );
    }
    if let Some(why) = &p.stopped {
        ui.colored_label(Color32::from_rgb(240, 110, 110), why);
    }
}

/// The reward curves and, in a comparison, the table of finished runs.
fn rl_returns_ui(ui: &mut egui::Ui, request: &RlRequest, p: &RlProgress) {
    let curve = |returns: &[f64]| -> PlotPoints<'static> {
        returns
            .iter()
            .enumerate()
            .map(|(i, r)| [i as f64, *r])
            .collect()
    };
    Plot::new("rl returns")
        .height(110.0)
        .y_axis_label("mean return")
        .x_axis_label("iteration")
        .allow_scroll(false)
        .show(ui, |plot| {
            for r in &p.finished {
                plot.line(
                    Line::new(format!("{} {}", r.name, r.seed), curve(&r.returns)).width(1.0),
                );
            }
            // A finished run's curve is already among the finished.
            if !p.done || p.finished.is_empty() {
                plot.line(Line::new("return", curve(&p.returns)));
            }
        });
    if !p.finished.is_empty() && request.runs.len() > 1 {
        runs_table(ui, &p.finished);
    }
}

/// A request for `runs` on the selected demo with the panel's settings.
fn request(view: &ViewState, runs: Vec<RlRun>) -> RlRequest {
    RlRequest {
        demo: view.selected,
        options: view.rl.options,
        steps: view.rl.steps,
        runs,
    }
}
