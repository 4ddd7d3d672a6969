//! What RL training is asked and what it reports (method.md section 8):
//! the request (a demo, the environment, runs of gains and seeds), one
//! run's state after an iteration ([`RunState`]), what a worker sends of
//! it ([`RunUpdate`]) and what the session shows ([`Progress`]), both made
//! of that one state.

use std::ops::Deref;

use dmpscope_core::Model;
use dmpscope_core::rl::env::{EnvOptions, GreedyRun};
use dmpscope_core::rl::run::{FirstReach, RunReport, TrainingRun};
use serde::{Deserialize, Serialize};

/// One run's state after an iteration.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct RunState {
    /// The mean return per iteration so far (finite: a non-finite one
    /// stops the run).
    pub returns: Vec<f64>,
    /// The policy's mean run after the latest iteration.
    pub greedy: Option<GreedyRun>,
    /// `d` of that run against the demo, metres.
    pub d: f64,
    /// When that mean run first ended within 5 mm of the goal.
    pub first_reach: Option<FirstReach>,
    /// Whether the learning curve so far diverged.
    pub diverged: bool,
    /// Training time so far, seconds.
    pub seconds: f64,
}

/// One run of a request: the gains and the seed.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RlRun {
    /// What the gains are ("extracted", a preset's name, ...).
    pub gains_name: String,
    /// D/M.
    pub dm: f64,
    /// K/M.
    pub km: f64,
    /// The seed.
    pub seed: u64,
}

/// What to train: a demo of the model, the environment, the budget per
/// run and the runs, in order.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RlRequest {
    /// The demo (model index).
    pub demo: usize,
    /// Decisions per episode and the action mode.
    pub options: EnvOptions,
    /// Decisions to train per run.
    pub steps: usize,
    /// The runs (at least one).
    pub runs: Vec<RlRun>,
}

/// What training has reached.
#[derive(Clone, Debug, Default)]
pub struct Progress {
    /// The run under way (index into the request's runs).
    pub run: usize,
    /// Decisions trained so far in it, and in all.
    pub decisions: (usize, usize),
    /// Its state after its latest iteration (read through `Deref`:
    /// `progress.returns`).
    pub state: RunState,
    /// The runs finished, in order.
    pub finished: Vec<RunReport>,
    /// Finished, cancelled or stopped.
    pub done: bool,
    /// Cancelled by the user.
    pub cancelled: bool,
    /// Why training stopped early, when it did.
    pub stopped: Option<String>,
}

/// One run's state after an iteration.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunUpdate {
    /// Decisions trained so far.
    pub decisions: usize,
    /// The run's state after the iteration (read through `Deref`).
    #[serde(flatten)]
    pub state: RunState,
    /// The run's report, in its last update (when it finished).
    pub report: Option<RunReport>,
    /// Why the run stopped early, in its last update (when it did).
    pub stopped: Option<String>,
    /// Whether this is the run's last update.
    pub last: bool,
}

impl RunUpdate {
    /// The state of `run` (on demo `demo` of `model`) after `seconds` of
    /// training; the last update when it is done (its report is added by
    /// [`RunUpdate::with_report`]).
    pub fn of(run: &TrainingRun, model: &Model, demo: usize, seconds: f64) -> Self {
        let greedy = run.greedy().cloned();
        let d = greedy
            .as_ref()
            .map_or(0.0, |g| model.path_error(demo, &g.path));
        Self {
            decisions: run.trainer().decisions(),
            state: RunState {
                returns: run.trainer().returns.clone(),
                greedy,
                d,
                first_reach: run.first_reach(),
                diverged: run.diverged(),
                seconds,
            },
            report: None,
            stopped: None,
            last: run.done(),
        }
    }

    /// This last update with the finished run's report (run `index` of
    /// `request`).
    pub fn with_report(
        mut self,
        run: &TrainingRun,
        model: &Model,
        request: &RlRequest,
        index: usize,
    ) -> Self {
        let name = request
            .runs
            .get(index)
            .map_or("", |r| r.gains_name.as_str());
        self.report = run.report(model, name, self.seconds);
        self
    }

    /// The last update of a run that stopped early, with why.
    pub fn stopped(request: &RlRequest, index: usize, why: &str) -> Self {
        Self {
            decisions: 0,
            state: RunState::default(),
            report: None,
            stopped: Some(format!("{}: {why}", run_label(request, index))),
            last: true,
        }
    }
}

/// "`gains` gains, seed `seed`" of run `index`, as messages name a run.
pub fn run_label(request: &RlRequest, index: usize) -> String {
    request.runs.get(index).map_or_else(
        || format!("run {index}"),
        |r| format!("{} gains, seed {}", r.gains_name, r.seed),
    )
}

impl Progress {
    /// Shows `update` as the run under way (of `steps` decisions).
    pub fn follow(&mut self, update: RunUpdate, steps: usize) {
        self.decisions = (update.decisions, steps);
        self.state = update.state;
    }
}

impl Deref for Progress {
    type Target = RunState;

    fn deref(&self) -> &RunState {
        &self.state
    }
}

impl Deref for RunUpdate {
    type Target = RunState;

    fn deref(&self) -> &RunState {
        &self.state
    }
}
