//! The executor interface: what the platform hands the session so that it
//! can run work off the frame without naming threads, the browser or a
//! test harness (as rerun hands its viewer an async runtime handle).
//!
//! An [`Executor`] runs [`Task`]s (a type-erased job step, see
//! [`crate::jobs`]), tells the time, says whether a step may use every
//! core, and may offer a pool of [`Workers`] that landscape tiles,
//! diagnostics parts and RL runs are handed out to, with the notices and
//! figures of that pool. This crate implements two executors for native
//! use, [`ThreadExecutor`] (a thread per job) and [`InlineExecutor`] (the
//! job runs to its end when first polled: tests); the browser's executor
//! (Web Workers, slices on the page's event loop) lives in the app's `web`
//! module, and the tests' fake pool in `tests/` of this crate.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use crate::workers::{WorkerStats, Workers};

/// What a task's step did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TaskStep {
    /// Keep going; nothing new.
    Working,
    /// Nothing to do until an answer from elsewhere arrives: the caller may
    /// yield (end a slice, sleep a little).
    Waiting,
    /// Keep going; there is news for the owner (call the wake function).
    News,
    /// Finished (or cancelled): never step again.
    Done,
}

/// A job's work, type-erased: the session wraps each [`crate::jobs::Work`]
/// into one, its results kept where its [`crate::jobs::Job`] reads them.
pub trait Task: Send {
    /// Advances the work by one short step.
    fn step(&mut self) -> TaskStep;
}

/// The executor's side of a running task, as its job sees it.
pub trait TaskHandle {
    /// Gives the task the caller's time if it runs on the caller's thread
    /// (inline: to its end; a slice where no thread could be started).
    /// Nothing for a task that runs elsewhere.
    fn drive(&mut self) {}
    /// Whether the task's runner ended (a thread that returned or died).
    fn ended(&self) -> bool;
    /// Work done on the caller's thread so far.
    fn page_time(&self) -> PageTime;
}

/// A task as started: its handle, and a note for the user about how it
/// runs (no thread could be started, say).
pub struct Spawned {
    /// The task's handle.
    pub handle: Box<dyn TaskHandle>,
    /// What to tell the user, once.
    pub notice: Option<String>,
}

/// Where the session's work runs (see the module's documentation).
pub trait Executor: Send + Sync {
    /// Starts `task`; `name` says what it is in messages.
    fn spawn(&self, name: &str, task: Box<dyn Task>) -> Spawned;
    /// Whether tasks get a thread of their own (each step may be long and
    /// the work may publish after every step).
    fn threaded(&self) -> bool;
    /// Whether one step may use every core of the machine (rayon).
    fn parallel(&self) -> bool;
    /// A monotonic clock: time since the executor's origin.
    fn now(&self) -> Duration;
    /// The pool of workers pieces of work can be handed out to, if any.
    fn workers(&self) -> Option<Arc<dyn Workers>> {
        None
    }
    /// What the user should be told about the executor since the last
    /// call (a worker that failed, none that started).
    fn take_notices(&self) -> Vec<String> {
        self.workers().map(|w| w.take_notices()).unwrap_or_default()
    }
    /// The pool's figures (zeros without one).
    fn worker_stats(&self) -> WorkerStats {
        self.workers().map(|w| w.stats()).unwrap_or_default()
    }
}

/// Work done on the caller's (the page's) own thread: the longest slice and
/// all slices together, milliseconds. Zero for work on its own thread.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PageTime {
    /// The longest slice, ms.
    pub longest_ms: f64,
    /// All slices, ms.
    pub total_ms: f64,
}

impl PageTime {
    /// Counts a slice of `slice`.
    pub fn add(&mut self, slice: Duration) {
        let ms = slice.as_secs_f64() * 1e3;
        self.longest_ms = self.longest_ms.max(ms);
        self.total_ms += ms;
    }
}

/// Time a slice of work may take on the caller's thread (the fallback
/// when no thread can be started).
pub const SLICE: Duration = Duration::from_millis(10);

/// Runs a task on the caller's thread when polled: to its end, or for a
/// slice of `slice` per poll, calling `wake` when it has news left.
struct InlineHandle {
    task: Box<dyn Task>,
    slice: Option<Duration>,
    wake: Arc<dyn Fn() + Send + Sync>,
    over: bool,
    time: PageTime,
}

impl TaskHandle for InlineHandle {
    fn drive(&mut self) {
        if self.over {
            return;
        }
        let start = Instant::now();
        let mut news = false;
        loop {
            match self.task.step() {
                TaskStep::Working | TaskStep::Waiting => {}
                TaskStep::News => news = true,
                TaskStep::Done => {
                    self.over = true;
                    break;
                }
            }
            if self.slice.is_some_and(|s| start.elapsed() >= s) {
                break;
            }
        }
        self.time.add(start.elapsed());
        if news || !self.over {
            (self.wake)();
        }
    }
    fn ended(&self) -> bool {
        false
    }
    fn page_time(&self) -> PageTime {
        self.time
    }
}

