//! Gain extraction (method.md section 6): the grid minimum of `J`, refined by
//! Nelder-Mead in the grid's even coordinates (ln for log axes), kept inside
//! the grid's box, with the edge flag the user must see.

use serde::Serialize;

use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use crate::error::{Error, Result};
use crate::extract::nelder_mead;
use crate::landscape::grid::{Grid, Landscape};
use crate::landscape::model::{Model, PointEval};
use crate::notice::Notice;

/// The simplex span (in the axes' coordinates) at which the refinement stops.
pub const SPAN_TOLERANCE: f64 = 1e-6;
/// An optimum this close to a bound (in coordinates) counts as on the edge.
pub const EDGE_TOLERANCE: f64 = 1e-6;

/// Which sides of the box an optimum touches.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Edges {
    /// At the smallest D/M.
    pub dm_low: bool,
    /// At the largest D/M.
    pub dm_high: bool,
    /// At the smallest K/M.
    pub km_low: bool,
    /// At the largest K/M.
    pub km_high: bool,
}

impl Edges {
    /// Whether any side is touched.
    pub fn any(&self) -> bool {
        self.dm_low || self.dm_high || self.km_low || self.km_high
    }

    /// The touched sides in words, e.g. `K/M = max`.
    pub fn describe(&self) -> String {
        let mut parts = Vec::new();
        for (on, text) in [
            (self.dm_low, "D/M at its minimum"),
            (self.dm_high, "D/M at its maximum"),
            (self.km_low, "K/M at its minimum"),
            (self.km_high, "K/M at its maximum"),
        ] {
            if on {
                parts.push(text);
            }
        }
        parts.join(", ")
    }
}

/// The extracted gains.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Extraction {
    /// The evaluation at the optimum.
    pub eval: PointEval,
    /// `J` at the optimum for `k`.
    pub j: f64,
    /// The `k` used.
    pub k: f64,
    /// The grid point the refinement started from, `(i_dm, i_km)`.
    pub grid_min: (usize, usize),
    /// `J` at that grid point.
    pub grid_min_j: f64,
    /// The box sides the optimum lies on.
    pub edges: Edges,
    /// Nelder-Mead iterations.
    pub iterations: usize,
    /// Whether the simplex shrank below the span tolerance.
    pub converged: bool,
}

impl Extraction {
    /// Whether the optimum lies on the box's edge.
    pub fn on_edge(&self) -> bool {
        self.edges.any()
    }
}

/// A grid minimum refined by Nelder-Mead (method.md section 6), of any
/// quantity: J for the extraction, S for the S minimum, J under an a_peak
/// limit for the constrained optimum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Refined {
    /// D/M.
    pub dm: f64,
    /// K/M.
    pub km: f64,
    /// The quantity there.
    pub value: f64,
    /// The grid point the refinement started from, `(i_dm, i_km)`.
    pub grid_min: (usize, usize),
    /// The quantity at that grid point.
    pub grid_min_value: f64,
    /// The box sides the result lies on.
    pub edges: Edges,
    /// Nelder-Mead iterations.
    pub iterations: usize,
    /// Whether the simplex shrank below the span tolerance.
    pub converged: bool,
}

