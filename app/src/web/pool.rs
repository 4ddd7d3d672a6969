//! The page's side of the browser's workers: a pool of dedicated Web
//! Workers (`web/worker.js`), as many as `navigator.hardwareConcurrency`
//! (at least 2, at most 8), each running its own instance of this module
//! (the page hands them its compiled `WebAssembly.Module`). Plain message
//! passing, no shared memory, so the page works on any static host.
//!
//! A landscape is a [`PoolFill`]: it sends its model once per worker (only
//! when the model changed since the last fill), then its grid under a new
//! generation, then tiles, at most [`IN_FLIGHT`] per worker, coarse levels
//! first. Answers come back in any order and are stored by the fill's
//! [`TiledFill`] bookkeeping, which refuses any answer of another
//! generation. Dropping the fill (a new grid or demo selection, or a
//! cancel) forgets its generation: the workers drop it, answers still on
//! their way are discarded. A worker that fails is terminated and its tiles
//! are handed to the others; with none left the page computes the rest
//! itself and says so in the log.

use std::cell::RefCell;
use std::collections::BTreeSet;
use std::rc::Rc;
use std::sync::Arc;

use dmpscope_core::landscape::{Grid, Landscape};
use dmpscope_core::{Model, Result};
use eframe::web_sys;
use wasm_bindgen::JsCast as _;
use wasm_bindgen::prelude::*;
use web_time::{Duration, Instant};

use super::worker::ModelInputs;
use crate::session::tiles::{Answer, TiledFill};

/// Tiles a worker holds at once (one computing, one waiting, so it never
/// idles while the page answers).
pub const IN_FLIGHT: usize = 2;
/// Points per tile: about 8 ms of one core.
const TILE_POINTS: usize = 128;
/// Workers at most, whatever the machine says.
const MAX_WORKERS: usize = 8;

/// A worker's answer, as the page received it.
struct Reply {
    worker: usize,
    generation: u64,
    tile: usize,
    values: std::result::Result<Vec<f64>, String>,
}

/// One worker and what it holds.
struct Slot {
    worker: web_sys::Worker,
    alive: bool,
    in_flight: Vec<(u64, usize)>,
    _on_message: Closure<dyn FnMut(web_sys::MessageEvent)>,
    _on_error: Closure<dyn FnMut(web_sys::ErrorEvent)>,
}

/// The workers and the answers they sent.
struct Pool {
    slots: Vec<Slot>,
    replies: Rc<RefCell<Vec<Reply>>>,
    deaths: Rc<RefCell<Vec<(usize, String)>>>,
    /// The model the workers hold last, and its id.
    model: Option<(Arc<Model>, u64)>,
    next_id: u64,
    live: BTreeSet<u64>,
    /// Tiles handed out whose worker died, by generation.
    lost: Vec<(u64, usize)>,
    tiles_from_workers: usize,
}

thread_local! {
    /// The page's pool: `None` before the first landscape, `Some(None)`
    /// where workers cannot be started.
    static POOL: RefCell<Option<Option<Pool>>> = const { RefCell::new(None) };
}

/// Runs `f` on the pool, starting it at the first call; `None` without one.
fn with_pool<R>(f: impl FnOnce(&mut Pool) -> R) -> Option<R> {
    POOL.with(|p| {
        let mut p = p.borrow_mut();
        let pool = p.get_or_insert_with(Pool::start);
        pool.as_mut().map(f)
    })
}

/// What the pool is doing, for the browser tests.
#[derive(Clone, Copy, Debug, Default, serde::Serialize)]
pub struct PoolStats {
    /// Workers started.
    pub workers: usize,
    /// Of those, still alive.
    pub alive: usize,
    /// Tiles the workers answered and a fill stored.
    pub tiles_from_workers: usize,
}

/// The pool's figures (zero before the first landscape).
pub fn stats() -> PoolStats {
    POOL.with(|p| match &*p.borrow() {
        Some(Some(pool)) => PoolStats {
            workers: pool.slots.len(),
            alive: pool.slots.iter().filter(|s| s.alive).count(),
            tiles_from_workers: pool.tiles_from_workers,
        },
        _ => PoolStats::default(),
    })
}

fn message(pairs: &[(&str, JsValue)]) -> JsValue {
    let object = js_sys::Object::new();
    for (key, value) in pairs {
        let _ = js_sys::Reflect::set(&object, &JsValue::from_str(key), value);
    }
    object.into()
}

fn field(data: &JsValue, key: &str) -> JsValue {
    js_sys::Reflect::get(data, &JsValue::from_str(key)).unwrap_or(JsValue::UNDEFINED)
}

