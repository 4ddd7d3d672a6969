//! RL training as a [`Work`]: the core's PPO [`Trainer`] stepped (one
//! episode or one minibatch per step, the same numbers as whole
//! iterations), publishing a [`Progress`] after every iteration: the
//! learning curve and the policy's latest mean path.

use std::sync::Arc;

use dmpscope_core::rl::{DmpEnv, GreedyRun, PpoConfig, Trainer};
use dmpscope_core::{Model, Result};
use web_time::Instant;

use super::jobs::{Step, Work};

/// What to train: a demo of the model and the gains.
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
    /// Mean return per iteration.
    pub returns: Vec<f64>,
    /// The policy's mean run after the latest iteration.
    pub greedy: Option<GreedyRun>,
    /// `d` of that run against the demo, metres.
    pub d: f64,
    /// Training time so far, seconds.
    pub seconds: f64,
    /// Finished, or cancelled.
    pub done: bool,
    /// Cancelled by the user.
    pub cancelled: bool,
}

/// Trains a PPO agent for one request.
pub struct RlWork {
    trainer: Trainer,
    model: Arc<Model>,
    request: RlRequest,
    started: Instant,
    progress: Progress,
}

impl RlWork {
    /// The work of `request` on `model`.
    pub fn new(model: Arc<Model>, request: RlRequest) -> Result<Self> {
        let demo = model.demos().get(request.demo).ok_or_else(|| {
            dmpscope_core::Error::InvalidSetting(format!("no demo {}", request.demo + 1))
        })?;
        let env = DmpEnv::new(demo, request.dm, request.km)?;
        let progress = Progress {
            decisions: (0, request.steps),
            ..Progress::default()
        };
        Ok(Self {
            trainer: Trainer::new(env, PpoConfig::default(), request.seed),
            model,
            request,
            started: Instant::now(),
            progress,
        })
    }
}

impl RlWork {
    /// How far training is (nothing trained yet, before the first step).
    pub fn progress(&self) -> &Progress {
        &self.progress
    }
}

impl Work for RlWork {
    type Output = Progress;

    fn step(&mut self) -> Step<Progress> {
        let Some(stats) = self.trainer.step() else {
            return Step::Working;
        };
        let greedy = self.trainer.greedy();
        let p = &mut self.progress;
        p.d = self.model.path_error(self.request.demo, &greedy.path);
        p.decisions = (stats.decisions, self.request.steps);
        p.returns.clone_from(&self.trainer.returns);
        p.greedy = Some(greedy);
        p.seconds = self.started.elapsed().as_secs_f64();
        // Training ends on an iteration's boundary.
        if stats.decisions >= self.request.steps {
            p.done = true;
            Step::Done(p.clone())
        } else {
            Step::Publish(p.clone())
        }
    }
}
