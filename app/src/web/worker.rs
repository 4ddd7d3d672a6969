//! The worker's side of the browser's pool: what `web/worker.js` calls in
//! a Web Worker's own instance of the module. It holds the models and grids
//! the page sent (by id and generation) and computes tiles of landscape
//! points with the core's kernels, the same bits as anywhere else.
//!
//! Messages, in order per worker (the page's side is [`super::pool`]):
//! a model (`id`, its demos and DMP settings as JSON); a generation, either
//! a landscape's (which model, the grid as JSON) with tiles (the points'
//! `(i_dm, i_km)` flat), or a diagnosis's (which model, the diagnostics'
//! grid, k) with parts (the demos of a resampled model), or an RL
//! request's (which model, the request as JSON) with runs (trained in
//! slices between messages, `web/worker.js` pumping them); and, when the
//! page no longer wants a generation, forget.

use std::cell::RefCell;
use std::collections::HashMap;
use std::sync::Arc;

use dmpscope_core::dmp::DmpSettings;
use dmpscope_core::landscape::{Grid, Landscape};
use dmpscope_core::rl::TrainingRun;
use dmpscope_core::{Model, PreparedDemo};
use serde::{Deserialize, Serialize};
use wasm_bindgen::prelude::*;
use web_time::{Duration, Instant};

use crate::session::RlRequest;
use crate::session::rl_board::RunUpdate;

/// A model as the page sends it: what [`Model::new`] needs.
#[derive(Serialize, Deserialize)]
pub struct ModelInputs {
    /// The prepared demos.
    pub demos: Vec<PreparedDemo>,
    /// The DMP settings.
    pub settings: DmpSettings,
}

/// Models a worker keeps at most (the page sends a new one per change of
/// demos or settings; older ones go first).
const KEPT_MODELS: usize = 4;

#[derive(Default)]
struct Held {
    models: Vec<(u64, Arc<Model>)>,
    grids: HashMap<u64, (Arc<Model>, Landscape)>,
    diags: HashMap<u64, (Arc<Model>, Grid, f64)>,
    requests: HashMap<u64, (Arc<Model>, RlRequest)>,
    runs: HashMap<(u64, usize), (TrainingRun, Instant)>,
}

impl Held {
    fn model(&self, id: f64) -> Result<Arc<Model>, JsValue> {
        self.models
            .iter()
            .find(|(m, _)| *m == id as u64)
            .map(|(_, m)| m.clone())
            .ok_or_else(|| js_error(format!("worker: no model {id}")))
    }
}

thread_local! {
    static HELD: RefCell<Held> = RefCell::new(Held::default());
}

fn js_error(message: String) -> JsValue {
    JsValue::from_str(&message)
}

/// Builds model `id` from its inputs (JSON of [`ModelInputs`]).
#[wasm_bindgen]
pub fn dmpscope_worker_model(id: f64, json: &str) -> Result<(), JsValue> {
    let inputs: ModelInputs = serde_json::from_str(json)
        .map_err(|e| js_error(format!("worker: the model's inputs: {e}")))?;
    let model = Model::new(inputs.demos, inputs.settings)
        .map_err(|e| js_error(format!("worker: the model: {e}")))?;
    HELD.with(|h| {
        let mut h = h.borrow_mut();
        h.models.retain(|(m, _)| *m != id as u64);
        h.models.push((id as u64, Arc::new(model)));
        let excess = h.models.len().saturating_sub(KEPT_MODELS);
        h.models.drain(..excess);
    });
    Ok(())
}

/// Starts `generation`: the grid (JSON of a [`Grid`]) over model `model`.
#[wasm_bindgen]
pub fn dmpscope_worker_grid(generation: f64, model: f64, json: &str) -> Result<(), JsValue> {
    let grid = parse_grid(json)?;
    HELD.with(|h| {
        let mut h = h.borrow_mut();
        let m = h.model(model)?;
        h.grids
            .insert(generation as u64, (m, Landscape::blank(grid)));
        Ok(())
    })
}

/// Starts `generation` of a diagnosis: resampled extractions of model
/// `model` on the diagnostics' grid (JSON of a [`Grid`]) for `k`.
#[wasm_bindgen]
pub fn dmpscope_worker_diag(
    generation: f64,
    model: f64,
    json: &str,
    k: f64,
) -> Result<(), JsValue> {
    let grid = parse_grid(json)?;
    HELD.with(|h| {
        let mut h = h.borrow_mut();
        let m = h.model(model)?;
        h.diags.insert(generation as u64, (m, grid, k));
        Ok(())
    })
}

fn parse_grid(json: &str) -> Result<Grid, JsValue> {
    let grid: Grid =
        serde_json::from_str(json).map_err(|e| js_error(format!("worker: the grid: {e}")))?;
    grid.validate()
        .map_err(|e| js_error(format!("worker: the grid: {e}")))?;
    Ok(grid)
}