impl Pool {
    fn start() -> Option<Self> {
        let window = web_sys::window()?;
        let cores = window.navigator().hardware_concurrency();
        let n = if cores.is_finite() { cores as usize } else { 2 }.clamp(2, MAX_WORKERS);
        let replies = Rc::new(RefCell::new(Vec::new()));
        let deaths = Rc::new(RefCell::new(Vec::new()));
        let module = wasm_bindgen::module();
        let mut slots = Vec::new();
        for i in 0..n {
            match Self::spawn(i, &module, &replies, &deaths) {
                Ok(slot) => slots.push(slot),
                Err(e) => log::warn!("dmpscope: cannot start worker {i}: {e:?}"),
            }
        }
        if slots.is_empty() {
            log::warn!("dmpscope: no Web Worker could be started; the page computes the landscape");
            return None;
        }
        Some(Self {
            slots,
            replies,
            deaths,
            model: None,
            next_id: 1,
            live: BTreeSet::new(),
            lost: Vec::new(),
            tiles_from_workers: 0,
        })
    }

    fn spawn(
        i: usize,
        module: &JsValue,
        replies: &Rc<RefCell<Vec<Reply>>>,
        deaths: &Rc<RefCell<Vec<(usize, String)>>>,
    ) -> std::result::Result<Slot, JsValue> {
        let options = web_sys::WorkerOptions::new();
        options.set_type(web_sys::WorkerType::Module);
        let worker = web_sys::Worker::new_with_options("./worker.js", &options)?;
        let (to_replies, to_deaths) = (replies.clone(), deaths.clone());
        let on_message = Closure::<dyn FnMut(web_sys::MessageEvent)>::new(
            move |event: web_sys::MessageEvent| {
                let data = event.data();
                let kind = field(&data, "kind").as_string().unwrap_or_default();
                let number = |key| field(&data, key).as_f64().unwrap_or(-1.0);
                match kind.as_str() {
                    "tile" => to_replies.borrow_mut().push(Reply {
                        worker: i,
                        generation: number("generation") as u64,
                        tile: number("tile") as usize,
                        values: Ok(js_sys::Float64Array::new(&field(&data, "values")).to_vec()),
                    }),
                    "error" => to_replies.borrow_mut().push(Reply {
                        worker: i,
                        generation: number("generation") as u64,
                        tile: number("tile") as usize,
                        values: Err(field(&data, "error").as_string().unwrap_or_default()),
                    }),
                    _ => to_deaths.borrow_mut().push((
                        i,
                        field(&data, "error")
                            .as_string()
                            .unwrap_or_else(|| kind.clone()),
                    )),
                }
            },
        );
        let deaths = deaths.clone();
        let on_error =
            Closure::<dyn FnMut(web_sys::ErrorEvent)>::new(move |event: web_sys::ErrorEvent| {
                deaths.borrow_mut().push((i, event.message()));
            });
        worker.set_onmessage(Some(on_message.as_ref().unchecked_ref()));
        worker.set_onerror(Some(on_error.as_ref().unchecked_ref()));
        worker.post_message(&message(&[
            ("kind", "init".into()),
            ("module", module.clone()),
        ]))?;
        Ok(Slot {
            worker,
            alive: true,
            in_flight: Vec::new(),
            _on_message: on_message,
            _on_error: on_error,
        })
    }

    /// Posts to every live worker; a worker that cannot take it dies.
    fn broadcast(&mut self, msg: &JsValue) {
        for (i, slot) in self.slots.iter_mut().enumerate() {
            if slot.alive
                && let Err(e) = slot.worker.post_message(msg)
            {
                self.deaths.borrow_mut().push((i, format!("{e:?}")));
            }
        }
    }

    /// Starts a generation for `model` over `grid`.
    fn begin(&mut self, model: &Arc<Model>, grid: Grid) -> Result<u64> {
        let same = self
            .model
            .as_ref()
            .is_some_and(|(m, _)| Arc::ptr_eq(m, model));
        if !same {
            let inputs = ModelInputs {
                demos: model.demos().to_vec(),
                settings: *model.settings(),
            };
            let json = serde_json::to_string(&inputs)
                .map_err(|e| dmpscope_core::Error::InvalidSetting(format!("the model: {e}")))?;
            let id = self.next_id;
            self.next_id += 1;
            self.broadcast(&message(&[
                ("kind", "model".into()),
                ("model", (id as f64).into()),
                ("json", json.into()),
            ]));
            self.model = Some((model.clone(), id));
        }
        let model_id = self.model.as_ref().map_or(0, |(_, id)| *id);
        let generation = self.next_id;
        self.next_id += 1;
        let grid_json = serde_json::to_string(&grid)
            .map_err(|e| dmpscope_core::Error::InvalidSetting(format!("the grid: {e}")))?;
        self.broadcast(&message(&[
            ("kind", "grid".into()),
            ("generation", (generation as f64).into()),
            ("model", (model_id as f64).into()),
            ("grid", grid_json.into()),
        ]));
        self.live.insert(generation);
        Ok(generation)
    }

