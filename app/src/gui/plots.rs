//! Time plots of one demo against its regeneration at the operating point:
//! position, velocity and acceleration per axis (the paper's Fig. 4), or,
//! for a demo with orientation (method.md section 12), the rotation to the
//! goal, the angular velocity and the angular acceleration per axis.

use super::cached_lines::{CachedLines, SnappedBounds};
use super::thinning::kept;
use dmpscope_core::fit::orientation::OrientationRollout;
use dmpscope_core::geom::Vec3;
use dmpscope_core::rotation;
use dmpscope_core::rotation::QuatXyzw;
use dmpscope_core::{PreparedDemo, Rollout};
use eframe::egui::{self, Color32};
use egui_plot::{Legend, Line, LineStyle, Plot, VLine};

const AXES: [(&str, Color32); 3] = [
    ("x", Color32::from_rgb(230, 90, 80)),
    ("y", Color32::from_rgb(90, 190, 100)),
    ("z", Color32::from_rgb(90, 140, 230)),
];

/// Points drawn per line at most: the series are on a 1001-point grid, and a
/// few hundred points are smooth at the plots' width while a software
/// rasteriser pays for every triangle (measured with `tests/frame_time.sh`).
const MAX_POINTS: usize = 300;

/// Screen points per segment of a pinned set's line: up to six sets of
/// three lines share each plot, and a segment every four points is smooth
/// at the plots' sizes while the tessellated meshes stay small enough to
/// keep the drag frame's budget with six pins (`tests/frame_time.sh`).
const PIN_SEGMENT_POINTS: f32 = 4.0;

/// One plot: its label, the demo's series, the regenerated series and the
/// factor from unit time to seconds.
type Row<'a> = (&'a str, &'a [Vec3], &'a [Vec3], f64);

/// A pinned gain set in the plots: its name, colour and regeneration of
/// the plotted demo.
#[derive(Clone, Copy)]
pub struct PlotPin<'a, T> {
    /// Its name.
    pub name: &'a str,
    /// Its colour.
    pub colour: Color32,
    /// Its regeneration of the demo: a [`Rollout`] for the position plots,
    /// an [`OrientationRollout`] for the orientation plots.
    pub regen: &'a T,
}

/// What the plots drew: the unit time under the pointer while it is over
/// a plot, and how many pinned sets each plot overlaid.
#[derive(Clone, Copy, Debug, Default)]
pub struct Drawn {
    /// The unit time under the pointer.
    pub hovered: Option<f64>,
    /// The pinned sets drawn in each plot.
    pub pin_items: usize,
}

/// A pin's three series in a [`show_rows`] (one per plot).
struct PinRows<'a> {
    name: &'a str,
    colour: Color32,
    rows: [&'a [Vec3]; 3],
}

/// Shows the three plots for `demo` and its `rollout`, stacked, sharing the
/// time axis (seconds of the demonstration), with a cursor at unit time
/// `t` and each pinned set's regeneration in its colour; says what it drew.
pub fn show(
    ui: &mut egui::Ui,
    demo: &PreparedDemo,
    rollout: &Rollout,
    t: f64,
    pins: &[PlotPin<'_, Rollout>],
) -> Drawn {
    let pins: Vec<PinRows<'_>> = pins
        .iter()
        .map(|p| PinRows {
            name: p.name,
            colour: p.colour,
            rows: [&p.regen.y, &p.regen.v, &p.regen.a],
        })
        .collect();
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
    show_rows(ui, demo.duration_s, rows, t, &pins)
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
    pins: &[PlotPin<'_, OrientationRollout>],
) -> Option<Drawn> {
    let o = demo.orientation.as_ref()?;
    let to_goal = |qs: &[QuatXyzw]| -> Vec<Vec3> {
        qs.iter()
            .map(|&q| Vec3::from(rotation::rotation_vector(o.goal, q)).map(f64::to_degrees))
            .collect()
    };
    let points = |v: &[[f64; 3]]| -> Vec<Vec3> { v.iter().map(|&p| Vec3::from(p)).collect() };
    let regen_rows = |r: &OrientationRollout| [to_goal(&r.q), points(&r.w), points(&r.a)];
    let [demo_rot, demo_w, demo_a] = [to_goal(&o.q_raw), points(&o.w), points(&o.wd)];
    let [dmp_rot, dmp_w, dmp_a] = regen_rows(turn);
    let pin_series: Vec<[Vec<Vec3>; 3]> = pins.iter().map(|p| regen_rows(p.regen)).collect();
    let pins: Vec<PinRows<'_>> = pins
        .iter()
        .zip(&pin_series)
        .map(|(p, [rot, w, a])| PinRows {
            name: p.name,
            colour: p.colour,
            rows: [rot, w, a],
        })
        .collect();
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
    Some(show_rows(ui, total, rows, t, &pins))
}

/// Three stacked plots sharing the time axis (seconds over `duration_s`),
/// the demo solid and the DMP dashed per axis, the pins' regenerations
/// (one series per row) under them in their colours, with a
/// cursor at unit time `t`; says what it drew.
fn show_rows(
    ui: &mut egui::Ui,
    duration_s: f64,
    rows: [Row<'_>; 3],
    t: f64,
    pins: &[PinRows<'_>],
) -> Drawn {
    let height = ((ui.available_height() - 12.0) / 3.0).max(60.0);
    let group = ui.scope_id().with("time plots");
    let mut drawn = Drawn::default();
    for (row, (label, target, regen, scale)) in rows.into_iter().enumerate() {
        let n = target.len().max(2);
        let t_of = |k: usize| duration_s * k as f64 / (n - 1) as f64;
        let series = |v: &[Vec3], ax: usize, max: usize| -> Vec<[f64; 2]> {
            kept(v.len(), max)
                .map(|k| [t_of(k), v[k][ax] * scale])
                .collect()
        };
        // The demo's range over the three axes: the steps the regeneration's
        // bounds snap to (an eighth of it).
        let (lo, hi) = target
            .iter()
            .flat_map(|p| [p.x, p.y, p.z])
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                (lo.min(v), hi.max(v))
            });
        let step = (hi - lo) * scale.abs() / 8.0;
        let plot_id = group.with(row);
        let pin_points =
            ((ui.available_width() / PIN_SEGMENT_POINTS) as usize).clamp(50, MAX_POINTS);
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
                // The pins first, under the demo and the DMP at the operating
                // point (where they coincide, the demo stays in sight).
                drawn.pin_items = pins.len();
                for (k, pin) in pins.iter().enumerate() {
                    let values = pin.rows[row];
                    let lines = (0..3).map(|ax| series(values, ax, pin_points)).collect();
                    plot.add(CachedLines::new(
                        pin.name,
                        pin.colour,
                        1.5,
                        lines,
                        plot_id.with(("pin", k)),
                    ));
                }
                for (ax, (name, colour)) in AXES.iter().enumerate() {
                    plot.add(CachedLines::new(
                        format!("demo {name}"),
                        *colour,
                        1.0,
                        vec![series(target, ax, MAX_POINTS)],
                        plot_id.with(("demo", ax)),
                    ));
                    let dmp = Line::new(format!("DMP {name}"), series(regen, ax, MAX_POINTS))
                        .color(*colour)
                        .style(LineStyle::dashed_loose());
                    plot.add(SnappedBounds::new(dmp, step));
                }
                plot.pointer_coordinate()
            });
        if response.response.hovered()
            && let Some(p) = response.inner
        {
            drawn.hovered = Some((p.x / duration_s).clamp(0.0, 1.0));
        }
    }
    drawn
}
