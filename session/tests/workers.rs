//! The hand-out code of the session's worker pool, run natively through a
//! fake transport whose workers compute with the session's own
//! [`WorkerState`] (as the browser's Web Workers do) but answer out of
//! order, lose an answer and fail, and build their models from the bytes
//! the browser's page sends (`ModelInputs::to_bytes`): the landscape, the
//! diagnostics and RL training still give exactly the numbers of the inline
//! session.

use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use dmpscope_core::Model;
use dmpscope_core::rl::env::EnvOptions;
use dmpscope_session::executor::InlineExecutor;
use dmpscope_session::worker_side::{ModelInputs, RunSlice, WorkerState};
use dmpscope_session::workers::{Dispatcher, FromWorker, Reply, Setup, ToWorker, Transport};
use dmpscope_session::{Command, RlRequest, RlRun, Runner, Session, Settings, Source};

/// A message as a fake worker keeps it.
enum Held {
    Model(u64, Arc<Model>),
    Begin(u64, u64, Setup),
    Piece(u64, &'static str, usize, Vec<u32>),
    Forget(u64),
}

/// One fake worker.
#[derive(Default)]
struct FakeWorker {
    state: WorkerState,
    inbox: Vec<Held>,
    pieces: usize,
    dead: bool,
}

/// Workers that answer in reverse order, lose the answer to one piece and
/// fail one worker after a few pieces.
struct Fake {
    workers: Vec<FakeWorker>,
    /// The (0-based) answered piece whose answer is lost, over all workers.
    lose: Option<usize>,
    answered: usize,
    /// `(worker, after n pieces)`: that worker dies at its n+1-th piece.
    fail: Option<(usize, usize)>,
    origin: Instant,
}

impl Fake {
    fn new(n: usize, lose: Option<usize>, fail: Option<(usize, usize)>) -> Self {
        Self {
            workers: (0..n).map(|_| FakeWorker::default()).collect(),
            lose,
            answered: 0,
            fail,
            origin: Instant::now(),
        }
    }

    fn answer(
        worker: usize,
        generation: u64,
        piece: usize,
        values: Result<Vec<f64>, String>,
    ) -> FromWorker {
        FromWorker::Reply(Reply {
            worker,
            generation,
            piece,
            values,
            json: None,
            last: true,
        })
    }

