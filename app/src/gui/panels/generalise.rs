//! The controls of the right panel's "New target" tab (method.md section
//! 10): the selected demo or the skill of all demos at the
//! operating point's gains, run from a typed (or, in the 3D view, dragged)
//! start to a goal over a duration, with the scaling mode, its peak speed,
//! peak acceleration and end error, and Reset.

use dmpscope_core::geom::Vec3;
use dmpscope_core::{Model, Scaling, Target};
use eframe::egui::{self, Color32};

use super::super::commands::{Command, Export};
use super::{PanelCtx, orientation_target};
use crate::session::{Command as SessionCommand, GeneraliseSpec, Session, TargetSource};

/// The source's own start, goal (absolute) and duration.
pub fn own_target(model: &Model, source: TargetSource) -> Option<(Vec3, Vec3, f64)> {
    let demos = model.demos();
    match source {
        TargetSource::Demo(i) => demos.get(i).map(|d| (d.p0, d.p0 + d.goal, d.duration_s)),
        TargetSource::Skill => {
            let n = demos.len().max(1) as f64;
            let mean = |f: &dyn Fn(&dmpscope_core::PreparedDemo) -> Vec3| -> Vec3 {
                Vec3::from_fn(|a, _| demos.iter().map(|d| f(d)[a]).sum::<f64>() / n)
            };
            let start = mean(&|d| d.p0);
            let shift = mean(&|d| d.goal);
            let goal = start + shift;
            let duration = demos.iter().map(|d| d.duration_s).sum::<f64>() / n;
            Some((start, goal, duration))
        }
    }
}

/// Three coordinates as drag values; returns the new value when edited.
fn triple(ui: &mut egui::Ui, label: &str, value: Vec3) -> Option<Vec3> {
    let mut v = value;
    let mut changed = false;
    ui.horizontal(|ui| {
        let l = ui.label(label);
        for (c, name) in v.iter_mut().zip(["x", "y", "z"]) {
            changed |= ui
                .add(
                    egui::DragValue::new(c)
                        .speed(0.002)
                        .fixed_decimals(3)
                        .prefix(format!("{name} "))
                        .suffix(" m"),
                )
                .labelled_by(l.id)
                .changed();
        }
    });
    changed.then_some(v)
}

/// The section.
pub fn generalise_ui(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>) {
    let session = cx.session;
    let Some(model) = session.model() else {
        ui.weak("Needs demonstrations.");
        return;
    };
    let current = session.generalise_spec().copied();
    let selected = cx.view.selected;
    if generalise_switch_ui(ui, current.is_some(), selected, cx) {
        return;
    }
    let Some(mut spec) = current else {
        return;
    };
    // (A demo source follows the selected demo: `DmpApp` sees to it each
    // frame, whichever tab is open.)
    let before = spec;
    generalise_source_ui(ui, &mut spec, selected);
    if spec.source != before.source {
        // A new source starts at its own target.
        spec = spec.reset();
    }
    if let Some(own) = own_target(model, spec.source) {
        generalise_target_ui(ui, &mut spec, own);
    }
    if let Some(own) = orientation_target::own_orientation(model, spec.source) {
        orientation_target::orientation_rows_ui(ui, cx, &mut spec.target, own);
    }
    generalise_gains_ui(ui, cx);
    generalise_result_ui(ui, session);
    generalise_export_ui(ui, cx);
    ui.weak("3D view: drag the white goal ring or start disc (Shift: height; Ctrl on the goal: turn its orientation)");
    if spec != before {
        cx.push(SessionCommand::SetGeneralise(Some(spec)));
    }
}

/// The on/off checkbox (explained while off); true when toggled (its command pushed).
fn generalise_switch_ui(
    ui: &mut egui::Ui,
    mut on: bool,
    selected: usize,
    cx: &mut PanelCtx<'_>,
) -> bool {
    if !on {
        ui.label(
            "Run the selected demo, or the skill of all demos, at the operating point's gains \
             from a new start to a new goal over a new duration: what a robot does with them.",
        );
    }
    let switch = ui.checkbox(&mut on, "Run the DMP at a new target");
    cx.view
        .click_targets
        .insert("Run at a new target", switch.rect);
    if switch
        .on_hover_text(
            "The selected demo (or the skill of all demos) at the operating point's gains, \
             from a new start to a new goal over a new duration",
        )
        .changed()
    {
        cx.push(SessionCommand::SetGeneralise(
            on.then(|| GeneraliseSpec::demo(selected)),
        ));
        return true;
    }
    false
}

/// The source (the selected demo or the skill) and the scaling mode.
fn generalise_source_ui(ui: &mut egui::Ui, spec: &mut GeneraliseSpec, selected: usize) {
    ui.horizontal(|ui| {
        ui.label("of");
        let demo = TargetSource::Demo(selected);
        ui.selectable_value(&mut spec.source, demo, "the selected demo");
        ui.selectable_value(
            &mut spec.source,
            TargetSource::Skill,
            "the skill of all demos",
        )
        .on_hover_text(
            "The mean of the demos' forcing terms, each mapped to the mean displacement \
                 by the scaling mode; the band is ±1 SD of the demos' own runs",
        );
    });
    ui.horizontal(|ui| {
        ui.label("scaling");
        ui.selectable_value(&mut spec.target.scaling, Scaling::Paper, "per axis (paper)")
            .on_hover_text("f_a (g'_a - y0'_a) / (g_a - y0_a) on each axis");
        ui.selectable_value(
            &mut spec.target.scaling,
            Scaling::Frame,
            "frame-independent",
        )
        .on_hover_text(
            "A rotation and a uniform scale taking g - y0 onto g' - y0': no per-axis \
                 singularity",
        );
    });
}

