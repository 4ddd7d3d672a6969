//! The app's state and frame: demos on the left, the three heat maps, Table I
//! and the time plots in the middle. Work that takes longer than a frame
//! (the landscape) runs in a [`Worker`]; everything else is recomputed in
//! the frame from the stage that changed (see ARCHITECTURE.md).

use std::path::PathBuf;
use std::sync::Arc;

use dmpscope_core::dmp::DmpSettings;
use dmpscope_core::presets::PAPER_PRESETS;
use dmpscope_core::{Extraction, Model, PrepSettings, TableRow, extract, prepare};
use eframe::egui::{self, Color32};

use super::frame_log::FrameLog;
use super::heatmap::{self, Cache, MapInput, Marker};
use super::loading::{DemoEntry, load_files, sample_path};
use super::settings::Settings;
use super::worker::{Snapshot, Worker};
use super::{plots, table};

const SETTINGS_KEY: &str = "dmpscope-settings";

/// The landscape as shown: the latest snapshot, its preview-filled grids and
/// J for the current k.
struct Shown {
    snapshot: Snapshot,
    d_sum: Vec<f64>,
    s: Vec<f64>,
    j: Vec<f64>,
    k: f64,
}

/// The desktop app.
pub struct DmpApp {
    /// The user's settings (persisted).
    pub settings: Settings,
    files: Vec<PathBuf>,
    demos: Vec<DemoEntry>,
    messages: Vec<String>,
    model: Option<Arc<Model>>,
    model_inputs: Option<(Vec<bool>, usize, usize, usize)>,
    worker: Option<Worker>,
    shown: Option<Shown>,
    /// The extracted gains for the current k, once the landscape is complete.
    pub extraction: Option<Extraction>,
    preset_rows: Vec<TableRow>,
    selected: usize,
    caches: [Cache; 3],
    frame_log: Option<FrameLog>,
}

impl DmpApp {
    /// The app on `files` (the bundled sample when empty), with settings
    /// restored from eframe's storage.
    pub fn new(cc: &eframe::CreationContext<'_>, files: Vec<PathBuf>) -> Self {
        let settings = cc
            .storage
            .and_then(|s| eframe::get_value::<Settings>(s, SETTINGS_KEY))
            .unwrap_or_default();
        Self::with_settings(settings, files)
    }

