//! Can the gains be trusted? The diagnostics of an extraction (method.md
//! section 9): the optimum's depth and balance, each demo's share of S, the
//! S minimum alone, leave-one-out and bootstrap optima, and the Pareto front
//! of `(sum d, S)`.
//!
//! The cheap parts are computed when a [`DiagnosticsJob`] is made; the
//! resampled extractions (one per demo left out, one per bootstrap resample)
//! are its steps, so a browser can slice them and an app can show them as
//! they come; [`DiagnosticsJob::run`] does them all (on every core with the
//! `parallel` feature). Resampled extractions use a coarser grid over the
//! same box ([`DiagSettings::grid`]), then the same Nelder-Mead refinement.

pub mod balance;
pub mod pareto;
pub mod resample;

use std::sync::Arc;

use serde::{Deserialize, Serialize};

pub use balance::{FLAT_DEPTH, balanced_k, depth, k_ratio};
pub use pareto::pareto_front;
pub use resample::{SubExtraction, SubOptimum, leave_out, optimum_of, percentiles, resamples};

use crate::extract::optimum::{Extraction, refine};
use crate::landscape::grid::{Axis, Grid, Landscape};
use crate::landscape::model::Model;

/// A demo whose share of S is above this many times the fair share `1/N` is
/// flagged as inconsistent with the others.
pub const INCONSISTENT_SHARE: f64 = 2.0;

/// How the diagnostics are computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default)]
pub struct DiagSettings {
    /// Points per axis of the resampled extractions' grid (at most the
    /// landscape's own).
    pub grid_points: usize,
    /// Bootstrap resamples.
    pub bootstrap: usize,
    /// The bootstrap's seed.
    pub seed: u64,
}

impl Default for DiagSettings {
    fn default() -> Self {
        Self {
            grid_points: 32,
            bootstrap: 100,
            seed: 1,
        }
    }
}

impl DiagSettings {
    /// The grid of the resampled extractions: `main`'s box and spacing with
    /// at most [`DiagSettings::grid_points`] points per axis.
    pub fn grid(&self, main: &Grid) -> Grid {
        let coarse = |a: Axis| Axis {
            n: a.n.min(self.grid_points.max(2)),
            ..a
        };
        Grid {
            dm: coarse(main.dm),
            km: coarse(main.km),
        }
    }
}

/// The grid minimum of S refined like J's.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SMinimum {
    /// D/M.
    pub dm: f64,
    /// K/M.
    pub km: f64,
    /// S there.
    pub s: f64,
}

/// One demo's diagnostics.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DemoDiagnostics {
    /// The demo's name.
    pub name: String,
    /// Its share of S at the optimum (`None` with fewer than two demos).
    pub s_share: Option<f64>,
    /// The optimum without it (`None` until computed, or with one demo).
    pub loo: Option<SubOptimum>,
}

impl DemoDiagnostics {
    /// Whether its share of S is well above the fair share of `n` demos.
    pub fn inconsistent(&self, n: usize) -> bool {
        self.s_share
            .is_some_and(|s| n >= 3 && s > INCONSISTENT_SHARE / n as f64)
    }
}

/// The bootstrap's summary.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Bootstrap {
    /// Resamples whose optimum was found.
    pub n: usize,
    /// The seed.
    pub seed: u64,
    /// Percentiles 5, 50, 95 of the optima's D/M.
    pub dm: [f64; 3],
    /// Percentiles 5, 50, 95 of the optima's K/M.
    pub km: [f64; 3],
    /// The fraction of optima on the box's edge.
    pub on_edge_fraction: f64,
}

/// Everything `extract --json` reports under `diagnostics`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Diagnostics {
    /// `max(0, min(boundary J) / J* - 1)` (`None` when undefined).
    pub depth: Option<f64>,
    /// Depth below [`FLAT_DEPTH`]: the data do not determine the gains.
    pub flat: bool,
    /// `k sum d / S` at the optimum (`None` where S is 0).
    pub k_ratio: Option<f64>,
    /// `median(S) / median(sum d)` over the grid (`None` where S is 0).
    pub balanced_k: Option<f64>,
    /// The S minimum alone (`None` with fewer than two demos).
    pub s_minimum: Option<SMinimum>,
    /// Per demo, in the model's order.
    pub demos: Vec<DemoDiagnostics>,
    /// The bootstrap (`None` until every resample is done, or with one demo).
    pub bootstrap: Option<Bootstrap>,
}

