//! RL runs trained elsewhere (the browser's workers, one run per worker at a
//! time): [`RunBoard`] gathers the [`RunUpdate`]s of a request's runs,
//! arriving from several workers at once and in any order, into the same
//! [`Progress`] a run trained on the page gives.

use crate::rl_request::{Progress, RlRequest, RunUpdate};

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
    use crate::rl_request::{RlRun, RunState};

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
            state: RunState {
                returns: vec![-(decisions as f64)],
                seconds: 1.0,
                ..RunState::default()
            },
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
