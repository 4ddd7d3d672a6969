//! The page's side of the browser's workers: a pool of dedicated Web
//! Workers (`web/worker.js`), as many as `navigator.hardwareConcurrency`
//! (at least 2, at most 8), each running its own instance of this module
//! (the page hands them its compiled `WebAssembly.Module`). Plain message
//! passing, no shared memory, so the page works on any static host.
//!
//! Work is handed out under generations ([`Handout`]): a landscape's tiles
//! (`fills::PoolFill`), a diagnosis's resampled extractions
//! (`fills::PoolDiag`) or RL runs (`rl::PoolRl`, one per worker at a time,
//! with an update after every iteration). A generation sends its model once per worker (only
//! when the model changed since the last generation), then its settings,
//! then pieces, at most [`IN_FLIGHT`] per worker. Answers come back in any
//! order; one for a generation no longer live is dropped, so nothing stale
//! reaches the view. Ending a generation (its owner was replaced or
//! cancelled) makes the workers forget it. A worker that fails is
//! terminated and its pieces are handed to the others; with none left the
//! owner computes on the page and the log says so.

use std::cell::RefCell;
use std::collections::BTreeSet;
use std::rc::Rc;
use std::sync::Arc;

use dmpscope_core::{Model, Result};
use eframe::web_sys;
use wasm_bindgen::JsCast as _;
use wasm_bindgen::prelude::*;

use super::worker::ModelInputs;

/// Pieces a worker holds at once (one computing, one waiting, so it never
/// idles while the page answers).
pub const IN_FLIGHT: usize = 2;
/// Workers at most, whatever the machine says.
const MAX_WORKERS: usize = 8;

/// A worker's answer, as the page received it.
struct Reply {
    worker: usize,
    generation: u64,
    piece: usize,
    values: std::result::Result<Vec<f64>, String>,
    /// A JSON answer (RL runs' updates).
    json: Option<String>,
    /// Whether the piece is answered (else an update on the way).
    last: bool,
}

/// One worker and what it holds.
struct Slot {
    worker: web_sys::Worker,
    alive: bool,
    in_flight: Vec<(u64, usize)>,
    _on_message: Closure<dyn FnMut(web_sys::MessageEvent)>,
    _on_error: Closure<dyn FnMut(JsValue)>,
}

/// The workers and the answers they sent.
pub(super) struct Pool {
    slots: Vec<Slot>,
    replies: Rc<RefCell<Vec<Reply>>>,
    deaths: Rc<RefCell<Vec<(usize, String)>>>,
    /// The model the workers hold last, and its id.
    model: Option<(Arc<Model>, u64)>,
    next_id: u64,
    live: BTreeSet<u64>,
    /// Pieces handed out whose worker died, by generation.
    lost: Vec<(u64, usize)>,
    tiles_from_workers: usize,
    parts_from_workers: usize,
    runs_from_workers: usize,
}

thread_local! {
    /// The page's pool: `None` before the first landscape, `Some(None)`
    /// where workers cannot be started.
    static POOL: RefCell<Option<Option<Pool>>> = const { RefCell::new(None) };
}

thread_local! {
    /// What the user should be told about the pool, not yet taken.
    static NOTICES: RefCell<Vec<String>> = const { RefCell::new(Vec::new()) };
}

/// Logs `text` and keeps it for the app's messages.
fn notice(text: String) {
    log::warn!("dmpscope: {text}");
    NOTICES.with(|n| n.borrow_mut().push(text));
}

/// What the user should be told about the workers since the last call (a
/// worker that failed, none that could start).
pub fn take_notices() -> Vec<String> {
    NOTICES.with(|n| std::mem::take(&mut *n.borrow_mut()))
}

/// Runs `f` on the pool, starting it at the first call; `None` without one.
pub(super) fn with_pool<R>(f: impl FnOnce(&mut Pool) -> R) -> Option<R> {
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
    /// Landscape tiles the workers answered and a fill stored.
    pub tiles_from_workers: usize,
    /// Resampled extractions of the diagnostics the workers answered.
    pub parts_from_workers: usize,
    /// RL runs the workers trained to their end.
    pub runs_from_workers: usize,
}

/// The pool's figures (zero before the first landscape).
pub fn stats() -> PoolStats {
    POOL.with(|p| match &*p.borrow() {
        Some(Some(pool)) => PoolStats {
            workers: pool.slots.len(),
            alive: pool.slots.iter().filter(|s| s.alive).count(),
            tiles_from_workers: pool.tiles_from_workers,
            parts_from_workers: pool.parts_from_workers,
            runs_from_workers: pool.runs_from_workers,
        },
        _ => PoolStats::default(),
    })
}