/// The start, goal and duration, with the source's `own` ones as defaults, and Reset.
fn generalise_target_ui(ui: &mut egui::Ui, spec: &mut GeneraliseSpec, own: (Vec3, Vec3, f64)) {
    let (own_start, own_goal, own_duration) = own;
    let start = spec.target.start.unwrap_or(own_start);
    let goal = spec.target.goal.unwrap_or(own_goal);
    if let Some(v) = triple(ui, "start", start) {
        spec.target.start = Some(v);
    }
    if let Some(v) = triple(ui, "goal ", goal) {
        spec.target.goal = Some(v);
    }
    ui.horizontal(|ui| {
        let l = ui.label("duration T'");
        let mut d = spec.target.duration_s.unwrap_or(own_duration);
        if ui
            .add(
                egui::DragValue::new(&mut d)
                    .speed(0.01)
                    .range(0.05..=120.0)
                    .clamp_existing_to_range(false)
                    .fixed_decimals(2)
                    .suffix(" s"),
            )
            .labelled_by(l.id)
            .changed()
        {
            spec.target.duration_s = Some(d);
        }
        ui.weak(format!("(own {own_duration:.2} s)"));
        let moved = spec.target
            != Target {
                scaling: spec.target.scaling,
                ..Target::default()
            };
        if ui
            .add_enabled(moved, egui::Button::new("Reset"))
            .on_hover_text("Back to the source's own start, goal and duration")
            .clicked()
        {
            *spec = spec.reset();
        }
    });
}

/// The run's peak speed, a_peak and end error with its warnings, or its error.
fn generalise_result_ui(ui: &mut egui::Ui, session: &Session) {
    match session.generalised() {
        Some(Ok(g)) => {
            let o = &g.out;
            ui.label(format!(
                "peak speed {:.3} m/s · a_peak {:.3} m/s² · ends {:.1} mm from the goal",
                o.peak_speed,
                o.a_peak,
                o.final_error * 1e3
            ))
            .on_hover_text("In real time over T'");
            if let (Some(turn), Some(end)) = (&o.orientation, turn_end(o)) {
                let peak = turn
                    .a
                    .iter()
                    .map(|a| (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt())
                    .fold(0.0, f64::max);
                let total = o.t.last().copied().unwrap_or(1.0).max(1e-9);
                ui.label(format!(
                    "orientation ends {end:.2}° from the goal orientation · alpha_peak {:.2} \
                     rad/s²",
                    peak / (total * total)
                ))
                .on_hover_text("In real time over T'");
            }
            for w in &o.warnings {
                ui.colored_label(Color32::from_rgb(240, 180, 80), w);
            }
        }
        Some(Err(e)) => {
            ui.colored_label(Color32::from_rgb(240, 120, 100), e);
        }
        None => {}
    }
}

/// The angle in degrees between a run's last orientation and the goal
/// orientation it ran to (its own when none was asked for).
fn turn_end(o: &dmpscope_core::Generalised) -> Option<f64> {
    let turn = o.orientation.as_ref()?;
    let last = *turn.q.last()?;
    let goal = o.orientation_goal.unwrap_or(last);
    Some(dmpscope_core::rotation::angle(last, goal).to_degrees())
}

/// The gains it runs at (the operating point's) and, when they differ, a
/// button that takes the gains picked in What the demos allow.
fn generalise_gains_ui(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>) {
    let op = cx.settings.op;
    ui.horizontal_wrapped(|ui| {
        ui.label(format!("gains: D/M {:.3}, K/M {:.3}", op.0, op.1));
        let pick = cx.session.allowed().and_then(|v| v.allowed.pick.as_ref());
        if let Some(p) = pick
            && (p.dm, p.km) != op
            && ui
                .button(format!("Use the pick ({})", p.rule.name()))
                .on_hover_text(format!("D/M {:.3}, K/M {:.3}: {}", p.dm, p.km, p.why))
                .clicked()
        {
            cx.settings.op = (p.dm, p.km);
        }
    });
}

/// The button exporting the DMP at this target for a robot.
fn generalise_export_ui(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>) {
    let session = cx.session;
    ui.horizontal_wrapped(|ui| {
        let ok = session.generalised().is_some_and(|g| g.is_ok());
        if ui
            .add_enabled(ok, egui::Button::new("Export for a robot (JSON)…"))
            .on_hover_text(
                "The DMP at this target with its equations and a golden rollout \
                 (docs/export.md; examples/run_dmp.py runs it)",
            )
            .clicked()
        {
            cx.push(Command::Export(Export::Dmp));
        }
    });
}
