//! The browser tests' view of the app (feature `testing`): the requests of
//! [`super::test_hooks::TestHooks`] served and [`DmpApp::test_state`]
//! returned. Nothing here recomputes the pipeline: it reads what the
//! session already holds.

use std::collections::BTreeMap;

use eframe::egui;

use web_time::Instant;

use super::app::DmpApp;
use super::test_hooks::SharedHooks;
use crate::session::Session;

impl DmpApp {
    /// Serves the tests through `hooks` (their requests in, the state out).
    pub fn with_test_hooks(mut self, hooks: SharedHooks) -> Self {
        self.hooks = Some(hooks);
        self
    }

    /// Applies the tests' requests (at the start of every frame's `ui`).
    pub(super) fn serve_test_hooks(&mut self, ctx: &egui::Context) {
        let Some(hooks) = self.hooks.clone() else {
            return;
        };
        // The hook's own time is not the app's.
        let spent = Instant::now();
        let (train, grid, pins) = {
            let mut h = hooks.borrow_mut();
            (
                std::mem::take(&mut h.train),
                std::mem::take(&mut h.grid),
                std::mem::take(&mut h.pin),
            )
        };
        for text in pins {
            self.pin_by_text(&text);
        }
        for (steps, seed) in train {
            self.start_test_training(steps, seed, ctx);
        }
        for n in grid {
            self.settings.set_grid_points(n);
            self.session.update(&self.settings);
        }
        self.frame_watch.exclude(spent.elapsed());
    }

    /// Publishes the state at the end of a frame's last pass: what the
    /// frame showed, where it drew what the tests click, its timing.
    pub(super) fn publish_test_state(&mut self, ctx: &egui::Context) {
        let Some(hooks) = self.hooks.clone() else {
            return;
        };
        let state = self.test_state(ctx).to_string();
        hooks.borrow_mut().state = state;
    }

    /// Per pin, the paths the 3D view drew for it last frame (0 when
    /// hidden).
    fn pin_paths_drawn(&self) -> Vec<usize> {
        let mut drawn = self.view.view3d.pin_paths.iter().copied();
        self.view
            .pins
            .list()
            .iter()
            .map(|p| {
                if p.shown {
                    drawn.next().unwrap_or(0)
                } else {
                    0
                }
            })
            .collect()
    }

    /// Starts training as the RL panel's Train button with the extracted
    /// gains does, on the selected demo, with the default environment.
    pub fn start_test_training(&mut self, steps: usize, seed: u64, ctx: &egui::Context) {
        let Some(x) = self.session().extraction() else {
            return;
        };
        let request = crate::session::RlRequest {
            demo: self.view.selected,
            options: dmpscope_core::rl::env::EnvOptions::default(),
            steps,
            runs: vec![crate::session::RlRun {
                gains_name: "extracted".into(),
                dm: x.eval.dm,
                km: x.eval.km,
                seed,
            }],
        };
        self.apply(crate::session::Command::StartRl(request).into(), ctx);
    }

    /// What the browser tests read: demos, operating point, optimum,
    /// landscape progress, a checksum of the regenerated paths at the
    /// operating point, Table I's rows, frame and slice timings, messages,
    /// the diagnostics so far, the run at a new target.
    pub fn test_state(&self, ctx: &egui::Context) -> serde_json::Value {
        let session = self.session();
        let (dm, km) = self.settings.op;
        let messages: Vec<&str> = session.messages().iter().map(|m| m.text.as_str()).collect();
        let page = session.landscape_page_time();
        let causes: Vec<String> = ctx
            .repaint_causes()
            .iter()
            .map(ToString::to_string)
            .collect();
        serde_json::json!({
            "demos": demo_names(session),
            "loading": session.loading(),
            "op": [dm, km],
            "optimum": optimum_json(session),
            "allowed": session.allowed().map(|v| &v.allowed),
            "buttons": click_targets(&self.view.click_targets),
            "landscape": landscape_progress(session),
            "landscape_points_here": crate::session::landscape::points_computed_here(),
            "workers": session.worker_stats(),
            "regen_checksum": regen_checksum(session),
            "rows": table_rows_json(session),
            "frames": self.frame_watch.frames,
            "longest_frame_ms_computing": self.frame_watch.longest_ms_computing,
            "longest_frame_at": self.frame_watch.longest_at.0,
            "longest_frame_after": self.frame_watch.longest_at.1,
            "longest_frame_cpu_ms": self.frame_watch.cpu_ms_computing.0,
            "longest_frame_cpu_after": self.frame_watch.cpu_ms_computing.1,
            "frame_log_computing": self.frame_watch.log,
            "longest_slice_ms": page.longest_ms,
            "compute_ms": page.total_ms,
            "messages": messages,
            "status": session.status().describe(),
            "diagnostics": diagnostics_json(session),
            "repaint_causes": causes,
            "rl": rl_json(session),
            "generalised": generalised_json(session),
            "raw_demos": raw_demos_json(session),
            "reading": reading_json(session),
            "wasm_memory_bytes": wasm_memory_bytes(),
            "page_frame_work_ms": self.frame_watch.work_ms,
            "page_frame_work_start_ms": self.frame_watch.start_work_ms,
            "page_frame_model_ms": self.frame_watch.model_work_ms,
            "page_frame_phases": self.frame_phases_json(),
            "pins": self.view.pins.list().iter().zip(self.pin_paths_drawn()).map(|(p, paths)| serde_json::json!({
                "name": p.name,
                "dm": p.dm,
                "km": p.km,
                "colour": p.colour,
                "shown": p.shown,
                "paths_3d": paths,
            })).collect::<Vec<_>>(),
            "plot_pin_lines": self.view.plot_pin_lines,
            "playback": {
                "playing": self.view.playback.playing,
                "t": self.view.t,
                "t_target": self.view.t_target,
            },
        })
    }

