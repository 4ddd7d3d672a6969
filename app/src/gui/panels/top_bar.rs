//! The top bar: Open (files, a folder), the bundled samples, Export, what is loaded, the loading
//! and landscape progress with Cancel or Restart.

use eframe::egui;

use super::super::commands::{Command, Export, Map};
use super::PanelCtx;
use crate::session::{self, Source, Status};

/// The top bar.
pub fn top_bar_ui(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>) {
    let session = cx.session;
    ui.horizontal(|ui| {
        ui.strong("dmpscope");
        if ui.button("Open…").clicked() {
            cx.push(Command::Open { folder: false });
        }
        if cfg!(not(target_arch = "wasm32")) {
            if ui
                .button("Open folder…")
                .on_hover_text("a rosbag2 folder, or any folder of .mcap files")
                .clicked()
            {
                cx.push(Command::Open { folder: true });
            }
            if ui
                .button("Browse…")
                .on_hover_text("dmpscope's own file browser")
                .clicked()
            {
                cx.push(Command::Browse);
            }
        }
        ui.menu_button("Samples", |ui| {
            for (sample, about) in Source::samples() {
                if ui.button(sample.name()).on_hover_text(about).clicked() {
                    cx.push(session::Command::OpenSample(sample));
                    ui.close();
                }
            }
        });
        ui.menu_button("Export", |ui| export_menu(ui, cx));
        // Files, not sources: a folder counts each recording in it.
        let files = session
            .demos()
            .iter()
            .map(|d| d.raw.file.as_str())
            .collect::<std::collections::BTreeSet<_>>()
            .len()
            .max(session.sources().count());
        ui.label(format!("{files} file(s), {} demos", session.demos().len()));
        if session.loading() {
            // A bar where the bytes are counted; a spinner (a frame each
            // frame) only where they are not.
            if !reading_ui(ui, cx) {
                crate::gui::busy::spinner(ui);
            }
            ui.label("loading…");
        }
        match session.status() {
            Status::Computing(done, total) if total > 0 => {
                ui.add(
                    egui::ProgressBar::new(done as f32 / total as f32)
                        .desired_width(200.0)
                        .text(format!("landscape {done}/{total}")),
                );
                if ui.button("Cancel").clicked() {
                    cx.push(session::Command::CancelLandscape);
                }
            }
            Status::Cancelled(done, total) | Status::Stopped(done, total) => {
                let what = if matches!(session.status(), Status::Cancelled(..)) {
                    "cancelled"
                } else {
                    "stopped"
                };
                ui.label(format!("landscape {what} at {done}/{total}"));
                if ui.button("Restart").clicked() {
                    cx.push(session::Command::RestartLandscape);
                }
            }
            _ => {}
        }
        ui.weak("or drop .mcap / .bag / .csv files on the window");
    });
}

/// The Export menu's items, each asking for its export when clicked.
fn export_menu(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>) {
    let session = cx.session;
    let pinned = !cx.view.pins.is_empty();
    let mut item = |ui: &mut egui::Ui, enabled: bool, label: &str, export: Export| {
        if ui.add_enabled(enabled, egui::Button::new(label)).clicked() {
            cx.push(Command::Export(export));
            ui.close();
        }
    };
    let maps = session.shown().is_some();
    for map in Map::all() {
        let label = format!("{} map (PNG)", map.label());
        item(ui, maps, &label, Export::Map(map));
    }
    let model = session.model().is_some();
    item(ui, model, "Gains and Table I (JSON)", Export::ReportJson);
    item(ui, model, "Table I (CSV)", Export::TableCsv);
    item(ui, model, "Table I (Markdown)", Export::TableMarkdown);
    item(
        ui,
        model,
        "Figure of the pinned sets (SVG)",
        Export::FigureSvg,
    );
    #[cfg(not(target_arch = "wasm32"))]
    item(
        ui,
        model,
        "Figure of the pinned sets (PNG)",
        Export::FigurePng,
    );
    item(ui, pinned, "Pinned sets compared (CSV)", Export::CompareCsv);
    item(
        ui,
        pinned,
        "Pinned sets compared (Markdown)",
        Export::CompareMarkdown,
    );
    let run = session.generalised().is_some_and(|g| g.is_ok());
    item(
        ui,
        run,
        "DMP at the new target (JSON for a controller)",
        Export::Dmp,
    );
}

/// Each recording being read: its name, the bytes read of its size, and
/// Cancel (the recording stays, unread); whether there was one.
fn reading_ui(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>) -> bool {
    let mut cancel = None;
    let mut any = false;
    for (i, slot) in cx.session.recordings().iter().enumerate() {
        let Some((read, size)) = slot.progress() else {
            continue;
        };
        any = true;
        let name = slot.source.name();
        let short = name.rsplit(['/', '\\']).next().unwrap_or(&name).to_owned();
        ui.add(
            egui::ProgressBar::new(read as f32 / size.max(1) as f32)
                .desired_width(220.0)
                .text(format!(
                    "reading {short}: {} of {} MB",
                    read / 1_000_000,
                    size / 1_000_000
                )),
        );
        if ui
            .button("Cancel")
            .on_hover_text(format!("stop reading {name}"))
            .clicked()
        {
            cancel = Some(i);
        }
    }
    if let Some(i) = cancel {
        cx.push(session::Command::CancelLoading(i));
    }
    any
}
