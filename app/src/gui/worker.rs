//! Filling a landscape off the frame: natively a thread steps the core's
//! coarse-to-fine job tile by tile and publishes a snapshot after each, so
//! the heat maps show a preview at once and sharpen; in the browser (no
//! threads) each frame steps the job for a few milliseconds. Dropping the
//! worker (a new setting) cancels it.

use std::sync::Arc;
#[cfg(not(target_arch = "wasm32"))]
use std::sync::Mutex;
#[cfg(not(target_arch = "wasm32"))]
use std::sync::atomic::{AtomicBool, Ordering};

use dmpscope_core::Model;
use dmpscope_core::landscape::{FillOrder, Grid, Landscape, LandscapeJob};

/// Points per published snapshot.
#[cfg(not(target_arch = "wasm32"))]
const TILE: usize = 1024;

/// The latest snapshot and how far the job is.
#[derive(Clone, Debug)]
pub struct Snapshot {
    /// The landscape so far.
    pub landscape: Landscape,
    /// Points done.
    pub done: usize,
    /// Points in all.
    pub total: usize,
    /// Increases with every publication.
    pub version: u64,
}

/// A landscape being computed on a background thread.
#[cfg(not(target_arch = "wasm32"))]
pub struct Worker {
    shared: Arc<Mutex<Option<Snapshot>>>,
    cancel: Arc<AtomicBool>,
}

#[cfg(not(target_arch = "wasm32"))]
impl Worker {
    /// Starts filling `grid`; `wake` is called after each snapshot.
    pub fn start(
        model: Arc<Model>,
        grid: Grid,
        wake: impl Fn() + Send + 'static,
    ) -> dmpscope_core::Result<Self> {
        let mut job = LandscapeJob::new(model, grid, FillOrder::CoarseToFine)?;
        let shared = Arc::new(Mutex::new(None));
        let cancel = Arc::new(AtomicBool::new(false));
        let (out, stop) = (shared.clone(), cancel.clone());
        std::thread::spawn(move || {
            let mut version = 0;
            loop {
                if stop.load(Ordering::Relaxed) {
                    return;
                }
                let done = job.step_par(TILE);
                version += 1;
                let (points, total) = job.progress();
                let snapshot = Snapshot {
                    landscape: job.landscape().clone(),
                    done: points,
                    total,
                    version,
                };
                if let Ok(mut slot) = out.lock() {
                    *slot = Some(snapshot);
                }
                wake();
                if done {
                    return;
                }
            }
        });
        Ok(Self { shared, cancel })
    }

    /// The latest snapshot, if any was published.
    pub fn latest(&mut self) -> Option<Snapshot> {
        self.shared.lock().ok().and_then(|s| s.clone())
    }

    /// Stops the job.
    pub fn cancel(&self) {
        self.cancel.store(true, Ordering::Relaxed);
    }
}

#[cfg(not(target_arch = "wasm32"))]
impl Drop for Worker {
    fn drop(&mut self) {
        self.cancel();
    }
}

/// Work per slice in the browser, milliseconds: short enough that input
/// and frames are served between slices.
#[cfg(target_arch = "wasm32")]
const SLICE_MS: f64 = 12.0;

/// Points per step inside a slice.
#[cfg(target_arch = "wasm32")]
const STEP: usize = 32;

/// Compute time before the browser's first preview, milliseconds; each next
/// preview waits twice as long (a frame under software WebGL costs about
/// 200 ms, so frames, not slices, would otherwise take the time).
#[cfg(target_arch = "wasm32")]
const FIRST_PUBLISH_MS: f64 = 60.0;

/// The state a browser job shares with the app.
#[cfg(target_arch = "wasm32")]
#[derive(Default)]
struct Shared {
    snapshot: Option<Snapshot>,
    cancelled: bool,
    /// The longest slice so far, ms.
    longest_slice_ms: f64,
    /// All slices so far, ms.
    compute_ms: f64,
}

/// A landscape computed on the browser's only thread in short slices
/// between which the event loop runs (input, frames), publishing a preview
/// a few times a second.
#[cfg(target_arch = "wasm32")]
pub struct Worker {
    shared: std::rc::Rc<std::cell::RefCell<Shared>>,
    seen: u64,
}

/// Lets the browser run its event loop (a zero-delay timeout).
#[cfg(target_arch = "wasm32")]
pub(super) async fn yield_to_browser() {
    let promise = js_sys::Promise::new(&mut |resolve, _| {
        if let Some(w) = web_sys::window() {
            let _ = w.set_timeout_with_callback_and_timeout_and_arguments_0(&resolve, 0);
        }
    });
    let _ = wasm_bindgen_futures::JsFuture::from(promise).await;
}

#[cfg(target_arch = "wasm32")]
impl Worker {
    /// Starts filling `grid` in slices; `wake` is called with each preview.
    pub fn start(
        model: Arc<Model>,
        grid: Grid,
        wake: impl Fn() + Send + 'static,
    ) -> dmpscope_core::Result<Self> {
        let mut job = LandscapeJob::new(model, grid, FillOrder::CoarseToFine)?;
        let shared = std::rc::Rc::new(std::cell::RefCell::new(Shared::default()));
        let state = shared.clone();
        wasm_bindgen_futures::spawn_local(async move {
            let mut version = 0;
            let mut since_publish = 0.0;
            let mut gap = FIRST_PUBLISH_MS;
            loop {
                if state.borrow().cancelled {
                    return;
                }
                let start = web_time::Instant::now();
                let mut done = false;
                while !done && start.elapsed().as_secs_f64() * 1e3 < SLICE_MS {
                    done = job.step(STEP);
                }
                let slice_ms = start.elapsed().as_secs_f64() * 1e3;
                since_publish += slice_ms;
                let publish = done || since_publish >= gap;
                {
                    let mut s = state.borrow_mut();
                    s.longest_slice_ms = s.longest_slice_ms.max(slice_ms);
                    s.compute_ms += slice_ms;
                    if publish {
                        version += 1;
                        let (points, total) = job.progress();
                        s.snapshot = Some(Snapshot {
                            landscape: job.landscape().clone(),
                            done: points,
                            total,
                            version,
                        });
                        since_publish = 0.0;
                        gap *= 2.0;
                    }
                }
                if publish {
                    wake();
                }
                if done {
                    return;
                }
                yield_to_browser().await;
            }
        });
        Ok(Self { shared, seen: 0 })
    }

    /// The latest preview, when a new one was published.
    pub fn latest(&mut self) -> Option<Snapshot> {
        let s = self.shared.borrow();
        let snapshot = s
            .snapshot
            .as_ref()
            .filter(|s| s.version != self.seen)?
            .clone();
        drop(s);
        self.seen = snapshot.version;
        Some(snapshot)
    }

    /// The longest slice of work so far and all slices, ms.
    pub fn slice_ms(&self) -> (f64, f64) {
        let s = self.shared.borrow();
        (s.longest_slice_ms, s.compute_ms)
    }

    /// Stops the job.
    pub fn cancel(&mut self) {
        self.shared.borrow_mut().cancelled = true;
    }
}

#[cfg(target_arch = "wasm32")]
impl Drop for Worker {
    fn drop(&mut self) {
        self.cancel();
    }
}
