//! A Web Worker's entry points: what `web/worker.js` calls in the worker's
//! own instance of the module. Each turns its JavaScript arguments into a
//! call on the session's [`WorkerState`] (models, generations, tiles,
//! resampled extractions, RL runs in slices), which holds everything and
//! computes with the core's kernels: the same bits as anywhere else.

use std::cell::RefCell;
use std::sync::Arc;
use std::time::Duration;

use dmpscope_core::landscape::grid::Grid;
use dmpscope_session::RlRequest;
use dmpscope_session::worker_side::{ModelInputs, RunSlice, WorkerState};
use dmpscope_session::workers::Setup;
use wasm_bindgen::prelude::*;
use web_time::Instant;

thread_local! {
    static HELD: RefCell<WorkerState> = RefCell::new(WorkerState::default());
    static ORIGIN: Instant = Instant::now();
}

fn js_error(message: String) -> JsValue {
    JsValue::from_str(&message)
}

fn parse<T: serde::de::DeserializeOwned>(what: &str, json: &str) -> Result<T, JsValue> {
    serde_json::from_str(json).map_err(|e| js_error(format!("worker: {what}: {e}")))
}

fn begin(generation: f64, model: f64, setup: Setup) -> Result<(), JsValue> {
    HELD.with(|h| h.borrow_mut().begin(generation as u64, model as u64, setup))
        .map_err(js_error)
}

/// Builds model `id` from its inputs ([`ModelInputs::to_bytes`]).
#[wasm_bindgen]
pub fn dmpscope_worker_model(id: f64, bytes: &[u8]) -> Result<(), JsValue> {
    let inputs = ModelInputs::from_bytes(bytes).map_err(js_error)?;
    let model = inputs.build().map_err(js_error)?;
    HELD.with(|h| h.borrow_mut().keep_model(id as u64, Arc::new(model)));
    Ok(())
}

/// Starts `generation`: the grid (JSON of a [`Grid`]) over model `model`.
#[wasm_bindgen]
pub fn dmpscope_worker_grid(generation: f64, model: f64, json: &str) -> Result<(), JsValue> {
    let grid: Grid = parse("the grid", json)?;
    begin(generation, model, Setup::Grid(grid))
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
    let grid: Grid = parse("the grid", json)?;
    begin(generation, model, Setup::Diag { grid, k })
}

/// Computes a part of diagnosis `generation`: the extraction of the model
/// of the demos at `indices` (`[dm, km, J, on_edge]`, or empty).
#[wasm_bindgen]
pub fn dmpscope_worker_part(generation: f64, indices: &[u32]) -> Result<Vec<f64>, JsValue> {
    HELD.with(|h| h.borrow().part(generation as u64, indices))
        .map_err(js_error)
}

/// Computes a tile of `generation`: `points` are `(i_dm, i_km)` pairs
/// flat; the answer is every quantity of the table (`[sum d, S, a_peak,
/// E]`, `core::quantity::ALL`'s order) per point, flat.
#[wasm_bindgen]
pub fn dmpscope_worker_tile(generation: f64, points: &[u32]) -> Result<Vec<f64>, JsValue> {
    HELD.with(|h| h.borrow().tile(generation as u64, points))
        .map_err(js_error)
}

/// Starts `generation` of RL training: runs of the request (JSON of an
/// `RlRequest`) on model `model`.
#[wasm_bindgen]
pub fn dmpscope_worker_rl(generation: f64, model: f64, json: &str) -> Result<(), JsValue> {
    let request: RlRequest = parse("the RL request", json)?;
    begin(generation, model, Setup::Rl(request))
}

/// Trains run `run` of RL `generation` for about `budget_ms` (starting it
/// at the first call). Returns `None` when the generation is forgotten (the
/// pump stops), `""` when no iteration ended, else `P` or, for the run's
/// last, `L` followed by the JSON of the run's update.
#[wasm_bindgen]
pub fn dmpscope_worker_run_step(generation: f64, run: f64, budget_ms: f64) -> Option<String> {
    let budget = Duration::from_secs_f64(budget_ms.max(1.0) / 1e3);
    let now = || ORIGIN.with(Instant::elapsed);
    let slice = HELD.with(|h| {
        h.borrow_mut()
            .run_step(generation as u64, run as usize, budget, &now)
    })?;
    let text =
        |tag: &str, update| format!("{tag}{}", serde_json::to_string(update).unwrap_or_default());
    Some(match slice {
        RunSlice::Nothing => String::new(),
        RunSlice::Progress(update) => text("P", &update),
        RunSlice::Last(update) => text("L", &update),
    })
}

/// Forgets `generation` (its owner was replaced or cancelled).
#[wasm_bindgen]
pub fn dmpscope_worker_forget(generation: f64) {
    HELD.with(|h| h.borrow_mut().forget(generation as u64));
}
