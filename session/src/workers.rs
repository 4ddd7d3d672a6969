//! A pool of workers that pieces of work are handed out to: the browser's
//! Web Workers, or the tests' fake. Pure bookkeeping over a [`Transport`]
//! (which moves the messages), so the hand-out code is compiled and tested
//! natively.
//!
//! Work is handed out under generations: a landscape's tiles, a
//! diagnosis's resampled extractions or RL runs ([`Setup`]). A generation
//! sends its model once per worker (only when the model changed since the
//! last generation), then its setup, then pieces, at most
//! [`Handout::in_flight`] per worker. Answers come back in any order; one
//! for a generation no longer live is dropped, so nothing stale reaches the
//! view. Ending a generation makes the workers forget it. A worker that
//! fails is terminated and its pieces are handed to the others; with none
//! left the owner computes itself, and the user is told. When an owner has
//! nothing left to hand out, an idle worker gets a copy of a piece another
//! worker still holds (where the owner allows copies; once per piece): with
//! two or more live workers a lost answer delays a fill, it does not stall
//! it.

use std::collections::BTreeSet;
use std::sync::{Arc, Mutex};

use dmpscope_core::landscape::grid::Grid;
use dmpscope_core::{Model, Result};
use serde::{Deserialize, Serialize};

use crate::rl_request::RlRequest;

/// Pieces a worker holds at once by default (one computing, one waiting,
/// so it never idles while the owner answers).
pub const IN_FLIGHT: usize = 2;

/// What a generation's pieces are.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Setup {
    /// Landscape tiles on this grid.
    Grid(Grid),
    /// Resampled extractions on the diagnostics' grid for this k.
    Diag {
        /// The diagnostics' grid.
        grid: Grid,
        /// The weight of sum d in J.
        k: f64,
    },
    /// Runs of an RL request.
    Rl(RlRequest),
}

impl Setup {
    /// The message kind of the generation (`grid`, `diag`, `rl`).
    pub fn kind(&self) -> &'static str {
        match self {
            Self::Grid(_) => "grid",
            Self::Diag { .. } => "diag",
            Self::Rl(_) => "rl",
        }
    }

    /// The message kind of its pieces (`tile`, `part`, `run`).
    pub fn piece_kind(&self) -> &'static str {
        match self {
            Self::Grid(_) => "tile",
            Self::Diag { .. } => "part",
            Self::Rl(_) => "run",
        }
    }
}

/// A message to a worker, in the order the pool sends them.
#[derive(Debug)]
pub enum ToWorker<'a> {
    /// Keep `model` as model `id`.
    Model {
        /// The model's id.
        id: u64,
        /// The model.
        model: &'a Arc<Model>,
    },
    /// A generation begins: its model and what its pieces are.
    Begin {
        /// The generation.
        generation: u64,
        /// Its model's id.
        model: u64,
        /// What its pieces are.
        setup: &'a Setup,
    },
    /// Compute a piece.
    Piece {
        /// Its generation.
        generation: u64,
        /// `tile`, `part` or `run`.
        kind: &'static str,
        /// Its id within the generation.
        piece: usize,
        /// What to compute (the tile's points, the part's demos).
        payload: Vec<u32>,
    },
    /// The generation is no longer wanted.
    Forget {
        /// The generation.
        generation: u64,
    },
}

/// What a worker sent back.
#[derive(Clone, Debug, PartialEq)]
pub enum FromWorker {
    /// An answer, or an update on a piece under way.
    Reply(Reply),
    /// The worker failed (its script did not load, it threw).
    Died {
        /// Which worker.
        worker: usize,
        /// Why.
        why: String,
    },
}

/// A worker's answer to a piece.
#[derive(Clone, Debug, PartialEq)]
pub struct Reply {
    /// Which worker.
    pub worker: usize,
    /// The piece's generation.
    pub generation: u64,
    /// The piece.
    pub piece: usize,
    /// Its numbers, or why it could not be computed.
    pub values: std::result::Result<Vec<f64>, String>,
    /// A JSON answer (RL runs' updates).
    pub json: Option<String>,
    /// Whether the piece is answered (else an update on the way).
    pub last: bool,
}

/// Moves messages between the pool and its workers.
pub trait Transport {
    /// What a worker is called in messages to the user (`Web Worker`).
    fn what(&self) -> &'static str {
        "worker"
    }
    /// What the user is told when every worker has failed, for `why`.
    fn all_failed(&self, why: &str) -> String {
        format!("the workers failed ({why}): the rest is computed here, more slowly")
    }
    /// Workers started (alive or not).
    fn workers(&self) -> usize;
    /// Posts `message` to `worker`; an error means the worker cannot take
    /// it (it is then treated as failed).
    fn send(&mut self, worker: usize, message: ToWorker<'_>) -> std::result::Result<(), String>;
    /// What the workers sent since the last call.
    fn receive(&mut self) -> Vec<FromWorker>;
    /// Stops a failed worker.
    fn terminate(&mut self, worker: usize);
}

