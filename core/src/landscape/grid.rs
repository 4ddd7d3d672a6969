//! `sum d` and `S` over a grid of gain pairs (method.md section 6), and the
//! engine that fills it: in lanes, coarse levels first, in slices or on all
//! cores, with progress and cancellation.
//!
//! `J` is not stored: it is `S + k sum d` for whatever `k` the user picks, so
//! changing `k` never integrates again ([`Landscape::j`]).

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// The paper's weight of the summed human-likeness error in J (method.md section 6).
pub const DEFAULT_K: f64 = 20.0;

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::landscape::model::{LANES, Model};
use crate::landscape::quantity;
use crate::landscape::quantity::{PointValues, Quantity};

/// How an axis spaces its values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AxisScale {
    /// Geometric spacing (NumPy's `geomspace`).
    Log,
    /// Even spacing (NumPy's `linspace`).
    Linear,
}

/// One axis of the gain grid.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Axis {
    /// The first value (> 0).
    pub lo: f64,
    /// The last value (> lo).
    pub hi: f64,
    /// Number of values (>= 2).
    pub n: usize,
    /// The spacing.
    pub scale: AxisScale,
}

impl Axis {
    /// The paper's default axis: 0.1 to 1000, 128 values, log-spaced.
    pub fn paper() -> Self {
        Self {
            lo: 0.1,
            hi: 1000.0,
            n: 128,
            scale: AxisScale::Log,
        }
    }

    /// Checks the axis, naming it in the error.
    pub fn validate(&self, name: &str) -> Result<()> {
        if !(self.lo.is_finite() && self.hi.is_finite() && self.lo > 0.0 && self.hi > self.lo) {
            return Err(Error::InvalidSetting(format!(
                "{name} range must satisfy 0 < lo < hi, got {} .. {}",
                self.lo, self.hi
            )));
        }
        if self.n < 2 || self.n > 4096 {
            return Err(Error::InvalidSetting(format!(
                "{name} needs 2 to 4096 values, got {}",
                self.n
            )));
        }
        Ok(())
    }

    /// The axis values.
    pub fn values(&self) -> Vec<f64> {
        let n = self.n;
        match self.scale {
            AxisScale::Linear => {
                let step = (self.hi - self.lo) / (n - 1) as f64;
                let mut v: Vec<f64> = (0..n).map(|i| i as f64 * step + self.lo).collect();
                v[n - 1] = self.hi;
                v
            }
            AxisScale::Log => {
                let (a, b) = (
                    crate::portable::log10(self.lo),
                    crate::portable::log10(self.hi),
                );
                let step = (b - a) / (n - 1) as f64;
                let mut v: Vec<f64> = (0..n)
                    .map(|i| crate::portable::pow(10.0, i as f64 * step + a))
                    .collect();
                v[0] = self.lo;
                v[n - 1] = self.hi;
                v
            }
        }
    }

    /// Maps a value to the coordinate the axis is even in (ln for log).
    pub fn to_coord(&self, value: f64) -> f64 {
        match self.scale {
            AxisScale::Log => crate::portable::ln(value),
            AxisScale::Linear => value,
        }
    }

    /// The inverse of [`Axis::to_coord`].
    pub fn from_coord(&self, coord: f64) -> f64 {
        match self.scale {
            AxisScale::Log => crate::portable::exp(coord),
            AxisScale::Linear => coord,
        }
    }

    /// One grid step in coordinates.
    pub fn coord_step(&self) -> f64 {
        (self.to_coord(self.hi) - self.to_coord(self.lo)) / (self.n - 1) as f64
    }
}

/// The gain grid: D/M along the first index, K/M along the second.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Grid {
    /// The D/M axis.
    pub dm: Axis,
    /// The K/M axis.
    pub km: Axis,
}

impl Default for Grid {
    fn default() -> Self {
        Self {
            dm: Axis::paper(),
            km: Axis::paper(),
        }
    }
}

impl Grid {
    /// Checks both axes.
    pub fn validate(&self) -> Result<()> {
        self.dm.validate("D/M")?;
        self.km.validate("K/M")
    }