    /// Where the frames' time went while computing: each frame's phase
    /// ends and each heat map image made, ms (`web/tests/phases_probe.mjs`).
    fn frame_phases_json(&self) -> serde_json::Value {
        serde_json::json!({
            "phases_ms": self.frame_watch.phases_ms,
            "heatmap_build_ms": crate::gui::heatmap::BUILD_MS.with(|ms| ms.borrow().clone()),
        })
    }
}

/// Every demo as loaded: its name, samples, first and last position (the
/// browser test compares them with the native build's).
fn raw_demos_json(session: &Session) -> serde_json::Value {
    session
        .demos()
        .iter()
        .map(|d| {
            let p = &d.raw.positions;
            serde_json::json!({
                "name": d.raw.name,
                "samples": p.len(),
                "first": p.first().map(|v| [v.x, v.y, v.z]),
                "last": p.last().map(|v| [v.x, v.y, v.z]),
                "first_ns": d.raw.stamps_ns.first(),
                "last_ns": d.raw.stamps_ns.last(),
            })
        })
        .collect()
}

/// Each recording being read: its name, bytes read and size.
fn reading_json(session: &Session) -> serde_json::Value {
    session
        .recordings()
        .iter()
        .filter_map(|slot| {
            let (read, size) = slot.progress()?;
            Some(serde_json::json!({"name": slot.source.name(), "read": read, "size": size}))
        })
        .collect()
}

/// The module's linear memory, bytes (0 natively).
fn wasm_memory_bytes() -> u64 {
    #[cfg(target_arch = "wasm32")]
    {
        core::arch::wasm32::memory_size(0) as u64 * 65536
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        0
    }
}

/// The demos' names, none before a model.
fn demo_names(session: &Session) -> Vec<&str> {
    session
        .model()
        .map(|m| m.demos().iter().map(|d| d.name.as_str()).collect())
        .unwrap_or_default()
}

/// The extracted optimum's gains and cost, if there is one.
fn optimum_json(session: &Session) -> Option<serde_json::Value> {
    session.extraction().map(|x| {
        serde_json::json!({
            "dm": x.eval.dm, "km": x.eval.km, "j": x.j,
        })
    })
}

/// Each preset button's rectangle (left, top, width, height) by preset name.
fn click_targets(buttons: &BTreeMap<&'static str, egui::Rect>) -> BTreeMap<String, [f32; 4]> {
    buttons
        .iter()
        .map(|(name, r)| (name.to_string(), [r.min.x, r.min.y, r.width(), r.height()]))
        .collect()
}

/// The shown landscape's progress: points done, of all, and the time so far.
fn landscape_progress(session: &Session) -> serde_json::Value {
    let (done, total, elapsed_ms) = session.shown().map_or((0, 0, 0.0), |s| {
        let snapshot = &s.snapshot;
        let ms = snapshot.elapsed.as_secs_f64() * 1e3;
        (snapshot.done, snapshot.total, ms)
    });
    serde_json::json!({"done": done, "total": total, "elapsed_ms": elapsed_ms})
}

/// A checksum of the regenerated paths at the operating point, once there is a model.
fn regen_checksum(session: &Session) -> Option<f64> {
    session.model().map(|_| {
        session
            .paths()
            .iter()
            .flat_map(|r| &r.y)
            .map(|p| p[0] + 2.0 * p[1] + 3.0 * p[2])
            .sum()
    })
}

/// Table I's rows.
fn table_rows_json(session: &Session) -> Vec<serde_json::Value> {
    session
        .table_rows()
        .iter()
        .map(|r| {
            serde_json::json!({
                "name": r.name, "dm": r.dm, "km": r.km, "j": r.j,
                "d_rot": r.d_rot, "alpha_peak": r.alpha_peak,
            })
        })
        .collect()
}

/// The diagnostics so far and their timings, once they have started.
fn diagnostics_json(session: &Session) -> Option<serde_json::Value> {
    session.diagnostics().map(|d| {
        serde_json::json!({
            "done": d.done,
            "total": d.total,
            "values": d.diagnostics,
            "compute_ms": session.diagnostics_page_time().total_ms,
            "longest_slice_ms": session.diagnostics_page_time().longest_ms,
        })
    })
}

/// The RL run's gains and progress, if there is one.
fn rl_json(session: &Session) -> Option<serde_json::Value> {
    session.rl().map(|(r, p)| {
        serde_json::json!({
            "dm": r.runs.first().map(|r| r.dm),
            "km": r.runs.first().map(|r| r.km),
            "done": p.done,
            "decisions": p.decisions.0,
            "returns": p.returns,
            "final_error": p.greedy.as_ref().map(|g| g.final_error),
            "first_reach": p.first_reach.map(|f| f.decisions),
            "stopped": p.stopped,
        })
    })
}

/// The run at a new target: its figures, or why there is none.
fn generalised_json(session: &Session) -> Option<serde_json::Value> {
    session.generalised().map(|g| match g {
        Ok(g) => serde_json::json!({
            "name": g.primitive.name,
            "start": g.out.start,
            "goal": g.out.goal,
            "duration_s": g.out.duration_s,
            "peak_speed": g.out.peak_speed,
            "a_peak": g.out.a_peak,
            "final_error": g.out.final_error,
        }),
        Err(e) => serde_json::json!({ "error": e }),
    })
}