/// What a generation hands out to the workers and takes back.
pub trait Handout {
    /// The generation its answers carry.
    fn generation(&self) -> u64;
    /// The message kind of its pieces (`tile`, `part`, `run`).
    fn kind(&self) -> &'static str;
    /// Pieces a worker may hold at once.
    fn in_flight(&self) -> usize {
        IN_FLIGHT
    }
    /// Whether a piece may be computed twice (a copy to an idle worker
    /// while another holds it; the second answer is refused).
    fn copies(&self) -> bool {
        true
    }
    /// The next piece to send: its id and payload.
    fn next(&mut self) -> Option<(usize, Vec<u32>)>;
    /// The payload of a piece already handed out (for a copy).
    fn payload(&self, _piece: usize) -> Option<Vec<u32>> {
        None
    }
    /// Stores the answer for a piece (numbers, or JSON); false when it is
    /// refused (a duplicate, a malformed answer).
    fn accept(&mut self, piece: usize, values: &[f64], json: Option<&str>) -> bool;
    /// An update on a piece still under way (JSON).
    fn progress(&mut self, _piece: usize, _json: &str) {}
    /// A piece whose answer will never come: hand it out again.
    fn again(&mut self, piece: usize);
}

/// What a pool has done, for the browser tests and the tests' fake.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct WorkerStats {
    /// Workers started.
    pub workers: usize,
    /// Of those, still alive.
    pub alive: usize,
    /// Landscape tiles the workers answered and a fill stored.
    pub tiles_from_workers: usize,
    /// Resampled extractions of the diagnostics the workers answered.
    pub parts_from_workers: usize,
    /// RL runs the workers trained to their end.
    pub runs_from_workers: usize,
    /// Copies of held pieces handed to idle workers.
    pub copies: usize,
    /// Answers refused (stale, duplicate, malformed).
    pub refused: usize,
}

/// What one exchange did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Exchanged {
    /// Answers and updates the owner stored.
    pub stored: usize,
    /// Whether any worker is alive (else the owner computes itself).
    pub alive: bool,
}

/// A pool of workers as the session's works see it.
pub trait Workers: Send + Sync {
    /// Starts a generation for `model` with `setup`; `None` where no worker
    /// could be started.
    fn begin(&self, model: &Arc<Model>, setup: &Setup) -> Result<Option<u64>>;
    /// Ends a generation: its pieces are no longer wanted.
    fn end(&self, generation: u64);
    /// Gives `owner` the answers of its generation, hands back the pieces
    /// of failed workers and sends its next pieces.
    fn exchange(&self, owner: &mut dyn Handout) -> Exchanged;
    /// The pool's figures.
    fn stats(&self) -> WorkerStats;
    /// What the user should be told since the last call.
    fn take_notices(&self) -> Vec<String>;
}

/// The pool's bookkeeping over a transport (see the module's
/// documentation).
pub struct Dispatcher<T> {
    transport: T,
    alive: Vec<bool>,
    in_flight: Vec<Vec<(u64, usize)>>,
    /// Answers for live generations whose owner has not asked yet.
    kept: Vec<Reply>,
    deaths: Vec<(usize, String)>,
    /// The model the workers hold last, and its id.
    model: Option<(Arc<Model>, u64)>,
    next_id: u64,
    live: BTreeSet<u64>,
    /// Pieces handed out whose worker died, by generation.
    lost: Vec<(u64, usize)>,
    /// Pieces answered, and pieces copied once, of live generations.
    answered: BTreeSet<(u64, usize)>,
    copied: BTreeSet<(u64, usize)>,
    stats: WorkerStats,
    notices: Vec<String>,
}

impl<T: Transport> Dispatcher<T> {
    /// A pool over `transport`'s workers; `notices` are what starting them
    /// had to say (a worker that could not start).
    pub fn new(transport: T, notices: Vec<String>) -> Self {
        let n = transport.workers();
        Self {
            transport,
            alive: vec![true; n],
            in_flight: vec![Vec::new(); n],
            kept: Vec::new(),
            deaths: Vec::new(),
            model: None,
            next_id: 1,
            live: BTreeSet::new(),
            lost: Vec::new(),
            answered: BTreeSet::new(),
            copied: BTreeSet::new(),
            stats: WorkerStats {
                workers: n,
                alive: n,
                ..WorkerStats::default()
            },
            notices,
        }
    }

    /// Whether any worker is alive.
    pub fn any_alive(&self) -> bool {
        self.alive.iter().any(|&a| a)
    }

