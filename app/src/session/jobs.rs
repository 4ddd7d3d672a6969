//! The one background mechanism for everything that takes longer than a
//! frame: loading, the landscape, the extraction, RL training.
//!
//! A [`Work`] advances in steps and says after each what to publish. A
//! [`Runner`] runs it: natively on a thread of its own, in the browser in
//! ~10 ms slices on the page's event loop (no threads there), or inline, at
//! the first [`Job::poll`], to the end (tests, which then need no sleeps).
//! Whatever runs it, the owner sees the same [`Job`]: `poll` hands over the
//! latest publication, `cancel` (or dropping the job) stops the work at its
//! next step (in the browser: its next slice) and nothing it does afterwards
//! reaches the owner; a work of one step (an extraction) runs to its end
//! unseen, so its owner starts at most one at a time. When a
//! thread cannot be started the work runs in slices at each poll instead,
//! and [`Job::take_notice`] says so once.

use std::sync::Arc;
#[cfg(not(target_arch = "wasm32"))]
use std::sync::Mutex;

use web_time::{Duration, Instant};

/// One step of a [`Work`]'s progress.
pub enum Step<T> {
    /// Keep going; nothing new to show.
    Working,
    /// Nothing to do until an answer from elsewhere arrives (the browser's
    /// workers): the slice ends early and the page's thread is free.
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

/// How jobs run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// Off the frame: a thread natively, time slices in the browser.
    Background,
    /// To the end at the first poll, on the caller's thread.
    Inline,
}

/// Starts jobs in one [`Mode`], calling `wake` when one has news.
#[derive(Clone)]
pub struct Runner {
    mode: Mode,
    wake: Arc<dyn Fn() + Send + Sync>,
}

impl std::fmt::Debug for Runner {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Runner").field("mode", &self.mode).finish()
    }
}

/// Time a slice of work may take on the caller's thread (browser slices,
/// and the fallback when no thread can be started).
const SLICE: Duration = Duration::from_millis(10);

impl Runner {
    /// Jobs off the frame; `wake` asks for a repaint.
    pub fn background(wake: impl Fn() + Send + Sync + 'static) -> Self {
        Self {
            mode: Mode::Background,
            wake: Arc::new(wake),
        }
    }

    /// Jobs that run to the end when first polled.
    pub fn inline() -> Self {
        Self {
            mode: Mode::Inline,
            wake: Arc::new(|| {}),
        }
    }

    /// Whether jobs get a thread of their own (so a work may use all cores
    /// in one step and take longer per step).
    pub fn threaded(&self) -> bool {
        self.mode == Mode::Background && cfg!(not(target_arch = "wasm32"))
    }

    /// Starts `work`; `name` says what it is in messages.
    pub fn start<W: Work>(&self, name: &str, work: W) -> Job<W::Output> {
        match self.mode {
            Mode::Inline => Job::inline(Box::new(work), None, self.wake.clone()),
            Mode::Background => self.spawn(name, work),
        }
    }

    #[cfg(not(target_arch = "wasm32"))]
    fn spawn<W: Work>(&self, name: &str, work: W) -> Job<W::Output> {
        let shared = Arc::new(Shared::<W::Output>::default());
        let handed = Arc::new(Mutex::new(Some(work)));
        let (thread_shared, thread_work, wake) =
            (shared.clone(), handed.clone(), self.wake.clone());
        let spawned = std::thread::Builder::new()
            .name(format!("dmpscope {name}"))
            .spawn(move || {
                let work = thread_work.lock().ok().and_then(|mut w| w.take());
                if let Some(work) = work {
                    run_thread(work, &thread_shared, &*wake);
                }
            });
        match spawned {
            Ok(handle) => Job::new(State::Thread { shared, handle }),
            Err(e) => {
                let work = handed.lock().ok().and_then(|mut w| w.take());
                let mut job = match work {
                    Some(work) => Job::inline(Box::new(work), Some(SLICE), self.wake.clone()),
                    None => Job::new(State::Over),
                };
                job.notice = Some(format!(
                    "cannot start a thread for {name} ({e}): it runs on the app's thread in slices"
                ));
                job
            }
        }
    }