/// Every job runs to its end on the caller's thread at its first poll:
/// tests drive the session synchronously, without sleeps.
pub struct InlineExecutor {
    origin: Instant,
    workers: Option<Arc<dyn Workers>>,
}

impl Default for InlineExecutor {
    fn default() -> Self {
        Self::new()
    }
}

impl InlineExecutor {
    /// Inline jobs, no workers.
    pub fn new() -> Self {
        Self {
            origin: Instant::now(),
            workers: None,
        }
    }

    /// Inline jobs whose pieces are handed out to `workers` (the tests'
    /// fake pool).
    pub fn with_workers(workers: Arc<dyn Workers>) -> Self {
        Self {
            origin: Instant::now(),
            workers: Some(workers),
        }
    }
}

impl Executor for InlineExecutor {
    fn spawn(&self, _name: &str, task: Box<dyn Task>) -> Spawned {
        Spawned {
            handle: Box::new(InlineHandle {
                task,
                slice: None,
                wake: Arc::new(|| {}),
                over: false,
                time: PageTime::default(),
            }),
            notice: None,
        }
    }
    fn threaded(&self) -> bool {
        false
    }
    fn parallel(&self) -> bool {
        true
    }
    fn now(&self) -> Duration {
        self.origin.elapsed()
    }
    fn workers(&self) -> Option<Arc<dyn Workers>> {
        self.workers.clone()
    }
}

/// A native thread per job; `wake` (a repaint) when a job has news. Where
/// no thread can be started the job runs in slices at each poll and the
/// user is told.
pub struct ThreadExecutor {
    origin: Instant,
    wake: Arc<dyn Fn() + Send + Sync>,
}

impl ThreadExecutor {
    /// Jobs on threads; `wake` asks for a repaint.
    pub fn new(wake: impl Fn() + Send + Sync + 'static) -> Self {
        Self {
            origin: Instant::now(),
            wake: Arc::new(wake),
        }
    }
}

/// A task on a thread of its own.
struct ThreadHandle {
    handle: std::thread::JoinHandle<()>,
    stop: Arc<AtomicBool>,
}

impl TaskHandle for ThreadHandle {
    fn ended(&self) -> bool {
        self.handle.is_finished()
    }
    fn page_time(&self) -> PageTime {
        PageTime::default()
    }
}

impl Drop for ThreadHandle {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
    }
}

impl Executor for ThreadExecutor {
    fn spawn(&self, name: &str, task: Box<dyn Task>) -> Spawned {
        let handed = Arc::new(std::sync::Mutex::new(Some(task)));
        let stop = Arc::new(AtomicBool::new(false));
        let (thread_task, thread_stop, wake) = (handed.clone(), stop.clone(), self.wake.clone());
        let spawned = std::thread::Builder::new()
            .name(format!("dmpscope {name}"))
            .spawn(move || {
                let task = thread_task.lock().ok().and_then(|mut t| t.take());
                if let Some(mut task) = task {
                    while !thread_stop.load(Ordering::Relaxed) {
                        match task.step() {
                            TaskStep::Working => {}
                            TaskStep::Waiting => std::thread::sleep(Duration::from_millis(1)),
                            TaskStep::News => wake(),
                            TaskStep::Done => {
                                wake();
                                return;
                            }
                        }
                    }
                }
            });
        match spawned {
            Ok(handle) => Spawned {
                handle: Box::new(ThreadHandle { handle, stop }),
                notice: None,
            },
            Err(e) => {
                let task = handed.lock().ok().and_then(|mut t| t.take());
                let notice = Some(format!(
                    "cannot start a thread for {name} ({e}): it runs on the app's thread in slices"
                ));
                let handle: Box<dyn TaskHandle> = match task {
                    Some(task) => Box::new(InlineHandle {
                        task,
                        slice: Some(SLICE),
                        wake: self.wake.clone(),
                        over: false,
                        time: PageTime::default(),
                    }),
                    None => Box::new(Ended),
                };
                Spawned { handle, notice }
            }
        }
    }
    fn threaded(&self) -> bool {
        true
    }
    fn parallel(&self) -> bool {
        true
    }
    fn now(&self) -> Duration {
        self.origin.elapsed()
    }
}

/// A task that never ran.
struct Ended;

impl TaskHandle for Ended {
    fn ended(&self) -> bool {
        true
    }
    fn page_time(&self) -> PageTime {
        PageTime::default()
    }
}
