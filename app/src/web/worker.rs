//! The worker's side of the browser's pool: what `web/worker.js` calls in
//! a Web Worker's own instance of the module. It holds the models and grids
//! the page sent (by id and generation) and computes tiles of landscape
//! points with the core's kernels, the same bits as anywhere else.
//!
//! Messages, in order per worker (the page's side is [`super::pool`]):
//! a model (`id`, its demos and DMP settings as JSON), a grid for a
//! generation (which model, the grid as JSON), tiles of that generation
//! (the points' `(i_dm, i_km)` flat) and, when the page no longer wants a
//! generation, forget.

use std::cell::RefCell;
use std::collections::HashMap;
use std::sync::Arc;

use dmpscope_core::dmp::DmpSettings;
use dmpscope_core::landscape::{Grid, Landscape};
use dmpscope_core::{Model, PreparedDemo};
use serde::{Deserialize, Serialize};
use wasm_bindgen::prelude::*;

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
    let grid: Grid =
        serde_json::from_str(json).map_err(|e| js_error(format!("worker: the grid: {e}")))?;
    grid.validate()
        .map_err(|e| js_error(format!("worker: the grid: {e}")))?;
    HELD.with(|h| {
        let mut h = h.borrow_mut();
        let Some(m) = h.models.iter().find(|(id, _)| *id == model as u64) else {
            return Err(js_error(format!("worker: no model {model}")));
        };
        let m = m.1.clone();
        h.grids
            .insert(generation as u64, (m, Landscape::blank(grid)));
        Ok(())
    })
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
        Ok(values.concat())
    })
}

/// Forgets `generation` (its landscape was replaced or cancelled).
#[wasm_bindgen]
pub fn dmpscope_worker_forget(generation: f64) {
    HELD.with(|h| h.borrow_mut().grids.remove(&(generation as u64)));
}
