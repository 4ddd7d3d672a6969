//! [`Stage`]: one step of the pipeline as the session keeps it: the key
//! its value is for, the job computing it (if it runs in the background),
//! the latest value and the error. Every stage of the session is one
//! (sources' streams, model, landscape, extraction, diagnostics,
//! constrained optimum, presets, operating point, generalisation, RL); the
//! session decides the keys, a stage only compares them.
//!
//! `ensure` (re)computes when the key changed: at once
//! ([`Stage::ensure_now`]) or by starting a job ([`Stage::ensure_job`],
//! dropping a job for an older key cancels it; [`Stage::ensure_serial`]
//! waits instead for a one-step job that cannot be stopped, so that a
//! dragged slider never piles up threads). `poll` takes the job's news.

use crate::executor::PageTime;
use crate::jobs::{Job, Update};

/// What [`Stage::poll`] found.
#[derive(Clone, Debug, PartialEq)]
pub enum Polled {
    /// Nothing new.
    Nothing,
    /// A new value (a preview or the result).
    Value,
    /// The job stopped without a result; the error says why.
    Failed(String),
}

/// One stage: key, job, latest value, error.
pub struct Stage<K, T: Send + 'static> {
    key: Option<K>,
    job: Option<Job<T>>,
    value: Option<T>,
    error: Option<String>,
    /// Counts the (re)computations: identifies the value downstream.
    version: u64,
    page_time: PageTime,
    cancelled: bool,
    /// The job stopped without a result (its thread died).
    died: bool,
    /// The key of a running job `ensure_serial` waits for (the stage's key
    /// is `None` meanwhile); a return to it keeps the job.
    awaited: Option<K>,
}

impl<K, T: Send + 'static> Default for Stage<K, T> {
    fn default() -> Self {
        Self {
            key: None,
            job: None,
            value: None,
            error: None,
            version: 0,
            page_time: PageTime::default(),
            cancelled: false,
            died: false,
            awaited: None,
        }
    }
}

