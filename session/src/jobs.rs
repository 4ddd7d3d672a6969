//! The one background mechanism for everything that takes longer than a
//! frame: loading, the landscape, the extraction, the diagnostics, RL.
//!
//! A [`Work`] advances in steps and says after each what to publish. A
//! [`Runner`] starts it on the session's [`Executor`] (a thread natively,
//! slices on the browser's event loop, or inline at the first poll in
//! tests). Whatever runs it, the owner sees the same [`Job`]: `poll` hands
//! over the latest publication, `cancel` (or dropping the job) stops the
//! work at its next step and nothing it does afterwards reaches the owner; a
//! work of one step (an extraction) runs to its end unseen, so its owner
//! starts at most one at a time.

use std::sync::{Arc, Mutex};
use std::time::Duration;

use crate::executor::{
    Executor, InlineExecutor, PageTime, Task, TaskHandle, TaskStep, ThreadExecutor,
};
use crate::workers::{WorkerStats, Workers};

/// One step of a [`Work`]'s progress.
pub enum Step<T> {
    /// Keep going; nothing new to show.
    Working,
    /// Nothing to do until an answer from elsewhere arrives (workers): the
    /// slice ends early and the caller's thread is free.
    Waiting,
    /// Keep going; here is something to show meanwhile (a preview).
    Publish(T),
    /// Finished with this result.
    Done(T),
}

/// Work that advances in steps, each short (milliseconds).
pub trait Work: Send + 'static {
    /// What the work publishes and finishes with.
    type Output: Send + 'static;
    /// Advances the work by one step.
    fn step(&mut self) -> Step<Self::Output>;
}

/// A step of work that is one call: the whole work in a single step.
pub struct Once<F>(Option<F>);

impl<F> Once<F> {
    /// Work that calls `f` once.
    pub fn new(f: F) -> Self {
        Self(Some(f))
    }
}

impl<T: Send + 'static, F: FnOnce() -> T + Send + 'static> Work for Once<F> {
    type Output = T;
    fn step(&mut self) -> Step<T> {
        match self.0.take() {
            Some(f) => Step::Done(f()),
            None => Step::Working,
        }
    }
}

/// What [`Job::poll`] found.
#[derive(Debug, PartialEq)]
pub enum Update<T> {
    /// A publication while the work goes on.
    Progress(T),
    /// The result; the job is over.
    Done(T),
    /// The work stopped without a result (its thread died); the job is over.
    Failed(String),
}

/// A monotonic clock the executor provides (works measure their compute
/// time and training seconds with it, on any platform).
#[derive(Clone)]
pub struct Clock(Arc<dyn Executor>);

impl Clock {
    /// Time since the executor's origin.
    pub fn now(&self) -> Duration {
        self.0.now()
    }
}

/// Starts jobs on an [`Executor`].
#[derive(Clone)]
pub struct Runner {
    executor: Arc<dyn Executor>,
}

impl std::fmt::Debug for Runner {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Runner")
            .field("threaded", &self.executor.threaded())
            .finish()
    }
}

impl Runner {
    /// Jobs on `executor`.
    pub fn new(executor: Arc<dyn Executor>) -> Self {
        Self { executor }
    }

    /// Jobs on native threads; `wake` asks for a repaint.
    pub fn background(wake: impl Fn() + Send + Sync + 'static) -> Self {
        Self::new(Arc::new(ThreadExecutor::new(wake)))
    }

    /// Jobs that run to the end when first polled.
    pub fn inline() -> Self {
        Self::new(Arc::new(InlineExecutor::new()))
    }

    /// Whether jobs get a thread of their own (so a work may publish after
    /// every step).
    pub fn threaded(&self) -> bool {
        self.executor.threaded()
    }

    /// Whether one step may use every core.
    pub fn parallel(&self) -> bool {
        self.executor.parallel()
    }

    /// The executor's clock.
    pub fn clock(&self) -> Clock {
        Clock(self.executor.clone())
    }

    /// The executor's pool of workers, if it has one.
    pub fn workers(&self) -> Option<Arc<dyn Workers>> {
        self.executor.workers()
    }

    /// What the user should be told about the executor since the last call.
    pub fn take_notices(&self) -> Vec<String> {
        self.executor.take_notices()
    }

    /// The executor's pool's figures.
    pub fn worker_stats(&self) -> WorkerStats {
        self.executor.worker_stats()
    }

    /// Starts `work`; `name` says what it is in messages.
    pub fn start<W: Work>(&self, name: &str, work: W) -> Job<W::Output> {
        let shared = Arc::new(Mutex::new(Slot {
            latest: None,
            done: false,
            cancelled: false,
        }));
        let task = Wrapped {
            work,
            shared: shared.clone(),
        };
        let spawned = self.executor.spawn(name, Box::new(task));
        Job {
            shared,
            handle: Some(spawned.handle),
            notice: spawned.notice,
            time: PageTime::default(),
        }
    }
}

