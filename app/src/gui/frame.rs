//! The frame: a top bar (files, progress, cancel), the side panel, the
//! heat maps over the 3D view in the middle, the time plots on the right and
//! Table I at the bottom.

use dmpscope_core::presets::PAPER_PRESETS;
use eframe::egui::{self, Color32};

use super::app::{DmpApp, SETTINGS_KEY};
use super::heatmap::{self, Cache, MapInput, Marker};
use super::{plots, table};

impl DmpApp {
    fn maps(&mut self, ui: &mut egui::Ui, height: f32) {
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
        // J on the left, sum d and S stacked on the right, within `height`.
        let width = ui.available_width();
        let big = heatmap::side_for(egui::vec2(width * 0.5, height));
        let small = heatmap::side_for(egui::vec2(width * 0.5, height * 0.5));
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
        self.frame_times.frame(complete);
        self.take_inputs(&ctx);
        self.refresh(&ctx);
        #[cfg(target_arch = "wasm32")]
        {
            let mut state = self.test_state();
            state["repaint_causes"] = ctx
                .repaint_causes()
                .iter()
                .map(|c| c.to_string())
                .collect::<Vec<_>>()
                .into();
            crate::web::publish_state(state.to_string());
        }
        egui::Panel::top("top").show(ui, |ui| self.top_bar(ui, &ctx));
        egui::Panel::left("side")
            .default_size(330.0)
            .min_size(280.0)
            .show(ui, |ui| {
                ui.set_min_size(ui.available_size());
                egui::ScrollArea::vertical().show(ui, |ui| self.side_panel(ui, &ctx));
            });
        let names = self.demo_names();
        let model = self.model.clone();
        // The regenerations of every demo at the operating point, every
        // frame (10 demos: about 0.1 ms).
        let (dm, km) = self.settings.op;
        let regen: Vec<_> = model
            .as_ref()
            .map(|m| (0..m.demos().len()).map(|i| m.rollout(i, dm, km)).collect())
            .unwrap_or_default();
        // Panels claim their whole size, so the layout does not depend on
        // what the first frames had to show (files load off the frame).
        egui::Panel::right("plots")
            .default_size(380.0)
            .min_size(340.0)
            .show(ui, |ui| {
                ui.set_min_size(ui.available_size());
                if let Some(model) = &model {
                    ui.horizontal(|ui| {
                        egui::ComboBox::from_label("demo")
                            .selected_text(names.get(self.selected).cloned().unwrap_or_default())
                            .show_ui(ui, |ui| {
                                for (i, n) in names.iter().enumerate() {
                                    ui.selectable_value(&mut self.selected, i, n);
                                }
                            });
                    });
                    let demo = &model.demos()[self.selected];
                    ui.horizontal(|ui| {
                        let label = ui.label("time");
                        let mut seconds = self.t * demo.duration_s;
                        ui.add(
                            egui::Slider::new(&mut seconds, 0.0..=demo.duration_s)
                                .suffix(" s")
                                .max_decimals(2),
                        )
                        .labelled_by(label.id);
                        self.t = (seconds / demo.duration_s).clamp(0.0, 1.0);
                    });
                    if let Some(rollout) = regen.get(self.selected)
                        && let Some(t) = plots::show(ui, demo, rollout, self.t)
                    {
                        self.t = t;
                    }
                }
            });
        let rows = self.table_rows();
        egui::Panel::bottom("table")
            .default_size(200.0)
            .min_size(150.0)
            .show(ui, |ui| {
                ui.set_min_size(ui.available_size());
                table::show(ui, &rows, &names);
            });
        egui::CentralPanel::default().show(ui, |ui| {
            let height = (ui.available_height() * 0.5).clamp(200.0, 420.0);
            self.maps(ui, height);
            if let Some(model) = &model {
                self.view3d.toggles(ui, model.demos().len());
                let learned = self.rl_path();
                let learned = learned.as_ref().map(|(i, p)| (*i, p.as_slice()));
                self.view3d
                    .show(ui, model, &regen, self.selected, self.t, learned);
            }
        });
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        eframe::set_value(storage, SETTINGS_KEY, &self.settings);
    }
}
