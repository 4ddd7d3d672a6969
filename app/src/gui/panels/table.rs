//! Table I, live: one row per gain set (extracted, picked, the paper's,
//! the operating point) with D/M, K/M, zeta, S, sum d, J, the skill error
//! E, the mean d_mean, the largest a_peak, each demo's d_mean and each
//! demo's e (method.md section 11); with orientation, the summed d_rot, the
//! largest alpha_peak and each demo's d_rot in degrees (section 12); copied
//! as Markdown or CSV (the core's report renders both).

use dmpscope_core::TableRow;
use eframe::egui;

use super::PanelCtx;

/// The Table I panel.
pub fn table_ui(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>) {
    let Some(report) = cx.session.report() else {
        return;
    };
    ui.horizontal(|ui| {
        ui.label(egui::RichText::new("Table I").strong());
        if ui.button("Copy Markdown").clicked() {
            ui.ctx().copy_text(report.markdown());
        }
        if ui.button("Copy CSV").clicked() {
            ui.ctx().copy_text(report.csv());
        }
    });
    let names = report.demo_names();
    let oriented = report.oriented();
    egui::ScrollArea::horizontal().show(ui, |ui| {
        egui::Grid::new("table-i").striped(true).show(ui, |ui| {
            for h in [
                "gains",
                "D/M",
                "K/M",
                "zeta",
                "S",
                "sum d [m]",
                "J",
                "E [m]",
                "mean d_mean [mm]",
                "max a_peak",
            ] {
                ui.label(egui::RichText::new(h).strong());
            }
            if oriented {
                for h in ["sum d_rot [deg]", "max alpha_peak"] {
                    ui.label(egui::RichText::new(h).strong());
                }
            }
            let mut prefixes = vec![("d", "mm"), ("e", "mm")];
            if oriented {
                prefixes.push(("d_rot", "deg"));
            }
            for (prefix, unit) in prefixes {
                for (i, name) in names.iter().enumerate() {
                    let title = format!("{prefix} {} [{unit}]", short(name, i));
                    ui.label(egui::RichText::new(title).strong());
                }
            }
            ui.end_row();
            for r in &report.table {
                row(ui, r, oriented);
                ui.end_row();
            }
        });
    });
}

fn row(ui: &mut egui::Ui, r: &TableRow, oriented: bool) {
    let c = r.cells(false);
    for cell in &c[..8] {
        ui.label(cell);
    }
    let mean = r.d_mean.iter().sum::<f64>() / r.d_mean.len().max(1) as f64;
    ui.label(format!("{:.3}", mean * 1e3));
    ui.label(format!(
        "{:.2}",
        r.a_peak.iter().fold(0.0f64, |a, &b| a.max(b))
    ));
    let largest = |v: &[f64]| {
        v.iter()
            .copied()
            .filter(|x| !x.is_nan())
            .fold(0.0f64, f64::max)
    };
    if oriented {
        ui.label(format!("{:.4}", r.d_rot_sum));
        ui.label(format!("{:.2}", largest(&r.alpha_peak)));
    }
    for d in r.d_mean.iter().chain(&r.e) {
        ui.label(format!("{:.3}", d * 1e3));
    }
    if oriented {
        for d in &r.d_rot {
            ui.label(format!("{d:.4}"));
        }
    }
}

/// A short column title for a demo: its topic's last part.
fn short(name: &str, i: usize) -> String {
    name.rsplit(['/', ':'])
        .next()
        .filter(|s| !s.is_empty())
        .map_or_else(|| format!("{}", i + 1), str::to_owned)
}
