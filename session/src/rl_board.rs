//! RL runs trained elsewhere (the browser's workers, one run per worker at a
//! time): [`RunUpdate`], what a worker sends after each iteration of a run,
//! made by [`RunUpdate::of`] from the core's `TrainingRun`, and
//! [`RunBoard`], which gathers the updates of a request's runs, arriving
//! from several workers at once and in any order, into the same
//! [`Progress`] a run trained on the page gives.

use dmpscope_core::Model;
use dmpscope_core::rl::env::GreedyRun;
use dmpscope_core::rl::run::{FirstReach, RunReport, TrainingRun};
use serde::{Deserialize, Serialize};

use super::rl::{Progress, RlRequest};

/// One run's state after an iteration.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunUpdate {
    /// Decisions trained so far.
    pub decisions: usize,
    /// The mean return per iteration so far.
    pub returns: Vec<f64>,
    /// The policy's mean run after the latest iteration.
    pub greedy: Option<GreedyRun>,
    /// `d` of that run against the demo, metres.
    pub d: f64,
    /// When that mean run first reached the goal.
    pub first_reach: Option<FirstReach>,
    /// Whether the learning curve so far diverged.
    pub diverged: bool,
    /// Training time so far, seconds.
    pub seconds: f64,
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
            returns: run.trainer().returns.clone(),
            greedy,
            d,
            first_reach: run.first_reach(),
            diverged: run.diverged(),
            seconds,
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
            returns: Vec::new(),
            greedy: None,
            d: 0.0,
            first_reach: None,
            diverged: false,
            seconds: 0.0,
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
        self.returns = update.returns;
        self.greedy = update.greedy;
        self.d = update.d;
        self.first_reach = update.first_reach;
        self.diverged = update.diverged;
        self.seconds = update.seconds;
    }
}

/// The updates of a request's runs, as one [`Progress`].
#[derive(Clone, Debug)]
pub struct RunBoard {
    steps: usize,
    runs: Vec<Option<RunUpdate>>,
}

impl RunBoard {
    /// A board for `request`, nothing trained yet.
    pub fn new(request: &RlRequest) -> Self {
        Self {
            steps: request.steps,
            runs: vec![None; request.runs.len()],
        }
    }

    /// Records an update of run `index`; an update for a run that is not
    /// in the request, or after its last, is ignored (false).
    pub fn update(&mut self, index: usize, update: RunUpdate) -> bool {
        match self.runs.get_mut(index) {
            Some(slot) if !slot.as_ref().is_some_and(|u| u.last) => {
                *slot = Some(update);
                true
            }
            _ => false,
        }
    }

    /// A run whose worker died: it starts again from nothing.
    pub fn restart(&mut self, index: usize) {
        if let Some(slot) = self.runs.get_mut(index)
            && !slot.as_ref().is_some_and(|u| u.last)
        {
            *slot = None;
        }
    }

    /// Why training stopped, when a run stopped early.
    fn stopped(&self) -> Option<String> {
        self.runs.iter().flatten().find_map(|u| u.stopped.clone())
    }

    /// Whether every run finished, or one stopped.
    pub fn done(&self) -> bool {
        self.stopped().is_some() || self.runs.iter().all(|u| u.as_ref().is_some_and(|u| u.last))
    }

    /// The progress: the first run not finished is the one under way; the
    /// finished runs' reports in the request's order.
    pub fn progress(&self) -> Progress {
        let run = self
            .runs
            .iter()
            .position(|u| !u.as_ref().is_some_and(|u| u.last))
            .unwrap_or(self.runs.len().saturating_sub(1));
        let finished = self
            .runs
            .iter()
            .flatten()
            .filter_map(|u| u.report.clone())
            .collect();
        let stopped = self.stopped();
        let mut p = Progress {
            run,
            decisions: (0, self.steps),
            finished,
            done: self.done(),
            stopped,
            ..Progress::default()
        };
        if let Some(Some(u)) = self.runs.get(run) {
            p.follow(u.clone(), self.steps);
        }
        p
    }
}

#[cfg(test)]
mod tests {
    use dmpscope_core::rl::env::EnvOptions;

    use super::*;
    use crate::rl::RlRun;

    fn request(n: usize) -> RlRequest {
        RlRequest {
            demo: 0,
            options: EnvOptions::default(),
            steps: 1000,
            runs: (0..n)
                .map(|i| RlRun {
                    gains_name: format!("g{i}"),
                    dm: 10.0,
                    km: 20.0,
                    seed: i as u64,
                })
                .collect(),
        }
    }

    fn update(decisions: usize, last: bool) -> RunUpdate {
        RunUpdate {
            decisions,
            returns: vec![-(decisions as f64)],
            greedy: None,
            d: 0.0,
            first_reach: None,
            diverged: false,
            seconds: 1.0,
            report: None,
            stopped: None,
            last,
        }
    }

    #[test]
    fn runs_finishing_out_of_order_show_the_first_unfinished_one() {
        let r = request(3);
        let mut board = RunBoard::new(&r);
        assert_eq!(board.progress().run, 0);
        assert!(board.update(2, update(1000, true)));
        assert!(board.update(0, update(400, false)));
        let p = board.progress();
        assert_eq!((p.run, p.decisions), (0, (400, 1000)));
        assert!(!p.done);
        assert!(board.update(0, update(1000, true)));
        assert!(
            !board.update(0, update(400, false)),
            "after its last update"
        );
        assert!(
            !board.update(7, update(1, false)),
            "not a run of the request"
        );
        assert_eq!(board.progress().run, 1);
        board.restart(1);
        assert!(board.update(1, update(1000, true)));
        assert!(board.done() && board.progress().done);
    }

    #[test]
    fn a_stopped_run_ends_the_request_with_its_message() {
        let r = request(2);
        let mut board = RunBoard::new(&r);
        board.update(1, RunUpdate::stopped(&r, 1, "a non-finite action"));
        let p = board.progress();
        assert!(p.done);
        assert_eq!(
            p.stopped.as_deref(),
            Some("g1 gains, seed 1: a non-finite action")
        );
    }
}
