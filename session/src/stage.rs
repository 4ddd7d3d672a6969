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
        self.version += 1;
    }

    /// Computes the value on the spot when the key changed; `true` when it
    /// did.
    pub fn ensure_now(&mut self, key: K, compute: impl FnOnce() -> Result<T, String>) -> bool {
        if self.is_for(&key) {
            return false;
        }
        self.restart(key);
        match compute() {
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
        self.value = None;
        self.error = None;
        if let Some(job) = &mut self.job {
            match job.poll() {
                None | Some(Update::Progress(_)) => {
                    // The running job is for no key any more: whatever it
                    // gives is dropped (see `poll`).
                    self.key = None;
                    return false;
                }
                Some(_) => self.job = None,
            }
        }
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
