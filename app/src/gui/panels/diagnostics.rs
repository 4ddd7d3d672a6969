//! "Can I trust these gains?": the extraction's diagnostics (method.md
//! section 9) as they come: the depth of J's optimum and the verdict, the
//! balance of S against k sum d with a button that sets the balanced k, the
//! S minimum, the demos flagged as inconsistent (one click excludes one),
//! the bootstrap's percentiles, the leave-one-out table, and the a_peak
//! limit with its constrained optimum.

use dmpscope_core::extract::diagnostics::balance::FLAT_DEPTH;
use dmpscope_core::extract::diagnostics::{DiagSettings, INCONSISTENT_SHARE};
use eframe::egui::{self, Color32};

use super::super::view_state::ViewState;
use super::PanelCtx;
use crate::session::{self, DiagSnapshot, Session, Settings};

const WARN: Color32 = Color32::from_rgb(240, 180, 80);
const GOOD: Color32 = Color32::from_rgb(130, 210, 130);

/// The diagnostics section.
pub fn diagnostics_ui(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>) {
    let session = cx.session;
    ui.heading("Can I trust these gains?");
    match session.diagnostics() {
        Some(d) => snapshot_ui(ui, cx, d),
        None if session.extracting() || session.diagnosing() => {
            ui.horizontal(|ui| {
                crate::gui::busy::spinner(ui);
                ui.label("Diagnosing…");
            });
        }
        None => {
            ui.weak("The diagnostics follow the extraction.");
        }
    }
    ui.separator();
    limit_ui(ui, session, cx.settings);
    ui.collapsing("Diagnostics settings", |ui| {
        settings_ui(ui, &mut cx.settings.diagnostics)
    });
}

/// The diagnostics of `snap`: the depth and verdict, the balance, the S
/// minimum, the flagged demos, the bootstrap and its progress.
fn snapshot_ui(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>, snap: &DiagSnapshot) {
    let d = &snap.diagnostics;
    match d.depth {
        Some(depth) if d.flat => {
            ui.colored_label(
                WARN,
                format!(
                    "The data do not determine the gains: J's optimum is only {:.1} % below the \
                     least J on the box's boundary (under {:.0} %).",
                    100.0 * depth,
                    100.0 * FLAT_DEPTH
                ),
            );
        }
        Some(depth) => {
            ui.colored_label(
                GOOD,
                format!(
                    "J's optimum is {:.0} % below the least J on the box's boundary: \
                     the data determine it.",
                    100.0 * depth
                ),
            );
        }
        None => {
            ui.colored_label(WARN, "The data do not determine the gains: J has no depth.");
        }
    }
    if let Some(r) = d.k_ratio {
        ui.label(format!("k sum d / S at the optimum: {r:.3}"));
    }
    if let Some(b) = d.balanced_k {
        ui.horizontal_wrapped(|ui| {
            ui.label(format!("Balanced k (median S / median sum d): {b:.3}"));
            if ui
                .button("Use it")
                .on_hover_text("set k so that S and k sum d weigh alike over the grid")
                .clicked()
            {
                cx.settings.k = b;
            }
        });
    }
    if let Some(m) = d.s_minimum {
        ui.horizontal_wrapped(|ui| {
            ui.label(format!(
                "S alone is least at D/M {:.3}, K/M {:.3} (S {:.4})",
                m.dm, m.km, m.s
            ));
            if ui.small_button("Go there").clicked() {
                cx.settings.op = (m.dm, m.km);
            }
        });
    }
    demos_ui(ui, cx, snap);
    bootstrap_ui(ui, snap);
    if !snap.complete() {
        ui.add(
            egui::ProgressBar::new(snap.done as f32 / snap.total.max(1) as f32).text(format!(
                "resampled extractions {}/{}",
                snap.done, snap.total
            )),
        );
    }
    for note in &snap.about.notes {
        ui.weak(note);
    }
}

