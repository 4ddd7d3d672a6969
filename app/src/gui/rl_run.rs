//! RL training off the frame: natively a thread runs the core's
//! [`Trainer`]; in the browser short slices of [`Trainer::step`] run
//! between frames. Either way the app reads a [`Progress`] (the learning
//! curve, the latest greedy path) and can cancel.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};

use dmpscope_core::Model;
use dmpscope_core::rl::{DmpEnv, GreedyRun, PpoConfig, Trainer};

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
    /// Finished (or cancelled).
    pub done: bool,
}

/// A training run.
pub struct RlRun {
    /// The demo (model index) and gains trained for.
    pub what: (usize, f64, f64, String),
    progress: Arc<Mutex<Progress>>,
    cancel: Arc<AtomicBool>,
}

/// The loop both platforms share: `slice` says whether to yield now.
struct Loop {
    trainer: Trainer,
    model: Arc<Model>,
    demo: usize,
    steps: usize,
    progress: Arc<Mutex<Progress>>,
    cancel: Arc<AtomicBool>,
    started: web_time::Instant,
}

impl Loop {
    fn finish(&self, wake: &dyn Fn()) -> bool {
        if let Ok(mut p) = self.progress.lock() {
            p.done = true;
        }
        wake();
        true
    }

    /// Steps until `stop()` says so; returns true when training is over.
    fn run(&mut self, mut stop: impl FnMut() -> bool, wake: &dyn Fn()) -> bool {
        loop {
            if self.cancel.load(Ordering::Relaxed) {
                return self.finish(wake);
            }
            if let Some(stats) = self.trainer.step() {
                let greedy = self.trainer.greedy();
                let d = self.model.path_error(self.demo, &greedy.path);
                if let Ok(mut p) = self.progress.lock() {
                    p.decisions = (stats.decisions, self.steps);
                    p.returns = self.trainer.returns.clone();
                    p.greedy = Some(greedy);
                    p.d = d;
                    p.seconds = self.started.elapsed().as_secs_f64();
                }
                wake();
                // Training ends on an iteration's boundary.
                if stats.decisions >= self.steps {
                    return self.finish(wake);
                }
            }
            if stop() {
                return false;
            }
        }
    }
}

impl RlRun {
    /// Starts training `steps` decisions on demo `demo` of `model` at
    /// (`dm`, `km`) from `seed`; `wake` repaints.
    pub fn start(
        model: Arc<Model>,
        demo: usize,
        gains: (String, f64, f64),
        steps: usize,
        seed: u64,
        wake: impl Fn() + Send + 'static,
    ) -> dmpscope_core::Result<Self> {
        let (name, dm, km) = gains;
        let env = DmpEnv::new(&model.demos()[demo], dm, km)?;
        let progress = Arc::new(Mutex::new(Progress {
            decisions: (0, steps),
            ..Progress::default()
        }));
        let cancel = Arc::new(AtomicBool::new(false));
        let mut lp = Loop {
            trainer: Trainer::new(env, PpoConfig::default(), seed),
            model,
            demo,
            steps,
            progress: progress.clone(),
            cancel: cancel.clone(),
            started: web_time::Instant::now(),
        };
        #[cfg(not(target_arch = "wasm32"))]
        std::thread::spawn(move || {
            lp.run(|| false, &wake);
        });
        #[cfg(target_arch = "wasm32")]
        wasm_bindgen_futures::spawn_local(async move {
            loop {
                let start = web_time::Instant::now();
                let over = lp.run(|| start.elapsed().as_secs_f64() > 0.010, &wake);
                if over {
                    return;
                }
                super::worker::yield_to_browser().await;
            }
        });
        Ok(Self {
            what: (demo, dm, km, name),
            progress,
            cancel,
        })
    }

    /// The progress so far.
    pub fn progress(&self) -> Progress {
        self.progress.lock().map(|p| p.clone()).unwrap_or_default()
    }

    /// Stops training (the last published policy stays).
    pub fn cancel(&self) {
        self.cancel.store(true, Ordering::Relaxed);
    }
}

impl Drop for RlRun {
    fn drop(&mut self) {
        self.cancel();
    }
}