    #[cfg(target_arch = "wasm32")]
    fn spawn<W: Work>(&self, _name: &str, work: W) -> Job<W::Output> {
        let shared = std::rc::Rc::new(std::cell::RefCell::new(Local::default()));
        wasm_bindgen_futures::spawn_local(run_slices(work, shared.clone(), self.wake.clone()));
        Job::new(State::Local(shared))
    }
}

/// What a thread shares with its job.
#[cfg(not(target_arch = "wasm32"))]
struct Shared<T> {
    slot: Mutex<Slot<T>>,
    cancel: std::sync::atomic::AtomicBool,
}

#[cfg(not(target_arch = "wasm32"))]
impl<T> Default for Shared<T> {
    fn default() -> Self {
        Self {
            slot: Mutex::new(Slot {
                latest: None,
                done: false,
            }),
            cancel: std::sync::atomic::AtomicBool::new(false),
        }
    }
}

#[cfg(not(target_arch = "wasm32"))]
struct Slot<T> {
    latest: Option<T>,
    done: bool,
}

#[cfg(not(target_arch = "wasm32"))]
fn run_thread<W: Work>(mut work: W, shared: &Shared<W::Output>, wake: &dyn Fn()) {
    use std::sync::atomic::Ordering;
    while !shared.cancel.load(Ordering::Relaxed) {
        let (value, done) = match work.step() {
            Step::Working => continue,
            Step::Waiting => {
                std::thread::sleep(Duration::from_millis(1));
                continue;
            }
            Step::Publish(v) => (v, false),
            Step::Done(v) => (v, true),
        };
        if let Ok(mut slot) = shared.slot.lock() {
            slot.latest = Some(value);
            slot.done = done;
        }
        wake();
        if done {
            return;
        }
    }
}

/// What a browser job shares with its slices.
#[cfg(target_arch = "wasm32")]
struct Local<T> {
    latest: Option<T>,
    done: bool,
    cancelled: bool,
    stats: PageTime,
}

#[cfg(target_arch = "wasm32")]
impl<T> Default for Local<T> {
    fn default() -> Self {
        Self {
            latest: None,
            done: false,
            cancelled: false,
            stats: PageTime::default(),
        }
    }
}

/// Lets the browser run its event loop (a zero-delay timeout).
#[cfg(target_arch = "wasm32")]
async fn yield_to_browser() {
    let promise = js_sys::Promise::new(&mut |resolve, _| {
        if let Some(w) = web_sys::window() {
            let _ = w.set_timeout_with_callback_and_timeout_and_arguments_0(&resolve, 0);
        }
    });
    let _ = wasm_bindgen_futures::JsFuture::from(promise).await;
}

#[cfg(target_arch = "wasm32")]
async fn run_slices<W: Work>(
    mut work: W,
    shared: std::rc::Rc<std::cell::RefCell<Local<W::Output>>>,
    wake: Arc<dyn Fn() + Send + Sync>,
) {
    loop {
        if shared.borrow().cancelled {
            return;
        }
        let start = Instant::now();
        let mut news = false;
        let mut done = false;
        while !done && start.elapsed() < SLICE {
            let value = match work.step() {
                Step::Working => continue,
                Step::Waiting => break,
                Step::Publish(v) => v,
                Step::Done(v) => {
                    done = true;
                    v
                }
            };
            let mut s = shared.borrow_mut();
            s.latest = Some(value);
            s.done = done;
            news = true;
        }
        shared.borrow_mut().stats.add(start.elapsed());
        if news {
            wake();
        }
        if done {
            return;
        }
        yield_to_browser().await;
    }
}

/// Work done on the page's (or the app's) own thread: the longest slice and
/// all slices together, milliseconds. Zero for work on its own thread.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PageTime {
    /// The longest slice, ms.
    pub longest_ms: f64,
    /// All slices, ms.
    pub total_ms: f64,
}

impl PageTime {
    fn add(&mut self, slice: Duration) {
        let ms = slice.as_secs_f64() * 1e3;
        self.longest_ms = self.longest_ms.max(ms);
        self.total_ms += ms;
    }
}