    /// What worker `i` sends for one message.
    fn handle(&mut self, i: usize, message: Held, out: &mut Vec<FromWorker>) {
        let origin = self.origin;
        let w = &mut self.workers[i];
        match message {
            Held::Model(id, model) => w.state.keep_model(id, model),
            Held::Begin(generation, model, setup) => {
                if let Err(why) = w.state.begin(generation, model, setup) {
                    out.push(FromWorker::Died { worker: i, why });
                }
            }
            Held::Forget(generation) => w.state.forget(generation),
            Held::Piece(generation, kind, piece, payload) => {
                if self
                    .fail
                    .is_some_and(|(f, after)| f == i && w.pieces == after)
                {
                    w.dead = true;
                    out.push(FromWorker::Died {
                        worker: i,
                        why: "the fake failed it".into(),
                    });
                    return;
                }
                w.pieces += 1;
                match kind {
                    "tile" => out.push(Self::answer(
                        i,
                        generation,
                        piece,
                        w.state.tile(generation, &payload),
                    )),
                    "part" => out.push(Self::answer(
                        i,
                        generation,
                        piece,
                        w.state.part(generation, &payload),
                    )),
                    _ => {
                        let now = move || origin.elapsed();
                        let budget = Duration::from_secs(3600);
                        while let Some(slice) = w.state.run_step(generation, piece, budget, &now) {
                            let (update, last) = match slice {
                                RunSlice::Nothing => continue,
                                RunSlice::Progress(u) => (u, false),
                                RunSlice::Last(u) => (u, true),
                            };
                            out.push(FromWorker::Reply(Reply {
                                worker: i,
                                generation,
                                piece,
                                values: Ok(Vec::new()),
                                json: serde_json::to_string(&update).ok(),
                                last,
                            }));
                            if last {
                                break;
                            }
                        }
                    }
                }
            }
        }
    }
}

impl Transport for Fake {
    fn workers(&self) -> usize {
        self.workers.len()
    }
    fn send(&mut self, worker: usize, message: ToWorker<'_>) -> Result<(), String> {
        let held = match message {
            // Through the bytes the browser's page sends its workers.
            ToWorker::Model { id, model } => {
                let bytes = ModelInputs::of(model).to_bytes()?;
                Held::Model(id, Arc::new(ModelInputs::from_bytes(&bytes)?.build()?))
            }
            ToWorker::Begin {
                generation,
                model,
                setup,
            } => Held::Begin(generation, model, setup.clone()),
            ToWorker::Piece {
                generation,
                kind,
                piece,
                payload,
            } => Held::Piece(generation, kind, piece, payload),
            ToWorker::Forget { generation } => Held::Forget(generation),
        };
        self.workers[worker].inbox.push(held);
        Ok(())
    }
    fn receive(&mut self) -> Vec<FromWorker> {
        let mut out = Vec::new();
        for i in 0..self.workers.len() {
            for message in std::mem::take(&mut self.workers[i].inbox) {
                if !self.workers[i].dead {
                    self.handle(i, message, &mut out);
                }
            }
        }
        // Out of order, and one answer lost on its way.
        out.reverse();
        let mut kept = Vec::new();
        for m in out {
            if matches!(&m, FromWorker::Reply(r) if r.last) {
                self.answered += 1;
                if self.lose == Some(self.answered - 1) {
                    continue;
                }
            }
            kept.push(m);
        }
        kept
    }
    fn terminate(&mut self, worker: usize) {
        self.workers[worker].dead = true;
    }
}

/// A session whose pieces go to `fake`'s workers, every job inline.
fn pooled(fake: Fake) -> Session {
    let pool = Arc::new(Mutex::new(Dispatcher::new(fake, Vec::new())));
    Session::new(Runner::new(Arc::new(InlineExecutor::with_workers(pool))))
}

fn on_sample(mut session: Session, settings: &Settings) -> Session {
    session.apply(Command::AddSources(vec![Source::planted_sample()]));
    session.update(settings);
    session
}

#[test]
fn tiles_out_of_order_lost_and_from_a_failed_worker_give_the_inline_landscape() {
    let settings = Settings::with_grid_points(24);
    let inline = on_sample(Session::new(Runner::inline()), &settings);
    let fake = Fake::new(3, Some(2), Some((1, 1)));
    let pooled = on_sample(pooled(fake), &settings);
    let (a, b) = (
        &inline.shown().expect("inline landscape").snapshot,
        &pooled.shown().expect("pooled landscape").snapshot,
    );
    assert!(a.complete() && b.complete());
    // Bit for bit (NaN, the d_rot map not asked for, is not equal to itself).
    let bits = |l: &dmpscope_core::Landscape| -> Vec<Vec<u64>> {
        l.values
            .iter()
            .map(|v| v.iter().map(|x| x.to_bits()).collect())
            .collect()
    };
    assert_eq!(
        (a.landscape.grid, a.landscape.filled),
        (b.landscape.grid, b.landscape.filled)
    );
    assert_eq!(
        bits(&a.landscape),
        bits(&b.landscape),
        "the same landscape, bit for bit"
    );
    assert_eq!(
        inline.extraction().map(|x| x.eval.dm.to_bits()),
        pooled.extraction().map(|x| x.eval.dm.to_bits())
    );
    let stats = pooled.worker_stats();
    assert_eq!((stats.workers, stats.alive), (3, 2), "{stats:?}");
    assert!(stats.tiles_from_workers >= 576 / 128, "{stats:?}");
    assert!(
        stats.copies >= 1,
        "the lost tile was handed out again: {stats:?}"
    );
    let told: Vec<&str> = pooled
        .messages()
        .iter()
        .map(|m| m.text.as_str())
        .filter(|t| t.contains("worker(s) failed"))
        .collect();
    assert_eq!(told.len(), 1, "the failure is told once: {told:?}");
}

#[test]
fn diagnostics_parts_from_the_pool_equal_the_inline_diagnostics() {
    let mut settings = Settings::with_grid_points(16);
    settings.diagnostics.bootstrap = 6;
    let inline = on_sample(Session::new(Runner::inline()), &settings);
    let pooled = on_sample(pooled(Fake::new(3, Some(0), Some((2, 2)))), &settings);
    let (a, b) = (
        inline.diagnostics().expect("inline diagnostics"),
        pooled.diagnostics().expect("pooled diagnostics"),
    );
    assert!(a.complete() && b.complete());
    assert_eq!(a.diagnostics, b.diagnostics, "the same diagnostics");
    assert!(pooled.worker_stats().parts_from_workers > 0);
}

#[test]
fn rl_runs_trained_by_the_pool_equal_the_inline_runs_and_a_dead_workers_run_restarts() {
    let settings = Settings::with_grid_points(8);
    let request = RlRequest {
        demo: 0,
        options: EnvOptions::default(),
        steps: 1000,
        runs: (0..2)
            .map(|seed| RlRun {
                gains_name: "Hrstc1".into(),
                dm: 25.0,
                km: 156.25,
                seed,
            })
            .collect(),
    };
    let train = |mut session: Session| {
        session.apply(Command::StartRl(request.clone()));
        session.update(&settings);
        session
    };
    let inline = train(on_sample(Session::new(Runner::inline()), &settings));
    // Worker 0 dies at its first run: that run goes to the others.
    let pooled = train(on_sample(
        pooled(Fake::new(3, None, Some((0, 0)))),
        &settings,
    ));
    let (a, b) = (
        inline.rl().expect("inline run").1,
        pooled.rl().expect("pooled run").1,
    );
    assert!(a.done && b.done);
    assert_eq!(a.finished.len(), 2);
    // The same runs, bit for bit, but for the wall-clock seconds.
    let numbers = |finished| {
        let mut v = serde_json::to_value(finished).expect("reports as JSON");
        strip_seconds(&mut v);
        v
    };
    assert_eq!(numbers(&a.finished), numbers(&b.finished), "the same runs");
    assert_eq!(pooled.worker_stats().runs_from_workers, 2);
}

/// Removes every `seconds` field (wall-clock time, different per run).
fn strip_seconds(value: &mut serde_json::Value) {
    match value {
        serde_json::Value::Object(map) => {
            map.remove("seconds");
            map.values_mut().for_each(strip_seconds);
        }
        serde_json::Value::Array(items) => items.iter_mut().for_each(strip_seconds),
        _ => {}
    }
}