impl<K: PartialEq, T: Send + 'static> Stage<K, T> {
    /// Whether the stage is (being) computed for `key`.
    pub fn is_for(&self, key: &K) -> bool {
        self.key.as_ref() == Some(key)
    }

    /// Starts over for `key`: the old value, error and job are gone.
    fn restart(&mut self, key: K) {
        self.key = Some(key);
        self.job = None;
        self.value = None;
        self.error = None;
        self.page_time = PageTime::default();
        self.cancelled = false;
        self.died = false;
        self.awaited = None;
        self.version += 1;
    }

    /// Computes the value on the spot when the key changed (`compute` is
    /// given the key); `true` when it did.
    pub fn ensure_now(&mut self, key: K, compute: impl FnOnce(&K) -> Result<T, String>) -> bool {
        if self.is_for(&key) {
            return false;
        }
        let computed = compute(&key);
        self.restart(key);
        match computed {
            Ok(v) => self.value = Some(v),
            Err(e) => self.error = Some(e),
        }
        true
    }

    /// Starts a job when the key changed (a job for an older key is
    /// cancelled); `start` gives the job, or why there is none. `true` when
    /// it started one (or tried).
    pub fn ensure_job(&mut self, key: K, start: impl FnOnce() -> Result<Job<T>, String>) -> bool {
        if self.is_for(&key) {
            return false;
        }
        self.restart(key);
        match start() {
            Ok(job) => self.job = Some(job),
            Err(e) => self.error = Some(e),
        }
        true
    }

    /// As [`Stage::ensure_job`], but one job at a time: while a job for
    /// another key runs, the value is dropped and the stage waits for the
    /// job to end (its answer is dropped too) before it starts the next.
    /// `true` when it started one.
    pub fn ensure_serial(
        &mut self,
        key: K,
        start: impl FnOnce() -> Result<Job<T>, String>,
    ) -> bool {
        if self.is_for(&key) {
            return false;
        }
        if self.awaited.as_ref() == Some(&key) {
            // Back to the key of the job still running: it is wanted again.
            self.key = self.awaited.take();
            return false;
        }
        self.value = None;
        self.error = None;
        if let Some(job) = &mut self.job {
            match job.poll() {
                None | Some(Update::Progress(_)) => {
                    // The running job is for no key any more: whatever it
                    // gives is dropped (see `poll`) unless its key returns.
                    if self.key.is_some() {
                        self.awaited = self.key.take();
                    }
                    return false;
                }
                Some(_) => self.job = None,
            }
        }
        self.awaited = None;
        self.ensure_job(key, start)
    }

    /// Takes the job's news.
    pub fn poll(&mut self) -> Polled {
        let Some(job) = &mut self.job else {
            return Polled::Nothing;
        };
        let update = job.poll();
        self.page_time = job.page_time();
        if self.key.is_none() {
            // A job awaited by `ensure_serial`: its answer is stale.
            if job.is_over() {
                self.job = None;
                self.awaited = None;
            }
            return Polled::Nothing;
        }
        match update {
            Some(Update::Progress(v)) => {
                self.value = Some(v);
                Polled::Value
            }
            Some(Update::Done(v)) => {
                self.value = Some(v);
                self.job = None;
                Polled::Value
            }
            Some(Update::Failed(e)) => {
                self.job = None;
                self.died = true;
                self.error = Some(e.clone());
                Polled::Failed(e)
            }
            None => Polled::Nothing,
        }
    }

    /// Stops the job (the value so far stays); `true` when one ran.
    pub fn cancel(&mut self) -> bool {
        let Some(mut job) = self.job.take() else {
            return false;
        };
        job.cancel();
        self.cancelled = true;
        true
    }

    /// Forgets everything (no input for the stage).
    pub fn clear(&mut self) {
        self.key = None;
        self.job = None;
        self.value = None;
        self.error = None;
        self.cancelled = false;
        self.died = false;
        self.awaited = None;
        self.page_time = PageTime::default();
    }

    /// The key of the value (or of the job computing it).
    pub fn key(&self) -> Option<&K> {
        self.key.as_ref()
    }

    /// The latest value.
    pub fn value(&self) -> Option<&T> {
        self.value.as_ref()
    }

    /// The latest value, to change in place (a value derived further).
    pub fn value_mut(&mut self) -> Option<&mut T> {
        self.value.as_mut()
    }

    /// Takes the latest value out (the stage keeps its key).
    pub fn take_value(&mut self) -> Option<T> {
        self.value.take()
    }

    /// Sets the value (a job's first state, before its first news).
    pub fn set_value(&mut self, value: T) {
        self.value = Some(value);
    }

    /// Sets the error (a job's result that is an error).
    pub fn set_error(&mut self, error: String) {
        self.error = Some(error);
    }

    /// Why the stage has no value, if it failed.
    pub fn error(&self) -> Option<&str> {
        self.error.as_deref()
    }

    /// Whether the stage waits for a job of an older key to end before it
    /// starts the next (see [`Stage::ensure_serial`]).
    pub fn waiting(&self) -> bool {
        self.key.is_none() && self.job.is_some()
    }

    /// Whether a job is running.
    pub fn running(&self) -> bool {
        self.job.is_some()
    }

    /// Whether the job stopped without a result (its thread died).
    pub fn died(&self) -> bool {
        self.died
    }

    /// Whether the user cancelled the job.
    pub fn cancelled(&self) -> bool {
        self.cancelled
    }

    /// Identifies the current computation: changes with every restart.
    pub fn version(&self) -> u64 {
        self.version
    }

    /// The job's work on the caller's thread so far.
    pub fn page_time(&self) -> PageTime {
        self.page_time
    }

    /// A note about how the job runs (no thread could be started), once.
    pub fn take_notice(&mut self) -> Option<String> {
        self.job.as_mut().and_then(Job::take_notice)
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;
    use std::sync::atomic::{AtomicBool, Ordering};

    use super::*;
    use crate::jobs::{Runner, Step, Work};

    /// Gives `value` once `go` is set.
    struct Gate {
        go: Arc<AtomicBool>,
        value: u32,
    }

    impl Work for Gate {
        type Output = u32;
        fn step(&mut self) -> Step<u32> {
            if self.go.load(Ordering::Relaxed) {
                Step::Done(self.value)
            } else {
                std::thread::sleep(std::time::Duration::from_millis(1));
                Step::Working
            }
        }
    }

    #[test]
    fn a_serial_stage_waits_for_its_job_and_keeps_it_when_its_key_returns() {
        let runner = Runner::background(|| {});
        let go = Arc::new(AtomicBool::new(false));
        let gate = |value| Gate {
            go: go.clone(),
            value,
        };
        let mut stage: Stage<u8, u32> = Stage::default();
        assert!(stage.ensure_serial(1, || Ok(runner.start("one", gate(1)))));
        // Another key while the job runs: nothing starts, nothing is shown.
        assert!(!stage.ensure_serial(2, || Ok(runner.start("two", gate(2)))));
        assert!(stage.waiting() && stage.key().is_none() && stage.value().is_none());
        // Back to the first key: its job is wanted again, not restarted.
        assert!(!stage.ensure_serial(1, || Ok(runner.start("again", gate(9)))));
        assert!(stage.is_for(&1) && stage.running());
        go.store(true, Ordering::Relaxed);
        let mut polled = Polled::Nothing;
        for _ in 0..10_000 {
            polled = stage.poll();
            if polled != Polled::Nothing {
                break;
            }
            std::thread::sleep(std::time::Duration::from_millis(1));
        }
        assert_eq!(polled, Polled::Value);
        assert_eq!(stage.value(), Some(&1));
        assert_eq!(stage.version(), 1, "one job started");
    }

    #[test]
    fn a_stale_answer_never_reaches_a_new_key() {
        let runner = Runner::background(|| {});
        let go = Arc::new(AtomicBool::new(false));
        let mut stage: Stage<u8, u32> = Stage::default();
        let first = Gate {
            go: go.clone(),
            value: 1,
        };
        stage.ensure_serial(1, || Ok(runner.start("one", first)));
        assert!(!stage.ensure_serial(2, || Ok(runner.start(
            "unused",
            Gate {
                go: go.clone(),
                value: 7,
            }
        ))));
        go.store(true, Ordering::Relaxed);
        // The old job ends: its answer is dropped, then key 2 starts.
        for _ in 0..10_000 {
            let _ = stage.poll();
            if !stage.running() {
                break;
            }
            std::thread::sleep(std::time::Duration::from_millis(1));
        }
        assert_eq!(stage.value(), None);
        let second = Gate { go, value: 2 };
        assert!(stage.ensure_serial(2, || Ok(runner.start("two", second))));
        for _ in 0..10_000 {
            if stage.poll() == Polled::Value {
                break;
            }
            std::thread::sleep(std::time::Duration::from_millis(1));
        }
        assert_eq!((stage.key(), stage.value()), (Some(&2), Some(&2)));
    }
}
