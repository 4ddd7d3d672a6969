//! RL training as a [`Work`]: one or more [`TrainingRun`]s (a single run,
//! or the comparison of the extracted gains with the paper's presets over
//! seeds), each stepped (one episode or one minibatch per step, the same
//! numbers as whole iterations), publishing a [`Progress`] after every
//! iteration: the current run's learning curve, the policy's latest mean
//! path and when it first reached the goal, and the reports of the runs
//! already finished. A run that stops (a non-finite action) finishes the
//! work with its message and keeps what it had.

use std::sync::Arc;

use dmpscope_core::rl::run::TrainingRun;
use dmpscope_core::{Error, Model, Result};
use std::time::Duration;

use crate::jobs::{Clock, Runner, Step, Work};
use crate::pooled::PoolRl;
use crate::rl_request::{Progress, RlRequest, RunUpdate, run_label};

/// Trains the runs of one request: one after the other on this thread, or
/// in the executor's workers, as many at once as it has.
pub struct RlWork {
    run: TrainingRun,
    model: Arc<Model>,
    request: RlRequest,
    clock: Clock,
    started: Duration,
    progress: Progress,
    pool: Option<PoolRl>,
}

fn start(model: &Model, request: &RlRequest, i: usize) -> Result<TrainingRun> {
    let r = request
        .runs
        .get(i)
        .ok_or_else(|| Error::InvalidSetting("an RL request needs at least one run".into()))?;
    TrainingRun::new(
        model,
        request.demo,
        (r.dm, r.km),
        request.options,
        request.steps,
        r.seed,
    )
    .map_err(|e| Error::InvalidSetting(format!("{} gains: {e}", r.gains_name)))
}

impl RlWork {
    /// The work of `request` on `model` on `runner`'s executor (its workers
    /// train the runs where it has them); every run's settings are checked
    /// before the first starts.
    pub fn new(model: Arc<Model>, request: RlRequest, runner: &Runner) -> Result<Self> {
        for i in 1..request.runs.len() {
            start(&model, &request, i)?;
        }
        let run = start(&model, &request, 0)?;
        let progress = Progress {
            decisions: (0, request.steps),
            ..Progress::default()
        };
        let pool = match runner.workers() {
            Some(workers) => PoolRl::start(&workers, &model, &request)?,
            None => None,
        };
        let clock = runner.clock();
        Ok(Self {
            run,
            model,
            request,
            started: clock.now(),
            clock,
            progress,
            pool,
        })
    }

    /// How far training is (nothing trained yet, before the first step).
    pub fn progress(&self) -> &Progress {
        &self.progress
    }

    /// Finishes the current run and starts the next; `false` when there is
    /// none.
    fn next_run(&mut self) -> Result<bool> {
        let p = &mut self.progress;
        let name = &self.request.runs[p.run].gains_name;
        if let Some(report) = self.run.report(&self.model, name, p.seconds) {
            p.finished.push(report);
        }
        if p.run + 1 >= self.request.runs.len() {
            return Ok(false);
        }
        p.run += 1;
        self.run = start(&self.model, &self.request, p.run)?;
        self.started = self.clock.now();
        *p = Progress {
            run: p.run,
            decisions: (0, self.request.steps),
            finished: std::mem::take(&mut p.finished),
            ..Progress::default()
        };
        Ok(true)
    }
}

impl Work for RlWork {
    type Output = Progress;

    fn step(&mut self) -> Step<Progress> {
        if let Some(pool) = &mut self.pool {
            match pool.exchange() {
                Some(stored) => {
                    self.progress = pool.progress();
                    if pool.done() {
                        return Step::Done(self.progress.clone());
                    }
                    return if stored == 0 {
                        Step::Waiting
                    } else {
                        Step::Publish(self.progress.clone())
                    };
                }
                None => {
                    // No worker left: the runs are trained here, from the
                    // start (the pool's notice says so).
                    self.pool = None;
                    self.started = self.clock.now();
                    self.progress = Progress {
                        decisions: (0, self.request.steps),
                        ..Progress::default()
                    };
                }
            }
        }
        let seconds = (self.clock.now() - self.started).as_secs_f64();
        let stopped = |p: &mut Progress, why: String| {
            p.stopped = Some(why);
            p.done = true;
            Step::Done(p.clone())
        };
        match self.run.step(seconds) {
            Ok(Some(_)) => {}
            Ok(None) => return Step::Working,
            Err(e) => {
                let why = format!("{}: {e}", run_label(&self.request, self.progress.run));
                return stopped(&mut self.progress, why);
            }
        }
        let update = RunUpdate::of(&self.run, &self.model, self.request.demo, seconds);
        // A run ends on an iteration's boundary.
        let last = update.last;
        self.progress.follow(update, self.request.steps);
        if !last {
            return Step::Publish(self.progress.clone());
        }
        match self.next_run() {
            Ok(true) => Step::Publish(self.progress.clone()),
            Ok(false) => {
                self.progress.done = true;
                Step::Done(self.progress.clone())
            }
            Err(e) => stopped(&mut self.progress, e.to_string()),
        }
    }
}
