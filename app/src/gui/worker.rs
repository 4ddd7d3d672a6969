//! Filling a landscape off the frame: a thread steps the core's
//! coarse-to-fine job tile by tile and publishes a snapshot after each, so
//! the heat maps show a preview at once and sharpen. Dropping the worker (a
//! new setting) cancels it.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};

use dmpscope_core::Model;
use dmpscope_core::landscape::{FillOrder, Grid, Landscape, LandscapeJob};

/// Points per published snapshot.
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
pub struct Worker {
    shared: Arc<Mutex<Option<Snapshot>>>,
    cancel: Arc<AtomicBool>,
}

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
    pub fn latest(&self) -> Option<Snapshot> {
        self.shared.lock().ok().and_then(|s| s.clone())
    }

    /// Stops the job.
    pub fn cancel(&self) {
        self.cancel.store(true, Ordering::Relaxed);
    }
}

impl Drop for Worker {
    fn drop(&mut self) {
        self.cancel();
    }
}
