//! A new model's first frames (egui_kittest): before the landscape's first
//! snapshot the heat maps are drawn empty, with their titles and
//! "computing…" across them, and the operating point can be dragged on
//! them already (the landscape's job held back by an executor that runs
//! every other job inline); paced as in the browser, the landscape starts
//! in the frame after the one that showed its model, even when egui ran
//! that frame's `ui` twice.

mod support;

use std::sync::{Arc, Mutex};
use std::time::Duration;

use dmpscope::gui::DmpApp;
use dmpscope::session::executor::{InlineExecutor, Spawned, Task, TaskHandle};
use dmpscope::session::{Executor, PageTime, Runner, Settings, Source, Status};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

/// Runs every job inline but the landscape's, which never steps.
struct HoldLandscape(InlineExecutor);

/// A job that never ends.
struct Held;

impl TaskHandle for Held {
    fn ended(&self) -> bool {
        false
    }
    fn page_time(&self) -> PageTime {
        PageTime::default()
    }
}

impl Executor for HoldLandscape {
    fn spawn(&self, name: &str, task: Box<dyn Task>) -> Spawned {
        if name == "the landscape" {
            Spawned {
                handle: Box::new(Held),
                notice: None,
            }
        } else {
            self.0.spawn(name, task)
        }
    }
    fn threaded(&self) -> bool {
        false
    }
    fn parallel(&self) -> bool {
        false
    }
    fn now(&self) -> Duration {
        self.0.now()
    }
}

#[test]
fn the_maps_are_drawn_empty_until_the_first_snapshot_and_take_the_operating_point() {
    let runner = Runner::new(Arc::new(HoldLandscape(InlineExecutor::new())));
    let sources = vec![Source::Path(support::sample_path())];
    let settings = Settings::with_grid_points(16);
    let mut h = Harness::builder()
        .with_size([1280.0, 800.0])
        .build_eframe(move |_cc| DmpApp::with_runner(settings, sources, runner));
    h.run_steps(3);
    let session = h.state().session();
    assert!(session.model().is_some(), "the model is built");
    assert!(session.shown().is_none(), "no snapshot yet");
    assert!(
        matches!(session.status(), Status::Computing(0, _)),
        "{:?}",
        session.status()
    );
    // J and the small maps, each saying nothing is computed yet.
    let title = h.get_by_label("J = S + k sum d").rect();
    let _j = h.get_by_label("J = S + k sum d map: computing…");
    assert!(
        h.query_all_by_label_contains("map: computing…").count() >= 3,
        "J and the small maps say so"
    );

    // A drag on the empty J map moves the operating point.
    let before = h.state().settings.op;
    let start = egui::pos2(title.left() + 60.0, title.bottom() + 20.0);
    support::drag_from(&mut h, start);
    assert_ne!(h.state().settings.op, before, "the drag moved the point");
    assert!(h.state().session().shown().is_none(), "still no snapshot");
}

/// Runs every job inline and notes the egui frame and pass in which the
/// landscape's job was started.
struct NoteLandscape {
    inline: InlineExecutor,
    ctx: egui::Context,
    started: Arc<Mutex<Vec<(u64, usize)>>>,
}

impl Executor for NoteLandscape {
    fn spawn(&self, name: &str, task: Box<dyn Task>) -> Spawned {
        if name == "the landscape" {
            let at = (
                self.ctx.cumulative_frame_nr(),
                self.ctx.current_pass_index(),
            );
            self.started.lock().expect("not poisoned").push(at);
        }
        self.inline.spawn(name, task)
    }
    fn threaded(&self) -> bool {
        false
    }
    fn parallel(&self) -> bool {
        true
    }
    fn now(&self) -> Duration {
        self.inline.now()
    }
}

#[test]
fn paced_the_landscape_starts_in_the_frame_after_its_model_is_shown() {
    let started = Arc::new(Mutex::new(Vec::new()));
    let noted = Arc::clone(&started);
    let h = Harness::builder()
        .with_size([1280.0, 800.0])
        .build_eframe(move |cc| {
            let runner = Runner::new(Arc::new(NoteLandscape {
                inline: InlineExecutor::new(),
                ctx: cc.egui_ctx.clone(),
                started: noted,
            }));
            let sources = vec![Source::Path(support::sample_path())];
            DmpApp::with_runner_paced(Settings::with_grid_points(16), sources, runner)
        });
    // The model was built before the first frame (frame 0), whose `ui`
    // egui ran twice (a first layout): the landscape starts in frame 1.
    assert!(
        h.ctx.cumulative_pass_nr() > h.ctx.cumulative_frame_nr(),
        "a pass was rerun"
    );
    let started = started.lock().expect("not poisoned").clone();
    assert_eq!(started.len(), 1, "{started:?}");
    assert_eq!(started[0].0, 1, "started in frame 1, pass {}", started[0].1);
}
