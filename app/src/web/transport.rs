//! The page's side of the browser's workers, as the session's
//! [`Transport`]: dedicated Web Workers (`web/worker.js`), as many as
//! `navigator.hardwareConcurrency` less one left to the page where there
//! are more than two cores (at least 2, at most 8), each running
//! its own instance of this module (the page hands them its compiled
//! `WebAssembly.Module`). `web/index.html` starts them with the page, so
//! that they have loaded their script by the time the module has compiled;
//! the pool adopts them (and starts its own where there are none). Plain
//! message passing, no shared memory, so the page works on any static host. What is handed out when, and what
//! happens when a worker fails, is the session's
//! [`Dispatcher`](dmpscope_session::workers::Dispatcher); this file only
//! turns its messages into JavaScript objects and back.

use std::cell::RefCell;
use std::rc::Rc;

use dmpscope_session::worker_side::ModelInputs;
use dmpscope_session::workers::{FromWorker, Reply, Setup, ToWorker, Transport};
use eframe::web_sys;
use wasm_bindgen::JsCast as _;
use wasm_bindgen::prelude::*;

/// Workers at most, whatever the machine says.
const MAX_WORKERS: usize = 8;

/// One worker and its message handlers.
struct Slot {
    worker: web_sys::Worker,
    _on_message: Closure<dyn FnMut(web_sys::MessageEvent)>,
    _on_error: Closure<dyn FnMut(JsValue)>,
}

/// The page's Web Workers and what they sent.
pub struct WebTransport {
    slots: Vec<Slot>,
    inbox: Rc<RefCell<Vec<FromWorker>>>,
    /// The last model sent, as bytes ([`ModelInputs::to_bytes`]), by id
    /// (made once for every worker).
    model_bytes: Option<(u64, js_sys::Uint8Array)>,
}

/// A message: a plain object of these fields.
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

/// JSON of `value` as a message field.
fn json(value: &impl serde::Serialize) -> Result<JsValue, String> {
    serde_json::to_string(value)
        .map(|j| JsValue::from_str(&j))
        .map_err(|e| e.to_string())
}

impl WebTransport {
    /// Starts the workers; the notices say which could not start. `None`
    /// where none could.
    pub fn start() -> (Option<Self>, Vec<String>) {
        let mut notices = Vec::new();
        let Some(window) = web_sys::window() else {
            return (None, notices);
        };
        let cores = window.navigator().hardware_concurrency();
        // One core is left to the page where there are more than two (its
        // frames); on two, both workers (the page's frames are short).
        let cores = if cores.is_finite() { cores as usize } else { 2 };
        let n = if cores > 2 { cores - 1 } else { cores }.clamp(2, MAX_WORKERS);
        let inbox = Rc::new(RefCell::new(Vec::new()));
        let module = wasm_bindgen::module();
        let mut slots = Vec::new();
        let mut started = adopt_early_workers(&window, &mut notices);
        while started.len() > n {
            if let Some(extra) = started.pop() {
                extra.terminate();
            }
        }
        for i in 0..n {
            // Worker numbers are positions among those that started.
            let worker = match started.pop() {
                Some(w) => Ok(w),
                None => new_worker(),
            };
            match worker.and_then(|w| Self::connect(w, slots.len(), &module, &inbox)) {
                Ok(slot) => slots.push(slot),
                Err(e) => notices.push(format!(
                    "the browser could not start Web Worker {i} ({e:?})"
                )),
            }
        }
        if slots.is_empty() {
            notices.push(
                "no Web Worker could be started: the page computes the landscape, the \
                 diagnostics and RL itself, more slowly"
                    .to_owned(),
            );
            return (None, notices);
        }
        (
            Some(Self {
                slots,
                inbox,
                model_bytes: None,
            }),
            notices,
        )
    }

    /// Listens to `worker` as worker `i` and hands it the module.
    fn connect(
        worker: web_sys::Worker,
        i: usize,
        module: &JsValue,
        inbox: &Rc<RefCell<Vec<FromWorker>>>,
    ) -> Result<Slot, JsValue> {
        let to_inbox = inbox.clone();
        let on_message = Closure::<dyn FnMut(web_sys::MessageEvent)>::new(
            move |event: web_sys::MessageEvent| {
                to_inbox.borrow_mut().push(read_reply(i, &event.data()));
            },
        );
        let to_inbox = inbox.clone();
        // A plain `Event` when the script does not load (no `message`), an
        // `ErrorEvent` when it throws: read as a value either way.
        let on_error = Closure::<dyn FnMut(JsValue)>::new(move |event: JsValue| {
            let why = field(&event, "message")
                .as_string()
                .filter(|m| !m.is_empty())
                .unwrap_or_else(|| "worker.js did not load".to_owned());
            to_inbox
                .borrow_mut()
                .push(FromWorker::Died { worker: i, why });
        });
        worker.set_onmessage(Some(on_message.as_ref().unchecked_ref()));
        worker.set_onerror(Some(on_error.as_ref().unchecked_ref()));
        worker.post_message(&message(&[
            ("kind", "init".into()),
            ("module", module.clone()),
        ]))?;
        Ok(Slot {
            worker,
            _on_message: on_message,
            _on_error: on_error,
        })
    }
}

/// A new worker running `web/worker.js`.
fn new_worker() -> Result<web_sys::Worker, JsValue> {
    let options = web_sys::WorkerOptions::new();
    options.set_type(web_sys::WorkerType::Module);
    web_sys::Worker::new_with_options("./worker.js", &options)
}