/// What a job shares with its task.
struct Slot<T> {
    latest: Option<T>,
    done: bool,
    cancelled: bool,
}

/// A [`Work`] as the executor's [`Task`]: its publications go to the slot.
struct Wrapped<W: Work> {
    work: W,
    shared: Arc<Mutex<Slot<W::Output>>>,
}

impl<W: Work> Task for Wrapped<W> {
    fn step(&mut self) -> TaskStep {
        if self.shared.lock().map_or(true, |s| s.cancelled) {
            return TaskStep::Done;
        }
        let (value, done) = match self.work.step() {
            Step::Working => return TaskStep::Working,
            Step::Waiting => return TaskStep::Waiting,
            Step::Publish(v) => (v, false),
            Step::Done(v) => (v, true),
        };
        let Ok(mut slot) = self.shared.lock() else {
            return TaskStep::Done;
        };
        if slot.cancelled {
            return TaskStep::Done;
        }
        slot.latest = Some(value);
        slot.done = done;
        if done { TaskStep::Done } else { TaskStep::News }
    }
}

/// A running piece of work, as its owner sees it.
pub struct Job<T: Send + 'static> {
    shared: Arc<Mutex<Slot<T>>>,
    /// `None` once the job is over.
    handle: Option<Box<dyn TaskHandle>>,
    notice: Option<String>,
    time: PageTime,
}

impl<T: Send + 'static> Job<T> {
    /// The latest publication or the result, if there is news.
    pub fn poll(&mut self) -> Option<Update<T>> {
        let handle = self.handle.as_mut()?;
        handle.drive();
        self.time = handle.page_time();
        // Whether the runner had ended is read before the slot: a task
        // writes its result before its runner ends, so a result is never
        // mistaken for a death.
        let ended = handle.ended();
        let taken = self
            .shared
            .lock()
            .ok()
            .and_then(|mut s| s.latest.take().map(|v| (v, s.done)));
        let update = match taken {
            Some((v, true)) => Update::Done(v),
            Some((v, false)) => return Some(Update::Progress(v)),
            None if ended => Update::Failed("the work stopped unexpectedly".into()),
            None => return None,
        };
        self.handle = None;
        Some(update)
    }

    /// Whether the job has ended (done, failed or cancelled).
    pub fn is_over(&self) -> bool {
        self.handle.is_none()
    }

    /// Stops the work after its current step; nothing more is reported.
    pub fn cancel(&mut self) {
        if let Ok(mut s) = self.shared.lock() {
            s.cancelled = true;
            s.latest = None;
        }
        self.handle = None;
    }

    /// A note for the user about how the job runs (once).
    pub fn take_notice(&mut self) -> Option<String> {
        self.notice.take()
    }

    /// The work this job did on the caller's thread so far.
    pub fn page_time(&self) -> PageTime {
        self.time
    }
}

impl<T: Send + 'static> Drop for Job<T> {
    fn drop(&mut self) {
        self.cancel();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Counts to `n`, publishing every number.
    struct Count(u32, u32);

    impl Work for Count {
        type Output = u32;
        fn step(&mut self) -> Step<u32> {
            self.0 += 1;
            if self.0 == self.1 {
                Step::Done(self.0)
            } else {
                Step::Publish(self.0)
            }
        }
    }

    #[test]
    fn an_inline_job_finishes_at_its_first_poll() {
        let mut job = Runner::inline().start("count", Count(0, 5));
        assert_eq!(job.poll(), Some(Update::Done(5)));
        assert!(job.is_over());
        assert_eq!(job.poll(), None);
    }

    #[test]
    fn a_background_job_reports_its_result_once() {
        let (tx, rx) = std::sync::mpsc::channel();
        let tx = Mutex::new(tx);
        let runner = Runner::background(move || {
            let _ = tx.lock().map(|t| t.send(()));
        });
        let mut job = runner.start("count", Count(0, 1000));
        let mut last = None;
        while last.is_none() {
            let _ = rx.recv_timeout(Duration::from_secs(10));
            while let Some(u) = job.poll() {
                if let Update::Done(v) = u {
                    last = Some(v);
                }
            }
        }
        assert_eq!(last, Some(1000));
        assert!(job.is_over());
    }

    #[test]
    fn a_cancelled_job_reports_nothing_more() {
        let runner = Runner::background(|| {});
        let mut job = runner.start("count", Count(0, u32::MAX));
        job.cancel();
        assert!(job.is_over());
        assert_eq!(job.poll(), None);
    }

    #[test]
    fn once_is_one_step() {
        let mut job = Runner::inline().start("once", Once::new(|| 6 * 7));
        assert_eq!(job.poll(), Some(Update::Done(42)));
    }
}