impl Diagnostics {
    /// The demos flagged as inconsistent, most inconsistent first.
    pub fn inconsistent(&self) -> Vec<usize> {
        let n = self.demos.len();
        let mut out: Vec<usize> = (0..n).filter(|&i| self.demos[i].inconsistent(n)).collect();
        out.sort_by(|&a, &b| {
            let share = |i: usize| self.demos[i].s_share.unwrap_or(0.0);
            share(b).total_cmp(&share(a))
        });
        out
    }
}

/// How the diagnostics were made: the resampled extractions' grid, the
/// resamples, and what could not be computed and why.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DiagAbout {
    /// The grid of the leave-one-out and bootstrap extractions.
    pub grid: Grid,
    /// The bootstrap resamples (demo indices).
    pub resamples: usize,
    /// What the user should know (too few demos for some parts).
    pub notes: Vec<String>,
}

/// The diagnostics being computed: the cheap parts at once, the resampled
/// extractions step by step.
pub struct DiagnosticsJob {
    model: Arc<Model>,
    k: f64,
    settings: DiagSettings,
    grid: Grid,
    diagnostics: Diagnostics,
    about: DiagAbout,
    /// The resampled extractions still to do: leave-one-out (`Loo(i)`) first.
    todo: Vec<Item>,
    done: usize,
    resample_list: Vec<Vec<usize>>,
    boot: Vec<Option<SubOptimum>>,
    /// The extraction [`DiagnosticsJob::step_points`] is filling.
    current: Option<(Item, SubExtraction)>,
    /// Parts handed out to be computed elsewhere ([`DiagnosticsJob::take_part`]).
    out: Vec<Item>,
}

/// A resampled extraction handed out to be computed elsewhere (the
/// browser's workers): [`optimum_of`] of the demos at `indices` on
/// [`DiagnosticsJob::part_grid`] for [`DiagnosticsJob::k`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Part {
    /// Its id, for [`DiagnosticsJob::put_part`].
    pub id: usize,
    /// The demos of its model (repeats allowed).
    pub indices: Vec<usize>,
}

/// One resampled extraction.
#[derive(Clone, Copy, Debug)]
enum Item {
    Loo(usize),
    Boot(usize),
}

impl DiagnosticsJob {
    /// The diagnostics of `extraction` on `landscape` (complete) of `model`.
    pub fn new(
        model: Arc<Model>,
        landscape: &Landscape,
        extraction: &Extraction,
        settings: DiagSettings,
    ) -> Self {
        let resample_list = resamples(model.demos().len(), settings.bootstrap, settings.seed);
        Self::with_resamples(model, landscape, extraction, settings, resample_list)
    }

    /// As [`DiagnosticsJob::new`] with a given resample list (tests against
    /// an independent implementation).
    pub fn with_resamples(
        model: Arc<Model>,
        landscape: &Landscape,
        extraction: &Extraction,
        settings: DiagSettings,
        resample_list: Vec<Vec<usize>>,
    ) -> Self {
        let n = model.demos().len();
        let resample_list = if n >= 2 { resample_list } else { Vec::new() };
        let (k, x) = (extraction.k, &extraction.eval);
        let depth = depth(landscape, k, extraction.j);
        let shares = model.similarity().shares(x.dm, x.km);
        let s_minimum = (n >= 2)
            .then(|| refine(landscape, landscape.s(), |dm, km| model.s(dm, km)))
            .flatten()
            .map(|r| SMinimum {
                dm: r.dm,
                km: r.km,
                s: r.value,
            });
        let demos = model
            .demos()
            .iter()
            .enumerate()
            .map(|(i, d)| DemoDiagnostics {
                name: d.name.clone(),
                s_share: shares.as_ref().map(|s| s[i]),
                loo: None,
            })
            .collect();
        let mut notes = Vec::new();
        let mut todo = Vec::new();
        match n {
            0 | 1 => notes.push(
                "S, its shares and minimum, leave-one-out and the bootstrap need two or more \
                 demonstrations"
                    .to_owned(),
            ),
            2 => notes.push(
                "with two demonstrations each leave-one-out model has one demo (S is 0 there, its \
                 optimum follows sum d alone), and the bootstrap has only three distinct resamples"
                    .to_owned(),
            ),
            _ => {}
        }
        if n >= 2 {
            todo.extend((0..n).map(Item::Loo));
            todo.extend((0..resample_list.len()).map(Item::Boot));
        }
        todo.reverse();
        let grid = settings.grid(&landscape.grid);
        Self {
            k,
            settings,
            grid,
            diagnostics: Diagnostics {
                flat: depth.is_none_or(|d| d < FLAT_DEPTH),
                depth,
                k_ratio: k_ratio(extraction),
                balanced_k: balanced_k(landscape),
                s_minimum,
                demos,
                bootstrap: None,
            },
            about: DiagAbout {
                grid,
                resamples: resample_list.len(),
                notes,
            },
            boot: vec![None; resample_list.len()],
            resample_list,
            todo,
            done: 0,
            current: None,
            out: Vec::new(),
            model,
        }
    }