    /// Posts to every live worker; a worker that cannot take it dies.
    fn broadcast(&mut self, message: impl Fn() -> ToWorker<'static>) {
        for i in 0..self.alive.len() {
            if self.alive[i]
                && let Err(e) = self.transport.send(i, message())
            {
                self.deaths.push((i, e));
            }
        }
    }

    /// Starts a generation for `model` (see [`Workers::begin`]).
    pub fn begin(&mut self, model: &Arc<Model>, setup: &Setup) -> Option<u64> {
        self.bury();
        if !self.any_alive() {
            return None;
        }
        let same = self
            .model
            .as_ref()
            .is_some_and(|(m, _)| Arc::ptr_eq(m, model));
        if !same {
            let id = self.next_id;
            self.next_id += 1;
            for i in 0..self.alive.len() {
                if self.alive[i]
                    && let Err(e) = self.transport.send(i, ToWorker::Model { id, model })
                {
                    self.deaths.push((i, e));
                }
            }
            self.model = Some((model.clone(), id));
        }
        let model_id = self.model.as_ref().map_or(0, |(_, id)| *id);
        let generation = self.next_id;
        self.next_id += 1;
        for i in 0..self.alive.len() {
            let message = ToWorker::Begin {
                generation,
                model: model_id,
                setup,
            };
            if self.alive[i]
                && let Err(e) = self.transport.send(i, message)
            {
                self.deaths.push((i, e));
            }
        }
        self.live.insert(generation);
        Some(generation)
    }

    /// Ends a generation: its pieces are no longer wanted.
    pub fn end(&mut self, generation: u64) {
        self.live.remove(&generation);
        for held in &mut self.in_flight {
            held.retain(|(g, _)| *g != generation);
        }
        self.lost.retain(|(g, _)| *g != generation);
        self.kept.retain(|r| r.generation != generation);
        self.answered.retain(|(g, _)| *g != generation);
        self.copied.retain(|(g, _)| *g != generation);
        self.broadcast(move || ToWorker::Forget { generation });
    }

    /// Buries workers that failed: their pieces go back to their owners.
    fn bury(&mut self) {
        for message in self.transport.receive() {
            match message {
                FromWorker::Reply(r) => self.kept.push(r),
                FromWorker::Died { worker, why } => self.deaths.push((worker, why)),
            }
        }
        let mut failed = Vec::new();
        for (i, why) in std::mem::take(&mut self.deaths) {
            if !self.alive.get(i).copied().unwrap_or(false) {
                continue;
            }
            self.alive[i] = false;
            self.transport.terminate(i);
            self.lost.append(&mut self.in_flight[i]);
            failed.push(why);
        }
        self.stats.alive = self.alive.iter().filter(|&&a| a).count();
        let Some(why) = failed.first() else {
            return;
        };
        // One message for the workers that failed together.
        let (n, what) = (failed.len(), self.transport.what());
        self.notices.push(if self.any_alive() {
            format!("{n} {what}(s) failed ({why}); the others take over their work")
        } else {
            self.transport.all_failed(why)
        });
    }

    /// Gives `owner` the answers of its generation, hands it back the
    /// pieces of failed workers and sends its next pieces.
    pub fn exchange(&mut self, owner: &mut dyn Handout) -> Exchanged {
        self.bury();
        let generation = owner.generation();
        let mut stored = 0;
        for reply in std::mem::take(&mut self.kept) {
            if reply.last
                && let Some(held) = self.in_flight.get_mut(reply.worker)
            {
                held.retain(|&x| x != (reply.generation, reply.piece));
            }
            if reply.generation != generation {
                if self.live.contains(&reply.generation) {
                    self.kept.push(reply);
                }
                continue;
            }
            stored += self.take(owner, reply);
        }
        self.bury();
        let (mine, others) = std::mem::take(&mut self.lost)
            .into_iter()
            .partition(|(g, _)| *g == generation);
        self.lost = others;
        for (_, piece) in mine {
            // A copy may still be under way elsewhere; a second answer is
            // refused.
            owner.again(piece);
        }
        self.hand_out(owner);
        Exchanged {
            stored,
            alive: self.any_alive(),
        }
    }

    /// Stores one reply of the owner's generation; 1 when stored.
    fn take(&mut self, owner: &mut dyn Handout, reply: Reply) -> usize {
        match &reply.values {
            Ok(_) if !reply.last => match &reply.json {
                Some(json) => {
                    owner.progress(reply.piece, json);
                    1
                }
                None => 0,
            },
            Ok(values) => {
                if !owner.accept(reply.piece, values, reply.json.as_deref()) {
                    self.stats.refused += 1;
                    return 0;
                }
                // A copy still under way elsewhere answers later (refused);
                // its worker keeps it until then.
                self.answered.insert((reply.generation, reply.piece));
                match owner.kind() {
                    "tile" => self.stats.tiles_from_workers += 1,
                    "part" => self.stats.parts_from_workers += 1,
                    _ => self.stats.runs_from_workers += 1,
                }
                1
            }
            Err(why) => {
                // A worker that cannot compute a piece computes none.
                self.deaths.push((reply.worker, why.clone()));
                owner.again(reply.piece);
                0
            }
        }
    }