/// The workers `index.html` started with the page
/// (`window.dmpscope_workers`), taken once; one whose script failed to
/// load is terminated and said in `notices`.
fn adopt_early_workers(
    window: &web_sys::Window,
    notices: &mut Vec<String>,
) -> Vec<web_sys::Worker> {
    let key = JsValue::from_str("dmpscope_workers");
    let early = js_sys::Reflect::get(window, &key).unwrap_or(JsValue::UNDEFINED);
    let _ = js_sys::Reflect::set(window, &key, &JsValue::UNDEFINED);
    let Ok(early) = early.dyn_into::<js_sys::Array>() else {
        return Vec::new();
    };
    let mut workers = Vec::new();
    for (i, value) in early.iter().enumerate() {
        let Ok(worker) = value.dyn_into::<web_sys::Worker>() else {
            continue;
        };
        match field(worker.as_ref(), "dmpscope_failed").as_string() {
            Some(why) => {
                worker.terminate();
                notices.push(format!(
                    "the browser could not start the page's Web Worker {i} ({why}); \
                     another is started in its place"
                ));
            }
            None => workers.push(worker),
        }
    }
    // `start` takes them from the end.
    workers.reverse();
    workers
}

/// A worker's message as the pool's [`FromWorker`].
fn read_reply(worker: usize, data: &JsValue) -> FromWorker {
    let kind = field(data, "kind").as_string().unwrap_or_default();
    let number = |key| field(data, key).as_f64().unwrap_or(-1.0);
    let values = match field(data, "values") {
        v if v.is_undefined() => Vec::new(),
        v => js_sys::Float64Array::new(&v).to_vec(),
    };
    let (values, last) = match kind.as_str() {
        "answer" => (Ok(values), true),
        "progress" => (Ok(values), false),
        "error" => (
            Err(field(data, "error").as_string().unwrap_or_default()),
            true,
        ),
        _ => {
            let why = field(data, "error").as_string().unwrap_or(kind);
            return FromWorker::Died { worker, why };
        }
    };
    FromWorker::Reply(Reply {
        worker,
        generation: number("generation") as u64,
        piece: number("piece") as usize,
        values,
        json: field(data, "json").as_string(),
        last,
    })
}

/// The fields of a generation's first message.
fn setup_fields(setup: &Setup) -> Result<Vec<(&'static str, JsValue)>, String> {
    Ok(match setup {
        Setup::Grid(grid) => vec![("grid", json(grid)?)],
        Setup::Diag { grid, k } => vec![("grid", json(grid)?), ("k", JsValue::from_f64(*k))],
        Setup::Rl(request) => vec![("request", json(request)?)],
    })
}

impl Transport for WebTransport {
    fn what(&self) -> &'static str {
        "Web Worker"
    }

    fn all_failed(&self, why: &str) -> String {
        format!(
            "the browser's Web Workers failed ({why}): the page computes the rest itself, more \
             slowly"
        )
    }

    fn workers(&self) -> usize {
        self.slots.len()
    }

    fn send(&mut self, worker: usize, msg: ToWorker<'_>) -> Result<(), String> {
        if let ToWorker::Model { id, model } = &msg
            && self.model_bytes.as_ref().is_none_or(|(m, _)| m != id)
        {
            let bytes = ModelInputs::of(model).to_bytes()?;
            self.model_bytes = Some((*id, js_sys::Uint8Array::from(bytes.as_slice())));
        }
        let slot = self.slots.get(worker).ok_or("no such worker")?;
        let posted = match msg {
            ToWorker::Model { id, .. } => {
                // Copied to each worker (structured clone), not transferred:
                // every worker gets the same bytes.
                let inputs = self
                    .model_bytes
                    .as_ref()
                    .map_or(JsValue::NULL, |(_, b)| b.clone().into());
                slot.worker.post_message(&message(&[
                    ("kind", "model".into()),
                    ("model", (id as f64).into()),
                    ("bytes", inputs),
                ]))
            }
            ToWorker::Begin {
                generation,
                model,
                setup,
            } => {
                let mut pairs = vec![
                    ("kind", JsValue::from_str(setup.kind())),
                    ("generation", (generation as f64).into()),
                    ("model", (model as f64).into()),
                ];
                pairs.extend(setup_fields(setup)?);
                slot.worker.post_message(&message(&pairs))
            }
            ToWorker::Piece {
                generation,
                kind,
                piece,
                payload,
            } => {
                let array = js_sys::Uint32Array::from(payload.as_slice());
                let msg = message(&[
                    ("kind", kind.into()),
                    ("generation", (generation as f64).into()),
                    ("piece", (piece as f64).into()),
                    ("payload", array.clone().into()),
                ]);
                let transfer = js_sys::Array::of1(&array.buffer());
                slot.worker.post_message_with_transfer(&msg, &transfer)
            }
            ToWorker::Forget { generation } => slot.worker.post_message(&message(&[
                ("kind", "forget".into()),
                ("generation", (generation as f64).into()),
            ])),
        };
        posted.map_err(|e| format!("{e:?}"))
    }

    fn receive(&mut self) -> Vec<FromWorker> {
        std::mem::take(&mut *self.inbox.borrow_mut())
    }

    fn terminate(&mut self, worker: usize) {
        if let Some(slot) = self.slots.get(worker) {
            slot.worker.terminate();
        }
    }
}
