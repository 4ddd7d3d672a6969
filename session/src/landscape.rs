//! The landscape as a [`Work`]: the core's coarse-to-fine [`LandscapeJob`]
//! stepped tile by tile, publishing a [`Snapshot`] for the heat maps to show
//! while it fills, and [`Shown`], the snapshot with its not-yet-computed
//! points filled from coarser ones and J for the current k.

use std::sync::Arc;

use dmpscope_core::landscape::grid::{FillOrder, Grid, Landscape, LandscapeJob};
use std::time::Duration;

use dmpscope_core::landscape::quantity;
use dmpscope_core::landscape::quantity::Quantity;
use dmpscope_core::{Model, Result};

use crate::jobs::{Clock, Runner, Step, Work};
use crate::pooled::PoolFill;
use crate::workers::Workers;

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
    /// Each quantity of the table with missing points filled from coarser
    /// ones, made with the snapshot (off the page's frames in the browser,
    /// off the GUI's thread natively).
    pub previews: [Vec<f64>; quantity::COUNT],
    /// Points done.
    pub done: usize,
    /// Points in all.
    pub total: usize,
    /// Wall time from the start of the fill (its job created, once the
    /// demos are loaded) to this snapshot, on the executor's clock: the
    /// browser tests' landscape time (to the last tile stored on the page,
    /// the model's transfer to the workers included).
    pub elapsed: Duration,
}

impl Snapshot {
    /// A snapshot of `landscape` with its previews.
    fn new(landscape: Landscape, (done, total): (usize, usize), elapsed: Duration) -> Self {
        let previews = std::array::from_fn(|q| landscape.preview(&landscape.values[q]));
        Self {
            landscape,
            previews,
            done,
            total,
            elapsed,
        }
    }

    /// Whether every point is computed.
    pub fn complete(&self) -> bool {
        self.done == self.total
    }
}

/// Fills a landscape in steps.
pub struct LandscapeWork {
    engine: Engine,
    clock: Clock,
    threaded: bool,
    parallel: bool,
    computed: Duration,
    next_preview: Duration,
    started: Duration,
}

/// Where the points are computed.
enum Engine {
    /// Not yet started: the executor's workers are given the model at the
    /// work's first step, not when the work is made (in the browser the
    /// work is made inside a frame and steps between frames, so the
    /// model's encoding and its posting to the workers, about 10 ms of the
    /// page's thread, stay out of the frame).
    Start(Arc<dyn Workers>, Arc<Model>, Grid),
    /// By this work itself (natively: on all cores).
    Here(LandscapeJob),
    /// In the executor's workers; this work only moves tiles.
    Workers(PoolFill),
}

/// Points computed by [`LandscapeWork`]s themselves, not by workers (the
/// browser tests check that the page computes none).
static POINTS_HERE: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);

/// Points [`LandscapeWork`]s computed themselves since the start.
pub fn points_computed_here() -> usize {
    POINTS_HERE.load(std::sync::atomic::Ordering::Relaxed)
}

impl LandscapeWork {
    /// The work of filling `grid` for `model` on `runner`'s executor: by
    /// its workers where it has them, here otherwise.
    pub fn new(model: Arc<Model>, grid: Grid, runner: &Runner) -> Result<Self> {
        let clock = runner.clock();
        let started = clock.now();
        grid.validate()?;
        let engine = match runner.workers() {
            Some(workers) => Engine::Start(workers, model, grid),
            None => Engine::Here(LandscapeJob::new(model, grid, FillOrder::CoarseToFine)?),
        };
        Ok(Self {
            engine,
            clock,
            threaded: runner.threaded(),
            parallel: runner.parallel(),
            computed: Duration::ZERO,
            next_preview: FIRST_PREVIEW,
            started,
        })
    }

    /// Gives the workers the model (or, where the pool has no worker or
    /// cannot start, computes here).
    fn start(&mut self) -> Result<()> {
        let Engine::Start(workers, model, grid) = &self.engine else {
            return Ok(());
        };
        let (model, grid) = (Arc::clone(model), *grid);
        self.engine = match PoolFill::start(workers, &model, grid, self.clock.clone()) {
            Ok(Some(fill)) => Engine::Workers(fill),
            Ok(None) | Err(_) => {
                Engine::Here(LandscapeJob::new(model, grid, FillOrder::CoarseToFine)?)
            }
        };
        Ok(())
    }

    fn snapshot(&self) -> Snapshot {
        let elapsed = self.clock.now().saturating_sub(self.started);
        match &self.engine {
            Engine::Start(_, model, grid) => {
                let blank = Landscape::for_model(*grid, model);
                let total = blank.grid.len();
                Snapshot::new(blank, (0, total), elapsed)
            }
            Engine::Here(job) => Snapshot::new(job.landscape().clone(), job.progress(), elapsed),
            Engine::Workers(fill) => {
                Snapshot::new(fill.landscape().clone(), fill.progress(), elapsed)
            }
        }
    }
}

impl Work for LandscapeWork {
    type Output = Snapshot;

    fn step(&mut self) -> Step<Snapshot> {
        if self.start().is_err() {
            // Not reached: `new` checked the grid, the only thing a start
            // refuses. The landscape stays blank (the window says it
            // cannot be computed).
            return Step::Done(self.snapshot());
        }
        let start = self.clock.now();
        let done = match &mut self.engine {
            Engine::Start(..) => return Step::Working,
            Engine::Here(job) => {
                let before = job.progress().0;
                // Natively a step uses every core (rayon) even off a thread
                // of its own; the browser's page has one.
                let done = if self.parallel {
                    job.step_par(TILE)
                } else {
                    job.step(SLICE_STEP)
                };
                let points = job.progress().0 - before;
                POINTS_HERE.fetch_add(points, std::sync::atomic::Ordering::Relaxed);
                done
            }
            Engine::Workers(fill) => {
                let exchange = fill.exchange();
                POINTS_HERE.fetch_add(exchange.points_here, std::sync::atomic::Ordering::Relaxed);
                if fill.is_complete() {
                    return Step::Done(self.snapshot());
                }
                if exchange.stored == 0 {
                    return Step::Waiting;
                }
                // Previews on the wall clock (the work is elsewhere), each
                // waiting twice as long as the last: a frame under software
                // WebGL costs the browser's workers a core for ~250 ms.
                if fill.since_start() >= self.next_preview {
                    self.next_preview = fill.since_start() * 2;
                    return Step::Publish(self.snapshot());
                }
                return Step::Working;
            }
        };
        self.computed += self.clock.now() - start;
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
    /// J for [`Shown::k`], filled likewise.
    pub j: Vec<f64>,
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
            j: l.preview(&l.j(k)),
            k,
            snapshot,
            version,
        }
    }

    /// A landscape of `grid` for `model` with nothing computed yet: what
    /// the heat maps draw before the first snapshot (their axes, lines and
    /// markers; the operating point can be moved on them already).
    pub fn blank(model: &Model, grid: Grid) -> Self {
        let landscape = Landscape::for_model(grid, model);
        let total = landscape.grid.len();
        Self::new(Snapshot::new(landscape, (0, total), Duration::ZERO), 0.0, 0)
    }

    /// Recombines J for a new `k` (no integration).
    pub fn set_k(&mut self, k: f64) {
        let l = &self.snapshot.landscape;
        self.j = l.preview(&l.j(k));
        self.k = k;
    }

    /// The preview of quantity `q`.
    pub fn values(&self, q: Quantity) -> &[f64] {
        &self.snapshot.previews[q.index()]
    }

    /// The grid.
    pub fn grid(&self) -> Grid {
        self.snapshot.landscape.grid
    }
}
