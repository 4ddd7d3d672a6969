//! The diagnostics of the extraction as a [`Work`] (method.md section 9):
//! the core's [`DiagnosticsJob`] made in its first step (depth, balance,
//! shares, the S minimum), then its resampled extractions (leave-one-out,
//! bootstrap) a batch per step natively and, in the executor's
//! workers where it has them ([`PoolDiag`]; a few landscape points per
//! step where it has none), each step publishing a [`DiagSnapshot`] for the
//! views to show as results come.

use std::sync::Arc;

use dmpscope_core::extract::diagnostics::resample::SubOptimum;
use dmpscope_core::extract::diagnostics::{DiagAbout, DiagSettings, Diagnostics, DiagnosticsJob};
use dmpscope_core::landscape::grid::Landscape;
use std::time::Duration;

use dmpscope_core::{Extraction, Model};

use crate::jobs::{Clock, Runner, Step, Work};
use crate::pooled::PoolDiag;
use crate::workers::Workers;

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
    /// The executor's workers, and the generation computing the resampled
    /// extractions there.
    workers: Option<Arc<dyn Workers>>,
    pool: Option<PoolDiag>,
    clock: Clock,
    started: Duration,
    threaded: bool,
    parallel: bool,
    /// Compute time so far, and when the next preview is due.
    computed: Duration,
    next_preview: Duration,
}

impl DiagnosticsWork {
    /// The diagnostics of `extraction` on `landscape` (complete) of `model`
    /// on `runner`'s executor (its workers compute the resampled
    /// extractions where it has them).
    pub fn new(
        model: Arc<Model>,
        landscape: Landscape,
        extraction: Extraction,
        settings: DiagSettings,
        runner: &Runner,
    ) -> Self {
        let clock = runner.clock();
        Self {
            pending: Some(Pending {
                model,
                landscape,
                extraction,
                settings,
            }),
            job: None,
            workers: runner.workers(),
            pool: None,
            started: clock.now(),
            clock,
            threaded: runner.threaded(),
            parallel: runner.parallel(),
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
            let model = p.model.clone();
            let job = DiagnosticsJob::new(p.model, &p.landscape, &p.extraction, p.settings);
            if let Some(workers) = &self.workers {
                self.pool = PoolDiag::start(workers, &model, &job).ok().flatten();
                self.started = self.clock.now();
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
        if let Some(pool) = &mut self.pool {
            let stored = pool.exchange(job, SLICE_POINTS);
            if job.is_done() {
                return Step::Done(Self::snapshot(job));
            }
            if stored == 0 {
                return Step::Waiting;
            }
            // Previews on the wall clock (the work is elsewhere).
            let elapsed = self.clock.now() - self.started;
            if elapsed >= self.next_preview {
                self.next_preview = elapsed * 3 / 2 + PREVIEW_EVERY;
                return Step::Publish(Self::snapshot(job));
            }
            return Step::Working;
        }
        let start = self.clock.now();
        let done = if self.parallel {
            // A couple of extractions per core per step: every core busy,
            // a preview every ~50 ms.
            let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
            job.step_par(2 * cores)
        } else {
            job.step_points(SLICE_POINTS)
        };
        self.computed += self.clock.now() - start;
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
