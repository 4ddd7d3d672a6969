//! The right panel, in four tabs: the demo shown with a time slider and
//! its time plots against its regeneration at the operating point; every
//! demo's standardised forcing term and sigma_f there; the Pareto front of
//! (sum d, S); the demo or the skill at a new start, goal and duration.

use dmpscope_core::Model;
use eframe::egui;

use super::super::commands::Command;
use super::super::view_state::{RightTab, ViewState};
use super::super::{forcing, playback, plots, target_plots, tradeoff};
use super::{PanelCtx, diagnostics, generalise};
use crate::session::{Session, Settings, TargetSource};

/// The plots panel.
pub fn plots_ui(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>) {
    let session = cx.session;
    let Some(model) = session.model() else {
        return;
    };
    ui.horizontal(|ui| {
        ui.selectable_value(&mut cx.view.right, RightTab::Demo, "Demo");
        ui.selectable_value(&mut cx.view.right, RightTab::Forcing, "Forcing terms");
        ui.selectable_value(&mut cx.view.right, RightTab::TradeOff, "Trade-off");
        let tab = ui.selectable_value(&mut cx.view.right, RightTab::Generalised, "New target");
        cx.view.click_targets.insert("New target", tab.rect);
    });
    ui.separator();
    match cx.view.right {
        RightTab::Demo => demo_tab(ui, cx, model),
        RightTab::Forcing => forcing_tab(ui, cx),
        RightTab::TradeOff => tradeoff_tab(ui, session, cx.settings, cx.view),
        RightTab::Generalised => generalised_tab(ui, cx),
    }
}

/// The demo shown (picking another asks for [`Command::Select`]), the time
/// slider and its time plots against its regeneration.
fn demo_tab(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>, model: &Model) {
    let session = cx.session;
    let demos = model.demos();
    let Some(demo) = demos.get(cx.view.selected) else {
        return;
    };
    ui.horizontal(|ui| {
        egui::ComboBox::from_label("demo")
            .selected_text(demo.name.clone())
            .show_ui(ui, |ui| {
                let mut selected = cx.view.selected;
                for (i, d) in demos.iter().enumerate() {
                    ui.selectable_value(&mut selected, i, &d.name);
                }
                if selected != cx.view.selected {
                    cx.push(Command::Select(selected));
                }
            });
    });
    let view = &mut *cx.view;
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
    ui.horizontal(|ui| {
        let target = session
            .generalised()
            .and_then(Result::ok)
            .map(|g| g.out.duration_s);
        let d = playback::Durations {
            demo: demo.duration_s,
            target,
        };
        playback::controls_ui(ui, &mut view.playback, d);
    });
    let turn = session.turns().get(view.selected).and_then(Option::as_ref);
    if turn.is_some() {
        ui.horizontal(|ui| {
            ui.selectable_value(&mut view.orientation_plots, false, "position");
            ui.selectable_value(&mut view.orientation_plots, true, "orientation");
        });
    }
    let selected = view.selected;
    let colour = |c: [u8; 3]| egui::Color32::from_rgb(c[0], c[1], c[2]);
    let drawn = match (turn, view.orientation_plots) {
        (Some(turn), true) => {
            let pins: Vec<plots::PlotPin<'_, _>> = view
                .pins
                .shown_turns(selected)
                .map(|(p, regen)| plots::PlotPin {
                    name: &p.name,
                    colour: colour(p.colour),
                    regen,
                })
                .collect();
            plots::show_orientation(ui, demo, turn, view.t, &pins)
        }
        _ => {
            let pins: Vec<plots::PlotPin<'_, _>> = view
                .pins
                .shown_regen()
                .filter_map(|(p, regen)| {
                    Some(plots::PlotPin {
                        name: &p.name,
                        colour: colour(p.colour),
                        regen: regen.get(selected)?,
                    })
                })
                .collect();
            session
                .paths()
                .get(selected)
                .map(|rollout| plots::show(ui, demo, rollout, view.t, &pins))
        }
    };
    view.plot_pin_lines = drawn.map_or(0, |d| d.pin_items);
    let hovered = drawn.and_then(|d| d.hovered);
    if let Some(t) = hovered {
        view.t = t;
    }
}