    /// Number of grid points.
    pub fn len(&self) -> usize {
        self.dm.n * self.km.n
    }

    /// Whether the grid has no points (never, once validated).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// The order in which a job visits the grid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FillOrder {
    /// Row by row.
    Raster,
    /// Every 2^L-th point of both axes first, then the points that halve the
    /// spacing, down to every point: a coarse preview appears at once.
    CoarseToFine,
}

/// The computed grids, `[i_dm][i_km]` row-major.
#[derive(Clone, Debug, PartialEq)]
pub struct Landscape {
    /// The grid.
    pub grid: Grid,
    /// The D/M values.
    pub dm: Vec<f64>,
    /// The K/M values.
    pub km: Vec<f64>,
    /// Each quantity of [`quantity::ALL`] per grid point (NaN where not
    /// computed yet), in the table's order.
    pub values: [Vec<f64>; quantity::COUNT],
    /// How many points are computed.
    pub filled: usize,
    /// The weight of `sum d_rot` in J ([`crate::fit::settings::DmpSettings::k_rot`];
    /// 0: the paper's J).
    pub k_rot: f64,
}

impl Landscape {
    /// The grid of quantity `q`.
    pub fn values(&self, q: Quantity) -> &[f64] {
        &self.values[q.index()]
    }

    /// `sum d` per grid point.
    pub fn d_sum(&self) -> &[f64] {
        self.values(Quantity::DSum)
    }

    /// `S` per grid point.
    pub fn s(&self) -> &[f64] {
        self.values(Quantity::S)
    }

    /// The largest `a_peak` of any demo per grid point, m/s^2 of the
    /// unit-time motion.
    pub fn a_peak(&self) -> &[f64] {
        self.values(Quantity::APeak)
    }

    /// Every quantity's values of `points` (`(i_dm, i_km)` of this grid)
    /// on this thread, without storing them: what a worker computes for a
    /// tile. Each point's numbers are the same bits whatever tile or order
    /// it is computed in (the kernels' lanes are independent).
    pub fn evaluate(&self, model: &Model, points: &[(u32, u32)]) -> Result<Vec<PointValues>> {
        self.check(points)?;
        Ok(eval_points(model, self, points))
    }

    /// Stores the numbers of `points` computed elsewhere
    /// ([`Landscape::evaluate`]); each point once (`filled` counts every
    /// point stored, so the caller refuses a point answered twice).
    pub fn store(&mut self, points: &[(u32, u32)], values: &[PointValues]) -> Result<()> {
        if points.len() != values.len() {
            return Err(Error::InvalidSetting(format!(
                "{} points but {} values",
                points.len(),
                values.len()
            )));
        }
        self.check(points)?;
        store(self, points, values);
        Ok(())
    }

    /// Refuses points outside the grid.
    fn check(&self, points: &[(u32, u32)]) -> Result<()> {
        let (n_dm, n_km) = (self.grid.dm.n as u32, self.grid.km.n as u32);
        match points.iter().find(|&&(i, j)| i >= n_dm || j >= n_km) {
            Some(&(i, j)) => Err(Error::InvalidSetting(format!(
                "grid point ({i}, {j}) is outside the {n_dm} x {n_km} grid"
            ))),
            None => Ok(()),
        }
    }

    /// A landscape over `grid` with no point computed yet (all NaN).
    pub fn blank(grid: Grid) -> Self {
        let len = grid.len();
        Self {
            grid,
            dm: grid.dm.values(),
            km: grid.km.values(),
            values: std::array::from_fn(|_| vec![f64::NAN; len]),
            filled: 0,
            k_rot: 0.0,
        }
    }

    /// A blank landscape over `grid` for `model`: its J weighs the
    /// orientation error as the model's settings say.
    pub fn for_model(grid: Grid, model: &Model) -> Self {
        Self {
            k_rot: model.settings().k_rot,
            ..Self::blank(grid)
        }
    }

    /// The flat index of `(i_dm, i_km)`.
    pub fn index(&self, i_dm: usize, i_km: usize) -> usize {
        i_dm * self.grid.km.n + i_km
    }

