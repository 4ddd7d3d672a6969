//! Time plots of a generalised run (method.md section 10) in real time over
//! its duration T': position from the start (with the goal per axis, so an
//! overshoot shows at the motion's own scale), velocity and acceleration per
//! axis; a skill's ±1 SD band around its position; the source at its own
//! target dashed for comparison.

use dmpscope_core::geom::Vec3;
use dmpscope_core::{Generalised, Rollout};
use eframe::egui::{self, Color32};
use egui_plot::{HLine, Legend, Line, LineStyle, Plot, PlotPoints, PlotUi, VLine};

use crate::gui::thinning::kept;
use crate::session::TargetView;

const AXES: [(&str, Color32); 3] = [
    ("x", Color32::from_rgb(230, 90, 80)),
    ("y", Color32::from_rgb(90, 190, 100)),
    ("z", Color32::from_rgb(90, 140, 230)),
];

/// Points drawn per line at most: a smooth rollout of 1001 steps drawn
/// with every sixth (about two pixels a segment in the side panel); 300
/// cost about 0.25 ms more a frame (`tests/frame_time.sh new-target`); a
/// screenshot at 200 shows the curves smooth.
const MAX_POINTS: usize = 200;

/// The source at its own target: its unit-time path and its own duration.
pub struct OwnRun<'a> {
    /// The regenerated path at the operating point, relative to its start
    /// (demo coordinates).
    pub rollout: &'a Rollout,
    /// Its duration, seconds.
    pub duration_s: f64,
}

/// A pinned set's run at the same target.
pub struct PinRun<'a> {
    /// Its name.
    pub name: &'a str,
    /// Its colour.
    pub colour: Color32,
    /// The run.
    pub run: &'a Generalised,
}

fn series(
    values: &[Vec3],
    axis: usize,
    time: impl Fn(usize) -> f64,
    value: impl Fn(f64) -> f64,
) -> PlotPoints<'static> {
    kept(values.len(), MAX_POINTS)
        .map(|k| [time(k), value(values[k][axis])])
        .collect()
}

/// Shows the three plots; `t` is the time cursor in unit time. Returns the
/// unit time under the pointer while it is over a plot.
pub fn show(
    ui: &mut egui::Ui,
    g: &TargetView,
    own: Option<OwnRun<'_>>,
    t: f64,
    pins: &[PinRun<'_>],
) -> Option<f64> {
    let o = &g.out;
    let tau = o.duration_s;
    let height = ((ui.available_height() - 12.0) / 3.0).max(60.0);
    let group = ui.scope_id().with("generalised plots");
    let mut hovered = None;
    for row in 0..3 {
        let label = [
            "position − start [m]",
            "velocity [m/s]",
            "acceleration [m/s²]",
        ][row];
        let response = Plot::new(("generalised", row))
            .height(height)
            .legend(Legend::default())
            .link_axis(group, [true, false])
            .link_cursor(group, [true, false])
            .y_axis_label(label)
            .x_axis_label("time [s]")
            .allow_scroll(false)
            .show(ui, |plot| {
                plot.vline(
                    VLine::new("time", t * tau)
                        .color(Color32::from_gray(200))
                        .width(1.0),
                );
                for (ax, (name, colour)) in AXES.iter().enumerate() {
                    let from = if row == 0 { o.start[ax] } else { 0.0 };
                    new_run_line(plot, o, row, ax, name, *colour, from);
                    if row == 0 {
                        goal_and_band(plot, o, ax, *colour, from);
                    }
                    if let Some(own) = &own {
                        own_run_line(plot, own, row, ax, name, *colour);
                    }
                    for pin in pins {
                        let from = if row == 0 { pin.run.start[ax] } else { 0.0 };
                        new_run_line(plot, pin.run, row, ax, pin.name, pin.colour, from);
                    }
                }
                plot.pointer_coordinate()
            });
        if response.response.hovered()
            && let Some(p) = response.inner
        {
            hovered = Some((p.x / tau).clamp(0.0, 1.0));
        }
    }
    hovered
}

/// The new run's line for axis `ax` on plot `row` (position, velocity,
/// acceleration), less `from`.
fn new_run_line(
    plot: &mut PlotUi<'_>,
    o: &Generalised,
    row: usize,
    ax: usize,
    name: &str,
    colour: Color32,
    from: f64,
) {
    let at = |k: usize| o.t[k];
    let values = match row {
        0 => &o.unit.y,
        1 => &o.v,
        _ => &o.a,
    };
    plot.line(
        Line::new(format!("new {name}"), series(values, ax, at, |v| v - from))
            .color(colour)
            .width(2.0),
    );
}

/// On the position plot: the goal of axis `ax` dotted, and a skill's ±1 SD
/// band around the run, less `from`.
fn goal_and_band(plot: &mut PlotUi<'_>, o: &Generalised, ax: usize, colour: Color32, from: f64) {
    let n = o.t.len();
    plot.hline(
        HLine::new("", o.goal[ax] - from)
            .color(colour.gamma_multiply(0.6))
            .style(LineStyle::dotted_dense()),
    );
    if o.band.len() == n {
        for sign in [-1.0, 1.0] {
            let points: PlotPoints<'static> = kept(n, MAX_POINTS)
                .map(|k| [o.t[k], o.unit.y[k][ax] - from + sign * o.band[k][ax]])
                .collect();
            plot.line(
                Line::new("", points)
                    .color(colour.gamma_multiply(0.45))
                    .width(1.0),
            );
        }
    }
}

/// The source at its own target, dashed, for axis `ax` on plot `row`, in
/// real time over its own duration.
fn own_run_line(
    plot: &mut PlotUi<'_>,
    own: &OwnRun<'_>,
    row: usize,
    ax: usize,
    name: &str,
    colour: Color32,
) {
    let m = own.rollout.y.len();
    let own_t = |k: usize| own.duration_s * k as f64 / (m.max(2) - 1) as f64;
    let (values, scale, shift) = match row {
        0 => (&own.rollout.y, 1.0, 0.0),
        1 => (&own.rollout.v, 1.0 / own.duration_s, 0.0),
        _ => (&own.rollout.a, 1.0 / (own.duration_s * own.duration_s), 0.0),
    };
    plot.line(
        Line::new(
            format!("own {name}"),
            series(values, ax, own_t, |v| v * scale + shift),
        )
        .color(colour.gamma_multiply(0.7))
        .style(LineStyle::dashed_loose()),
    );
}
