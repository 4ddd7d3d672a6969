//! The app's state and how it follows the settings: demos -> model ->
//! landscape (in a [`Worker`]) -> extraction and Table I. Work that takes
//! longer than a frame (the landscape) runs in the worker; everything else
//! is recomputed from the stage that changed (see ARCHITECTURE.md). The
//! frame's layout is in `frame.rs`, the side panel in `side.rs`.

use std::path::PathBuf;
use std::sync::Arc;

use dmpscope_core::dmp::DmpSettings;
use dmpscope_core::{Extraction, Model, PrepSettings, TableRow, extract, prepare};
use eframe::egui;
use eframe::egui_wgpu;

use super::file_dialog::Dialogs;
use super::frame_log::{FrameLog, FrameWatch};
use super::heatmap::Cache;
use super::loading::{DemoEntry, PendingLoad, Source, sample_source};
use super::rl_panel::RlChoices;
use super::rl_run::RlRun;
use super::settings::Settings;
use super::task::Task;
use super::view3d::View3d;
use super::worker::{Snapshot, Worker};

/// An extraction off the frame.
type ExtractionTask = Task<dmpscope_core::Result<Extraction>>;

pub(super) const SETTINGS_KEY: &str = "dmpscope-settings";

/// The landscape as shown: the latest snapshot, its preview-filled grids and
/// J for the current k.
pub(super) struct Shown {
    pub(super) snapshot: Snapshot,
    pub(super) d_sum: Vec<f64>,
    pub(super) s: Vec<f64>,
    pub(super) j: Vec<f64>,
    pub(super) k: f64,
}

/// The desktop app.
pub struct DmpApp {
    /// The user's settings (persisted).
    pub settings: Settings,
    /// Names of the sources loaded or loading.
    pub(super) files: Vec<String>,
    /// Open and save dialogs under way.
    pub(super) dialogs: Dialogs,
    /// Loads under way.
    pub(super) pending: Vec<PendingLoad>,
    pub(super) demos: Vec<DemoEntry>,
    pub(super) messages: Vec<String>,
    pub(super) model: Option<Arc<Model>>,
    pub(super) model_inputs: Option<(Vec<bool>, usize, usize, usize)>,
    pub(super) worker: Option<Worker>,
    pub(super) shown: Option<Shown>,
    /// The extracted gains for the current k, once the landscape is complete.
    pub extraction: Option<Extraction>,
    /// The extraction under way, keyed by (k bits, snapshot version).
    pub(super) extracting: Option<((u64, u64), ExtractionTask)>,
    pub(super) preset_rows: Vec<TableRow>,
    pub(super) selected: usize,
    pub(super) caches: [Cache; 3],
    pub(super) frame_log: Option<FrameLog>,
    /// The 3D view's camera and toggles.
    pub(super) view3d: View3d,
    /// The time cursor shared by the 3D view and the plots, unit time.
    pub(super) t: f64,
    /// The longest frame interval while the landscape computes.
    pub(super) frame_times: FrameWatch,
    /// The RL panel's choices.
    pub rl_choices: RlChoices,
    /// The RL training run, if one was started.
    pub(super) rl: Option<RlRun>,
}

impl DmpApp {
    /// The app on `files` (the bundled sample when empty), with settings
    /// restored from eframe's storage.
    pub fn new(cc: &eframe::CreationContext<'_>, files: Vec<PathBuf>) -> Self {
        let settings = cc
            .storage
            .and_then(|s| eframe::get_value::<Settings>(s, SETTINGS_KEY))
            .unwrap_or_default();
        Self::with_settings(settings, files).with_render_state(cc.wgpu_render_state.as_ref())
    }

    /// The app with explicit settings (tests).
    pub fn with_settings(settings: Settings, files: Vec<PathBuf>) -> Self {
        let sources = if files.is_empty() {
            vec![sample_source()]
        } else {
            files.into_iter().map(Source::Path).collect()
        };
        let mut app = Self {
            settings,
            files: Vec::new(),
            pending: Vec::new(),
            dialogs: Dialogs::default(),
            demos: Vec::new(),
            messages: Vec::new(),
            model: None,
            model_inputs: None,
            worker: None,
            shown: None,
            extraction: None,
            extracting: None,
            preset_rows: Vec::new(),
            selected: 0,
            caches: Default::default(),
            frame_log: FrameLog::from_env(),
            view3d: View3d::new(None),
            t: 0.5,
            frame_times: FrameWatch::default(),
            rl_choices: RlChoices::default(),
            rl: None,
        };
        app.add_sources(sources, || {});
        app
    }

    /// Draws the 3D view with the wgpu pipeline of `render_state` (none:
    /// the view says it needs one).
    pub fn with_render_state(mut self, render_state: Option<&egui_wgpu::RenderState>) -> Self {
        self.view3d = View3d::new(render_state);
        self
    }