    /// Whether every point is computed.
    pub fn is_complete(&self) -> bool {
        self.filled == self.grid.len()
    }

    /// `J = S + k sum d` (plus `k_rot sum d_rot`, [`crate::landscape::model::j_of`])
    /// at every point (recombination, no integration).
    pub fn j(&self, k: f64) -> Vec<f64> {
        let rot = self.values(Quantity::DRotSum);
        self.s()
            .iter()
            .zip(self.d_sum())
            .zip(rot)
            .map(|((&s, &d), &r)| crate::landscape::model::j_of(s, d, r, k, self.k_rot))
            .collect()
    }

    /// The computed point of least `J` for this `k`: `(i_dm, i_km, J)`.
    pub fn argmin(&self, k: f64) -> Option<(usize, usize, f64)> {
        let n_km = self.grid.km.n;
        self.j(k)
            .into_iter()
            .enumerate()
            .filter(|(_, j)| !j.is_nan())
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(i, j)| (i / n_km, i % n_km, j))
    }

    /// A grid of one quantity as rows `[i_dm][i_km]`.
    pub fn rows(&self, values: &[f64]) -> Vec<Vec<f64>> {
        values.chunks(self.grid.km.n).map(<[f64]>::to_vec).collect()
    }

    /// For a partly filled landscape: each point's value or, if not computed
    /// yet, that of the nearest computed coarser point to its lower left.
    pub fn preview(&self, values: &[f64]) -> Vec<f64> {
        let (n_dm, n_km) = (self.grid.dm.n, self.grid.km.n);
        let mut out = values.to_vec();
        for i in 0..n_dm {
            for j in 0..n_km {
                let mut stride = 1;
                while out[i * n_km + j].is_nan() && stride < n_dm.max(n_km) {
                    stride *= 2;
                    let (pi, pj) = (i - i % stride, j - j % stride);
                    out[i * n_km + j] = values[pi * n_km + pj];
                }
            }
        }
        out
    }
}

/// The visiting order of a grid.
pub fn fill_order(grid: &Grid, order: FillOrder) -> Vec<(u32, u32)> {
    let (n_dm, n_km) = (grid.dm.n as u32, grid.km.n as u32);
    let all = (0..n_dm).flat_map(|i| (0..n_km).map(move |j| (i, j)));
    match order {
        FillOrder::Raster => all.collect(),
        FillOrder::CoarseToFine => {
            // The level of a point: the largest stride that divides both indices.
            let top = (n_dm.max(n_km).next_power_of_two() / 2).max(1);
            let level = |(i, j): (u32, u32)| {
                let mut stride = top;
                while stride > 1 && (i % stride != 0 || j % stride != 0) {
                    stride /= 2;
                }
                stride
            };
            let mut points: Vec<(u32, u32)> = all.collect();
            // Stable: raster order within a level.
            points.sort_by_key(|&p| std::cmp::Reverse(level(p)));
            points
        }
    }
}

/// A landscape being filled: call [`LandscapeJob::step`] for slices (a
/// browser frame) or [`LandscapeJob::run`] to finish it with progress.
pub struct LandscapeJob {
    model: Arc<Model>,
    order: Vec<(u32, u32)>,
    next: usize,
    landscape: Landscape,
}

impl LandscapeJob {
    /// A job over `grid` in the given order.
    pub fn new(model: Arc<Model>, grid: Grid, order: FillOrder) -> Result<Self> {
        grid.validate()?;
        let landscape = Landscape::for_model(grid, &model);
        Ok(Self {
            model,
            order: fill_order(&grid, order),
            next: 0,
            landscape,
        })
    }

    /// Points done and in all.
    pub fn progress(&self) -> (usize, usize) {
        (self.next, self.order.len())
    }

    /// Whether every point is computed.
    pub fn is_done(&self) -> bool {
        self.next == self.order.len()
    }

    /// The landscape so far.
    pub fn landscape(&self) -> &Landscape {
        &self.landscape
    }

    /// The finished (or partial) landscape.
    pub fn into_landscape(self) -> Landscape {
        self.landscape
    }