    /// The app with explicit settings (tests).
    pub fn with_settings(settings: Settings, files: Vec<PathBuf>) -> Self {
        let files = if files.is_empty() {
            vec![sample_path()]
        } else {
            files
        };
        let loaded = load_files(&files);
        Self {
            settings,
            files,
            demos: loaded.demos,
            messages: loaded.messages,
            model: None,
            model_inputs: None,
            worker: None,
            shown: None,
            extraction: None,
            preset_rows: Vec::new(),
            selected: 0,
            caches: Default::default(),
            frame_log: FrameLog::from_env(),
        }
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

    /// Adds files (a drop, a dialog) and reloads.
    pub fn add_files(&mut self, files: Vec<PathBuf>) {
        let loaded = load_files(&files);
        self.messages.extend(loaded.messages);
        self.demos.extend(loaded.demos);
        self.files.extend(files);
    }

    /// Brings the model, the worker, the extraction and the cached rows up to
    /// date with the settings; cheap when nothing changed.
    pub fn refresh(&mut self, ctx: &egui::Context) {
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
        if let Some(worker) = &self.worker
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
        if self.extraction.is_none()
            && self.landscape_complete()
            && let (Some(model), Some(shown)) = (&self.model, &self.shown)
        {
            match extract(model, &shown.snapshot.landscape, k) {
                Ok(x) => self.extraction = Some(x),
                Err(e) => self.messages.push(format!("extraction: {e}")),
            }
        }
    }

    fn rebuild_model(&mut self) {
        self.model = None;
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

    /// Blocks until the landscape is complete (tests and screenshots).
    pub fn wait_for_landscape(&mut self, ctx: &egui::Context) {
        self.refresh(ctx);
        while self.worker.is_some() && !self.landscape_complete() {
            std::thread::sleep(std::time::Duration::from_millis(5));
            self.refresh(ctx);
        }
        self.refresh(ctx);
    }

    fn side_panel(&mut self, ui: &mut egui::Ui, ctx: &egui::Context) {
        ui.heading("Demos");
        let mut changed = false;
        egui::ScrollArea::vertical()
            .max_height(220.0)
            .show(ui, |ui| {
                for entry in &mut self.demos {
                    let info = &entry.info;
                    let text = format!(
                        "{}  ({} samples, {:.2} s)",
                        info.name, info.n_samples, info.duration_s
                    );
                    changed |= ui.checkbox(&mut entry.included, text).changed();
                }
            });
        if changed {
            self.refresh(ctx);
        }
        if !self.messages.is_empty() {
            ui.separator();
            for m in &self.messages {
                ui.colored_label(Color32::from_rgb(240, 120, 100), m);
            }
            if ui.small_button("Clear messages").clicked() {
                self.messages.clear();
            }
        }
        ui.separator();
        ui.heading("Gains");
        let s = &mut self.settings;
        ui.horizontal(|ui| {
            let label = ui.label("k");
            ui.add(egui::Slider::new(&mut s.k, 0.0..=200.0).logarithmic(true))
                .labelled_by(label.id);
        });
        ui.horizontal(|ui| {
            let label = ui.label("D/M");
            ui.add(
                egui::DragValue::new(&mut s.op.0)
                    .speed(0.1)
                    .range(s.dm_range.0..=s.dm_range.1),
            )
            .labelled_by(label.id);
            let label = ui.label("K/M");
            ui.add(
                egui::DragValue::new(&mut s.op.1)
                    .speed(0.5)
                    .range(s.km_range.0..=s.km_range.1),
            )
            .labelled_by(label.id);
        });
        ui.horizontal_wrapped(|ui| {
            for p in PAPER_PRESETS {
                if ui.button(p.name).clicked() {
                    s.op = (p.dm, p.km);
                }
            }
            if let Some(x) = &self.extraction
                && ui.button("Extracted").clicked()
            {
                s.op = (x.eval.dm, x.eval.km);
            }
        });
        match &self.extraction {
            Some(x) => {
                ui.label(format!(
                    "Extracted (M:D:K) = 1 : {:.3} : {:.3}, zeta {:.3}, J {:.4}",
                    x.eval.dm, x.eval.km, x.eval.zeta, x.j
                ));
                if x.on_edge() {
                    ui.colored_label(
                        Color32::from_rgb(240, 180, 80),
                        format!("On the box edge: {}", x.edges.describe()),
                    );
                    if ui.button("Widen the box 10x that way").clicked() {
                        let e = x.edges;
                        let s = &mut self.settings;
                        if e.dm_low {
                            s.dm_range.0 /= 10.0;
                        }
                        if e.dm_high {
                            s.dm_range.1 *= 10.0;
                        }
                        if e.km_low {
                            s.km_range.0 /= 10.0;
                        }
                        if e.km_high {
                            s.km_range.1 *= 10.0;
                        }
                        self.restart_landscape(ctx);
                    }
                }
            }
            None => {
                ui.label("Extracted: waiting for the full landscape");
            }
        }
        ui.separator();
        ui.collapsing("Settings", |ui| self.settings_ui(ui, ctx));
    }

    fn settings_ui(&mut self, ui: &mut egui::Ui, ctx: &egui::Context) {
        let before = self.settings.clone();
        let s = &mut self.settings;
        egui::Grid::new("settings").show(ui, |ui| {
            let l = ui.label("grid points");
            ui.add(egui::DragValue::new(&mut s.grid_n).range(8..=512))
                .labelled_by(l.id);
            ui.end_row();
            let l = ui.label("D/M range");
            ui.horizontal(|ui| {
                ui.add(
                    egui::DragValue::new(&mut s.dm_range.0)
                        .speed(0.01)
                        .range(1e-6..=1e6),
                )
                .labelled_by(l.id);
                ui.add(
                    egui::DragValue::new(&mut s.dm_range.1)
                        .speed(1.0)
                        .range(1e-6..=1e7),
                )
                .labelled_by(l.id);
            });
            ui.end_row();
            let l = ui.label("K/M range");
            ui.horizontal(|ui| {
                ui.add(
                    egui::DragValue::new(&mut s.km_range.0)
                        .speed(0.01)
                        .range(1e-6..=1e6),
                )
                .labelled_by(l.id);
                ui.add(
                    egui::DragValue::new(&mut s.km_range.1)
                        .speed(1.0)
                        .range(1e-6..=1e7),
                )
                .labelled_by(l.id);
            });
            ui.end_row();
            ui.label("axes");
            ui.checkbox(&mut s.log_axes, "log-spaced");
            ui.end_row();
            ui.label("colours");
            ui.checkbox(&mut s.log_colour, "log scale");
            ui.end_row();
            let l = ui.label("SG window / order");
            ui.horizontal(|ui| {
                ui.add(egui::DragValue::new(&mut s.sg_window).range(5..=101))
                    .labelled_by(l.id);
                ui.add(egui::DragValue::new(&mut s.sg_order).range(2..=6))
                    .labelled_by(l.id);
            });
            ui.end_row();
            let l = ui.label("basis functions");
            ui.add(egui::DragValue::new(&mut s.basis).range(2..=500))
                .labelled_by(l.id);
            ui.end_row();
        });
        if s.sg_window.is_multiple_of(2) {
            s.sg_window += 1;
        }
        let grid_changed = s.grid_n != before.grid_n
            || s.dm_range != before.dm_range
            || s.km_range != before.km_range
            || s.log_axes != before.log_axes;
        if grid_changed && self.settings.grid().validate().is_ok() {
            self.restart_landscape(ctx);
        }
    }

    fn maps(&mut self, ui: &mut egui::Ui) {
        let Some(shown) = &self.shown else {
            ui.label("Computing the landscape…");
            return;
        };
        let grid = shown.snapshot.landscape.grid;
        let mut markers: Vec<Marker> = PAPER_PRESETS
            .iter()
            .map(|p| Marker {
                label: p.name.to_owned(),
                dm: p.dm,
                km: p.km,
                colour: Color32::from_rgb(255, 160, 200),
            })
            .collect();
        if let Some(x) = &self.extraction {
            markers.push(Marker {
                label: "optimum".into(),
                dm: x.eval.dm,
                km: x.eval.km,
                colour: Color32::from_rgb(255, 90, 60),
            });
        }
        let n_km = grid.km.n;
        let readout = |i: usize, j: usize| {
            let idx = i * n_km + j;
            (shown.d_sum[idx], shown.s[idx], shown.j[idx])
        };
        let version = shown.snapshot.version;
        let k_bits = shown.k.to_bits();
        let maps: [(&str, &[f64]); 3] = [
            ("sum d [m]", &shown.d_sum),
            ("S", &shown.s),
            ("J = S + k sum d", &shown.j),
        ];
        let mut op = self.settings.op;
        let log_colour = self.settings.log_colour;
        let [c_d, c_s, c_j] = &mut self.caches;
        let mut map = |ui: &mut egui::Ui,
                       cache: &mut Cache,
                       (title, values): (&str, &[f64]),
                       k_key: u64,
                       side: f32| {
            let input = MapInput {
                title,
                values,
                key: (version, k_key),
                grid,
                log_colour,
                readout: &readout,
            };
            heatmap::show(ui, cache, &input, &markers, &mut op, side);
        };
        // J large on the left, sum d and S stacked on the right.
        let size = ui.available_size();
        let big = heatmap::side_for(egui::vec2(size.x * 0.6, size.y));
        let small = heatmap::side_for(egui::vec2(size.x * 0.4, size.y / 2.0));
        ui.horizontal_top(|ui| {
            ui.vertical(|ui| map(ui, c_j, maps[2], k_bits, big));
            ui.vertical(|ui| {
                map(ui, c_d, maps[0], 0, small);
                map(ui, c_s, maps[1], 0, small);
            });
        });
        self.settings.op = op;
    }
}

impl eframe::App for DmpApp {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        let ctx = ui.ctx().clone();
        let complete = self.landscape_complete();
        if let Some(log) = &mut self.frame_log {
            // Only frames after the landscape is complete: the drag.
            if complete {
                log.frame(frame.info().cpu_usage);
            } else {
                log.reset();
            }
        }
        let dropped: Vec<PathBuf> = ctx.input(|i| {
            i.raw
                .dropped_files
                .iter()
                .map(|f| f.path().to_path_buf())
                .filter(|p| !p.as_os_str().is_empty())
                .collect()
        });
        if !dropped.is_empty() {
            self.add_files(dropped);
        }
        self.refresh(&ctx);
        egui::Panel::top("top").show(ui, |ui| {
            ui.horizontal(|ui| {
                ui.strong("dmpscope");
                ui.label(format!(
                    "{} file(s), {} demos",
                    self.files.len(),
                    self.demos.len()
                ));
                if let Some(shown) = &self.shown {
                    let (done, total) = (shown.snapshot.done, shown.snapshot.total);
                    if done < total {
                        ui.add(
                            egui::ProgressBar::new(done as f32 / total.max(1) as f32)
                                .desired_width(200.0)
                                .text(format!("landscape {done}/{total}")),
                        );
                        if ui.button("Cancel").clicked()
                            && let Some(w) = &self.worker
                        {
                            w.cancel();
                        }
                    }
                }
                ui.label("Drop .mcap or .csv files on the window to add them.");
            });
        });
        egui::Panel::left("side")
            .default_size(330.0)
            .show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| self.side_panel(ui, &ctx));
            });
        let names = self.demo_names();
        egui::Panel::right("plots")
            .default_size(380.0)
            .show(ui, |ui| {
                if let Some(model) = self.model.clone() {
                    egui::ComboBox::from_label("demo")
                        .selected_text(names.get(self.selected).cloned().unwrap_or_default())
                        .show_ui(ui, |ui| {
                            for (i, n) in names.iter().enumerate() {
                                ui.selectable_value(&mut self.selected, i, n);
                            }
                        });
                    let (dm, km) = self.settings.op;
                    let rollout = model.rollout(self.selected, dm, km);
                    plots::show(ui, &model.demos()[self.selected], &rollout);
                }
            });
        let rows = self.table_rows();
        egui::Panel::bottom("table")
            .default_size(200.0)
            .show(ui, |ui| {
                table::show(ui, &rows, &names);
            });
        egui::CentralPanel::default().show(ui, |ui| self.maps(ui));
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        eframe::set_value(storage, SETTINGS_KEY, &self.settings);
    }
}
