//! A worker's side of the pool ([`crate::workers`]): what one worker holds
//! (the models and generations it was sent) and computes (tiles of
//! landscape points, resampled extractions, RL runs in slices) with the
//! core's kernels, the same bits as anywhere else. The browser's Web
//! Workers call it through the app's worker entry points; the tests' fake pool
//! calls it directly.
//!
//! Messages, in order per worker: a model (an id and the model); a
//! generation, either a landscape's (which model, the grid) with tiles
//! (the points' `(i_dm, i_km)` flat), or a diagnosis's (which model, the
//! diagnostics' grid, k) with parts (the demos of a resampled model), or an
//! RL request's (which model, the request) with runs (trained in slices
//! between messages); and, when the owner no longer wants a generation,
//! forget.

use std::collections::HashMap;
use std::sync::Arc;
use std::time::Duration;

use dmpscope_core::fit::settings::DmpSettings;
use dmpscope_core::landscape::grid::{Grid, Landscape};
use dmpscope_core::rl::run::TrainingRun;
use dmpscope_core::{Model, PreparedDemo};
use serde::{Deserialize, Serialize};

use crate::rl_request::RlRequest;
use crate::rl_request::RunUpdate;
use crate::workers::Setup;

/// A model as it travels to a worker: what [`Model::new`] needs, as
/// bytes ([`ModelInputs::to_bytes`]).
#[derive(Serialize, Deserialize)]
pub struct ModelInputs {
    /// The prepared demos.
    pub demos: Vec<PreparedDemo>,
    /// The DMP settings.
    pub settings: DmpSettings,
}

impl ModelInputs {
    /// The inputs of `model`.
    pub fn of(model: &Model) -> Self {
        Self {
            demos: model.demos().to_vec(),
            settings: *model.settings(),
        }
    }

    /// The inputs as bytes: postcard, every `f64` as its eight bytes, so a
    /// worker builds the page's model to the bit. For the planted sample
    /// about a third of the JSON it replaced, and written and read several
    /// times faster (ARCHITECTURE.md, "The browser").
    pub fn to_bytes(&self) -> Result<Vec<u8>, String> {
        postcard::to_allocvec(self).map_err(|e| format!("the model's inputs: {e}"))
    }

    /// The inputs [`ModelInputs::to_bytes`] wrote.
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, String> {
        postcard::from_bytes(bytes).map_err(|e| format!("worker: the model's inputs: {e}"))
    }

    /// The model they make.
    pub fn build(self) -> Result<Model, String> {
        Model::new(self.demos, self.settings).map_err(|e| format!("worker: the model: {e}"))
    }
}

/// Models a worker keeps at most (the owner sends a new one per change of
/// demos or settings; older ones go first).
const KEPT_MODELS: usize = 4;

/// What an RL run's slice gave.
#[derive(Clone, Debug, PartialEq)]
pub enum RunSlice {
    /// No iteration ended within the slice.
    Nothing,
    /// An update after an iteration; the run goes on.
    Progress(RunUpdate),
    /// The run's last update.
    Last(RunUpdate),
}

/// A worker's models, generations and RL runs.
#[derive(Default)]
pub struct WorkerState {
    models: Vec<(u64, Arc<Model>)>,
    grids: HashMap<u64, (Arc<Model>, Landscape)>,
    diags: HashMap<u64, (Arc<Model>, Grid, f64)>,
    requests: HashMap<u64, (Arc<Model>, RlRequest)>,
    runs: HashMap<(u64, usize), (TrainingRun, Duration)>,
}

impl WorkerState {
    /// Keeps `model` as model `id` (the oldest beyond a few go).
    pub fn keep_model(&mut self, id: u64, model: Arc<Model>) {
        self.models.retain(|(m, _)| *m != id);
        self.models.push((id, model));
        let excess = self.models.len().saturating_sub(KEPT_MODELS);
        self.models.drain(..excess);
    }

    fn model(&self, id: u64) -> Result<Arc<Model>, String> {
        self.models
            .iter()
            .find(|(m, _)| *m == id)
            .map(|(_, m)| m.clone())
            .ok_or_else(|| format!("worker: no model {id}"))
    }