    /// Computes up to `max_points` more points on this thread (rounded up to
    /// whole lanes). Returns whether the job is done.
    pub fn step(&mut self, max_points: usize) -> bool {
        let end = (self.next + max_points.max(1)).min(self.order.len());
        let batch = &self.order[self.next..end];
        let values = eval_points(&self.model, &self.landscape, batch);
        store(&mut self.landscape, batch, &values);
        self.next = end;
        self.is_done()
    }

    /// Computes up to `max_points` more points on all cores (with the
    /// `parallel` feature; on this thread without). Returns whether the job
    /// is done. Between calls the caller may look at [`LandscapeJob::landscape`].
    pub fn step_par(&mut self, max_points: usize) -> bool {
        let end = (self.next + max_points.max(1)).min(self.order.len());
        let batch = &self.order[self.next..end];
        let values = eval_tile(&self.model, &self.landscape, batch);
        store(&mut self.landscape, batch, &values);
        self.next = end;
        self.is_done()
    }

    /// Finishes the job, on all cores with the `parallel` feature, calling
    /// `progress(done, total)` between tiles and stopping with
    /// [`Error::Cancelled`] once `cancel` is set (the points done so far stay).
    pub fn run(
        &mut self,
        cancel: &AtomicBool,
        progress: &mut dyn FnMut(usize, usize),
    ) -> Result<()> {
        const TILE: usize = 1024;
        while !self.is_done() {
            if cancel.load(Ordering::Relaxed) {
                return Err(Error::Cancelled);
            }
            self.step_par(TILE);
            progress(self.next, self.order.len());
        }
        Ok(())
    }
}

/// Every quantity of a tile of points, spread over all cores.
#[cfg(feature = "parallel")]
fn eval_tile(model: &Model, landscape: &Landscape, batch: &[(u32, u32)]) -> Vec<PointValues> {
    use rayon::prelude::*;
    row_runs(batch)
        .par_iter()
        .flat_map_iter(|run| eval_points(model, landscape, run))
        .collect()
}

/// Every quantity of a tile of points on this thread.
#[cfg(not(feature = "parallel"))]
fn eval_tile(model: &Model, landscape: &Landscape, batch: &[(u32, u32)]) -> Vec<PointValues> {
    eval_points(model, landscape, batch)
}

/// Splits points into runs of at most [`LANES`] that share a row (D/M).
fn row_runs(points: &[(u32, u32)]) -> Vec<&[(u32, u32)]> {
    let mut runs = Vec::new();
    let mut start = 0;
    for end in 1..=points.len() {
        if end == points.len() || end - start == LANES || points[end].0 != points[start].0 {
            runs.push(&points[start..end]);
            start = end;
        }
    }
    runs
}

/// Every quantity of each point, in lanes of points that share a row.
fn eval_points(model: &Model, landscape: &Landscape, points: &[(u32, u32)]) -> Vec<PointValues> {
    let mut out = Vec::with_capacity(points.len());
    for run in row_runs(points) {
        let dm = landscape.dm[run[0].0 as usize];
        // A short run repeats its first point in the spare lanes.
        let km: [f64; LANES] = std::array::from_fn(|l| {
            landscape.km[run[if l < run.len() { l } else { 0 }].1 as usize]
        });
        let values = model.evaluate_lanes(dm, km);
        out.extend_from_slice(&values[..run.len()]);
    }
    out
}

fn store(landscape: &mut Landscape, points: &[(u32, u32)], values: &[PointValues]) {
    for (&(i, j), point) in points.iter().zip(values) {
        let idx = landscape.index(i as usize, j as usize);
        for (grid, &v) in landscape.values.iter_mut().zip(point) {
            grid[idx] = v;
        }
    }
    landscape.filled += points.len();
}

/// Computes the whole landscape (all cores with the `parallel` feature).
pub fn compute(
    model: Arc<Model>,
    grid: Grid,
    cancel: &AtomicBool,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Landscape> {
    let mut job = LandscapeJob::new(model, grid, FillOrder::CoarseToFine)?;
    job.run(cancel, progress)?;
    Ok(job.into_landscape())
}