fn generalised_tab(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>) {
    let session = cx.session;
    let Some(model) = session.model() else {
        return;
    };
    generalise::generalise_ui(ui, cx);
    let Some(Ok(g)) = session.generalised() else {
        return;
    };
    ui.weak("solid: at the new target · dashed: at its own · dotted: the new goal");
    let own = session
        .generalise_spec()
        .and_then(|spec| match spec.source {
            TargetSource::Demo(i) => Some(i),
            TargetSource::Skill => None,
        })
        .and_then(|i| {
            let d = model.demos().get(i)?;
            Some(target_plots::OwnRun {
                rollout: session.paths().get(i)?,
                duration_s: d.duration_s,
            })
        });
    if let Some(d) = model.demos().get(cx.view.selected).map(|d| d.duration_s) {
        ui.horizontal(|ui| {
            let d = playback::Durations {
                demo: d,
                target: Some(g.out.duration_s),
            };
            playback::controls_ui(ui, &mut cx.view.playback, d);
        });
    }
    let pins: Vec<target_plots::PinRun<'_>> = cx
        .view
        .pins
        .shown_targets()
        .map(|(p, run)| target_plots::PinRun {
            name: &p.name,
            colour: egui::Color32::from_rgb(p.colour[0], p.colour[1], p.colour[2]),
            run,
        })
        .collect();
    if let Some(t) = target_plots::show(ui, g, own, cx.view.t_target, &pins) {
        cx.view.t_target = t;
    }
}

fn forcing_tab(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>) {
    let session = cx.session;
    let (Some(model), Some(terms)) = (session.model(), session.forcing_terms()) else {
        return;
    };
    if model.demos().len() < 2 {
        ui.label("S compares the demos' forcing terms: it needs two or more demonstrations.");
    }
    let names: Vec<String> = model.demos().iter().map(|d| d.name.clone()).collect();
    let flagged = session
        .diagnostics()
        .map(|d| d.diagnostics.inconsistent())
        .unwrap_or_default();
    let (dm, km) = session
        .point()
        .map_or((f64::NAN, f64::NAN), |p| (p.dm, p.km));
    ui.weak(format!("at the operating point D/M {dm:.3}, K/M {km:.3}"));
    // The flagged demos, each excluded in one click.
    if !flagged.is_empty() {
        ui.horizontal_wrapped(|ui| {
            ui.label("flagged:");
            for &i in &flagged {
                let label = format!("Exclude {}", names.get(i).map_or("", String::as_str));
                diagnostics::exclude_button(ui, cx, i, &label);
            }
        });
    }
    let selected = cx.view.selected;
    let pins: Vec<forcing::ForcingPin<'_>> = cx
        .view
        .pins
        .shown_forcing(selected)
        .map(|(p, f)| forcing::ForcingPin {
            name: &p.name,
            colour: egui::Color32::from_rgb(p.colour[0], p.colour[1], p.colour[2]),
            f,
        })
        .collect();
    if !pins.is_empty() {
        ui.weak(format!(
            "pinned sets: {}'s term at each, in the set's colour",
            names.get(selected).map_or("", String::as_str)
        ));
    }
    let input = forcing::ForcingInput {
        terms,
        names: &names,
        shares: session.point_shares(),
        flagged: &flagged,
        hovered: cx.view.hovered,
        pins: &pins,
    };
    if let Some(i) = forcing::show(ui, &input) {
        cx.view.hovering = Some(i);
    }
}

fn tradeoff_tab(ui: &mut egui::Ui, session: &Session, s: &mut Settings, view: &mut ViewState) {
    let Some(shown) = session.shown() else {
        ui.label("The trade-off needs the landscape.");
        return;
    };
    let marks = tradeoff::Marks {
        optimum: session.extraction().map(|x| [x.eval.d_sum, x.eval.s]),
        op: session.point().map(|p| [p.d_sum, p.s]),
        k: s.k,
    };
    let front = view.pareto.front(shown);
    if let Some(idx) = tradeoff::show(ui, shown, front, &marks) {
        let grid = shown.grid();
        let l = &shown.snapshot.landscape;
        let (i, j) = (idx / grid.km.n, idx % grid.km.n);
        if let (Some(&dm), Some(&km)) = (l.dm.get(i), l.km.get(j)) {
            s.op = (dm, km);
        }
    }
}
