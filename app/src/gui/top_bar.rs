//! The top bar: Open (dialog) and Export, what is loaded, the loading and
//! landscape progress with Cancel; and the files that arrive by a drop or a
//! dialog.

use eframe::egui;

use super::app::DmpApp;
use super::export;
use super::file_dialog::Answer;
use super::loading::Source;
use super::table;

impl DmpApp {
    /// Takes dropped files (paths natively, bytes in the browser) and the
    /// dialogs' answers.
    pub(super) fn take_inputs(&mut self, ctx: &egui::Context) {
        let dropped: Vec<egui::DroppedFileHandle> = ctx.input(|i| i.raw.dropped_files.clone());
        let dropped = if cfg!(target_arch = "wasm32") {
            // The browser reads dropped files asynchronously: the answer
            // comes back through the dialogs.
            let ctx = ctx.clone();
            self.dialogs
                .read_dropped(dropped, move || ctx.request_repaint());
            Vec::new()
        } else {
            dropped
                .iter()
                .map(|f| f.path().to_path_buf())
                .filter(|p| !p.as_os_str().is_empty())
                .map(Source::Path)
                .collect()
        };
        for answer in std::iter::once(dropped)
            .filter(|d| !d.is_empty())
            .map(Answer::Open)
            .chain(self.dialogs.poll())
        {
            match answer {
                Answer::Open(sources) => {
                    let ctx = ctx.clone();
                    self.add_sources(sources, move || ctx.request_repaint());
                }
                Answer::Message(m) => self.messages.push(m),
            }
        }
        if self.loading() {
            ctx.request_repaint_after(std::time::Duration::from_millis(30));
        }
    }

    pub(super) fn top_bar(&mut self, ui: &mut egui::Ui, ctx: &egui::Context) {
        ui.horizontal(|ui| {
            ui.strong("dmpscope");
            if ui.button("Open…").clicked() {
                let ctx = ctx.clone();
                self.dialogs.open(move || ctx.request_repaint());
            }
            ui.menu_button("Export", |ui| self.export_menu(ui, ctx));
            ui.label(format!(
                "{} file(s), {} demos",
                self.files.len(),
                self.demos.len()
            ));
            if self.loading() {
                ui.spinner();
                ui.label("loading…");
            }
            if let Some(shown) = &self.shown {
                let (done, total) = (shown.snapshot.done, shown.snapshot.total);
                if done < total {
                    ui.add(
                        egui::ProgressBar::new(done as f32 / total.max(1) as f32)
                            .desired_width(200.0)
                            .text(format!("landscape {done}/{total}")),
                    );
                    if ui.button("Cancel").clicked()
                        && let Some(w) = &mut self.worker
                    {
                        w.cancel();
                    }
                }
            }
            ui.weak("or drop .mcap / .csv files on the window");
        });
    }

    fn export_menu(&mut self, ui: &mut egui::Ui, ctx: &egui::Context) {
        let wake = {
            let ctx = ctx.clone();
            move || ctx.request_repaint()
        };
        let names = self.demo_names();
        let rows = self.table_rows();
        if let Some(shown) = &self.shown {
            let grid = shown.snapshot.landscape.grid;
            let log = self.settings.log_colour;
            for (label, file, values) in [
                ("J map (PNG)", "dmpscope-J.png", &shown.j),
                ("sum d map (PNG)", "dmpscope-sum-d.png", &shown.d_sum),
                ("S map (PNG)", "dmpscope-S.png", &shown.s),
            ] {
                if ui.button(label).clicked() {
                    match export::heatmap_png(values, &grid, log) {
                        Ok(bytes) => self.dialogs.save(file, bytes, wake.clone()),
                        Err(e) => self.messages.push(format!("{label}: {e}")),
                    }
                    ui.close();
                }
            }
        }
        if ui.button("Gains (JSON)").clicked() {
            let text = export::gains_json(self.settings.k, self.extraction.as_ref(), &rows, &names);
            self.dialogs
                .save("dmpscope-gains.json", text.into_bytes(), wake.clone());
            ui.close();
        }
        if ui.button("Table I (CSV)").clicked() {
            let text = table::csv(&rows, &names);
            self.dialogs
                .save("dmpscope-table.csv", text.into_bytes(), wake.clone());
            ui.close();
        }
        if ui.button("Table I (Markdown)").clicked() {
            let text = table::markdown(&rows, &names);
            self.dialogs
                .save("dmpscope-table.md", text.into_bytes(), wake);
            ui.close();
        }
    }
}
