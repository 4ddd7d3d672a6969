//! Why S is what it is: every demo's standardised target forcing term per
//! axis over unit time at the operating point, and below them sigma_f(t),
//! the spread across demos whose integral is S (method.md sections 5 and
//! 9). Hovering a demo's curve highlights it (here, in the 3D view and the
//! demos list); demos flagged as inconsistent are drawn dashed.

use dmpscope_core::kernels::similarity::Standardised;
use eframe::egui::{self, Color32};
use egui_plot::{ItemId, Line, LineStyle, Plot, PlotPoints};

/// Points drawn per line at most (as the time plots).
const MAX_POINTS: usize = 200;

/// A demo's colour: Tableau 10, repeated.
pub fn demo_colour(i: usize) -> Color32 {
    let c = colorous::TABLEAU10[i % colorous::TABLEAU10.len()];
    Color32::from_rgb(c.r, c.g, c.b)
}

/// What the view shows.
pub struct ForcingInput<'a> {
    /// The terms and sigma_f at the operating point.
    pub terms: &'a Standardised,
    /// The model demos' names.
    pub names: &'a [String],
    /// Each demo's share of S at the operating point.
    pub shares: Option<&'a [f64]>,
    /// The demos flagged as inconsistent (at the optimum).
    pub flagged: &'a [usize],
    /// The demo highlighted (hovered elsewhere).
    pub hovered: Option<usize>,
    /// The pinned sets: the selected demo's term at each.
    pub pins: &'a [ForcingPin<'a>],
}

/// A pinned set's standardised forcing term of the selected demo.
pub struct ForcingPin<'a> {
    /// Its name.
    pub name: &'a str,
    /// Its colour.
    pub colour: Color32,
    /// The term on the grid.
    pub f: &'a [[f64; 3]],
}

fn series(values: impl ExactSizeIterator<Item = f64>) -> PlotPoints<'static> {
    let n = values.len();
    let stride = n.div_ceil(MAX_POINTS).max(1);
    let last = n.saturating_sub(1);
    let dt = 1.0 / last.max(1) as f64;
    values
        .enumerate()
        .filter(|(k, _)| k % stride == 0 || *k == last)
        .map(|(k, v)| [k as f64 * dt, v])
        .collect()
}

/// Shows the four plots; returns the demo under the pointer, if any.
pub fn show(ui: &mut egui::Ui, input: &ForcingInput<'_>) -> Option<usize> {
    let hovered_name = input.hovered.and_then(|i| input.names.get(i));
    let caption = match (input.hovered, hovered_name) {
        (Some(i), Some(name)) => {
            let share = input
                .shares
                .and_then(|s| s.get(i))
                .map_or(String::new(), |s| format!(", {:.0} % of S here", 100.0 * s));
            let flag = if input.flagged.contains(&i) {
                ", flagged"
            } else {
                ""
            };
            format!("{name}{share}{flag}")
        }
        _ => "hover a curve to find its demo (dashed: flagged as inconsistent)".to_owned(),
    };
    ui.label(caption);
    let height = ((ui.available_height() - 12.0) / 4.0).max(60.0);
    let group = ui.scope_id().with("forcing plots");
    let mut hovered = None;
    for (axis, label) in ["f_stand x", "f_stand y", "f_stand z"].iter().enumerate() {
        let response = Plot::new(label)
            .height(height)
            .link_axis(group, [true, false])
            .link_cursor(group, [true, false])
            .y_axis_label(*label)
            .allow_scroll(false)
            .show(ui, |plot| {
                for (i, f) in input.terms.f.iter().enumerate() {
                    let lit = input.hovered == Some(i);
                    let dim = input.hovered.is_some() && !lit;
                    let colour = demo_colour(i);
                    let colour = if dim {
                        colour.gamma_multiply(0.35)
                    } else {
                        colour
                    };
                    let name = input.names.get(i).cloned().unwrap_or_default();
                    let mut line = Line::new(name, series(f.iter().map(|p| p[axis])))
                        .id(("f", i))
                        .color(colour)
                        .width(if lit { 2.5 } else { 1.0 });
                    if input.flagged.contains(&i) {
                        line = line.style(LineStyle::dashed_dense());
                    }
                    plot.line(line);
                }
                for pin in input.pins {
                    plot.line(
                        Line::new(pin.name, series(pin.f.iter().map(|p| p[axis])))
                            .color(pin.colour)
                            .width(2.0),
                    );
                }
            });
        if let Some(id) = response.hovered_plot_item {
            hovered = (0..input.terms.f.len()).find(|&i| ItemId::new(("f", i)) == id);
        }
    }
    Plot::new("sigma_f")
        .height(height)
        .link_axis(group, [true, false])
        .link_cursor(group, [true, false])
        .y_axis_label("sigma_f (S = its integral)")
        .x_axis_label("unit time")
        .allow_scroll(false)
        .show(ui, |plot| {
            plot.line(
                Line::new("sigma_f", series(input.terms.sigma.iter().copied()))
                    .color(Color32::from_gray(220))
                    .fill(0.0),
            );
        });
    hovered
}
