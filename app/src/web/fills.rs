//! What the browser's workers compute, as the page's jobs see it: a
//! landscape's tiles ([`PoolFill`], bookkept by `session::tiles::TiledFill`)
//! and a diagnosis's resampled extractions ([`PoolDiag`], bookkept by the
//! core's `DiagnosticsJob` parts). Each is a generation of the pool
//! ([`super::pool::Generation`]); dropping it ends the generation. When no worker is
//! left, the page computes the rest itself, in short slices.

use std::sync::Arc;

use dmpscope_core::diagnostics::{DiagnosticsJob, SubOptimum};
use dmpscope_core::landscape::{Grid, Landscape};
use dmpscope_core::{Model, Result};
use wasm_bindgen::JsValue;
use web_time::{Duration, Instant};

use super::pool::{Generation, Handout, json_field, with_pool};
use crate::session::tiles::{Answer, TiledFill};

/// Points per tile: about 8 ms of one core.
const TILE_POINTS: usize = 128;
/// Page time an exchange may spend computing when no worker is left.
const HERE_BUDGET: Duration = Duration::from_millis(8);

/// What one exchange did.
pub struct Exchange {
    /// Answers stored (from the workers, or computed here).
    pub stored: usize,
    /// Landscape points the page computed itself (no worker left).
    pub points_here: usize,
}

/// A landscape filled by the pool's workers.
pub struct PoolFill {
    fill: TiledFill,
    _generation: Generation,
    model: Arc<Model>,
    started: Instant,
}

impl Handout for TiledFill {
    fn generation(&self) -> u64 {
        TiledFill::generation(self)
    }
    fn kind(&self) -> &'static str {
        "tile"
    }
    fn next(&mut self) -> Option<(usize, Vec<u32>)> {
        self.next_tile()
            .map(|(t, points)| (t, points.iter().flat_map(|&(a, b)| [a, b]).collect()))
    }
    fn accept(&mut self, piece: usize, values: &[f64], _json: Option<&str>) -> bool {
        let generation = TiledFill::generation(self);
        TiledFill::accept(self, generation, piece, values) == Answer::Stored
    }
    fn again(&mut self, piece: usize) {
        self.hand_out_again(piece);
    }
}

impl PoolFill {
    /// Starts filling `grid` for `model` in the workers; `None` where the
    /// page has no workers (it computes the landscape itself).
    pub fn start(model: &Arc<Model>, grid: Grid) -> Result<Option<Self>> {
        grid.validate()?;
        let fields = vec![("grid", json_field("the grid", &grid)?)];
        let Some(generation) = Generation::begin(model, "grid", fields)? else {
            return Ok(None);
        };
        Ok(Some(Self {
            fill: TiledFill::new(grid, generation.0, TILE_POINTS)?,
            _generation: generation,
            model: model.clone(),
            started: Instant::now(),
        }))
    }

    /// Takes in the workers' answers and sends new tiles; computes tiles on
    /// the page only when every worker has failed.
    pub fn exchange(&mut self) -> Exchange {
        let (stored, alive) =
            with_pool(|p| (p.exchange(&mut self.fill), p.any_alive())).unwrap_or((0, false));
        let mut points_here = 0;
        if !alive {
            let start = Instant::now();
            while start.elapsed() < HERE_BUDGET {
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
        Exchange {
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
        self.started.elapsed()
    }
}

/// A diagnosis whose resampled extractions the pool's workers compute.
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
    /// Starts the resampled extractions of `job` (of `model`) in the
    /// workers; `None` where the page has no workers.
    pub fn start(model: &Arc<Model>, job: &DiagnosticsJob) -> Result<Option<Self>> {
        let fields = vec![
            ("grid", json_field("the grid", &job.part_grid())?),
            ("k", JsValue::from_f64(job.k())),
        ];
        Ok(Generation::begin(model, "diag", fields)?.map(|generation| Self { generation }))
    }

    /// Takes in the workers' answers and sends new parts; with no worker
    /// left, computes on the page a slice of landscape points. Returns the
    /// parts stored (or 1 for a slice computed here).
    pub fn exchange(&mut self, job: &mut DiagnosticsJob, here_points: usize) -> usize {
        let mut handout = DiagHandout {
            generation: self.generation.0,
            job,
        };
        let (stored, alive) =
            with_pool(|p| (p.exchange(&mut handout), p.any_alive())).unwrap_or((0, false));
        if alive {
            return stored;
        }
        job.step_points(here_points);
        stored + 1
    }
}
