//! The browser tests' hooks (feature `testing`, off in release builds):
//! [`TestHooks`], shared with whoever serves the tests (the page's
//! `window.dmpscope_*` functions, installed by the app's `web` module),
//! carries their requests in and the app's state out
//! (`testing.rs`), and [`FrameWatch`] counts frames.

use std::cell::RefCell;
use std::rc::Rc;

use web_time::Instant;

/// What the tests asked for and what they read.
#[derive(Debug)]
pub struct TestHooks {
    /// Training runs asked for, `(steps, seed)`, not yet started.
    pub train: Vec<(usize, u64)>,
    /// Grid sizes asked for (points per axis), not yet applied.
    pub grid: Vec<usize>,
    /// Gain sets to pin (Table I names or `DM:KM`), not yet pinned.
    pub pin: Vec<String>,
    /// The app's state as JSON, written every frame.
    pub state: String,
    /// The parts of the window `web/tests/frame_probe.mjs` leaves out and
    /// its other requests (frames back to back): bits of `app::part`.
    pub hide: u32,
}

impl Default for TestHooks {
    /// No requests, and an empty JSON object until the first frame.
    fn default() -> Self {
        Self {
            train: Vec::new(),
            grid: Vec::new(),
            pin: Vec::new(),
            state: "{}".to_owned(),
            hide: 0,
        }
    }
}

/// [`TestHooks`] shared between the app and the tests' entry points.
pub type SharedHooks = Rc<RefCell<TestHooks>>;

