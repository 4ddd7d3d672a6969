//! One training run as the CLI and the app show it: the [`Trainer`] on a
//! [`DmpEnv`] stepped to a budget of decisions, the policy's mean run after
//! every iteration, and the first iteration whose mean run reached the goal
//! (decisions and seconds). The core has no clock: the caller passes the
//! seconds so far to [`TrainingRun::step`].

use super::env::{DmpEnv, EnvOptions, GreedyRun};
use super::outcome::diverged;
use super::ppo::{IterStats, PpoConfig, Trainer};
use super::REACHED_M;
use crate::{Error, Model, Result};

/// When a run's mean first ended within [`REACHED_M`] of the goal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FirstReach {
    /// Decisions of training by then.
    pub decisions: usize,
    /// Seconds of training by then.
    pub seconds: f64,
}

/// A training run to a budget.
pub struct TrainingRun {
    trainer: Trainer<DmpEnv>,
    budget: usize,
    greedy: Option<GreedyRun>,
    first_reach: Option<FirstReach>,
}

impl TrainingRun {
    /// A run of `budget` decisions on demo `demo` of `model` at (`dm`,
    /// `km`), with PPO's defaults for the episode's length
    /// ([`PpoConfig::for_episode`]) and `seed`.
    pub fn new(
        model: &Model,
        demo: usize,
        (dm, km): (f64, f64),
        options: EnvOptions,
        budget: usize,
        seed: u64,
    ) -> Result<Self> {
        if budget == 0 {
            return Err(Error::InvalidSetting(
                "a training run needs at least 1 decision".into(),
            ));
        }
        let env = DmpEnv::new(model, demo, dm, km, options)?;
        let config = PpoConfig::for_episode(super::Task::decisions(&env), budget);
        Ok(Self {
            trainer: Trainer::new(env, config, seed),
            budget,
            greedy: None,
            first_reach: None,
        })
    }

    /// A few milliseconds of training; after an iteration completes, the
    /// policy's mean is run and its summary returned. `elapsed_s` is the
    /// training time so far.
    pub fn step(&mut self, elapsed_s: f64) -> Result<Option<IterStats>> {
        let Some(stats) = self.trainer.step()? else {
            return Ok(None);
        };
        let run = self.trainer.task().greedy(self.trainer.policy())?;
        if self.first_reach.is_none() && run.final_error <= REACHED_M {
            self.first_reach = Some(FirstReach {
                decisions: stats.decisions,
                seconds: elapsed_s,
            });
        }
        self.greedy = Some(run);
        Ok(Some(stats))
    }

    /// Whether the budget is spent (training ends on an iteration's
    /// boundary, so it may take a little more).
    pub fn done(&self) -> bool {
        self.trainer.decisions() >= self.budget
    }

    /// The budget in decisions.
    pub fn budget(&self) -> usize {
        self.budget
    }

    /// The trainer.
    pub fn trainer(&self) -> &Trainer<DmpEnv> {
        &self.trainer
    }

    /// The policy's mean run after the latest iteration.
    pub fn greedy(&self) -> Option<&GreedyRun> {
        self.greedy.as_ref()
    }

    /// The first iteration whose mean run reached the goal.
    pub fn first_reach(&self) -> Option<FirstReach> {
        self.first_reach
    }

    /// Whether the learning curve so far diverged ([`diverged`]).
    pub fn diverged(&self) -> bool {
        diverged(&self.trainer.returns)
    }
}
