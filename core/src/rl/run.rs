//! One training run as the CLI and the app show it: the [`Trainer`] on a
//! [`DmpEnv`] stepped to a budget of decisions, the policy's mean run after
//! every iteration, the first iteration whose mean run reached the goal
//! (decisions and seconds) and how steadily it stayed reached after. The core has no clock: the caller passes the
//! seconds so far to [`TrainingRun::step`].

use serde::{Deserialize, Serialize};

use crate::rl::env::{DmpEnv, EnvOptions, GreedyRun};
use crate::rl::outcome::diverged;
use crate::rl::ppo::{IterStats, PpoConfig, Trainer};
use crate::{Error, Model, Result};

/// Within this distance of the goal an episode "reached" it (issue 6).
pub const REACHED_M: f64 = 0.005;

/// When a run's mean first ended within [`REACHED_M`] of the goal.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct FirstReach {
    /// Decisions of training by then.
    pub decisions: usize,
    /// Seconds of training by then.
    pub seconds: f64,
}

/// A finished (or stopped) run's figures, as the CLI's table and the app's
/// comparison show them.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunReport {
    /// The gain set's name (a preset's, "Extracted", ...).
    pub name: String,
    /// D/M.
    pub dm: f64,
    /// K/M.
    pub km: f64,
    /// The seed.
    pub seed: u64,
    /// The policy's mean run at the end.
    pub greedy: GreedyRun,
    /// `d` of that run against the demo, metres.
    pub d: f64,
    /// Whether it ends within [`REACHED_M`] of the goal.
    pub reached: bool,
    /// Whether the learning curve diverged.
    pub diverged: bool,
    /// When the mean first reached.
    pub first_reach: Option<FirstReach>,
    /// The share of iterations from the first reach on that reached.
    pub held: Option<f64>,
    /// The learning curve (mean return per iteration).
    pub returns: Vec<f64>,
    /// Training time, seconds.
    pub seconds: f64,
}

/// The runs of one gain set, summarised.
#[derive(Clone, Debug, PartialEq)]
pub struct SetSummary {
    /// The gain set's name.
    pub name: String,
    /// Its runs.
    pub runs: usize,
    /// How many reached.
    pub reached: usize,
    /// How many did not diverge.
    pub stable: usize,
    /// The median final error, metres (the upper median for an even count).
    pub median_final_error: f64,
}

/// One summary per gain set of `reports`, in order of first appearance.
pub fn summarise(reports: &[RunReport]) -> Vec<SetSummary> {
    let mut names: Vec<&str> = Vec::new();
    for r in reports {
        if !names.contains(&r.name.as_str()) {
            names.push(&r.name);
        }
    }
    names
        .into_iter()
        .map(|name| {
            let of: Vec<&RunReport> = reports.iter().filter(|r| r.name == name).collect();
            let mut errs: Vec<f64> = of.iter().map(|r| r.greedy.final_error).collect();
            errs.sort_by(f64::total_cmp);
            SetSummary {
                name: name.to_owned(),
                runs: of.len(),
                reached: of.iter().filter(|r| r.reached).count(),
                stable: of.iter().filter(|r| !r.diverged).count(),
                median_final_error: errs[errs.len() / 2],
            }
        })
        .collect()
}

/// A training run to a budget.
pub struct TrainingRun {
    trainer: Trainer<DmpEnv>,
    demo: usize,
    seed: u64,
    budget: usize,
    greedy: Option<GreedyRun>,
    first_reach: Option<FirstReach>,
    /// Iterations since the first reach, and how many of them reached.
    since: (usize, usize),
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
        let config = PpoConfig::for_episode(crate::rl::task::Task::decisions(&env), budget);
        Ok(Self {
            trainer: Trainer::new(env, config, seed),
            demo,
            seed,
            budget,
            greedy: None,
            first_reach: None,
            since: (0, 0),
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
        let reached = run.final_error <= REACHED_M;
        if self.first_reach.is_none() && reached {
            self.first_reach = Some(FirstReach {
                decisions: stats.decisions,
                seconds: elapsed_s,
            });
        }
        if self.first_reach.is_some() {
            self.since.0 += 1;
            self.since.1 += usize::from(reached);
        }
        self.greedy = Some(run);
        Ok(Some(stats))
    }

    /// Whether the budget is spent and the iteration that spent it is
    /// complete (training ends on an iteration's boundary, so it may take a
    /// little more).
    pub fn done(&self) -> bool {
        self.trainer.decisions() >= self.budget && !self.trainer.mid_iteration()
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

    /// The run's figures under `name`, after `seconds` of training (`None`
    /// before its first iteration); `model` is the one it was made from.
    pub fn report(&self, model: &Model, name: &str, seconds: f64) -> Option<RunReport> {
        let greedy = self.greedy.clone()?;
        let env = self.trainer.task();
        Some(RunReport {
            name: name.to_owned(),
            dm: env.dm,
            km: env.km,
            seed: self.seed,
            d: model.path_error(self.demo, &greedy.path),
            reached: greedy.final_error <= REACHED_M,
            diverged: self.diverged(),
            first_reach: self.first_reach,
            held: self.held(),
            returns: self.trainer.returns.clone(),
            greedy,
            seconds,
        })
    }

    /// The share of the iterations from the first reach on whose mean run
    /// reached (1 when it stayed reached; `None` before a first reach).
    pub fn held(&self) -> Option<f64> {
        (self.since.0 > 0).then(|| self.since.1 as f64 / self.since.0 as f64)
    }

    /// Whether the learning curve so far diverged ([`diverged`]).
    pub fn diverged(&self) -> bool {
        diverged(&self.trainer.returns)
    }
}
