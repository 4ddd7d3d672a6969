//! RL training in the browser's workers: a request's runs are handed out
//! one per worker at a time (a Compare trains as many runs at once as the
//! page has workers), each worker sends an update after every iteration
//! and the page gathers them on a [`RunBoard`] into the RL panel's
//! progress. Dropping the [`PoolRl`] (cancel, a new request or model) ends
//! its generation: the workers stop training its runs.

use std::collections::VecDeque;
use std::sync::Arc;

use dmpscope_core::{Model, Result};

use super::pool::{Generation, Handout, json_field, with_pool};
use crate::session::RlRequest;
use crate::session::rl::Progress;
use crate::session::rl_board::{RunBoard, RunUpdate};

/// A request whose runs the pool's workers train.
pub struct PoolRl {
    generation: Generation,
    todo: VecDeque<usize>,
    board: RunBoard,
}

impl Handout for PoolRl {
    fn generation(&self) -> u64 {
        self.generation.0
    }
    fn kind(&self) -> &'static str {
        "run"
    }
    fn in_flight(&self) -> usize {
        1
    }
    fn next(&mut self) -> Option<(usize, Vec<u32>)> {
        self.todo.pop_front().map(|run| (run, Vec::new()))
    }
    fn accept(&mut self, piece: usize, _values: &[f64], json: Option<&str>) -> bool {
        match json.map(serde_json::from_str::<RunUpdate>) {
            Some(Ok(update)) => self.board.update(piece, update),
            Some(Err(e)) => {
                log::warn!("dmpscope: a worker's RL update could not be read: {e}");
                false
            }
            None => false,
        }
    }
    fn progress(&mut self, piece: usize, json: &str) {
        if let Ok(update) = serde_json::from_str::<RunUpdate>(json) {
            self.board.update(piece, update);
        }
    }
    fn again(&mut self, piece: usize) {
        self.board.restart(piece);
        if !self.todo.contains(&piece) {
            self.todo.push_front(piece);
        }
    }
}

impl PoolRl {
    /// Starts training `request`'s runs on `model` in the workers; `None`
    /// where the page has no workers (it trains on its own thread).
    pub fn start(model: &Arc<Model>, request: &RlRequest) -> Result<Option<Self>> {
        let fields = vec![("request", json_field("the RL request", request)?)];
        let Some(generation) = Generation::begin(model, "rl", fields)? else {
            return Ok(None);
        };
        Ok(Some(Self {
            generation,
            todo: (0..request.runs.len()).collect(),
            board: RunBoard::new(request),
        }))
    }

    /// Takes in the workers' updates and hands out the next runs. Returns
    /// the updates stored, and `None` when no worker is left (the page then
    /// trains what is left itself).
    pub fn exchange(&mut self) -> Option<usize> {
        let (stored, alive) = with_pool(|p| (p.exchange(self), p.any_alive()))?;
        alive.then_some(stored)
    }

    /// The progress so far.
    pub fn progress(&self) -> Progress {
        self.board.progress()
    }

    /// Whether every run finished, or one stopped.
    pub fn done(&self) -> bool {
        self.board.done()
    }
}
