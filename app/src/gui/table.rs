//! Table I, live: one row per gain set (extracted, the paper's, the
//! operating point) with D/M, K/M, zeta, J and per demo d_mean and a_peak;
//! copied as Markdown or CSV.

use dmpscope_core::TableRow;
use eframe::egui;

/// The rows as a Markdown table.
pub fn markdown(rows: &[TableRow], demos: &[String]) -> String {
    let mut head = vec!["gains", "D/M", "K/M", "zeta", "S", "sum d [m]", "J"]
        .into_iter()
        .map(str::to_owned)
        .collect::<Vec<_>>();
    head.extend(demos.iter().map(|d| format!("d_mean {d} [mm]")));
    head.extend(demos.iter().map(|d| format!("a_peak {d}")));
    let mut out = format!("| {} |\n|{}\n", head.join(" | "), "---|".repeat(head.len()));
    for r in rows {
        out.push_str(&format!("| {} |\n", cells(r).join(" | ")));
    }
    out
}

/// The rows as CSV.
pub fn csv(rows: &[TableRow], demos: &[String]) -> String {
    let mut head = vec!["gains", "dm", "km", "zeta", "s", "d_sum", "j"]
        .into_iter()
        .map(str::to_owned)
        .collect::<Vec<_>>();
    head.extend(demos.iter().map(|d| format!("d_mean_mm:{d}")));
    head.extend(demos.iter().map(|d| format!("a_peak:{d}")));
    let mut out = head.join(",") + "\n";
    for r in rows {
        out.push_str(&(cells(r).join(",") + "\n"));
    }
    out
}

fn cells(r: &TableRow) -> Vec<String> {
    let mut c = vec![
        r.name.clone(),
        format!("{:.3}", r.dm),
        format!("{:.3}", r.km),
        format!("{:.3}", r.zeta),
        format!("{:.5}", r.s),
        format!("{:.5}", r.d_sum),
        format!("{:.5}", r.j),
    ];
    c.extend(r.d_mean.iter().map(|d| format!("{:.3}", d * 1e3)));
    c.extend(r.a_peak.iter().map(|a| format!("{a:.2}")));
    c
}

/// Shows the table with copy buttons.
pub fn show(ui: &mut egui::Ui, rows: &[TableRow], demos: &[String]) {
    ui.horizontal(|ui| {
        ui.label(egui::RichText::new("Table I").strong());
        if ui.button("Copy Markdown").clicked() {
            ui.ctx().copy_text(markdown(rows, demos));
        }
        if ui.button("Copy CSV").clicked() {
            ui.ctx().copy_text(csv(rows, demos));
        }
    });
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
                "mean d_mean [mm]",
                "max a_peak",
            ] {
                ui.label(egui::RichText::new(h).strong());
            }
            for (i, name) in demos.iter().enumerate() {
                ui.label(egui::RichText::new(format!("d {}", short(name, i))).strong());
            }
            ui.end_row();
            for r in rows {
                let c = cells(r);
                for cell in &c[..7] {
                    ui.label(cell);
                }
                let mean = r.d_mean.iter().sum::<f64>() / r.d_mean.len().max(1) as f64;
                ui.label(format!("{:.3}", mean * 1e3));
                ui.label(format!(
                    "{:.2}",
                    r.a_peak.iter().fold(0.0f64, |a, &b| a.max(b))
                ));
                for d in &r.d_mean {
                    ui.label(format!("{:.3}", d * 1e3));
                }
                ui.end_row();
            }
        });
    });
}

/// A short column title for a demo: its topic's last part.
fn short(name: &str, i: usize) -> String {
    name.rsplit(['/', ':'])
        .next()
        .filter(|s| !s.is_empty())
        .map_or_else(|| format!("{}", i + 1), str::to_owned)
}
