//! The Compare section (issue 45): pin gain sets (the operating point, a
//! Table I row, a typed `DM:KM`), up to six, each in its colour; list them
//! with show, rename, go-to and remove; open their comparison table; save
//! the figure of their regenerations.

use dmpscope_core::report::compare::MAX_SETS;
use eframe::egui::{self, Color32};

use super::super::commands::{Command, Export};
use super::PanelCtx;

/// The Compare section.
pub fn compare_ui(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>) {
    if cx.session.model().is_none() {
        ui.weak("Pin gain sets once a model is fitted.");
        return;
    }
    pin_buttons_ui(ui, cx);
    if let Some(e) = &cx.view.pin_error {
        ui.colored_label(Color32::from_rgb(240, 180, 80), e);
    }
    pins_list_ui(ui, cx);
    if !cx.view.pins.is_empty() {
        ui.horizontal(|ui| {
            ui.checkbox(&mut cx.view.compare_table, "comparison table")
                .on_hover_text("show the pinned sets side by side where Table I is");
            if ui
                .button("Save figure (SVG)")
                .on_hover_text("the selected demo's x, y, z against time and the 3D paths, every shown set overlaid")
                .clicked()
            {
                cx.push(Command::Export(Export::FigureSvg));
            }
            #[cfg(not(target_arch = "wasm32"))]
            if ui.button("PNG").clicked() {
                cx.push(Command::Export(Export::FigurePng));
            }
        });
    }
}

/// Pin the operating point, a Table I row, or typed gains.
fn pin_buttons_ui(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>) {
    let rows = cx.session.table_rows();
    let mut wanted: Option<(String, f64, f64)> = None;
    ui.horizontal_wrapped(|ui| {
        ui.label("pin");
        if ui
            .button("operating point")
            .on_hover_text("pin the operating point (click or drag on a map to move it first)")
            .clicked()
        {
            let (dm, km) = cx.settings.op;
            wanted = Some((format!("{dm:.2}:{km:.2}"), dm, km));
        }
        egui::ComboBox::from_label("a Table I row")
            .selected_text("choose")
            .show_ui(ui, |ui| {
                for r in rows.iter().filter(|r| r.name != "Operating point") {
                    if ui.selectable_label(false, &r.name).clicked() {
                        wanted = Some((r.name.clone(), r.dm, r.km));
                    }
                }
            });
    });
    ui.horizontal(|ui| {
        let edit = ui.add(
            egui::TextEdit::singleline(&mut cx.view.pin_text)
                .hint_text("D/M:K/M, e.g. 25:156.25")
                .desired_width(150.0),
        );
        let enter = edit.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
        if ui.button("Pin").clicked() || enter {
            let text = cx.view.pin_text.trim().to_owned();
            match dmpscope_core::report::compare::resolve(&text, &rows) {
                Ok(sets) => {
                    for s in sets {
                        add(cx, &s.name, s.dm, s.km);
                    }
                    cx.view.pin_text.clear();
                }
                Err(e) => cx.view.pin_error = Some(e.to_string()),
            }
        }
    });
    if let Some((name, dm, km)) = wanted {
        add(cx, &name, dm, km);
    }
}

fn add(cx: &mut PanelCtx<'_>, name: &str, dm: f64, km: f64) {
    cx.view.pin_error = cx.view.pins.add(name, dm, km).err();
}

/// Each pin: its colour, shown or not (its name), rename, go to, remove.
fn pins_list_ui(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>) {
    let n = cx.view.pins.list().len();
    if n == 0 {
        ui.weak(format!(
            "No sets pinned: pin up to {MAX_SETS} to see their regenerations together."
        ));
        return;
    }
    let mut remove = None;
    for i in 0..n {
        let pin = &cx.view.pins.list()[i];
        let (colour, mut shown, mut name) = (pin.colour, pin.shown, pin.name.clone());
        let (dm, km) = (pin.dm, pin.km);
        ui.horizontal(|ui| {
            let c = Color32::from_rgb(colour[0], colour[1], colour[2]);
            let (rect, _) = ui.allocate_exact_size(egui::vec2(12.0, 12.0), egui::Sense::hover());
            ui.painter().rect_filled(rect, 2.0, c);
            let label = ui.colored_label(c, format!("set {}", i + 1));
            let edit = ui
                .add(egui::TextEdit::singleline(&mut name).desired_width(110.0))
                .labelled_by(label.id)
                .on_hover_text("its name (Table I's, typed, or yours)");
            if ui
                .checkbox(&mut shown, "shown")
                .on_hover_text("show or hide its overlays")
                .changed()
            {
                cx.view.pins.set_shown(i, shown);
            }
            if edit.changed() {
                cx.view.pins.rename(i, &name);
            }
            ui.weak(format!("{dm:.2} / {km:.2}"));
            if ui
                .small_button("Go")
                .on_hover_text("make it the operating point")
                .clicked()
            {
                cx.settings.op = (dm, km);
            }
            if ui.small_button("remove").clicked() {
                remove = Some(i);
            }
        });
        if let Some(why) = cx.view.pins.target_failure(i) {
            ui.weak(format!("no run at the new target: {why}"));
        }
    }
    if let Some(i) = remove {
        cx.view.pins.remove(i);
    }
}