    /// Ends a generation: its tiles are no longer wanted.
    fn end(&mut self, generation: u64) {
        self.live.remove(&generation);
        for slot in &mut self.slots {
            slot.in_flight.retain(|(g, _)| *g != generation);
        }
        self.lost.retain(|(g, _)| *g != generation);
        self.broadcast(&message(&[
            ("kind", "forget".into()),
            ("generation", (generation as f64).into()),
        ]));
    }

    /// Buries workers that failed: their tiles go back to their fills.
    fn bury(&mut self) {
        let deaths: Vec<(usize, String)> = self.deaths.borrow_mut().drain(..).collect();
        for (i, why) in deaths {
            let Some(slot) = self.slots.get_mut(i) else {
                continue;
            };
            if !slot.alive {
                continue;
            }
            log::warn!("dmpscope: worker {i} failed ({why}); the others take its tiles");
            slot.alive = false;
            slot.worker.terminate();
            self.lost.append(&mut slot.in_flight);
        }
    }

    /// Stores the answers for `fill`, hands it the tiles of dead workers
    /// again and sends it new tiles. Returns the tiles stored.
    fn exchange(&mut self, fill: &mut TiledFill) -> usize {
        self.bury();
        let generation = fill.generation();
        let mut stored = 0;
        let replies: Vec<Reply> = self.replies.borrow_mut().drain(..).collect();
        let mut keep = Vec::new();
        for reply in replies {
            if let Some(slot) = self.slots.get_mut(reply.worker) {
                slot.in_flight
                    .retain(|&x| x != (reply.generation, reply.tile));
            }
            if reply.generation != generation {
                if self.live.contains(&reply.generation) {
                    keep.push(reply);
                }
                continue;
            }
            match &reply.values {
                Ok(values) => match fill.accept(generation, reply.tile, values) {
                    Answer::Stored => {
                        stored += 1;
                        self.tiles_from_workers += 1;
                    }
                    other => log::warn!("dmpscope: a worker's tile was dropped: {other:?}"),
                },
                Err(why) => {
                    // A worker that cannot compute a tile computes none.
                    self.deaths.borrow_mut().push((reply.worker, why.clone()));
                    fill.hand_out_again(reply.tile);
                }
            }
        }
        self.replies.borrow_mut().extend(keep);
        self.bury();
        let mine: Vec<usize> = self
            .lost
            .iter()
            .filter(|(g, _)| *g == generation)
            .map(|(_, t)| *t)
            .collect();
        self.lost.retain(|(g, _)| *g != generation);
        for tile in mine {
            fill.hand_out_again(tile);
        }
        for i in 0..self.slots.len() {
            while self.slots[i].alive && self.slots[i].in_flight.len() < IN_FLIGHT {
                let Some((tile, points)) = fill.next_tile() else {
                    return stored;
                };
                let flat: Vec<u32> = points.iter().flat_map(|&(a, b)| [a, b]).collect();
                let array = js_sys::Uint32Array::from(flat.as_slice());
                let msg = message(&[
                    ("kind", "tile".into()),
                    ("generation", (generation as f64).into()),
                    ("tile", (tile as f64).into()),
                    ("points", array.clone().into()),
                ]);
                let transfer = js_sys::Array::of1(&array.buffer());
                match self.slots[i]
                    .worker
                    .post_message_with_transfer(&msg, &transfer)
                {
                    Ok(()) => self.slots[i].in_flight.push((generation, tile)),
                    Err(e) => {
                        fill.hand_out_again(tile);
                        self.deaths.borrow_mut().push((i, format!("{e:?}")));
                        break;
                    }
                }
            }
        }
        stored
    }

    fn any_alive(&self) -> bool {
        self.slots.iter().any(|s| s.alive)
    }
}

/// What one [`PoolFill::exchange`] did.
pub struct Exchange {
    /// Tiles stored from the workers.
    pub stored: usize,
    /// Points the page computed itself (no worker left).
    pub points_here: usize,
}

/// A landscape filled by the pool's workers.
pub struct PoolFill {
    fill: TiledFill,
    model: Arc<Model>,
    started: Instant,
}

/// Page time a fill may spend computing per exchange when no worker is
/// left.
const HERE_BUDGET: Duration = Duration::from_millis(8);

impl PoolFill {
    /// Starts filling `grid` for `model` in the workers; `None` where the
    /// page has no workers (it computes the landscape itself).
    pub fn start(model: &Arc<Model>, grid: Grid) -> Result<Option<Self>> {
        grid.validate()?;
        let Some(generation) = with_pool(|p| p.begin(model, grid)) else {
            return Ok(None);
        };
        Ok(Some(Self {
            fill: TiledFill::new(grid, generation?, TILE_POINTS)?,
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
                self.fill.accept(generation, tile, &values.concat());
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

impl Drop for PoolFill {
    fn drop(&mut self) {
        let generation = self.fill.generation();
        let _ = with_pool(|p| p.end(generation));
    }
}
