//! What the demos allow (method.md section 11), in the Gains section: the
//! pick rule and the region's eps, the verdict (the region's ranges, the
//! pick and why, E's identifiability sentence), the gains for the robot at
//! the pick and the operating point, and a button to go to the pick.

use dmpscope_core::extract::allowed::{Pick, PickRule, mean_duration};
use dmpscope_core::extract::robot::RobotGains;
use eframe::egui::{self, Color32};

use super::PanelCtx;
use crate::session::Settings;

/// The colour of the pick's marker and text.
pub const PICK_COLOUR: Color32 = Color32::from_rgb(255, 150, 255);

/// The "What the demos allow" part of the Gains section: one line with
/// the pick (or why there is none) that opens to the rule, the region, the
/// verdict and the robot's gains.
pub fn allowed_ui(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>) {
    let summary = match cx.session.allowed().map(|v| &v.allowed) {
        Some(a) => match &a.pick {
            // Short: the side panel is as wide as its widest line.
            Some(p) => format!(
                "What the demos allow: {}, {} / {}",
                p.rule.name(),
                dmpscope_core::extract::allowed::num(p.dm),
                dmpscope_core::extract::allowed::num(p.km)
            ),
            None => "What the demos allow: no pick (open)".to_owned(),
        },
        None => "What the demos allow".to_owned(),
    };
    egui::CollapsingHeader::new(summary)
        .id_salt("what the demos allow")
        .show(ui, |ui| allowed_body_ui(ui, cx));
}

/// The rule, the region, the verdict and the robot's gains.
fn allowed_body_ui(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>) {
    let session = cx.session;
    let s = &mut *cx.settings;
    rule_settings_ui(ui, s);
    let Some(view) = session.allowed() else {
        ui.weak("What the demos allow: waiting for the full landscape and the optimum");
        return;
    };
    let a = &view.allowed;
    let region = a.acceptable.text();
    let share = 100.0 * a.acceptable.fraction;
    if a.j_flat {
        ui.label(format!(
            "The data allow {region} ({share:.1} % of the grid)."
        ));
    } else {
        ui.label(format!("Acceptable: {region} ({share:.1} % of the grid)."));
    }
    match &a.pick {
        Some(p) => pick_ui(ui, p, s),
        None => {
            let why = a.pick_failure.as_deref().unwrap_or("no pick");
            ui.colored_label(Color32::from_rgb(240, 180, 80), why);
        }
    }
    if let Some(model) = session.model() {
        let op = RobotGains::new(s.op.0, s.op.1, mean_duration(model));
        ui.weak(format!("Operating point for the robot: {}", op.text()));
    }
    ui.label(a.identifiability_text().trim());
}

/// The pick rule, the acceptable region's tolerance and "settle within".
fn rule_settings_ui(ui: &mut egui::Ui, s: &mut Settings) {
    ui.horizontal(|ui| {
        let auto = "auto (optimum if J is not flat, else compliant)";
        egui::ComboBox::from_label("pick")
            .selected_text(s.pick.map_or(auto, PickRule::name))
            .show_ui(ui, |ui| {
                ui.selectable_value(&mut s.pick, None, auto);
                for rule in PickRule::ALL {
                    ui.selectable_value(&mut s.pick, Some(rule), rule.name())
                        .on_hover_text(rule.rule_text());
                }
            });
    });
    ui.horizontal(|ui| {
        let l = ui.label("acceptable: J within").on_hover_text(
            "the acceptable region: every grid point whose J is within this fraction of the \
             optimum's (drawn as a green contour on the maps)",
        );
        ui.add(
            egui::DragValue::new(&mut s.accept_eps)
                .range(0.001..=10.0)
                .speed(0.005)
                .fixed_decimals(3),
        )
        .labelled_by(l.id);
        ui.label("of J*");
    });
    ui.horizontal(|ui| {
        let mut on = s.settle_within.is_some();
        if ui
            .checkbox(&mut on, "settle within")
            .on_hover_text(
                "keep the compliant, critical and smooth picks to gains whose spring-damper \
                 settles (2 %) within this many unit times (1: the motion's own duration)",
            )
            .changed()
        {
            s.settle_within = on.then_some(1.0);
        }
        if let Some(v) = &mut s.settle_within {
            ui.add(
                egui::DragValue::new(v)
                    .range(0.05..=20.0)
                    .speed(0.02)
                    .fixed_decimals(2),
            );
            ui.label("unit times");
        }
    });
}

/// The pick: its gains, why, the button to go there, settling and the edge.
fn pick_ui(ui: &mut egui::Ui, p: &Pick, s: &mut Settings) {
    ui.colored_label(
        PICK_COLOUR,
        format!(
            "Picked by {}: D/M {:.3}, K/M {:.3} (zeta {:.3})",
            p.rule.name(),
            p.dm,
            p.km,
            p.zeta
        ),
    );
    ui.weak(&p.why);
    if ui
        .button("Go to the pick")
        .on_hover_text("make the pick the operating point (Table I, New target, Export, RL use it)")
        .clicked()
    {
        s.op = (p.dm, p.km);
    }
    ui.label(format!("For the robot: {}", p.robot.text()));
    ui.label(format!(
        "Settles (2 %) in {:.3} unit times, {:.3} s",
        p.settling.unit, p.settling.seconds
    ));
    if p.on_edge {
        ui.colored_label(
            Color32::from_rgb(240, 180, 80),
            format!(
                "On the edge: the pick lies on {} of the box, where its rule would go \
                         further; widen the box (Settings) or set \"settle within\"",
                p.edge
            ),
        );
    }
}
