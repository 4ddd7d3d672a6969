//! The computation's settings: the grid (points, ranges, spacing), the
//! colour scale, Savitzky-Golay and the DMP's basis. Whatever changes here,
//! the session recomputes exactly the stages it affects.

use eframe::egui;

use super::PanelCtx;
use crate::session::Settings;

/// The window-as-a-duration row (`--sg-seconds`), which overrides the
/// window in samples.
fn sg_seconds_ui(ui: &mut egui::Ui, sg_seconds: &mut Option<f64>) {
    let l = ui.label("SG window in seconds");
    ui.horizontal(|ui| {
        let mut on = sg_seconds.is_some();
        if ui
            .checkbox(&mut on, "")
            .labelled_by(l.id)
            .on_hover_text(
                "beyond the method: the window as a duration, an odd number of samples at \
                 each demo's own rate (for recordings at hundreds of Hz)",
            )
            .changed()
        {
            *sg_seconds = on.then_some(0.2);
        }
        if let Some(secs) = sg_seconds {
            ui.add(
                egui::DragValue::new(secs)
                    .range(0.005..=2.0)
                    .speed(0.005)
                    .suffix(" s"),
            );
        }
    });
    ui.end_row();
}

/// The Settings section.
pub fn settings_ui(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>) {
    let s = &mut *cx.settings;
    let window_before = s.prep.sg_window;
    egui::Grid::new("settings").show(ui, |ui| {
        grid_rows(ui, s);
        preprocessing_rows(ui, &mut s.prep);
        dmp_rows(ui, &mut s.dmp);
    });
    // The window is odd: an even value moves on the way it was going.
    let w = &mut s.prep.sg_window;
    if w.is_multiple_of(2) {
        *w = if *w < window_before { *w - 1 } else { *w + 1 };
    }
    if ui.button("Reset to the paper's settings").clicked() {
        let keep = (s.load.clone(), s.op, s.log_colour);
        *s = Settings::default();
        (s.load, s.op, s.log_colour) = keep;
    }
}

/// The grid's rows (points, D/M and K/M ranges, spacing) and the colour scale's.
fn grid_rows(ui: &mut egui::Ui, s: &mut Settings) {
    let l = ui.label("grid points");
    let mut n = s.grid_points();
    if ui
        .add(egui::DragValue::new(&mut n).range(8..=512))
        .labelled_by(l.id)
        .changed()
    {
        s.set_grid_points(n);
    }
    ui.end_row();
    for (name, axis) in [("D/M range", &mut s.grid.dm), ("K/M range", &mut s.grid.km)] {
        let l = ui.label(name);
        ui.horizontal(|ui| {
            ui.add(
                egui::DragValue::new(&mut axis.lo)
                    .speed(0.01)
                    .range(1e-6..=1e6),
            )
            .labelled_by(l.id);
            ui.add(
                egui::DragValue::new(&mut axis.hi)
                    .speed(1.0)
                    .range(1e-6..=1e7),
            )
            .labelled_by(l.id);
        });
        ui.end_row();
    }
    ui.label("axes");
    let mut log = s.log_axes();
    if ui.checkbox(&mut log, "log-spaced").changed() {
        s.set_log_axes(log);
    }
    ui.end_row();
    ui.label("colours");
    ui.checkbox(&mut s.log_colour, "log scale");
    ui.end_row();
}

/// The Savitzky-Golay rows: window and order, and the window in seconds.
fn preprocessing_rows(ui: &mut egui::Ui, prep: &mut dmpscope_core::PrepSettings) {
    let l = ui.label("SG window / order");
    ui.horizontal(|ui| {
        ui.add(egui::DragValue::new(&mut prep.sg_window).range(5..=101))
            .labelled_by(l.id);
        ui.add(egui::DragValue::new(&mut prep.sg_order).range(2..=6))
            .labelled_by(l.id);
    });
    ui.end_row();
    sg_seconds_ui(ui, &mut prep.sg_seconds);
}

/// The DMP's rows: basis functions, S's axis SD floor, E's skill mode, the orientation's.
fn dmp_rows(ui: &mut egui::Ui, dmp: &mut dmpscope_core::fit::settings::DmpSettings) {
    let l = ui.label("basis functions");
    ui.add(egui::DragValue::new(&mut dmp.basis_functions).range(2..=500))
        .labelled_by(l.id);
    ui.end_row();
    let l = ui.label("S: axis SD floor").on_hover_text(
        "beyond the method: each axis's SD in S's standardisation is floored at this \
         fraction of the demo's largest, so an axis that barely moves is not blown up \
         to unit variance (0: the method as written)",
    );
    ui.add(
        egui::DragValue::new(&mut dmp.axis_sd_floor)
            .range(0.0..=1.0)
            .speed(0.01),
    )
    .labelled_by(l.id);
    ui.end_row();
    let l = ui.label("E: skill mode").on_hover_text(
        "how the one skill of all demos follows each demo's start and goal in the skill \
         error E: frame (turned and scaled with the goal), per-axis (the paper's factors) \
         or none (one absolute forcing term)",
    );
    egui::ComboBox::from_id_salt("skill mode")
        .selected_text(dmp.skill_mode.name())
        .show_ui(ui, |ui| {
            for mode in dmpscope_core::fit::settings::SkillMode::ALL {
                ui.selectable_value(&mut dmp.skill_mode, mode, mode.name())
                    .on_hover_text(mode.assumes());
            }
        })
        .response
        .labelled_by(l.id);
    ui.end_row();
    orientation_rows(ui, dmp);
}

/// The orientation's options (method.md section 12, beyond the paper):
/// k_rot in J and separate orientation gains.
fn orientation_rows(ui: &mut egui::Ui, dmp: &mut dmpscope_core::fit::settings::DmpSettings) {
    let l = ui.label("J: k_rot").on_hover_text(
        "beyond the paper: J = S + k sum d + k_rot sum d_rot, d_rot in degrees (0: the \
         paper's J on positions; needs demos with orientation)",
    );
    ui.add(
        egui::DragValue::new(&mut dmp.k_rot)
            .range(0.0..=100.0)
            .speed(0.01),
    )
    .labelled_by(l.id);
    ui.end_row();
    let l = ui.label("orientation gains").on_hover_text(
        "the orientation DMP at its own D/M and K/M instead of the position's (one pair \
         for the pose, as CartesianDMP)",
    );
    ui.horizontal(|ui| {
        let mut own = dmp.orientation_gains.is_some();
        if ui.checkbox(&mut own, "own").labelled_by(l.id).changed() {
            dmp.orientation_gains = own.then_some([25.0, 156.25]);
        }
        if let Some([dm, km]) = &mut dmp.orientation_gains {
            ui.add(
                egui::DragValue::new(dm)
                    .range(0.01..=10_000.0)
                    .prefix("D/M "),
            );
            ui.add(
                egui::DragValue::new(km)
                    .range(0.01..=100_000.0)
                    .prefix("K/M "),
            );
        }
    });
    ui.end_row();
}
