//! The session's long works as a pool's handouts: a landscape's tiles
//! ([`PoolFill`], bookkept by [`TiledFill`]), a diagnosis's resampled
//! extractions ([`PoolDiag`], bookkept by the core's `DiagnosticsJob`
//! parts) and RL runs ([`PoolRl`], gathered on a [`RunBoard`]). Each is a
//! [`Generation`] of the executor's [`Workers`]; dropping it ends the
//! generation. When no worker is left, the owner computes the rest itself,
//! in short slices.

use std::collections::VecDeque;
use std::sync::Arc;
use std::time::Duration;

use dmpscope_core::extract::diagnostics::DiagnosticsJob;
use dmpscope_core::extract::diagnostics::resample::SubOptimum;
use dmpscope_core::landscape::grid::{Grid, Landscape};
use dmpscope_core::{Model, Result};

use crate::jobs::Clock;
use crate::rl_board::RunBoard;
use crate::rl_request::{Progress, RlRequest, RunUpdate};
use crate::tiles::{Answer, TiledFill};
use crate::workers::{Exchanged, Generation, Handout, Setup, Workers};

/// Points per tile: about 8 ms of one core.
pub const TILE_POINTS: usize = 128;

/// Tiles a worker holds at once: enough queued work that it keeps
/// computing while the page's thread draws a frame (which hands out no
/// tile; under a software rasteriser 150-900 ms while the workers hold the
/// cores), so with two workers the whole 128 x 128 landscape (128 tiles) is
/// handed out at once. A cancelled landscape wastes no more for it: the
/// worker drops the tiles it has not started when told to forget them
/// (`web/worker.js`).
pub const TILES_IN_FLIGHT: usize = 64;
/// Time an exchange may spend computing when no worker is left.
const HERE_BUDGET: Duration = Duration::from_millis(8);

/// What one exchange of a fill did.
pub struct FillExchange {
    /// Answers stored (from the workers, or computed here).
    pub stored: usize,
    /// Landscape points computed here (no worker left).
    pub points_here: usize,
}

/// A landscape filled by a pool's workers.
pub struct PoolFill {
    fill: TiledFill,
    generation: Generation,
    model: Arc<Model>,
    clock: Clock,
    started: Duration,
}

impl Handout for TiledFill {
    fn generation(&self) -> u64 {
        TiledFill::generation(self)
    }
    fn kind(&self) -> &'static str {
        "tile"
    }
    fn in_flight(&self) -> usize {
        TILES_IN_FLIGHT
    }
    fn next(&mut self) -> Option<(usize, Vec<u32>)> {
        self.next_tile().map(|(t, points)| (t, flat(points)))
    }
    fn payload(&self, piece: usize) -> Option<Vec<u32>> {
        self.tile_points(piece).map(flat)
    }
    fn accept(&mut self, piece: usize, values: &[f64], _json: Option<&str>) -> bool {
        let generation = TiledFill::generation(self);
        TiledFill::accept(self, generation, piece, values) == Answer::Stored
    }
    fn again(&mut self, piece: usize) {
        self.hand_out_again(piece);
    }
}

/// A tile's points as a payload: `(i_dm, i_km)` pairs, flat.
fn flat(points: &[(u32, u32)]) -> Vec<u32> {
    points.iter().flat_map(|&(a, b)| [a, b]).collect()
}

impl PoolFill {
    /// Starts filling `grid` for `model` in `workers`; `None` where the
    /// pool has no worker (the owner computes the landscape itself).
    pub fn start(
        workers: &Arc<dyn Workers>,
        model: &Arc<Model>,
        grid: Grid,
        clock: Clock,
    ) -> Result<Option<Self>> {
        grid.validate()?;
        let Some(generation) = Generation::begin(workers, model, &Setup::Grid(grid))? else {
            return Ok(None);
        };
        Ok(Some(Self {
            fill: TiledFill::new(grid, generation.id(), TILE_POINTS, model.settings().k_rot)?,
            generation,
            model: model.clone(),
            started: clock.now(),
            clock,
        }))
    }

    /// Takes in the workers' answers and sends new tiles; computes tiles
    /// here only when every worker has failed.
    pub fn exchange(&mut self) -> FillExchange {
        let Exchanged { stored, alive } = self.generation.exchange(&mut self.fill);
        let mut points_here = 0;
        if !alive {
            let start = self.clock.now();
            while self.clock.now() - start < HERE_BUDGET {
                let Some((tile, points)) = self.fill.next_tile() else {
                    break;
                };
                let points = points.to_vec();
                let Ok(values) = self.fill.landscape().evaluate(&self.model, &points) else {
                    break;
                };
                let generation = self.fill.generation();
                self.fill.accept(generation, tile, values.as_flattened());
                points_here += points.len();
            }
        }
        FillExchange {
            stored: stored + usize::from(points_here > 0),
            points_here,
        }
    }

    /// Points stored and in all.
    pub fn progress(&self) -> (usize, usize) {
        self.fill.progress()
    }

    /// Whether every point is stored.
    pub fn is_complete(&self) -> bool {
        self.fill.is_complete()
    }

    /// The landscape so far.
    pub fn landscape(&self) -> &Landscape {
        self.fill.landscape()
    }

