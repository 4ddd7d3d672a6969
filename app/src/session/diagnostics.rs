//! The diagnostics of the extraction as a [`Work`] (method.md section 9):
//! the core's [`DiagnosticsJob`] made in its first step (depth, balance,
//! shares, the S minimum), then its resampled extractions (leave-one-out,
//! bootstrap) a batch per step natively and, in the browser, in the page's
//! workers (`web::fills::PoolDiag`; a few landscape points per step on the
//! page where it has none), each step publishing a [`DiagSnapshot`] for the
//! views to show as results come.

use std::sync::Arc;

use dmpscope_core::diagnostics::{
    DiagAbout, DiagSettings, Diagnostics, DiagnosticsJob, SubOptimum,
};
use dmpscope_core::landscape::Landscape;
use dmpscope_core::{Extraction, Model};
use web_time::{Duration, Instant};

use super::jobs::{Step, Work};

/// Landscape points per step in the browser (a slice holds several).
const SLICE_POINTS: usize = 48;
/// Compute time before the first preview on the page's thread; each next
/// one waits that long plus half the time computed so far (a frame under
/// software WebGL costs 200-400 ms, so frames, not computation, would
/// otherwise take the time).
const PREVIEW_EVERY: Duration = Duration::from_millis(300);

/// The diagnostics so far.
#[derive(Clone, Debug)]
pub struct DiagSnapshot {
    /// The diagnostics (leave-one-out optima and the bootstrap fill in).
    pub diagnostics: Diagnostics,
    /// How they are made (the resampled extractions' grid, notes).
    pub about: DiagAbout,
    /// The bootstrap optima found so far (the cloud on the J map).
    pub cloud: Vec<SubOptimum>,
    /// Resampled extractions done.
    pub done: usize,
    /// Resampled extractions in all.
    pub total: usize,
}

impl DiagSnapshot {
    /// Whether every part is computed.
    pub fn complete(&self) -> bool {
        self.done == self.total
    }
}

/// What the first step builds the job from.
struct Pending {
    model: Arc<Model>,
    landscape: Landscape,
    extraction: Extraction,
    settings: DiagSettings,
}

/// Computes the diagnostics in steps.
pub struct DiagnosticsWork {
    pending: Option<Pending>,
    job: Option<DiagnosticsJob>,
    /// The browser's workers computing the resampled extractions.
    #[cfg(target_arch = "wasm32")]
    pool: Option<crate::web::fills::PoolDiag>,
    #[cfg(target_arch = "wasm32")]
    started: Instant,
    threaded: bool,
    /// Compute time so far, and when the next preview is due.
    computed: Duration,
    next_preview: Duration,
}

impl DiagnosticsWork {
    /// The diagnostics of `extraction` on `landscape` (complete) of `model`;
    /// `threaded` when the work has a thread of its own.
    pub fn new(
        model: Arc<Model>,
        landscape: Landscape,
        extraction: Extraction,
        settings: DiagSettings,
        threaded: bool,
    ) -> Self {
        Self {
            pending: Some(Pending {
                model,
                landscape,
                extraction,
                settings,
            }),
            job: None,
            #[cfg(target_arch = "wasm32")]
            pool: None,
            #[cfg(target_arch = "wasm32")]
            started: Instant::now(),
            threaded,
            computed: Duration::ZERO,
            next_preview: PREVIEW_EVERY,
        }
    }

    fn snapshot(job: &DiagnosticsJob) -> DiagSnapshot {
        let (done, total) = job.progress();
        DiagSnapshot {
            diagnostics: job.diagnostics().clone(),
            about: job.about().clone(),
            cloud: job.bootstrap_optima(),
            done,
            total,
        }
    }
}

impl Work for DiagnosticsWork {
    type Output = DiagSnapshot;

    fn step(&mut self) -> Step<DiagSnapshot> {
        if let Some(p) = self.pending.take() {
            #[cfg(target_arch = "wasm32")]
            let model = p.model.clone();
            let job = DiagnosticsJob::new(p.model, &p.landscape, &p.extraction, p.settings);
            #[cfg(target_arch = "wasm32")]
            {
                self.pool = crate::web::fills::PoolDiag::start(&model, &job)
                    .ok()
                    .flatten();
                self.started = Instant::now();
            }
            let snapshot = Self::snapshot(&job);
            let done = job.is_done();
            self.job = Some(job);
            return if done {
                Step::Done(snapshot)
            } else {
                Step::Publish(snapshot)
            };
        }
        let Some(job) = &mut self.job else {
            return Step::Working;
        };
        #[cfg(target_arch = "wasm32")]
        if let Some(pool) = &mut self.pool {
            let stored = pool.exchange(job, SLICE_POINTS);
            if job.is_done() {
                return Step::Done(Self::snapshot(job));
            }
            if stored == 0 {
                return Step::Waiting;
            }
            // Previews on the wall clock (the work is elsewhere).
            let elapsed = self.started.elapsed();
            if elapsed >= self.next_preview {
                self.next_preview = elapsed * 3 / 2 + PREVIEW_EVERY;
                return Step::Publish(Self::snapshot(job));
            }
            return Step::Working;
        }
        let start = Instant::now();
        let done = if cfg!(target_arch = "wasm32") {
            job.step_points(SLICE_POINTS)
        } else {
            // A couple of extractions per core per step: every core busy,
            // a preview every ~50 ms.
            let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
            job.step_par(2 * cores)
        };
        self.computed += start.elapsed();
        if done {
            Step::Done(Self::snapshot(job))
        } else if self.threaded || self.computed >= self.next_preview {
            self.next_preview = self.computed * 3 / 2 + PREVIEW_EVERY;
            Step::Publish(Self::snapshot(job))
        } else {
            Step::Working
        }
    }
}