enum State<T: Send + 'static> {
    #[cfg(not(target_arch = "wasm32"))]
    Thread {
        shared: Arc<Shared<T>>,
        handle: std::thread::JoinHandle<()>,
    },
    #[cfg(target_arch = "wasm32")]
    Local(std::rc::Rc<std::cell::RefCell<Local<T>>>),
    Inline {
        work: Box<dyn Work<Output = T>>,
        /// `None`: to the end at once; else this much per poll.
        slice: Option<Duration>,
        wake: Arc<dyn Fn() + Send + Sync>,
    },
    Over,
}

/// A running piece of work, as its owner sees it.
pub struct Job<T: Send + 'static> {
    state: State<T>,
    notice: Option<String>,
    own_thread_time: PageTime,
}

impl<T: Send + 'static> Job<T> {
    fn new(state: State<T>) -> Self {
        Self {
            state,
            notice: None,
            own_thread_time: PageTime::default(),
        }
    }

    fn inline(
        work: Box<dyn Work<Output = T>>,
        slice: Option<Duration>,
        wake: Arc<dyn Fn() + Send + Sync>,
    ) -> Self {
        Self::new(State::Inline { work, slice, wake })
    }

    /// The latest publication or the result, if there is news.
    pub fn poll(&mut self) -> Option<Update<T>> {
        let (update, over) = match &mut self.state {
            #[cfg(not(target_arch = "wasm32"))]
            State::Thread { shared, handle } => {
                // Whether the thread had ended is read before the slot: a
                // thread writes its result before it ends, so a result is
                // never mistaken for a death.
                let ended = handle.is_finished();
                let taken = shared
                    .slot
                    .lock()
                    .ok()
                    .and_then(|mut s| s.latest.take().map(|v| (v, s.done)));
                match taken {
                    Some((v, true)) => (Some(Update::Done(v)), true),
                    Some((v, false)) => (Some(Update::Progress(v)), false),
                    None if ended => (
                        Some(Update::Failed("the work stopped unexpectedly".into())),
                        true,
                    ),
                    None => (None, false),
                }
            }
            #[cfg(target_arch = "wasm32")]
            State::Local(shared) => {
                let mut s = shared.borrow_mut();
                self.own_thread_time = s.stats;
                match s.latest.take() {
                    Some(v) if s.done => (Some(Update::Done(v)), true),
                    Some(v) => (Some(Update::Progress(v)), false),
                    None => (None, false),
                }
            }
            State::Inline { work, slice, wake } => {
                let start = Instant::now();
                let mut latest = None;
                let mut result = None;
                loop {
                    match work.step() {
                        Step::Working | Step::Waiting => {}
                        Step::Publish(v) => latest = Some(v),
                        Step::Done(v) => {
                            result = Some(v);
                            break;
                        }
                    }
                    if slice.is_some_and(|s| start.elapsed() >= s) {
                        break;
                    }
                }
                self.own_thread_time.add(start.elapsed());
                match result {
                    Some(v) => (Some(Update::Done(v)), true),
                    None => {
                        wake();
                        (latest.map(Update::Progress), false)
                    }
                }
            }
            State::Over => (None, false),
        };
        if over {
            self.state = State::Over;
        }
        update
    }

    /// Whether the job has ended (done, failed or cancelled).
    pub fn is_over(&self) -> bool {
        matches!(self.state, State::Over)
    }

    /// Stops the work after its current step; nothing more is reported.
    pub fn cancel(&mut self) {
        match &self.state {
            #[cfg(not(target_arch = "wasm32"))]
            State::Thread { shared, .. } => {
                shared
                    .cancel
                    .store(true, std::sync::atomic::Ordering::Relaxed);
            }
            #[cfg(target_arch = "wasm32")]
            State::Local(shared) => shared.borrow_mut().cancelled = true,
            State::Inline { .. } | State::Over => {}
        }
        self.state = State::Over;
    }

    /// A note for the user about how the job runs (once).
    pub fn take_notice(&mut self) -> Option<String> {
        self.notice.take()
    }

    /// The work this job did on the caller's thread so far.
    pub fn page_time(&self) -> PageTime {
        self.own_thread_time
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
