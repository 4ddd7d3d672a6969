//! RL training as a [`Work`]: the core's [`TrainingRun`] stepped (one
//! episode or one minibatch per step, the same numbers as whole
//! iterations), publishing a [`Progress`] after every iteration: the
//! learning curve, the policy's latest mean path and when it first reached
//! the goal. A run that stops (a non-finite action) finishes with its
//! message and keeps what it had.

use std::sync::Arc;

use dmpscope_core::rl::{EnvOptions, FirstReach, GreedyRun, TrainingRun};
use dmpscope_core::{Model, Result};
use web_time::Instant;

use super::jobs::{Step, Work};

/// What to train: a demo of the model, the gains and the environment.
#[derive(Clone, Debug, PartialEq)]
pub struct RlRequest {
    /// The demo (model index).
    pub demo: usize,
    /// What the gains are ("extracted", a preset's name, ...).
    pub gains_name: String,
    /// D/M.
    pub dm: f64,
    /// K/M.
    pub km: f64,
    /// Decisions per episode and the action mode.
    pub options: EnvOptions,
    /// Decisions to train.
    pub steps: usize,
    /// The seed.
    pub seed: u64,
}

/// What training has reached.
#[derive(Clone, Debug, Default)]
pub struct Progress {
    /// Decisions trained so far, and in all.
    pub decisions: (usize, usize),
    /// Mean return per iteration (finite: a non-finite one stops the run).
    pub returns: Vec<f64>,
    /// The policy's mean run after the latest iteration.
    pub greedy: Option<GreedyRun>,
    /// `d` of that run against the demo, metres.
    pub d: f64,
    /// When the mean run first ended within 5 mm of the goal.
    pub first_reach: Option<FirstReach>,
    /// Whether the learning curve so far diverged.
    pub diverged: bool,
    /// Training time so far, seconds.
    pub seconds: f64,
    /// Finished, cancelled or stopped.
    pub done: bool,
    /// Cancelled by the user.
    pub cancelled: bool,
    /// Why training stopped early, when it did.
    pub stopped: Option<String>,
}

/// Trains a PPO agent for one request.
pub struct RlWork {
    run: TrainingRun,
    model: Arc<Model>,
    request: RlRequest,
    started: Instant,
    progress: Progress,
}

impl RlWork {
    /// The work of `request` on `model`.
    pub fn new(model: Arc<Model>, request: RlRequest) -> Result<Self> {
        let run = TrainingRun::new(
            &model,
            request.demo,
            (request.dm, request.km),
            request.options,
            request.steps,
            request.seed,
        )?;
        let progress = Progress {
            decisions: (0, request.steps),
            ..Progress::default()
        };
        Ok(Self {
            run,
            model,
            request,
            started: Instant::now(),
            progress,
        })
    }

    /// How far training is (nothing trained yet, before the first step).
    pub fn progress(&self) -> &Progress {
        &self.progress
    }
}

impl Work for RlWork {
    type Output = Progress;

    fn step(&mut self) -> Step<Progress> {
        let seconds = self.started.elapsed().as_secs_f64();
        let stats = match self.run.step(seconds) {
            Ok(Some(stats)) => stats,
            Ok(None) => return Step::Working,
            Err(e) => {
                let p = &mut self.progress;
                p.stopped = Some(e.to_string());
                p.done = true;
                p.seconds = seconds;
                return Step::Done(p.clone());
            }
        };
        let p = &mut self.progress;
        if let Some(greedy) = self.run.greedy() {
            p.d = self.model.path_error(self.request.demo, &greedy.path);
            p.greedy = Some(greedy.clone());
        }
        p.decisions = (stats.decisions, self.request.steps);
        p.returns.clone_from(&self.run.trainer().returns);
        p.first_reach = self.run.first_reach();
        p.diverged = self.run.diverged();
        p.seconds = seconds;
        // Training ends on an iteration's boundary.
        if self.run.done() {
            p.done = true;
            Step::Done(p.clone())
        } else {
            Step::Publish(p.clone())
        }
    }
}