/// Refines the least of `values` (one per grid point of `landscape`, NaN and
/// infinity never chosen) by Nelder-Mead on `cost(dm, km)` in the axes'
/// even coordinates, every vertex clipped into the box; the grid point stays
/// the answer when the refinement finds nothing better. `None` when no
/// value is finite.
pub fn refine(
    landscape: &Landscape,
    values: &[f64],
    mut cost: impl FnMut(f64, f64) -> f64,
) -> Option<Refined> {
    let n_km = landscape.grid.km.n;
    let (best, grid_min_value) = values
        .iter()
        .copied()
        .enumerate()
        .filter(|(_, v)| v.is_finite())
        .min_by(|a, b| a.1.total_cmp(&b.1))?;
    let (i_dm, i_km) = (best / n_km, best % n_km);
    let (ax_dm, ax_km) = (landscape.grid.dm, landscape.grid.km);
    let lo = [ax_dm.to_coord(ax_dm.lo), ax_km.to_coord(ax_km.lo)];
    let hi = [ax_dm.to_coord(ax_dm.hi), ax_km.to_coord(ax_km.hi)];
    let x0 = [
        ax_dm.to_coord(landscape.dm[i_dm]),
        ax_km.to_coord(landscape.km[i_km]),
    ];
    // One grid step along each axis, pointing inward at the upper edge.
    let step_dm = if i_dm + 1 == ax_dm.n {
        -ax_dm.coord_step()
    } else {
        ax_dm.coord_step()
    };
    let step_km = if i_km + 1 == ax_km.n {
        -ax_km.coord_step()
    } else {
        ax_km.coord_step()
    };
    let start = [x0, [x0[0] + step_dm, x0[1]], [x0[0], x0[1] + step_km]];
    let clip = |p: [f64; 2]| [p[0].clamp(lo[0], hi[0]), p[1].clamp(lo[1], hi[1])];
    let to_gains = |p: [f64; 2]| (ax_dm.from_coord(p[0]), ax_km.from_coord(p[1]));
    let found = nelder_mead::minimise(
        |p| {
            let (dm, km) = to_gains(p);
            cost(dm, km)
        },
        clip,
        start,
        SPAN_TOLERANCE,
        2000,
    );
    // Mapping a clipped coordinate back (exp of ln) can miss the bound by an
    // ulp: clamp the gains themselves. The grid point stays the answer when
    // the refinement found nothing better.
    let clamp = |(dm, km): (f64, f64)| (dm.clamp(ax_dm.lo, ax_dm.hi), km.clamp(ax_km.lo, ax_km.hi));
    let (mut dm, mut km) = clamp(to_gains(found.x));
    let mut value = cost(dm, km);
    let mut x = found.x;
    if value.is_nan() || value > grid_min_value {
        (dm, km) = (landscape.dm[i_dm], landscape.km[i_km]);
        value = cost(dm, km);
        x = x0;
    }
    let edges = Edges {
        dm_low: x[0] - lo[0] < EDGE_TOLERANCE,
        dm_high: hi[0] - x[0] < EDGE_TOLERANCE,
        km_low: x[1] - lo[1] < EDGE_TOLERANCE,
        km_high: hi[1] - x[1] < EDGE_TOLERANCE,
    };
    Some(Refined {
        dm,
        km,
        value,
        grid_min: (i_dm, i_km),
        grid_min_value,
        edges,
        iterations: found.iterations,
        converged: found.converged,
    })
}

/// Extracts the gains minimising `J = S + k sum d` from a complete landscape.
pub fn extract(model: &Model, landscape: &Landscape, k: f64) -> Result<Extraction> {
    check_k(k)?;
    let r = refine(landscape, &landscape.j(k), |dm, km| model.j(dm, km, k))
        .ok_or_else(|| Error::InvalidSetting("the landscape has no computed point".into()))?;
    let eval = model.evaluate(r.dm, r.km);
    Ok(Extraction {
        j: eval.j(k),
        eval,
        k,
        grid_min: r.grid_min,
        grid_min_j: r.grid_min_value,
        edges: r.edges,
        iterations: r.iterations,
        converged: r.converged,
    })
}

/// Checks J's weight `k` (finite, >= 0).
pub fn check_k(k: f64) -> Result<()> {
    if !k.is_finite() || k < 0.0 {
        return Err(Error::InvalidSetting(format!(
            "k must be finite and >= 0, got {k}"
        )));
    }
    Ok(())
}

/// The landscape of `model` over `grid` (all cores with the `parallel`
/// feature; `progress(done, total)` between tiles, [`Error::Cancelled`]
/// once `cancel` is set) and J's optimum on it for `k`, with a warning
/// when the optimum lies on the box's edge: what the CLI's `landscape`,
/// `extract` and the Python package compute first.
pub fn map_and_extract(
    model: &Arc<Model>,
    grid: Grid,
    k: f64,
    cancel: &AtomicBool,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<(Landscape, Extraction, Vec<Notice>)> {
    check_k(k)?;
    let landscape = crate::landscape::grid::compute(Arc::clone(model), grid, cancel, progress)?;
    let optimum = extract(model, &landscape, k)?;
    let notices = optimum
        .on_edge()
        .then(|| {
            Notice::warning(format!(
                "the optimum lies on the edge of the gain box ({}): widen the range to see \
                 whether J keeps falling",
                optimum.edges.describe()
            ))
        })
        .into_iter()
        .collect();
    Ok((landscape, optimum, notices))
}

/// The least J for `k` among the gains whose largest peak acceleration (any
/// demo) stays within `limit` m/s^2 (method.md section 9): the grid minimum
/// of J over the points within the limit, refined by Nelder-Mead with the
/// points beyond it costing infinity. `None` when no grid point is within
/// the limit.
pub fn constrained(model: &Model, landscape: &Landscape, k: f64, limit: f64) -> Option<Refined> {
    let masked: Vec<f64> = landscape
        .j(k)
        .iter()
        .zip(landscape.a_peak())
        .map(|(&j, &a)| if a <= limit { j } else { f64::NAN })
        .collect();
    refine(landscape, &masked, |dm, km| {
        let e = model.evaluate(dm, km);
        let a = e.a_peak.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        if a <= limit { e.j(k) } else { f64::INFINITY }
    })
}