    /// The grid of the resampled extractions.
    pub fn part_grid(&self) -> Grid {
        self.grid
    }

    /// The k of the extraction diagnosed.
    pub fn k(&self) -> f64 {
        self.k
    }

    fn id_of(&self, item: Item) -> usize {
        match item {
            Item::Loo(i) => i,
            Item::Boot(b) => self.model.demos().len() + b,
        }
    }

    /// Hands out the next resampled extraction to be computed elsewhere;
    /// `None` when none is left to hand out. The job is done only when every
    /// part handed out is put back ([`DiagnosticsJob::put_part`]); the
    /// answers may come in any order and give the same diagnostics.
    pub fn take_part(&mut self) -> Option<Part> {
        let item = self.todo.pop()?;
        self.out.push(item);
        Some(Part {
            id: self.id_of(item),
            indices: self.indices(item),
        })
    }

    /// The demos of part `id`, while it is handed out (a copy of it for
    /// another worker); `None` when it is not out.
    pub fn part_out(&self, id: usize) -> Option<Vec<usize>> {
        let item = self.out.iter().find(|&&it| self.id_of(it) == id)?;
        Some(self.indices(*item))
    }

    /// Records the answer for part `id` (`None`: it has no optimum).
    /// Returns false, recording nothing, when `id` is not out (an answer
    /// given twice, or for another job).
    pub fn put_part(&mut self, id: usize, found: Option<SubOptimum>) -> bool {
        let Some(pos) = self.out.iter().position(|&it| self.id_of(it) == id) else {
            return false;
        };
        let item = self.out.swap_remove(pos);
        self.record(item, found);
        true
    }

    /// A part handed out whose answer will never come: it is handed out
    /// again.
    pub fn return_part(&mut self, id: usize) {
        if let Some(pos) = self.out.iter().position(|&it| self.id_of(it) == id) {
            let item = self.out.swap_remove(pos);
            self.todo.push(item);
        }
    }

    /// The diagnostics so far.
    pub fn diagnostics(&self) -> &Diagnostics {
        &self.diagnostics
    }

    /// How they were made.
    pub fn about(&self) -> &DiagAbout {
        &self.about
    }

    /// The bootstrap optima found so far (the cloud the app draws).
    pub fn bootstrap_optima(&self) -> Vec<SubOptimum> {
        self.boot.iter().flatten().copied().collect()
    }

    /// Resampled extractions done, and in all.
    pub fn progress(&self) -> (usize, usize) {
        let open = self.todo.len() + usize::from(self.current.is_some()) + self.out.len();
        (self.done, self.done + open)
    }

    /// Whether every part is computed.
    pub fn is_done(&self) -> bool {
        self.todo.is_empty() && self.current.is_none() && self.out.is_empty()
    }

    fn indices(&self, item: Item) -> Vec<usize> {
        match item {
            Item::Loo(i) => leave_out(self.model.demos().len(), i),
            Item::Boot(b) => self.resample_list[b].clone(),
        }
    }

    fn record(&mut self, item: Item, found: Option<SubOptimum>) {
        match item {
            Item::Loo(i) => {
                if let Some(d) = self.diagnostics.demos.get_mut(i) {
                    d.loo = found;
                }
            }
            Item::Boot(b) => {
                if let Some(slot) = self.boot.get_mut(b) {
                    *slot = found;
                }
            }
        }
        self.done += 1;
        if self.is_done() && !self.boot.is_empty() {
            self.summarise_bootstrap();
        }
    }