/// Computes a part of diagnosis `generation`: the extraction of the model
/// of the demos at `indices`. The answer is `[dm, km, J, on_edge]`, or
/// empty where that model has no optimum.
#[wasm_bindgen]
pub fn dmpscope_worker_part(generation: f64, indices: &[u32]) -> Result<Vec<f64>, JsValue> {
    let indices: Vec<usize> = indices.iter().map(|&i| i as usize).collect();
    let (model, grid, k) = HELD.with(|h| {
        h.borrow()
            .diags
            .get(&(generation as u64))
            .cloned()
            .ok_or_else(|| js_error(format!("worker: no diagnosis {generation}")))
    })?;
    Ok(
        match dmpscope_core::diagnostics::optimum_of(&model, &indices, grid, k) {
            Ok(o) => vec![o.dm, o.km, o.j, f64::from(u8::from(o.on_edge))],
            Err(_) => Vec::new(),
        },
    )
}

/// Computes a tile of `generation`: `points` are `(i_dm, i_km)` pairs
/// flat; the answer is `[sum d, S, a_peak]` per point, flat.
#[wasm_bindgen]
pub fn dmpscope_worker_tile(generation: f64, points: &[u32]) -> Result<Vec<f64>, JsValue> {
    let pairs: Vec<(u32, u32)> = points.chunks_exact(2).map(|p| (p[0], p[1])).collect();
    HELD.with(|h| {
        let h = h.borrow();
        let Some((model, blank)) = h.grids.get(&(generation as u64)) else {
            return Err(js_error(format!("worker: no generation {generation}")));
        };
        let values = blank
            .evaluate(model, &pairs)
            .map_err(|e| js_error(format!("worker: {e}")))?;
        Ok(values.as_flattened().to_vec())
    })
}

/// Starts `generation` of RL training: runs of the request (JSON of an
/// `RlRequest`) on model `model`.
#[wasm_bindgen]
pub fn dmpscope_worker_rl(generation: f64, model: f64, json: &str) -> Result<(), JsValue> {
    let request: RlRequest =
        serde_json::from_str(json).map_err(|e| js_error(format!("worker: the RL request: {e}")))?;
    HELD.with(|h| {
        let mut h = h.borrow_mut();
        let m = h.model(model)?;
        h.requests.insert(generation as u64, (m, request));
        Ok(())
    })
}

/// Trains run `run` of RL `generation` for about `budget_ms` (starting it
/// at the first call). Returns `None` when the generation is forgotten (the
/// pump stops), `""` when no iteration ended, else `P` or, for the run's
/// last, `L` followed by the JSON of a [`RunUpdate`].
#[wasm_bindgen]
pub fn dmpscope_worker_run_step(generation: f64, run: f64, budget_ms: f64) -> Option<String> {
    let key = (generation as u64, run as usize);
    HELD.with(|h| {
        let mut h = h.borrow_mut();
        let Some((model, request)) = h.requests.get(&key.0).cloned() else {
            h.runs.remove(&key);
            return None;
        };
        let (mut training, started) = match h.runs.remove(&key) {
            Some(held) => held,
            None => {
                let Some(r) = request.runs.get(key.1) else {
                    return Some(last(&RunUpdate::stopped(&request, key.1, "no such run")));
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
                    Ok(training) => (training, Instant::now()),
                    Err(e) => {
                        return Some(last(&RunUpdate::stopped(&request, key.1, &e.to_string())));
                    }
                }
            }
        };
        let budget = Duration::from_secs_f64(budget_ms.max(1.0) / 1e3);
        let slice = Instant::now();
        loop {
            let seconds = started.elapsed().as_secs_f64();
            match training.step(seconds) {
                Err(e) => {
                    return Some(last(&RunUpdate::stopped(&request, key.1, &e.to_string())));
                }
                Ok(Some(_)) => {
                    let update = RunUpdate::of(&training, &model, request.demo, seconds);
                    if update.last {
                        let update = update.with_report(&training, &model, &request, key.1);
                        return Some(last(&update));
                    }
                    h.runs.insert(key, (training, started));
                    let json = serde_json::to_string(&update).unwrap_or_default();
                    return Some(format!("P{json}"));
                }
                Ok(None) if slice.elapsed() >= budget => {
                    h.runs.insert(key, (training, started));
                    return Some(String::new());
                }
                Ok(None) => {}
            }
        }
    })
}

fn last(update: &RunUpdate) -> String {
    format!("L{}", serde_json::to_string(update).unwrap_or_default())
}

/// Forgets `generation` (its landscape was replaced or cancelled).
#[wasm_bindgen]
pub fn dmpscope_worker_forget(generation: f64) {
    HELD.with(|h| {
        let mut h = h.borrow_mut();
        let g = generation as u64;
        h.grids.remove(&g);
        h.diags.remove(&g);
        h.requests.remove(&g);
        h.runs.retain(|(run_generation, _), _| *run_generation != g);
    });
}