    /// Time since the fill started.
    pub fn since_start(&self) -> Duration {
        self.clock.now() - self.started
    }
}

/// A diagnosis whose resampled extractions a pool's workers compute.
pub struct PoolDiag {
    generation: Generation,
}

/// A [`DiagnosticsJob`] as a generation's handout.
struct DiagHandout<'a> {
    generation: u64,
    job: &'a mut DiagnosticsJob,
}

impl Handout for DiagHandout<'_> {
    fn generation(&self) -> u64 {
        self.generation
    }
    fn kind(&self) -> &'static str {
        "part"
    }
    fn next(&mut self) -> Option<(usize, Vec<u32>)> {
        self.job
            .take_part()
            .map(|p| (p.id, p.indices.iter().map(|&i| i as u32).collect()))
    }
    fn payload(&self, piece: usize) -> Option<Vec<u32>> {
        self.job
            .part_out(piece)
            .map(|indices| indices.iter().map(|&i| i as u32).collect())
    }
    fn accept(&mut self, piece: usize, values: &[f64], _json: Option<&str>) -> bool {
        let found = match values {
            [dm, km, j, edge] => Some(SubOptimum {
                dm: *dm,
                km: *km,
                j: *j,
                on_edge: *edge != 0.0,
            }),
            [] => None,
            _ => return false,
        };
        self.job.put_part(piece, found)
    }
    fn again(&mut self, piece: usize) {
        self.job.return_part(piece);
    }
}

impl PoolDiag {
    /// Starts the resampled extractions of `job` (of `model`) in
    /// `workers`; `None` where the pool has no worker.
    pub fn start(
        workers: &Arc<dyn Workers>,
        model: &Arc<Model>,
        job: &DiagnosticsJob,
    ) -> Result<Option<Self>> {
        let setup = Setup::Diag {
            grid: job.part_grid(),
            k: job.k(),
        };
        Ok(Generation::begin(workers, model, &setup)?.map(|generation| Self { generation }))
    }

    /// Takes in the workers' answers and sends new parts; with no worker
    /// left, computes a slice of `here_points` landscape points here.
    /// Returns the parts stored (or 1 for a slice computed here).
    pub fn exchange(&mut self, job: &mut DiagnosticsJob, here_points: usize) -> usize {
        let mut handout = DiagHandout {
            generation: self.generation.id(),
            job,
        };
        let Exchanged { stored, alive } = self.generation.exchange(&mut handout);
        if alive {
            return stored;
        }
        job.step_points(here_points);
        stored + 1
    }
}

/// A request whose runs a pool's workers train, one per worker at a time
/// (a Compare trains as many runs at once as there are workers); each
/// worker sends an update after every iteration.
pub struct PoolRl {
    generation: Generation,
    board: Board,
}

/// The runs still to hand out and the updates gathered.
struct Board {
    generation: u64,
    todo: VecDeque<usize>,
    board: RunBoard,
}

impl Handout for Board {
    fn generation(&self) -> u64 {
        self.generation
    }
    fn kind(&self) -> &'static str {
        "run"
    }
    fn in_flight(&self) -> usize {
        1
    }
    fn copies(&self) -> bool {
        false
    }
    fn next(&mut self) -> Option<(usize, Vec<u32>)> {
        self.todo.pop_front().map(|run| (run, Vec::new()))
    }
    fn accept(&mut self, piece: usize, _values: &[f64], json: Option<&str>) -> bool {
        match json.map(serde_json::from_str::<RunUpdate>) {
            Some(Ok(update)) => self.board.update(piece, update),
            Some(Err(_)) | None => false,
        }
    }
    fn progress(&mut self, piece: usize, json: &str) {
        if let Ok(update) = serde_json::from_str::<RunUpdate>(json) {
            self.board.update(piece, update);
        }
    }
    fn again(&mut self, piece: usize) {
        self.board.restart(piece);
        if !self.todo.contains(&piece) {
            self.todo.push_front(piece);
        }
    }
}

impl PoolRl {
    /// Starts training `request`'s runs on `model` in `workers`; `None`
    /// where the pool has no worker (the owner trains itself).
    pub fn start(
        workers: &Arc<dyn Workers>,
        model: &Arc<Model>,
        request: &RlRequest,
    ) -> Result<Option<Self>> {
        let setup = Setup::Rl(request.clone());
        let Some(generation) = Generation::begin(workers, model, &setup)? else {
            return Ok(None);
        };
        Ok(Some(Self {
            board: Board {
                generation: generation.id(),
                todo: (0..request.runs.len()).collect(),
                board: RunBoard::new(request),
            },
            generation,
        }))
    }

    /// Takes in the workers' updates and hands out the next runs. Returns
    /// the updates stored, and `None` when no worker is left (the owner
    /// then trains what is left itself).
    pub fn exchange(&mut self) -> Option<usize> {
        let Exchanged { stored, alive } = self.generation.exchange(&mut self.board);
        alive.then_some(stored)
    }

    /// The progress so far.
    pub fn progress(&self) -> Progress {
        self.board.board.progress()
    }

    /// Whether every run finished, or one stopped.
    pub fn done(&self) -> bool {
        self.board.board.done()
    }
}
