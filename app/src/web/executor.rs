//! The browser's [`Executor`]: jobs in ~10 ms slices on the page's event
//! loop (the page has no threads), the clock of `performance.now()`, and
//! the pool of Web Workers ([`WebTransport`] under the session's
//! [`Dispatcher`]), started with the app ([`start_pool`]) and kept for the
//! page's life. Jobs start stepping after the page's first paint.

use std::cell::RefCell;
use std::rc::Rc;
use std::sync::Arc;
use std::time::Duration;

use dmpscope_core::{Model, Result};
use dmpscope_session::executor::{Executor, PageTime, Spawned, Task, TaskHandle, TaskStep};
use dmpscope_session::workers::{Dispatcher, Exchanged, Handout, Setup, WorkerStats, Workers};
use eframe::web_sys;
use web_time::Instant;

use super::transport::WebTransport;

/// Time a slice of work may take on the page's thread.
const SLICE: Duration = Duration::from_millis(10);

/// Jobs in slices on the page's event loop, pieces in the Web Workers.
pub struct WebExecutor {
    origin: Instant,
    wake: Arc<dyn Fn() + Send + Sync>,
}

impl WebExecutor {
    /// The executor; `wake` asks for a repaint.
    pub fn new(wake: impl Fn() + Send + Sync + 'static) -> Self {
        Self {
            origin: Instant::now(),
            wake: Arc::new(wake),
        }
    }
}

/// A job's slices as its handle sees them.
struct SliceHandle {
    time: Rc<RefCell<PageTime>>,
}

impl TaskHandle for SliceHandle {
    fn ended(&self) -> bool {
        false
    }
    fn page_time(&self) -> PageTime {
        *self.time.borrow()
    }
}

/// Lets the browser run its event loop (a zero-delay timeout).
async fn yield_to_browser() {
    let promise = js_sys::Promise::new(&mut |resolve, _| {
        if let Some(w) = web_sys::window() {
            let _ = w.set_timeout_with_callback_and_timeout_and_arguments_0(&resolve, 0);
        }
    });
    let _ = wasm_bindgen_futures::JsFuture::from(promise).await;
}

thread_local! {
    /// Whether the page has painted its first frame ([`after_first_paint`]).
    static PAINTED: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Waits, once per page, until the page has painted its first frame: two
/// animation frames from now (or a 500 ms timer each in a hidden tab, which
/// has no animation frames and throttles timers to about a second). The
/// workers start with the page; every job (the sample's loading, and so
/// the landscape after it) waits for the window to show first, as under a
/// software rasteriser the first frame (300-700 ms) would otherwise share
/// the cores with the workers and come a second later.
async fn after_first_paint() {
    if PAINTED.with(std::cell::Cell::get) {
        return;
    }
    for _ in 0..2 {
        let promise = js_sys::Promise::new(&mut |resolve, _| {
            if let Some(w) = web_sys::window() {
                let _ = w.request_animation_frame(&resolve);
                let _ = w.set_timeout_with_callback_and_timeout_and_arguments_0(&resolve, 500);
            }
        });
        let _ = wasm_bindgen_futures::JsFuture::from(promise).await;
    }
    PAINTED.with(|p| p.set(true));
}

/// Steps `task` in slices until it is done, yielding between slices.
async fn run_slices(
    mut task: Box<dyn Task>,
    time: Rc<RefCell<PageTime>>,
    wake: Arc<dyn Fn() + Send + Sync>,
) {
    after_first_paint().await;
    loop {
        let start = Instant::now();
        let mut news = false;
        let mut done = false;
        while !done && start.elapsed() < SLICE {
            match task.step() {
                TaskStep::Working => {}
                TaskStep::Waiting => break,
                TaskStep::News => news = true,
                TaskStep::Done => {
                    news = true;
                    done = true;
                }
            }
        }
        time.borrow_mut().add(start.elapsed());
        if news {
            wake();
        }
        if done {
            return;
        }
        yield_to_browser().await;
    }
}

impl Executor for WebExecutor {
    fn spawn(&self, _name: &str, task: Box<dyn Task>) -> Spawned {
        let time = Rc::new(RefCell::new(PageTime::default()));
        wasm_bindgen_futures::spawn_local(run_slices(task, time.clone(), self.wake.clone()));
        Spawned {
            handle: Box::new(SliceHandle { time }),
            notice: None,
        }
    }
    fn threaded(&self) -> bool {
        false
    }
    fn parallel(&self) -> bool {
        false
    }
    fn now(&self) -> Duration {
        self.origin.elapsed()
    }
    fn workers(&self) -> Option<Arc<dyn Workers>> {
        Some(Arc::new(WebWorkers))
    }
}

thread_local! {
    /// The page's pool: `None` before it is started ([`start_pool`], or
    /// the first generation), `Some(None)` where no worker could be started.
    static POOL: RefCell<Option<Option<Dispatcher<WebTransport>>>> = const { RefCell::new(None) };
    /// What starting the pool had to say, where it could not start.
    static NOTICES: RefCell<Vec<String>> = const { RefCell::new(Vec::new()) };
}

/// Starts the page's pool now rather than at the first generation, so that
/// the workers load their script and instantiate the module while the page
/// draws its first frames (about a quarter of a second under a software
/// rasteriser that the first landscape would otherwise wait).
pub fn start_pool() {
    let _ = with_pool(|_| ());
}

/// The page's Web Workers (one pool per page, on the page's thread).
struct WebWorkers;

/// Runs `f` on the pool, starting it at the first call; `None` without one.
fn with_pool<R>(f: impl FnOnce(&mut Dispatcher<WebTransport>) -> R) -> Option<R> {
    POOL.with(|p| {
        let mut p = p.borrow_mut();
        let pool = p.get_or_insert_with(|| {
            let (transport, notices) = WebTransport::start();
            match transport {
                Some(t) => Some(Dispatcher::new(t, notices)),
                None => {
                    NOTICES.with(|all| all.borrow_mut().extend(notices));
                    None
                }
            }
        });
        pool.as_mut().map(f)
    })
}

impl Workers for WebWorkers {
    fn begin(&self, model: &Arc<Model>, setup: &Setup) -> Result<Option<u64>> {
        Ok(with_pool(|p| p.begin(model, setup)).flatten())
    }
    fn end(&self, generation: u64) {
        let _ = with_pool(|p| p.end(generation));
    }
    fn exchange(&self, owner: &mut dyn Handout) -> Exchanged {
        with_pool(|p| p.exchange(owner)).unwrap_or_default()
    }
    fn stats(&self) -> WorkerStats {
        POOL.with(|p| match &*p.borrow() {
            Some(Some(pool)) => pool.stats(),
            _ => WorkerStats::default(),
        })
    }
    fn take_notices(&self) -> Vec<String> {
        let mut notices = NOTICES.with(|n| std::mem::take(&mut *n.borrow_mut()));
        POOL.with(|p| {
            if let Some(Some(pool)) = &mut *p.borrow_mut() {
                notices.extend(pool.take_notices());
            }
        });
        for n in &notices {
            log::warn!("dmpscope: {n}");
        }
        notices
    }
}
