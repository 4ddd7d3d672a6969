//! The optimum of part of the demos (method.md section 9): each demo left
//! out in turn, and bootstrap resamples drawn with replacement from a seeded
//! generator. Each is the extraction of section 6 on the diagnostics' grid,
//! from a [`Model::subset`] (no demo is prepared or fitted again).

use std::sync::Arc;

use serde::{Deserialize, Serialize};

use crate::error::Result;
use crate::extract::optimum::extract;
use crate::landscape::grid::{FillOrder, Grid, LandscapeJob};
use crate::landscape::model::Model;
use crate::rng::Rng;

/// The optimum of a subset of the demos.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SubOptimum {
    /// D/M.
    pub dm: f64,
    /// K/M.
    pub km: f64,
    /// J there.
    pub j: f64,
    /// Whether it lies on the box's edge.
    pub on_edge: bool,
}

/// The extraction (grid minimum on `grid`, refined by Nelder-Mead) of the
/// model of the demos at `indices` (repeats allowed).
pub fn optimum_of(model: &Model, indices: &[usize], grid: Grid, k: f64) -> Result<SubOptimum> {
    let mut part = SubExtraction::new(model, indices, grid)?;
    while !part.landscape.step_par(usize::MAX) {}
    part.finish(k)
}

/// One resampled extraction in steps (the browser slices it): the subset's
/// landscape, filled point by point, then its refined minimum.
pub struct SubExtraction {
    model: Arc<Model>,
    landscape: LandscapeJob,
}

impl SubExtraction {
    /// The extraction of the demos at `indices` on `grid`, not started.
    pub fn new(model: &Model, indices: &[usize], grid: Grid) -> Result<Self> {
        let model = Arc::new(model.subset(indices)?);
        let landscape = LandscapeJob::new(model.clone(), grid, FillOrder::Raster)?;
        Ok(Self { model, landscape })
    }

    /// Computes up to `max_points` points; returns whether the landscape is
    /// complete.
    pub fn step(&mut self, max_points: usize) -> bool {
        self.landscape.step(max_points)
    }

    /// The refined minimum of J for `k` on the complete landscape.
    pub fn finish(&self, k: f64) -> Result<SubOptimum> {
        let x = extract(&self.model, self.landscape.landscape(), k)?;
        Ok(SubOptimum {
            dm: x.eval.dm,
            km: x.eval.km,
            j: x.j,
            on_edge: x.on_edge(),
        })
    }
}

/// The demos without demo `left`, in order.
pub fn leave_out(n: usize, left: usize) -> Vec<usize> {
    (0..n).filter(|&i| i != left).collect()
}

/// `count` resamples of `n` demos drawn with replacement: resample `b` is
/// `n` indices `floor(u * n)` from consecutive uniforms `u` of
/// [`Rng::new(seed)`](Rng).
pub fn resamples(n: usize, count: usize, seed: u64) -> Vec<Vec<usize>> {
    let mut rng = Rng::new(seed);
    (0..count)
        .map(|_| {
            (0..n)
                .map(|_| ((rng.uniform() * n as f64) as usize).min(n.saturating_sub(1)))
                .collect()
        })
        .collect()
}

/// The `q`-th percentiles (0..100) of `values`, interpolated linearly
/// between order statistics as NumPy's default; NaN for no values.
pub fn percentiles<const N: usize>(values: &[f64], q: [f64; N]) -> [f64; N] {
    let mut v: Vec<f64> = values.iter().copied().filter(|x| !x.is_nan()).collect();
    v.sort_by(f64::total_cmp);
    q.map(|q| {
        if v.is_empty() {
            return f64::NAN;
        }
        let pos = q / 100.0 * (v.len() - 1) as f64;
        let lo = pos.floor() as usize;
        let hi = (lo + 1).min(v.len() - 1);
        v[lo] + (pos - lo as f64) * (v[hi] - v[lo])
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percentiles_interpolate_as_numpy() {
        let v = [3.0, 1.0, 4.0, 1.0, 5.0];
        // numpy.percentile([3, 1, 4, 1, 5], [5, 50, 95]) = [1.0, 3.0, 4.8]
        let p = percentiles(&v, [5.0, 50.0, 95.0]);
        assert_eq!(p[1], 3.0);
        assert!(
            (p[0] - 1.0).abs() < 1e-15 && (p[2] - 4.8).abs() < 1e-12,
            "{p:?}"
        );
    }

    #[test]
    fn resamples_draw_every_index_in_range_and_repeat_from_the_seed() {
        let a = resamples(7, 50, 3);
        assert_eq!(a, resamples(7, 50, 3));
        assert!(a.iter().flatten().all(|&i| i < 7));
        let repeats = |r: &Vec<usize>| {
            let mut s = r.clone();
            s.sort_unstable();
            s.windows(2).any(|w| w[0] == w[1])
        };
        assert!(a.iter().any(repeats), "drawn with replacement");
        assert_eq!(leave_out(4, 2), [0, 1, 3]);
    }
}