    fn summarise_bootstrap(&mut self) {
        let optima = self.bootstrap_optima();
        if optima.len() < self.boot.len() {
            self.about.notes.push(format!(
                "{} of {} bootstrap resamples had no optimum",
                self.boot.len() - optima.len(),
                self.boot.len()
            ));
        }
        if optima.is_empty() {
            return;
        }
        let dm: Vec<f64> = optima.iter().map(|o| o.dm).collect();
        let km: Vec<f64> = optima.iter().map(|o| o.km).collect();
        let edge = optima.iter().filter(|o| o.on_edge).count();
        self.diagnostics.bootstrap = Some(Bootstrap {
            n: optima.len(),
            seed: self.settings.seed,
            dm: percentiles(&dm, [5.0, 50.0, 95.0]),
            km: percentiles(&km, [5.0, 50.0, 95.0]),
            on_edge_fraction: edge as f64 / optima.len() as f64,
        });
    }

    /// Advances the resampled extractions by at most `max_points` landscape
    /// points (or one refinement): the browser's time slices. Returns
    /// whether all are done.
    pub fn step_points(&mut self, max_points: usize) -> bool {
        if self.current.is_none()
            && let Some(item) = self.todo.pop()
        {
            match SubExtraction::new(&self.model, &self.indices(item), self.grid) {
                Ok(part) => self.current = Some((item, part)),
                Err(_) => self.record(item, None),
            }
            return self.is_done();
        }
        if let Some((item, part)) = &mut self.current
            && part.step(max_points)
        {
            let (item, found) = (*item, part.finish(self.k).ok());
            self.current = None;
            self.record(item, found);
        }
        self.is_done()
    }

    /// Computes one resampled extraction; returns whether all are done.
    pub fn step(&mut self) -> bool {
        self.step_par(1)
    }

    /// Finishes the extraction [`DiagnosticsJob::step_points`] left part
    /// done, if any.
    fn finish_current(&mut self) {
        if let Some((item, mut part)) = self.current.take() {
            while !part.step(usize::MAX) {}
            let found = part.finish(self.k).ok();
            self.record(item, found);
        }
    }

    /// Computes up to `count` resampled extractions at once (on all cores
    /// with `parallel`); returns whether all are done.
    pub fn step_par(&mut self, count: usize) -> bool {
        self.finish_current();
        let take = count.min(self.todo.len());
        let items: Vec<Item> = self.todo.iter().rev().take(take).copied().collect();
        let work: Vec<(Item, Vec<usize>)> =
            items.iter().map(|&it| (it, self.indices(it))).collect();
        let (model, grid, k) = (&self.model, self.grid, self.k);
        let one = |idx: &Vec<usize>| optimum_of(model, idx, grid, k).ok();
        #[cfg(feature = "parallel")]
        let found: Vec<Option<SubOptimum>> = {
            use rayon::prelude::*;
            work.par_iter().map(|(_, idx)| one(idx)).collect()
        };
        #[cfg(not(feature = "parallel"))]
        let found: Vec<Option<SubOptimum>> = work.iter().map(|(_, idx)| one(idx)).collect();
        for ((item, _), f) in work.into_iter().zip(found) {
            self.todo.pop();
            self.record(item, f);
        }
        self.is_done()
    }

    /// Computes every remaining part (on all cores with `parallel`),
    /// calling `progress(done)` after each batch.
    pub fn run(&mut self, progress: &(dyn Fn(usize) + Sync)) {
        let batch = run_batch();
        while !self.step_par(batch) {
            progress(self.done);
        }
        progress(self.done);
    }

    /// As [`DiagnosticsJob::run`] (the same batches, so the same numbers),
    /// calling `progress(done, total)` after each batch and stopping with
    /// [`crate::error::Error::Cancelled`] once `cancel` is set (the parts
    /// done so far stay; calling it again goes on).
    pub fn run_cancellable(
        &mut self,
        cancel: &std::sync::atomic::AtomicBool,
        progress: &mut dyn FnMut(usize, usize),
    ) -> crate::error::Result<()> {
        let batch = run_batch();
        loop {
            if cancel.load(std::sync::atomic::Ordering::Relaxed) {
                return Err(crate::error::Error::Cancelled);
            }
            let done = self.step_par(batch);
            let (now, total) = self.progress();
            progress(now, total);
            if done {
                return Ok(());
            }
        }
    }
}

/// Resampled extractions per batch of [`DiagnosticsJob::run`]: a few per
/// core keep the cores busy and report often.
fn run_batch() -> usize {
    4 * std::thread::available_parallelism().map_or(1, |n| n.get())
}
