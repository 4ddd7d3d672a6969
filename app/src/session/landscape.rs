//! The landscape as a [`Work`]: the core's coarse-to-fine [`LandscapeJob`]
//! stepped tile by tile, publishing a [`Snapshot`] for the heat maps to show
//! while it fills, and [`Shown`], the snapshot with its not-yet-computed
//! points filled from coarser ones and J for the current k.

use std::sync::Arc;

use dmpscope_core::landscape::{FillOrder, Grid, Landscape, LandscapeJob};
use dmpscope_core::{Model, Result};
use web_time::{Duration, Instant};

use super::jobs::{Step, Work};

/// Points per step natively (all cores per step).
const TILE: usize = 1024;
/// Points per step in the browser (a slice holds many steps).
const SLICE_STEP: usize = 32;
/// Compute time before the first preview on the page's thread; each next
/// preview waits twice as long (a frame under software WebGL costs about
/// 200 ms, so frames, not computation, would otherwise take the time).
const FIRST_PREVIEW: Duration = Duration::from_millis(60);

/// The landscape so far.
#[derive(Clone, Debug)]
pub struct Snapshot {
    /// The landscape (NaN where not computed yet).
    pub landscape: Landscape,
    /// Points done.
    pub done: usize,
    /// Points in all.
    pub total: usize,
}

impl Snapshot {
    /// Whether every point is computed.
    pub fn complete(&self) -> bool {
        self.done == self.total
    }
}

/// Fills a landscape in steps.
pub struct LandscapeWork {
    job: LandscapeJob,
    threaded: bool,
    computed: Duration,
    next_preview: Duration,
}

impl LandscapeWork {
    /// The work of filling `grid` for `model`; `threaded` when it has a
    /// thread of its own.
    pub fn new(model: Arc<Model>, grid: Grid, threaded: bool) -> Result<Self> {
        Ok(Self {
            job: LandscapeJob::new(model, grid, FillOrder::CoarseToFine)?,
            threaded,
            computed: Duration::ZERO,
            next_preview: FIRST_PREVIEW,
        })
    }

    fn snapshot(&self) -> Snapshot {
        let (done, total) = self.job.progress();
        Snapshot {
            landscape: self.job.landscape().clone(),
            done,
            total,
        }
    }
}

impl Work for LandscapeWork {
    type Output = Snapshot;

    fn step(&mut self) -> Step<Snapshot> {
        let start = Instant::now();
        // Natively a step uses every core (rayon) even off a thread of its
        // own; the browser has one.
        let done = if cfg!(target_arch = "wasm32") {
            self.job.step(SLICE_STEP)
        } else {
            self.job.step_par(TILE)
        };
        self.computed += start.elapsed();
        if done {
            Step::Done(self.snapshot())
        } else if self.threaded || self.computed >= self.next_preview {
            self.next_preview = self.computed * 2;
            Step::Publish(self.snapshot())
        } else {
            Step::Working
        }
    }
}

/// A snapshot as the heat maps show it.
#[derive(Clone, Debug)]
pub struct Shown {
    /// The snapshot.
    pub snapshot: Snapshot,
    /// sum d with missing points filled from coarser ones.
    pub d_sum: Vec<f64>,
    /// S, filled likewise.
    pub s: Vec<f64>,
    /// J for [`Shown::k`], filled likewise.
    pub j: Vec<f64>,
    /// The largest a_peak of any demo, filled likewise.
    pub a_peak: Vec<f64>,
    /// The k of `j`.
    pub k: f64,
    /// Changes with every snapshot shown (with `k`, keys the heat maps'
    /// textures).
    pub version: u64,
}

impl Shown {
    /// The snapshot's previews, J for `k`.
    pub fn new(snapshot: Snapshot, k: f64, version: u64) -> Self {
        let l = &snapshot.landscape;
        Self {
            d_sum: l.preview(&l.d_sum),
            s: l.preview(&l.s),
            j: l.preview(&l.j(k)),
            a_peak: l.preview(&l.a_peak),
            k,
            snapshot,
            version,
        }
    }

    /// Recombines J for a new `k` (no integration).
    pub fn set_k(&mut self, k: f64) {
        let l = &self.snapshot.landscape;
        self.j = l.preview(&l.j(k));
        self.k = k;
    }

    /// The grid.
    pub fn grid(&self) -> Grid {
        self.snapshot.landscape.grid
    }
}