thread_local! {
    /// This frame's phase ends so far (see [`mark`]).
    static MARKS: RefCell<Vec<(&'static str, Instant)>> =
        const { RefCell::new(Vec::new()) };
}

/// Marks the end of phase `name` of this frame (the session's update, a
/// panel, a part of one), wherever the frame's code is: the browser probes
/// read where a long frame's time went.
pub fn mark(name: &'static str) {
    MARKS.with(|m| m.borrow_mut().push((name, Instant::now())));
}

/// A mark on the page's timeline (Chromium's trace shows it, so a probe
/// can pick the frames while the landscape computes); nothing natively.
fn page_mark(name: &str) {
    #[cfg(target_arch = "wasm32")]
    if let Some(p) = web_sys::window().and_then(|w| w.performance()) {
        let _ = p.mark(name);
    }
    #[cfg(not(target_arch = "wasm32"))]
    let _ = name;
}

/// Frames drawn and the longest interval between frames while the
/// landscape was computing.
#[derive(Default)]
pub struct FrameWatch {
    pub(super) last: Option<Instant>,
    pub(super) frames: u64,
    pub(super) longest_ms_computing: f64,
    /// The frame that ended the longest interval, and what the session was
    /// doing at the frame before it.
    pub(super) longest_at: (u64, String),
    /// The session's status at the last frame.
    pub(super) status: String,
    /// The app's own CPU time of its longest frame while computing (egui's
    /// `cpu_usage`, without the renderer's), and the status then.
    pub(super) cpu_ms_computing: (f64, String),
    /// When this frame's `ui` started.
    pub(super) ui_start: Option<Instant>,
    /// Per frame while computing (the first 40): the interval before it,
    /// egui's CPU of the frame before it (logic and painting) and the
    /// app's own `ui` time of the frame before it, ms.
    pub(super) log: Vec<[f64; 3]>,
    /// The last frame's own `ui` time, ms.
    pub(super) last_ui_ms: f64,
    /// Whether the landscape was computing at the last frame.
    pub(super) last_computing: bool,
    /// The app's own `ui` time of each frame while computing (the first
    /// 5000), ms: the page's own main-thread work per frame. The frame
    /// that starts the landscape (the model built, its bytes posted to the
    /// workers) counts as one.
    pub(super) work_ms: Vec<f64>,
    /// The app's own `ui` time of the frame that started the landscape, ms.
    pub(super) start_work_ms: Option<f64>,
    /// The model version the last frame drew.
    pub(super) model_drawn: Option<u64>,
    /// Whether this frame is the first to draw its model.
    pub(super) new_model: bool,
    /// The app's own `ui` time of each frame that first drew a model (the
    /// first 100), ms: a new model's first layout (in the browser the
    /// landscape starts in the frame after it).
    pub(super) model_work_ms: Vec<f64>,
    /// Per frame while computing (the first 40): the ends of its phases
    /// (see [`mark`]), ms from its `ui` start: where a long frame's time
    /// went.
    pub(super) phases_ms: Vec<Vec<(&'static str, f64)>>,
}

impl FrameWatch {
    /// Records a frame; `computing` says whether the landscape has started
    /// and is not complete, `status` what the session is doing. An interval
    /// counts as one while computing when the landscape was computing at
    /// either of its frames (a frame that starts during the landscape and
    /// ends after it is one the user waited for).
    /// `pass` is egui's pass of the frame: a pass after the first reruns
    /// the same frame (its first pass was discarded) and counts with it.
    pub fn frame(&mut self, computing: bool, status: String, cpu_s: Option<f32>, pass: usize) {
        if pass > 0 && self.ui_start.is_some() {
            return;
        }
        let counts = computing || self.last_computing;
        if computing != self.last_computing {
            page_mark(if computing {
                "dmpscope-landscape-start"
            } else {
                "dmpscope-landscape-end"
            });
        }
        if computing && !self.last_computing && self.start_work_ms.is_none() {
            // The frame before this one started the landscape.
            self.start_work_ms = Some(self.last_ui_ms);
            self.work_ms.push(self.last_ui_ms);
        }
        self.last_computing = computing;
        let now = Instant::now();
        self.ui_start = Some(now);
        let cpu_ms = f64::from(cpu_s.unwrap_or(0.0)) * 1e3;
        if counts && self.log.len() < 40 {
            let gap = self
                .last
                .map_or(0.0, |l| now.duration_since(l).as_secs_f64() * 1e3);
            self.log.push([gap, cpu_ms, self.last_ui_ms]);
        }
        if counts && cpu_ms > self.cpu_ms_computing.0 {
            self.cpu_ms_computing = (cpu_ms, self.status.clone());
        }
        if let Some(last) = self.last
            && counts
        {
            let ms = now.duration_since(last).as_secs_f64() * 1e3;
            if ms > self.longest_ms_computing {
                self.longest_ms_computing = ms;
                self.longest_at = (self.frames, std::mem::take(&mut self.status));
            }
        }
        self.last = Some(now);
        self.frames += 1;
        self.status = status;
    }
}

impl FrameWatch {
    /// Leaves `spent` (the tests' own hook) out of this frame's `ui` time.
    pub fn exclude(&mut self, spent: std::time::Duration) {
        if let Some(start) = &mut self.ui_start {
            *start += spent;
        }
    }

    /// Records the model version this frame drew.
    pub fn model_drawn(&mut self, version: Option<u64>) {
        // Or'ed: a pass egui discards and its rerun are one frame.
        self.new_model |= version.is_some() && version != self.model_drawn;
        self.model_drawn = version;
    }

    /// Records the end of this frame's `ui`, unless egui discards this
    /// pass (`discarded`): the next pass is the same frame, its time
    /// counted from this one's start.
    pub fn ui_done(&mut self, discarded: bool) {
        if discarded {
            return;
        }
        let marks = MARKS.with(|m| std::mem::take(&mut *m.borrow_mut()));
        if let Some(start) = self.ui_start.take() {
            self.last_ui_ms = start.elapsed().as_secs_f64() * 1e3;
            if self.last_computing && self.phases_ms.len() < 40 {
                let ms = |at: Instant| at.saturating_duration_since(start).as_secs_f64() * 1e3;
                self.phases_ms
                    .push(marks.into_iter().map(|(name, at)| (name, ms(at))).collect());
            }
            if std::mem::take(&mut self.new_model) && self.model_work_ms.len() < 100 {
                self.model_work_ms.push(self.last_ui_ms);
            }
            if self.last_computing && self.work_ms.len() < 5000 {
                self.work_ms.push(self.last_ui_ms);
            }
        }
    }
}