/// A message: a plain object of these fields.
pub(super) fn message(pairs: &[(&str, JsValue)]) -> JsValue {
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
                Err(e) => notice(format!(
                    "the browser could not start Web Worker {i} ({e:?})"
                )),
            }
        }
        if slots.is_empty() {
            notice(
                "no Web Worker could be started: the page computes the landscape, the \
                 diagnostics and RL itself, more slowly"
                    .to_owned(),
            );
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
            parts_from_workers: 0,
            runs_from_workers: 0,
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
                let json = field(&data, "json").as_string();
                let values = || match field(&data, "values") {
                    v if v.is_undefined() => Vec::new(),
                    v => js_sys::Float64Array::new(&v).to_vec(),
                };
                match kind.as_str() {
                    "answer" | "progress" => to_replies.borrow_mut().push(Reply {
                        worker: i,
                        generation: number("generation") as u64,
                        piece: number("piece") as usize,
                        values: Ok(values()),
                        json,
                        last: kind == "answer",
                    }),
                    "error" => to_replies.borrow_mut().push(Reply {
                        worker: i,
                        generation: number("generation") as u64,
                        piece: number("piece") as usize,
                        values: Err(field(&data, "error").as_string().unwrap_or_default()),
                        json: None,
                        last: true,
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
        // A plain `Event` when the script does not load (no `message`), an
        // `ErrorEvent` when it throws: read as a value either way.
        let on_error = Closure::<dyn FnMut(JsValue)>::new(move |event: JsValue| {
            let why = field(&event, "message")
                .as_string()
                .filter(|m| !m.is_empty())
                .unwrap_or_else(|| "worker.js did not load".to_owned());
            deaths.borrow_mut().push((i, why));
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

    /// Starts a generation for `model`: `kind` and `fields` say what its
    /// pieces are (the workers' side is `web::worker`).
    pub(super) fn begin(
        &mut self,
        model: &Arc<Model>,
        kind: &str,
        fields: Vec<(&str, JsValue)>,
    ) -> Result<u64> {
        let same = self
            .model
            .as_ref()
            .is_some_and(|(m, _)| Arc::ptr_eq(m, model));
        if !same {
            let inputs = ModelInputs {
                demos: model.demos().to_vec(),
                settings: *model.settings(),
            };
            let json = json_field("the model", &inputs)?;
            let id = self.next_id;
            self.next_id += 1;
            self.broadcast(&message(&[
                ("kind", "model".into()),
                ("model", (id as f64).into()),
                ("json", json),
            ]));
            self.model = Some((model.clone(), id));
        }
        let model_id = self.model.as_ref().map_or(0, |(_, id)| *id);
        let generation = self.next_id;
        self.next_id += 1;
        let mut pairs = vec![
            ("kind", JsValue::from_str(kind)),
            ("generation", (generation as f64).into()),
            ("model", (model_id as f64).into()),
        ];
        pairs.extend(fields);
        self.broadcast(&message(&pairs));
        self.live.insert(generation);
        Ok(generation)
    }

    /// Ends a generation: its pieces are no longer wanted.
    pub(super) fn end(&mut self, generation: u64) {
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

    /// Buries workers that failed: their pieces go back to their owners.
    fn bury(&mut self) {
        let deaths: Vec<(usize, String)> = self.deaths.borrow_mut().drain(..).collect();
        let mut failed = Vec::new();
        for (i, why) in deaths {
            let Some(slot) = self.slots.get_mut(i) else {
                continue;
            };
            if !slot.alive {
                continue;
            }
            slot.alive = false;
            slot.worker.terminate();
            self.lost.append(&mut slot.in_flight);
            failed.push(why);
        }
        let Some(why) = failed.first() else {
            return;
        };
        // One message for the workers that failed together.
        let n = failed.len();
        let text = if self.any_alive() {
            format!("{n} Web Worker(s) failed ({why}); the others take over their work")
        } else {
            format!(
                "the browser's Web Workers failed ({why}): the page computes the rest itself, \
                 more slowly"
            )
        };
        notice(text);
    }

    /// Gives `owner` the answers of its generation, hands it back the
    /// pieces of dead workers and sends its next pieces. Returns the
    /// answers it stored.
    pub(super) fn exchange(&mut self, owner: &mut dyn Handout) -> usize {
        self.bury();
        let generation = owner.generation();
        let mut stored = 0;
        let replies: Vec<Reply> = self.replies.borrow_mut().drain(..).collect();
        let mut keep = Vec::new();
        for reply in replies {
            if reply.last
                && let Some(slot) = self.slots.get_mut(reply.worker)
            {
                slot.in_flight
                    .retain(|&x| x != (reply.generation, reply.piece));
            }
            if reply.generation != generation {
                if self.live.contains(&reply.generation) {
                    keep.push(reply);
                }
                continue;
            }
            match &reply.values {
                Ok(_) if !reply.last => {
                    if let Some(json) = &reply.json {
                        owner.progress(reply.piece, json);
                        stored += 1;
                    }
                }
                Ok(values) => {
                    if owner.accept(reply.piece, values, reply.json.as_deref()) {
                        stored += 1;
                        match owner.kind() {
                            "tile" => self.tiles_from_workers += 1,
                            "part" => self.parts_from_workers += 1,
                            _ => self.runs_from_workers += 1,
                        }
                    } else {
                        log::warn!("dmpscope: a worker's answer was dropped");
                    }
                }
                Err(why) => {
                    // A worker that cannot compute a piece computes none.
                    self.deaths.borrow_mut().push((reply.worker, why.clone()));
                    owner.again(reply.piece);
                }
            }
        }
        self.replies.borrow_mut().extend(keep);
        self.bury();
        let (mine, others) = std::mem::take(&mut self.lost)
            .into_iter()
            .partition(|(g, _)| *g == generation);
        self.lost = others;
        for (_, piece) in mine {
            owner.again(piece);
        }
        for i in 0..self.slots.len() {
            while self.slots[i].alive && self.slots[i].in_flight.len() < owner.in_flight() {
                let Some((piece, payload)) = owner.next() else {
                    return stored;
                };
                let array = js_sys::Uint32Array::from(payload.as_slice());
                let msg = message(&[
                    ("kind", owner.kind().into()),
                    ("generation", (generation as f64).into()),
                    ("piece", (piece as f64).into()),
                    ("payload", array.clone().into()),
                ]);
                let transfer = js_sys::Array::of1(&array.buffer());
                match self.slots[i]
                    .worker
                    .post_message_with_transfer(&msg, &transfer)
                {
                    Ok(()) => self.slots[i].in_flight.push((generation, piece)),
                    Err(e) => {
                        owner.again(piece);
                        self.deaths.borrow_mut().push((i, format!("{e:?}")));
                        break;
                    }
                }
            }
        }
        stored
    }

    /// Whether any worker is alive.
    pub(super) fn any_alive(&self) -> bool {
        self.slots.iter().any(|s| s.alive)
    }
}

/// A live generation of the pool; dropping it ends the generation (the
/// workers forget it, its answers still on their way are dropped).
pub(super) struct Generation(pub(super) u64);

impl Generation {
    /// Starts a generation for `model` (see [`Pool::begin`]); `None` where
    /// the page has no workers.
    pub(super) fn begin(
        model: &Arc<Model>,
        kind: &str,
        fields: Vec<(&str, JsValue)>,
    ) -> Result<Option<Self>> {
        with_pool(|p| p.begin(model, kind, fields))
            .transpose()
            .map(|g| g.map(Self))
    }
}

impl Drop for Generation {
    fn drop(&mut self) {
        let generation = self.0;
        let _ = with_pool(|p| p.end(generation));
    }
}

/// JSON of `value` as a message field.
pub(super) fn json_field(what: &str, value: &impl serde::Serialize) -> Result<JsValue> {
    serde_json::to_string(value)
        .map(|j| JsValue::from_str(&j))
        .map_err(|e| dmpscope_core::Error::InvalidSetting(format!("{what}: {e}")))
}

/// What a generation hands out to the workers and takes back.
pub(super) trait Handout {
    /// The generation its answers carry.
    fn generation(&self) -> u64;
    /// The message kind of its pieces (`tile`, `part`, `run`).
    fn kind(&self) -> &'static str;
    /// Pieces a worker may hold at once.
    fn in_flight(&self) -> usize {
        IN_FLIGHT
    }
    /// The next piece to send: its id and payload.
    fn next(&mut self) -> Option<(usize, Vec<u32>)>;
    /// Stores the answer for a piece (numbers, or JSON); false when it is
    /// refused.
    fn accept(&mut self, piece: usize, values: &[f64], json: Option<&str>) -> bool;
    /// An update on a piece still under way (JSON).
    fn progress(&mut self, _piece: usize, _json: &str) {}
    /// A piece whose answer will never come: hand it out again.
    fn again(&mut self, piece: usize);
}