    /// Sends the owner's next pieces to workers with room; when it has
    /// none left, copies of held pieces to idle workers.
    fn hand_out(&mut self, owner: &mut dyn Handout) {
        let generation = owner.generation();
        let mut exhausted = false;
        // One piece per worker with room per pass, so that the pieces (in
        // the owner's order: coarse tiles first) spread over the workers.
        let mut failed = vec![false; self.alive.len()];
        let mut posted = true;
        while posted && !exhausted {
            posted = false;
            for i in 0..self.alive.len() {
                if !self.alive[i] || failed[i] || self.in_flight[i].len() >= owner.in_flight() {
                    continue;
                }
                let Some((piece, payload)) = owner.next() else {
                    exhausted = true;
                    break;
                };
                let held = self.in_flight[i].len();
                self.post(i, owner, generation, piece, payload);
                // A worker that cannot take a piece gets no more this time.
                failed[i] = self.in_flight[i].len() == held;
                posted |= !failed[i];
            }
        }
        if !exhausted || !owner.copies() {
            return;
        }
        for i in 0..self.alive.len() {
            if !self.alive[i] || !self.in_flight[i].is_empty() {
                continue;
            }
            // A piece of this generation another worker holds, not answered
            // and not copied yet: the last it was handed, the least likely
            // to be under way there (a worker computes its pieces in order).
            let unanswered = self
                .in_flight
                .iter()
                .flat_map(|held| held.iter().rev())
                .filter(|&&(g, p)| {
                    g == generation
                        && !self.answered.contains(&(g, p))
                        && !self.copied.contains(&(g, p))
                })
                .map(|&(_, p)| p)
                .next();
            let Some(piece) = unanswered else { return };
            self.copied.insert((generation, piece));
            let Some(payload) = owner.payload(piece) else {
                continue;
            };
            self.stats.copies += 1;
            self.post(i, owner, generation, piece, payload);
        }
    }

    fn post(
        &mut self,
        worker: usize,
        owner: &mut dyn Handout,
        generation: u64,
        piece: usize,
        payload: Vec<u32>,
    ) {
        let message = ToWorker::Piece {
            generation,
            kind: owner.kind(),
            piece,
            payload,
        };
        match self.transport.send(worker, message) {
            Ok(()) => self.in_flight[worker].push((generation, piece)),
            Err(e) => {
                owner.again(piece);
                self.deaths.push((worker, e));
            }
        }
    }

    /// The pool's figures.
    pub fn stats(&self) -> WorkerStats {
        self.stats
    }

    /// What the user should be told since the last call.
    pub fn take_notices(&mut self) -> Vec<String> {
        std::mem::take(&mut self.notices)
    }
}

impl<T: Transport + Send> Workers for Mutex<Dispatcher<T>> {
    fn begin(&self, model: &Arc<Model>, setup: &Setup) -> Result<Option<u64>> {
        Ok(self.lock().ok().and_then(|mut d| d.begin(model, setup)))
    }
    fn end(&self, generation: u64) {
        if let Ok(mut d) = self.lock() {
            d.end(generation);
        }
    }
    fn exchange(&self, owner: &mut dyn Handout) -> Exchanged {
        self.lock()
            .map(|mut d| d.exchange(owner))
            .unwrap_or_default()
    }
    fn stats(&self) -> WorkerStats {
        self.lock().map(|d| d.stats()).unwrap_or_default()
    }
    fn take_notices(&self) -> Vec<String> {
        self.lock()
            .map(|mut d| d.take_notices())
            .unwrap_or_default()
    }
}

/// A live generation of a pool; dropping it ends the generation (the
/// workers forget it, its answers still on their way are dropped).
pub struct Generation {
    id: u64,
    workers: Arc<dyn Workers>,
}

impl Generation {
    /// Starts a generation for `model` on `workers`; `None` where the pool
    /// has no worker.
    pub fn begin(
        workers: &Arc<dyn Workers>,
        model: &Arc<Model>,
        setup: &Setup,
    ) -> Result<Option<Self>> {
        Ok(workers.begin(model, setup)?.map(|id| Self {
            id,
            workers: workers.clone(),
        }))
    }

    /// The generation's id.
    pub fn id(&self) -> u64 {
        self.id
    }

    /// Exchanges `owner`'s pieces with the pool.
    pub fn exchange(&self, owner: &mut dyn Handout) -> Exchanged {
        self.workers.exchange(owner)
    }
}

impl Drop for Generation {
    fn drop(&mut self) {
        self.workers.end(self.id);
    }
}
