//! Time plots of one demo against its regeneration at the operating point:
//! position, velocity and acceleration per axis (the paper's Fig. 4), or,
//! for a demo with orientation (method.md section 12), the rotation to the
//! goal, the angular velocity and the angular acceleration per axis.

use dmpscope_core::fit::orientation::OrientationRollout;
use dmpscope_core::geom::Vec3;
use dmpscope_core::rotation;
use dmpscope_core::rotation::QuatXyzw;
use dmpscope_core::{PreparedDemo, Rollout};
use eframe::egui::{self, Color32};
use egui_plot::{Legend, Line, LineStyle, Plot, PlotPoints, VLine};

const AXES: [(&str, Color32); 3] = [
    ("x", Color32::from_rgb(230, 90, 80)),
    ("y", Color32::from_rgb(90, 190, 100)),
    ("z", Color32::from_rgb(90, 140, 230)),
];

/// Points drawn per line at most: the series are on a 1001-point grid, and a
/// few hundred points are smooth at the plots' width while a software
/// rasteriser pays for every triangle (measured with `tests/frame_time.sh`).
const MAX_POINTS: usize = 300;

/// One plot: its label, the demo's series, the regenerated series and the
/// factor from unit time to seconds.
type Row<'a> = (&'a str, &'a [Vec3], &'a [Vec3], f64);

/// A pinned gain set in the plots: its name, colour and regeneration of
/// the plotted demo.
#[derive(Clone, Copy)]
pub struct PlotPin<'a> {
    /// Its name.
    pub name: &'a str,
    /// Its colour.
    pub colour: Color32,
    /// Its regeneration of the demo.
    pub rollout: &'a Rollout,
}

/// Shows the three plots for `demo` and its `rollout`, stacked, sharing the
/// time axis (seconds of the demonstration), with a cursor at unit time
/// `t` and each pinned set's regeneration in its colour. Returns the unit
/// time under the pointer while it is over a plot.
pub fn show(
    ui: &mut egui::Ui,
    demo: &PreparedDemo,
    rollout: &Rollout,
    t: f64,
    pins: &[PlotPin<'_>],
) -> Option<f64> {
    let rows: [Row<'_>; 3] = [
        ("position [m]", &demo.y_raw, &rollout.y, 1.0),
        (
            "velocity [m/s]",
            &demo.yd,
            &rollout.v,
            1.0 / demo.duration_s,
        ),
        (
            "acceleration [m/s²]",
            &demo.ydd,
            &rollout.a,
            1.0 / (demo.duration_s * demo.duration_s),
        ),
    ];
    show_rows(ui, demo.duration_s, rows, t, pins)
}

/// The orientation plots of `demo` against its regenerated orientation
/// `turn`: the rotation vector from each orientation to the demo's goal
/// (`2 log(q_g * conj(q))`, degrees), the angular velocity (rad/s) and the
/// angular acceleration (rad/s²), per axis; `None` when the demo has no
/// orientation.
pub fn show_orientation(
    ui: &mut egui::Ui,
    demo: &PreparedDemo,
    turn: &OrientationRollout,
    t: f64,
) -> Option<Option<f64>> {
    let o = demo.orientation.as_ref()?;
    let to_goal = |qs: &[QuatXyzw]| -> Vec<Vec3> {
        qs.iter()
            .map(|&q| Vec3::from(rotation::rotation_vector(o.goal, q)).map(f64::to_degrees))
            .collect()
    };
    let points = |v: &[[f64; 3]]| -> Vec<Vec3> { v.iter().map(|&p| Vec3::from(p)).collect() };
    let (demo_rot, dmp_rot) = (to_goal(&o.q_raw), to_goal(&turn.q));
    let (demo_w, dmp_w) = (points(&o.w), points(&turn.w));
    let (demo_a, dmp_a) = (points(&o.wd), points(&turn.a));
    let total = demo.duration_s;
    let rows: [Row<'_>; 3] = [
        ("rotation to the goal [deg]", &demo_rot, &dmp_rot, 1.0),
        ("angular velocity [rad/s]", &demo_w, &dmp_w, 1.0 / total),
        (
            "angular acceleration [rad/s²]",
            &demo_a,
            &dmp_a,
            1.0 / (total * total),
        ),
    ];
    Some(show_rows(ui, total, rows, t, &[]))
}

/// Three stacked plots sharing the time axis (seconds over `duration_s`),
/// the demo solid and the DMP dashed per axis, the pins' regenerations
/// (position, velocity, acceleration by row) in their colours, with a
/// cursor at unit time `t`; returns the unit time under the pointer.
fn show_rows(
    ui: &mut egui::Ui,
    duration_s: f64,
    rows: [Row<'_>; 3],
    t: f64,
    pins: &[PlotPin<'_>],
) -> Option<f64> {
    let height = ((ui.available_height() - 12.0) / 3.0).max(60.0);
    let group = ui.scope_id().with("time plots");
    let mut hovered = None;
    for (row, (label, target, regen, scale)) in rows.into_iter().enumerate() {
        let n = target.len().max(2);
        let t_of = |k: usize| duration_s * k as f64 / (n - 1) as f64;
        let response = Plot::new(label)
            .height(height)
            .legend(Legend::default())
            .link_axis(group, [true, false])
            .link_cursor(group, [true, false])
            .y_axis_label(label)
            .allow_scroll(false)
            .show(ui, |plot| {
                plot.vline(
                    VLine::new("time", t * duration_s)
                        .color(Color32::from_gray(200))
                        .width(1.0),
                );
                for (ax, (name, colour)) in AXES.iter().enumerate() {
                    let series = |v: &[Vec3]| -> PlotPoints<'static> {
                        let stride = v.len().div_ceil(MAX_POINTS).max(1);
                        let last = v.len().saturating_sub(1);
                        v.iter()
                            .enumerate()
                            .filter(|(k, _)| k % stride == 0 || *k == last)
                            .map(|(k, p)| [t_of(k), p[ax] * scale])
                            .collect()
                    };
                    plot.line(Line::new(format!("demo {name}"), series(target)).color(*colour));
                    plot.line(
                        Line::new(format!("DMP {name}"), series(regen))
                            .color(*colour)
                            .style(LineStyle::dashed_loose()),
                    );
                    for pin in pins {
                        let values = match row {
                            0 => &pin.rollout.y,
                            1 => &pin.rollout.v,
                            _ => &pin.rollout.a,
                        };
                        plot.line(
                            Line::new(pin.name, series(values))
                                .color(pin.colour)
                                .width(1.5),
                        );
                    }
                }
                plot.pointer_coordinate()
            });
        if response.response.hovered()
            && let Some(p) = response.inner
        {
            hovered = Some((p.x / duration_s).clamp(0.0, 1.0));
        }
    }
    hovered
}