/// A button that excludes model demo `i` from the model (hovering it
/// highlights the demo); its command is pushed when clicked.
pub fn exclude_button(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>, i: usize, label: &str) {
    let Some(&demo) = cx.session.model_demos().get(i) else {
        return;
    };
    let r = ui
        .button(label)
        .on_hover_text("leave this demo out of the model");
    if r.hovered() {
        cx.view.hovering = Some(i);
    }
    if r.clicked() {
        cx.push(session::Command::SetIncluded {
            demo,
            included: false,
        });
    }
}

/// The flagged demos, then the leave-one-out table.
fn demos_ui(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>, snap: &DiagSnapshot) {
    let session = cx.session;
    let d = &snap.diagnostics;
    let n = d.demos.len();
    let flagged = d.inconsistent();
    if n >= 3 && flagged.is_empty() {
        ui.label(format!(
            "No demo stands out: every share of S is under {:.0} % ({INCONSISTENT_SHARE} / {n}).",
            100.0 * INCONSISTENT_SHARE / n as f64
        ));
    }
    for &i in &flagged {
        let demo = &d.demos[i];
        ui.horizontal_wrapped(|ui| {
            let r = ui.colored_label(
                WARN,
                format!(
                    "{}: {:.0} % of S (fair share {:.0} %)",
                    demo.name,
                    100.0 * demo.s_share.unwrap_or(0.0),
                    100.0 / n as f64
                ),
            );
            if r.hovered() {
                cx.view.hovering = Some(i);
            }
            exclude_button(ui, cx, i, "Exclude");
        });
    }
    if n < 2 {
        return;
    }
    egui::CollapsingHeader::new(format!(
        "Per demo: share of S, leave-one-out ({} x {})",
        snap.about.grid.dm.n, snap.about.grid.km.n
    ))
    .id_salt("leave-one-out")
    .show(ui, |ui| {
        // Its own horizontal scroll: the table must not widen the panel
        // (the wrapped lines above would then run past its edge).
        egui::ScrollArea::horizontal()
            .id_salt("loo scroll")
            .show(ui, |ui| loo_table(ui, session, snap, &flagged, cx.view));
    });
}

/// The per-demo table: share of S at the optimum and at the operating
/// point, the optimum without the demo.
fn loo_table(
    ui: &mut egui::Ui,
    session: &Session,
    snap: &DiagSnapshot,
    flagged: &[usize],
    view: &mut ViewState,
) {
    let d = &snap.diagnostics;
    {
        egui::Grid::new("loo table").striped(true).show(ui, |ui| {
            for h in ["demo", "share", "here", "D/M", "K/M", "J", ""] {
                ui.strong(h);
            }
            ui.end_row();
            for (i, demo) in d.demos.iter().enumerate() {
                let name = if flagged.contains(&i) {
                    egui::RichText::new(&demo.name).color(WARN)
                } else {
                    egui::RichText::new(&demo.name)
                };
                if ui.label(name).hovered() {
                    view.hovering = Some(i);
                }
                let percent =
                    |v: Option<f64>| v.map_or("-".into(), |v| format!("{:.1} %", 100.0 * v));
                ui.label(percent(demo.s_share))
                    .on_hover_text("its share of S at the optimum");
                let here = session.point_shares().and_then(|s| s.get(i).copied());
                ui.label(percent(here))
                    .on_hover_text("its share of S at the operating point");
                match &demo.loo {
                    Some(o) => {
                        ui.label(format!("{:.2}", o.dm));
                        ui.label(format!("{:.2}", o.km));
                        ui.label(format!("{:.4}", o.j));
                        ui.label(if o.on_edge { "edge" } else { "" });
                    }
                    None => {
                        for _ in 0..4 {
                            ui.weak("…");
                        }
                    }
                }
                ui.end_row();
            }
        });
    }
}

