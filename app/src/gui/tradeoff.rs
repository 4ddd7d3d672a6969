//! The trade-off view: the Pareto front of `(sum d, S)` over the grid, the
//! line of slope `-k` through the optimum (J's level line: the optimum is
//! where it touches the front), the operating point; a click moves the
//! operating point to the grid point of the front nearest it.

use dmpscope_core::extract::diagnostics::pareto::pareto_front;
use eframe::egui::{self, Color32};
use egui_plot::{Line, MarkerShape, Plot, PlotPoint, PlotTransform, PlotUi, Points};

use crate::session::Shown;
use dmpscope_core::Quantity;

/// The front of one snapshot, computed once per snapshot.
#[derive(Default)]
pub struct FrontCache {
    version: Option<u64>,
    /// Grid indices on the front, by increasing sum d.
    front: Vec<usize>,
}

impl FrontCache {
    /// The front of `shown` (recomputed when it is a new snapshot).
    pub fn front(&mut self, shown: &Shown) -> &[usize] {
        if self.version != Some(shown.version) {
            self.front = pareto_front(shown.values(Quantity::DSum), shown.values(Quantity::S));
            self.version = Some(shown.version);
        }
        &self.front
    }
}

/// What the view marks besides the front.
pub struct Marks {
    /// `(sum d, S)` of the optimum, if extracted.
    pub optimum: Option<[f64; 2]>,
    /// `(sum d, S)` of the operating point.
    pub op: Option<[f64; 2]>,
    /// The k of J.
    pub k: f64,
}

/// Shows the front; returns the grid index of the front point nearest a
/// click (on screen), if any.
pub fn show(ui: &mut egui::Ui, shown: &Shown, front: &[usize], marks: &Marks) -> Option<usize> {
    let points = front_points(shown, front);
    ui.label(format!(
        "{} of {} grid points are Pareto-optimal in (sum d, S): none beats them in both. \
         J's optimum is where the line of slope -k touches the front (the refined optimum \
         may lie a little below this front of grid points). Click to move the \
         operating point to the nearest point of the front.",
        front.len(),
        shown.values(Quantity::DSum).len()
    ));
    let response = Plot::new("pareto front")
        .height((ui.available_height() - 8.0).max(120.0))
        .x_axis_label("sum d [m]")
        .y_axis_label("S")
        .allow_scroll(false)
        .show(ui, |plot| {
            front_items(plot, &points);
            optimum_items(plot, &points, marks);
            if let Some(p) = marks.op {
                plot.points(
                    Points::new("operating point", vec![p])
                        .radius(5.0)
                        .color(Color32::WHITE),
                );
            }
            let clicked = plot.response().clicked();
            (clicked, plot.pointer_coordinate(), *plot.transform())
        });
    let (clicked, pointer, transform) = response.inner;
    if !clicked {
        return None;
    }
    let pointer = pointer?;
    let nearest = nearest_on_screen(&points, &transform, &pointer)?;
    Some(front[nearest])
}

/// `(sum d, S)` of each grid point on the front.
fn front_points(shown: &Shown, front: &[usize]) -> Vec<[f64; 2]> {
    front
        .iter()
        .map(|&i| {
            [
                shown.values(Quantity::DSum)[i],
                shown.values(Quantity::S)[i],
            ]
        })
        .collect()
}

/// The front as segments between its (thinned) points, and its grid points.
fn front_items(plot: &mut PlotUi<'_>, points: &[[f64; 2]]) {
    // Segment by segment: the stroked path of these points came out
    // as a filled wedge under the software renderers.
    for (n, pair) in thinned(points).windows(2).enumerate() {
        plot.line(
            Line::new("front", pair.to_vec())
                .id(("front", n))
                .color(Color32::from_rgb(120, 200, 255))
                .width(1.0),
        );
    }
    plot.points(
        Points::new("grid points", points.to_vec())
            .radius(2.0)
            .color(Color32::from_rgb(120, 200, 255)),
    );
}

/// The optimum, if extracted, and the line of slope -k through it across the front.
fn optimum_items(plot: &mut PlotUi<'_>, points: &[[f64; 2]], marks: &Marks) {
    if let (Some([x0, y0]), Some(first), Some(last)) =
        (marks.optimum, points.first(), points.last())
    {
        let (a, b) = (first[0].min(x0), last[0].max(x0));
        let y = |x: f64| y0 - marks.k * (x - x0);
        plot.line(
            Line::new("slope -k", vec![[a, y(a)], [b, y(b)]])
                .color(Color32::from_rgb(255, 90, 60))
                .width(1.0),
        );
        plot.points(
            Points::new("optimum", vec![[x0, y0]])
                .shape(MarkerShape::Diamond)
                .radius(6.0)
                .color(Color32::from_rgb(255, 90, 60)),
        );
    }
}

/// The index in `points` of the one nearest `pointer` on screen.
fn nearest_on_screen(
    points: &[[f64; 2]],
    transform: &PlotTransform,
    pointer: &PlotPoint,
) -> Option<usize> {
    // The nearest front point on screen.
    let at = transform.position_from_point(pointer);
    let nearest = points
        .iter()
        .enumerate()
        .map(|(n, p)| {
            let q = transform.position_from_point(&PlotPoint::new(p[0], p[1]));
            (n, q.distance_sq(at))
        })
        .min_by(|a, b| a.1.total_cmp(&b.1))?;
    Some(nearest.0)
}

/// The front's points without those closer than a thousandth of its span
/// to the previous one kept: near-duplicates make a stroked path's joins
/// spike.
fn thinned(points: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let span = |i: usize| {
        let (lo, hi) = points
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                (a.min(p[i]), b.max(p[i]))
            });
        (hi - lo).max(f64::MIN_POSITIVE)
    };
    let (sx, sy) = (span(0), span(1));
    let mut out: Vec<[f64; 2]> = Vec::with_capacity(points.len());
    for (n, p) in points.iter().enumerate() {
        let far = out
            .last()
            .is_none_or(|q| (p[0] - q[0]).abs() / sx > 1e-3 || (p[1] - q[1]).abs() / sy > 1e-3);
        if far || n + 1 == points.len() {
            out.push(*p);
        }
    }
    out
}