    /// What the browser tests read (`window.dmpscope_state()`): demos,
    /// operating point, optimum, landscape progress, a checksum of the
    /// regenerated paths at the operating point, Table I's rows and the
    /// longest frame interval while the landscape computed.
    pub fn test_state(&self) -> serde_json::Value {
        let (dm, km) = self.settings.op;
        let (done, total) = self
            .shown
            .as_ref()
            .map_or((0, 0), |s| (s.snapshot.done, s.snapshot.total));
        let regen_checksum = self.model.as_ref().map(|m| {
            (0..m.demos().len())
                .flat_map(|i| m.rollout(i, dm, km).y)
                .map(|p| p[0] + 2.0 * p[1] + 3.0 * p[2])
                .sum::<f64>()
        });
        let rows: Vec<_> = self
            .table_rows()
            .iter()
            .map(|r| serde_json::json!({"name": r.name, "dm": r.dm, "km": r.km, "j": r.j}))
            .collect();
        serde_json::json!({
            "demos": self.demo_names(),
            "loading": self.loading(),
            "op": [dm, km],
            "optimum": self.extraction.as_ref().map(|x| serde_json::json!({
                "dm": x.eval.dm, "km": x.eval.km, "j": x.j,
            })),
            "landscape": {"done": done, "total": total},
            "regen_checksum": regen_checksum,
            "rows": rows,
            "frames": self.frame_times.frames,
            "longest_frame_ms_computing": self.frame_times.longest_ms_computing,
            "longest_slice_ms": self.slice_ms().0,
            "compute_ms": self.slice_ms().1,
            "messages": self.messages,
        })
    }

    /// The longest slice of landscape work in the browser and all slices,
    /// ms (0 natively, where a thread computes it).
    fn slice_ms(&self) -> (f64, f64) {
        #[cfg(target_arch = "wasm32")]
        if let Some(w) = &self.worker {
            return w.slice_ms();
        }
        (0.0, 0.0)
    }

    /// The RL training's progress, if a run was started.
    pub fn rl_progress(&self) -> Option<super::rl_run::Progress> {
        self.rl.as_ref().map(RlRun::progress)
    }

    /// Whether the landscape is complete.
    pub fn landscape_complete(&self) -> bool {
        self.shown
            .as_ref()
            .is_some_and(|s| s.snapshot.done == s.snapshot.total)
    }

    /// Names of the demos in the model.
    pub fn demo_names(&self) -> Vec<String> {
        self.model
            .as_ref()
            .map(|m| m.demos().iter().map(|d| d.name.clone()).collect())
            .unwrap_or_default()
    }

    /// Table I: extracted (when known), the paper's gains, the operating point.
    pub fn table_rows(&self) -> Vec<TableRow> {
        let Some(model) = &self.model else {
            return Vec::new();
        };
        let k = self.settings.k;
        let mut rows = Vec::new();
        if let Some(x) = &self.extraction {
            rows.push(TableRow::from_eval("Extracted", &x.eval, k));
        }
        rows.extend(self.preset_rows.iter().cloned());
        let (dm, km) = self.settings.op;
        rows.push(TableRow::from_eval(
            "Operating point",
            &model.evaluate(dm, km),
            k,
        ));
        rows
    }

    /// Adds files (a drop, a dialog, the command line): they load off the
    /// frame and join the demos when done; `wake` is called then.
    pub fn add_sources(&mut self, sources: Vec<Source>, wake: impl Fn() + Send + 'static) {
        if sources.is_empty() {
            return;
        }
        self.files.extend(sources.iter().map(Source::name));
        self.pending.push(PendingLoad::start(sources, wake));
    }

    /// Adds files by path (see [`Self::add_sources`]).
    pub fn add_files(&mut self, files: Vec<PathBuf>, ctx: &egui::Context) {
        let ctx = ctx.clone();
        self.add_sources(files.into_iter().map(Source::Path).collect(), move || {
            ctx.request_repaint();
        });
    }

    /// Whether files are still loading.
    pub fn loading(&self) -> bool {
        !self.pending.is_empty()
    }

    fn poll_loads(&mut self) {
        let mut still = Vec::new();
        for mut p in std::mem::take(&mut self.pending) {
            match p.poll() {
                Some(loaded) => {
                    self.messages.extend(loaded.messages);
                    self.demos.extend(loaded.demos);
                }
                None => still.push(p),
            }
        }
        self.pending = still;
    }

