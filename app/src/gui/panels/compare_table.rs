//! The pinned sets side by side where Table I is (issue 45): the core's
//! comparison cells (Table I's numbers for the same gains, the settling
//! time, each demo's d_mean, the target run's end error and peak
//! acceleration), the best of each column in green; copied as Markdown or
//! CSV.

use dmpscope_core::report::compare_text::CompareTable;
use eframe::egui::{self, Color32, RichText};

use super::PanelCtx;

/// The colour of a column's best value.
const BEST: Color32 = Color32::from_rgb(120, 230, 140);

/// The comparison of the pinned sets.
pub fn compare_table_ui(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>) {
    let Some(model) = cx.session.model() else {
        return;
    };
    let names: Vec<String> = model.demos().iter().map(|d| d.name.clone()).collect();
    let table = CompareTable::new(cx.view.pins.rows(), &names);
    ui.horizontal(|ui| {
        ui.selectable_value(&mut cx.view.compare_table, false, "Table I");
        ui.selectable_value(&mut cx.view.compare_table, true, "Pinned sets")
            .on_hover_text("the pinned sets side by side; green: the best (least) of the column");
        if ui.button("Copy Markdown").clicked() {
            ui.ctx().copy_text(table.markdown());
        }
        if ui.button("Copy CSV").clicked() {
            ui.ctx().copy_text(table.csv());
        }
    });
    if table.cells.is_empty() {
        ui.weak("No sets pinned (Compare gain sets, in the side panel).");
        return;
    }
    egui::ScrollArea::horizontal().show(ui, |ui| {
        egui::Grid::new("compare-table")
            .striped(true)
            .show(ui, |ui| {
                for title in &table.titles {
                    ui.label(RichText::new(title).strong());
                }
                ui.end_row();
                for (r, (cells, best)) in table.cells.iter().zip(&table.best).enumerate() {
                    for (c, (cell, &b)) in cells.iter().zip(best).enumerate() {
                        let text = RichText::new(cell);
                        let text = match (b, c) {
                            (true, _) => text.color(BEST).strong(),
                            (_, 0) => {
                                let [red, green, blue] = cx
                                    .view
                                    .pins
                                    .list()
                                    .get(r)
                                    .map_or([200, 200, 200], |p| p.colour);
                                text.color(Color32::from_rgb(red, green, blue))
                            }
                            _ => text,
                        };
                        ui.label(text);
                    }
                    ui.end_row();
                }
            });
    });
}