fn bootstrap_ui(ui: &mut egui::Ui, snap: &DiagSnapshot) {
    match &snap.diagnostics.bootstrap {
        Some(b) => {
            ui.label(format!(
                "Bootstrap ({} resamples, seed {}): D/M {:.2} [{:.2} … {:.2}], K/M {:.2} \
                 [{:.2} … {:.2}] (median [5 % … 95 %]); {:.0} % of the optima on the box edge",
                b.n,
                b.seed,
                b.dm[1],
                b.dm[0],
                b.dm[2],
                b.km[1],
                b.km[0],
                b.km[2],
                100.0 * b.on_edge_fraction
            ));
        }
        None if snap.about.resamples > 0 => {
            ui.weak(format!(
                "Bootstrap: {} of {} optima so far (dots on the J map)",
                snap.cloud.len(),
                snap.about.resamples
            ));
        }
        None => {}
    }
}

/// The a_peak limit and the constrained optimum.
fn limit_ui(ui: &mut egui::Ui, session: &Session, s: &mut Settings) {
    ui.horizontal(|ui| {
        let mut on = s.a_peak_limit.is_some();
        if ui
            .checkbox(&mut on, "Limit a_peak to")
            .on_hover_text("mask the J map where some demo's peak acceleration exceeds it")
            .changed()
        {
            s.a_peak_limit = on.then(|| first_limit(session));
        }
        if let Some(limit) = &mut s.a_peak_limit {
            ui.add(
                egui::DragValue::new(limit)
                    .speed(0.05)
                    .range(0.01..=1e6)
                    .suffix(" m/s²"),
            );
        }
    });
    let Some(limit) = s.a_peak_limit else {
        return;
    };
    match session.constrained() {
        Some(Some(c)) => {
            ui.horizontal_wrapped(|ui| {
                let free = session.extraction().map(|x| x.j);
                let above = free.map_or(String::new(), |f| {
                    format!(
                        ", {:.1} % above the free optimum",
                        100.0 * (c.value / f - 1.0)
                    )
                });
                ui.label(format!(
                    "Constrained optimum: D/M {:.3}, K/M {:.3}, J {:.4}{above}",
                    c.dm, c.km, c.value
                ));
                if ui.small_button("Go there").clicked() {
                    s.op = (c.dm, c.km);
                }
            });
        }
        Some(None) => {
            ui.colored_label(
                WARN,
                format!("No gains on the grid keep every demo's a_peak within {limit} m/s²."),
            );
        }
        None => {
            ui.horizontal(|ui| {
                crate::gui::busy::spinner(ui);
                ui.label("Finding the constrained optimum…");
            });
        }
    }
}

/// A first limit that binds but leaves gains within it: halfway from the
/// least a_peak on the grid to the free optimum's, rounded up.
fn first_limit(session: &Session) -> f64 {
    let free = session
        .extraction()
        .map(|x| x.eval.a_peak.iter().copied().fold(0.0, f64::max));
    let least = session.shown().map(|s| {
        s.values(dmpscope_core::landscape::quantity::Quantity::APeak)
            .iter()
            .copied()
            .filter(|v| v.is_finite())
            .fold(f64::INFINITY, f64::min)
    });
    let limit = match (free, least) {
        (Some(f), Some(l)) if l.is_finite() && l < f => 0.5 * (l + f),
        (Some(f), _) => f,
        _ => 10.0,
    };
    (limit * 100.0).ceil() / 100.0
}

fn settings_ui(ui: &mut egui::Ui, d: &mut DiagSettings) {
    ui.horizontal(|ui| {
        let label = ui.label("bootstrap resamples");
        ui.add(egui::DragValue::new(&mut d.bootstrap).range(0..=1000))
            .labelled_by(label.id);
    });
    ui.horizontal(|ui| {
        let label = ui.label("seed");
        ui.add(egui::DragValue::new(&mut d.seed))
            .labelled_by(label.id);
    });
    ui.horizontal(|ui| {
        let label = ui.label("resampled grid points per axis");
        ui.add(egui::DragValue::new(&mut d.grid_points).range(4..=256))
            .labelled_by(label.id);
    });
}