    /// Starts `generation` over model `model` with `setup`.
    pub fn begin(&mut self, generation: u64, model: u64, setup: Setup) -> Result<(), String> {
        let m = self.model(model)?;
        match setup {
            Setup::Grid(grid) => {
                grid.validate()
                    .map_err(|e| format!("worker: the grid: {e}"))?;
                self.grids.insert(generation, (m, Landscape::blank(grid)));
            }
            Setup::Diag { grid, k } => {
                grid.validate()
                    .map_err(|e| format!("worker: the grid: {e}"))?;
                self.diags.insert(generation, (m, grid, k));
            }
            Setup::Rl(request) => {
                self.requests.insert(generation, (m, request));
            }
        }
        Ok(())
    }

    /// A tile of `generation`: `points` are `(i_dm, i_km)` pairs flat; the
    /// answer is every quantity of the table per point, flat.
    pub fn tile(&self, generation: u64, points: &[u32]) -> Result<Vec<f64>, String> {
        let pairs: Vec<(u32, u32)> = points.chunks_exact(2).map(|p| (p[0], p[1])).collect();
        let Some((model, blank)) = self.grids.get(&generation) else {
            return Err(format!("worker: no generation {generation}"));
        };
        let values = blank
            .evaluate(model, &pairs)
            .map_err(|e| format!("worker: {e}"))?;
        Ok(values.as_flattened().to_vec())
    }

    /// A part of diagnosis `generation`: the extraction of the model of the
    /// demos at `indices`. The answer is `[dm, km, J, on_edge]`, or empty
    /// where that model has no optimum.
    pub fn part(&self, generation: u64, indices: &[u32]) -> Result<Vec<f64>, String> {
        let indices: Vec<usize> = indices.iter().map(|&i| i as usize).collect();
        let (model, grid, k) = self
            .diags
            .get(&generation)
            .ok_or_else(|| format!("worker: no diagnosis {generation}"))?;
        Ok(
            match dmpscope_core::extract::diagnostics::resample::optimum_of(
                model, &indices, *grid, *k,
            ) {
                Ok(o) => vec![o.dm, o.km, o.j, f64::from(u8::from(o.on_edge))],
                Err(_) => Vec::new(),
            },
        )
    }

    /// Trains run `run` of RL `generation` for about `budget` (starting it
    /// at the first call); `now` is the worker's clock. `None` when the
    /// generation is forgotten (stop pumping).
    pub fn run_step(
        &mut self,
        generation: u64,
        run: usize,
        budget: Duration,
        now: &dyn Fn() -> Duration,
    ) -> Option<RunSlice> {
        let key = (generation, run);
        let Some((model, request)) = self.requests.get(&generation).cloned() else {
            self.runs.remove(&key);
            return None;
        };
        let (mut training, started) = match self.runs.remove(&key) {
            Some(held) => held,
            None => {
                let Some(r) = request.runs.get(run) else {
                    return Some(RunSlice::Last(RunUpdate::stopped(
                        &request,
                        run,
                        "no such run",
                    )));
                };
                let made = TrainingRun::new(
                    &model,
                    request.demo,
                    (r.dm, r.km),
                    request.options,
                    request.steps,
                    r.seed,
                );
                match made {
                    Ok(training) => (training, now()),
                    Err(e) => {
                        let why = e.to_string();
                        return Some(RunSlice::Last(RunUpdate::stopped(&request, run, &why)));
                    }
                }
            }
        };
        let slice = now();
        loop {
            let seconds = (now() - started).as_secs_f64();
            match training.step(seconds) {
                Err(e) => {
                    let why = e.to_string();
                    return Some(RunSlice::Last(RunUpdate::stopped(&request, run, &why)));
                }
                Ok(Some(_)) => {
                    let update = RunUpdate::of(&training, &model, request.demo, seconds);
                    if update.last {
                        let update = update.with_report(&training, &model, &request, run);
                        return Some(RunSlice::Last(update));
                    }
                    self.runs.insert(key, (training, started));
                    return Some(RunSlice::Progress(update));
                }
                Ok(None) if now() - slice >= budget => {
                    self.runs.insert(key, (training, started));
                    return Some(RunSlice::Nothing);
                }
                Ok(None) => {}
            }
        }
    }

    /// Forgets `generation` (its owner was replaced or cancelled).
    pub fn forget(&mut self, generation: u64) {
        self.grids.remove(&generation);
        self.diags.remove(&generation);
        self.requests.remove(&generation);
        self.runs.retain(|(g, _), _| *g != generation);
    }
}
