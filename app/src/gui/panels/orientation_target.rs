//! The New target tab's orientation rows (method.md section 12), for a
//! demo with orientation: the new start and goal orientation typed as
//! roll, pitch and yaw in degrees or as a quaternion (normalised with a
//! notice), each with its own as the default, and the end angle reached.

use dmpscope_core::geom::{quat_from_xyzw, xyzw};
use dmpscope_core::rotation::QuatXyzw;
use dmpscope_core::{Model, Notice, Target};
use eframe::egui;

use super::PanelCtx;
use crate::session::{Command as SessionCommand, TargetSource};

/// Which orientation a row edits.
#[derive(Clone, Copy)]
enum End {
    Start,
    Goal,
}

impl End {
    fn name(self) -> &'static str {
        match self {
            Self::Start => "start",
            Self::Goal => "goal",
        }
    }

    fn of(self, target: &mut Target) -> &mut Option<QuatXyzw> {
        match self {
            Self::Start => &mut target.start_orientation,
            Self::Goal => &mut target.goal_orientation,
        }
    }
}

/// The demo's own start and goal orientation, `None` for the skill or a
/// demo without orientation.
pub fn own_orientation(model: &Model, source: TargetSource) -> Option<(QuatXyzw, QuatXyzw)> {
    let TargetSource::Demo(i) = source else {
        return None;
    };
    let o = model.demos().get(i)?.orientation.as_ref()?;
    Some((*o.q.first()?, o.goal))
}

/// Roll, pitch and yaw (x, y, z fixed axes), degrees, of `q`.
pub fn rpy_degrees(q: QuatXyzw) -> [f64; 3] {
    let Some(u) = quat_from_xyzw(q) else {
        return [0.0; 3];
    };
    let (r, p, y) = u.euler_angles();
    [r, p, y].map(f64::to_degrees)
}

/// The orientation of roll, pitch and yaw in degrees.
pub fn from_rpy_degrees(rpy: [f64; 3]) -> QuatXyzw {
    let [r, p, y] = rpy.map(f64::to_radians);
    xyzw(&dmpscope_core::geom::Quat::from_euler_angles(r, p, y))
}

/// The start and goal orientation rows of `target` with `own` as their
/// defaults; edits change `target` and a non-unit quaternion is normalised
/// with a notice pushed to `cx`.
pub fn orientation_rows_ui(
    ui: &mut egui::Ui,
    cx: &mut PanelCtx<'_>,
    target: &mut Target,
    own: (QuatXyzw, QuatXyzw),
) {
    for (end, own) in [(End::Start, own.0), (End::Goal, own.1)] {
        let current = end.of(target).unwrap_or(own);
        ui.horizontal(|ui| {
            let l = ui.label(format!("{} orientation", end.name()));
            let mut rpy = rpy_degrees(current);
            let mut changed = false;
            for (v, name) in rpy.iter_mut().zip(["roll", "pitch", "yaw"]) {
                changed |= ui
                    .add(
                        egui::DragValue::new(v)
                            .speed(0.5)
                            .fixed_decimals(1)
                            .prefix(format!("{name} "))
                            .suffix("°"),
                    )
                    .labelled_by(l.id)
                    .on_hover_text("degrees, about the fixed x, y and z axes (in that order)")
                    .changed();
            }
            if changed {
                *end.of(target) = Some(from_rpy_degrees(rpy));
            }
        });
        egui::CollapsingHeader::new(format!("{} orientation as a quaternion", end.name()))
            .id_salt(("quaternion", end.name()))
            .show(ui, |ui| quaternion_ui(ui, cx, target, end, current));
    }
}

/// The four components of a quaternion, typed; normalised (with a notice)
/// when they are not unit, refused when zero or not finite.
fn quaternion_ui(
    ui: &mut egui::Ui,
    cx: &mut PanelCtx<'_>,
    target: &mut Target,
    end: End,
    q: QuatXyzw,
) {
    let mut typed = q;
    let mut changed = false;
    ui.horizontal(|ui| {
        for (c, name) in typed.iter_mut().zip(["x", "y", "z", "w"]) {
            changed |= ui
                .add(
                    egui::DragValue::new(c)
                        .speed(0.005)
                        .fixed_decimals(4)
                        .prefix(format!("{name} ")),
                )
                .changed();
        }
    });
    if !changed {
        return;
    }
    let norm = typed.iter().map(|c| c * c).sum::<f64>().sqrt();
    match quat_from_xyzw(typed) {
        Some(u) => {
            if (norm - 1.0).abs() > 1e-9 {
                cx.push(SessionCommand::Say(Notice::info(format!(
                    "the {} orientation typed has norm {norm:.4}: normalised",
                    end.name()
                ))));
            }
            *end.of(target) = Some(xyzw(&u));
        }
        None => cx.push(SessionCommand::Say(Notice::warning(format!(
            "the {} orientation typed ({typed:?}) is zero or not finite: not used",
            end.name()
        )))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roll_pitch_yaw_round_trip() {
        let rpy = [10.0, -20.0, 135.0];
        let back = rpy_degrees(from_rpy_degrees(rpy));
        for (a, b) in rpy.iter().zip(back) {
            assert!((a - b).abs() < 1e-9, "{rpy:?} -> {back:?}");
        }
    }
}