    /// Brings the model, the worker, the extraction and the cached rows up to
    /// date with the settings; cheap when nothing changed.
    pub fn refresh(&mut self, ctx: &egui::Context) {
        self.poll_loads();
        let inputs = (
            self.demos.iter().map(|d| d.included).collect::<Vec<_>>(),
            self.settings.sg_window,
            self.settings.sg_order,
            self.settings.basis,
        );
        if self.model_inputs.as_ref() != Some(&inputs) {
            self.model_inputs = Some(inputs);
            self.rebuild_model();
            self.restart_landscape(ctx);
        }
        if let Some(worker) = &mut self.worker
            && let Some(snapshot) = worker.latest()
            && self
                .shown
                .as_ref()
                .is_none_or(|s| s.snapshot.version != snapshot.version)
        {
            self.show_snapshot(snapshot);
        }
        let k = self.settings.k;
        if let Some(shown) = &mut self.shown
            && shown.k != k
        {
            shown.j = shown
                .snapshot
                .landscape
                .preview(&shown.snapshot.landscape.j(k));
            shown.k = k;
            self.extraction = None;
            self.refresh_presets();
        }
        self.refresh_extraction(ctx);
    }

    /// Extracts the optimum off the frame once the landscape is complete,
    /// again for each new k; a stale answer (k or landscape changed) is
    /// dropped.
    fn refresh_extraction(&mut self, ctx: &egui::Context) {
        let k = self.settings.k;
        if let Some((key, task)) = &mut self.extracting
            && let Some(answer) = task.poll()
        {
            let current = self
                .shown
                .as_ref()
                .map(|s| (k.to_bits(), s.snapshot.version));
            if current == Some(*key) {
                match answer.and_then(|r| r.map_err(|e| e.to_string())) {
                    Ok(x) => self.extraction = Some(x),
                    Err(e) => self.messages.push(format!("extraction: {e}")),
                }
            }
            self.extracting = None;
        }
        if self.extraction.is_none()
            && self.extracting.is_none()
            && self.landscape_complete()
            && let (Some(model), Some(shown)) = (&self.model, &self.shown)
        {
            let key = (k.to_bits(), shown.snapshot.version);
            let (model, landscape) = (Arc::clone(model), shown.snapshot.landscape.clone());
            let wake = {
                let ctx = ctx.clone();
                move || ctx.request_repaint()
            };
            let task = Task::start("extraction", move || extract(&model, &landscape, k), wake);
            self.extracting = Some((key, task));
        }
    }

    /// Whether the optimum is being extracted.
    pub fn extracting(&self) -> bool {
        self.extracting.is_some()
    }

    fn rebuild_model(&mut self) {
        self.model = None;
        self.rl = None;
        self.view3d.reset();
        self.shown = None;
        self.extraction = None;
        self.preset_rows.clear();
        let prep = PrepSettings {
            sg_window: self.settings.sg_window,
            sg_order: self.settings.sg_order,
            ..PrepSettings::default()
        };
        let mut prepared = Vec::new();
        for entry in self.demos.iter().filter(|d| d.included) {
            match prepare(&entry.raw, &prep) {
                Ok(p) => prepared.push(p),
                Err(e) => self.messages.push(e.to_string()),
            }
        }
        if prepared.is_empty() {
            return;
        }
        let dmp = DmpSettings {
            basis_functions: self.settings.basis,
            ..DmpSettings::default()
        };
        match Model::new(prepared, dmp) {
            Ok(m) => {
                self.model = Some(Arc::new(m));
                self.selected = self.selected.min(self.demo_names().len().saturating_sub(1));
                self.refresh_presets();
            }
            Err(e) => self.messages.push(e.to_string()),
        }
    }

    fn refresh_presets(&mut self) {
        if let Some(model) = &self.model {
            self.preset_rows = dmpscope_core::presets::preset_rows(model, self.settings.k);
        }
    }

    /// Starts the landscape again for the current grid (a new setting
    /// cancels the stale work: dropping the old worker stops it).
    pub fn restart_landscape(&mut self, ctx: &egui::Context) {
        self.worker = None;
        self.shown = None;
        self.extraction = None;
        let Some(model) = &self.model else { return };
        let wake = {
            let ctx = ctx.clone();
            move || ctx.request_repaint()
        };
        match Worker::start(model.clone(), self.settings.grid(), wake) {
            Ok(w) => self.worker = Some(w),
            Err(e) => self.messages.push(e.to_string()),
        }
    }

    fn show_snapshot(&mut self, snapshot: Snapshot) {
        let l = &snapshot.landscape;
        let k = self.settings.k;
        let shown = Shown {
            d_sum: l.preview(&l.d_sum),
            s: l.preview(&l.s),
            j: l.preview(&l.j(k)),
            k,
            snapshot,
        };
        self.shown = Some(shown);
    }

    /// Blocks until loading, the landscape and the extraction are done
    /// (tests and screenshots).
    pub fn wait_for_landscape(&mut self, ctx: &egui::Context) {
        self.refresh(ctx);
        while self.loading() {
            std::thread::sleep(std::time::Duration::from_millis(2));
            self.refresh(ctx);
        }
        while self.worker.is_some() && !self.landscape_complete() {
            std::thread::sleep(std::time::Duration::from_millis(5));
            self.refresh(ctx);
        }
        self.refresh(ctx);
        while self.extracting() {
            std::thread::sleep(std::time::Duration::from_millis(2));
            self.refresh(ctx);
        }
    }
}
