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
///
/// The table is wider than the panel (three columns per demo), so only the
/// cells inside the visible part are laid out; the others keep last
/// frame's width ([`Columns`]). The operating point's row changes every
/// frame of a drag, and laying out all its cells cost about a tenth of the
/// frame.
pub fn table_ui(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>) {
    let Some(model) = cx.session.model() else {
        return;
    };
    let rows = cx.session.table_rows();
    ui.horizontal(|ui| {
        ui.label(egui::RichText::new("Table I").strong());
        if ui.button("Copy Markdown").clicked()
            && let Some(report) = cx.session.report()
        {
            ui.ctx().copy_text(report.markdown());
        }
        if ui.button("Copy CSV").clicked()
            && let Some(report) = cx.session.report()
        {
            ui.ctx().copy_text(report.csv());
        }
    });
    let oriented = rows.iter().any(TableRow::oriented);
    let names: Vec<&str> = model.demos().iter().map(|d| d.name.as_str()).collect();
    egui::ScrollArea::horizontal().show(ui, |ui| {
        // The widths are remembered for these columns only.
        let id = ui.scope_id().with(("table-i-columns", oriented, &names));
        let mut columns = Columns::load(ui, id);
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
                columns.cell(ui, || egui::RichText::new(h).strong());
            }
            if oriented {
                for h in ["sum d_rot [deg]", "max alpha_peak"] {
                    columns.cell(ui, || egui::RichText::new(h).strong());
                }
            }
            let mut prefixes = vec![("d", "mm"), ("e", "mm")];
            if oriented {
                prefixes.push(("d_rot", "deg"));
            }
            for (prefix, unit) in prefixes {
                for (i, name) in names.iter().enumerate() {
                    columns.cell(ui, || {
                        let title = format!("{prefix} {} [{unit}]", short(name, i));
                        egui::RichText::new(title).strong()
                    });
                }
            }
            columns.end_row(ui);
            for r in &rows {
                row(ui, &mut columns, r, oriented);
                columns.end_row(ui);
            }
        });
        columns.store(ui, id);
    });
}

/// The grid's column widths, remembered from frame to frame: a cell out of
/// sight takes its column's width without being formatted or laid out (so
/// it has no AccessKit node either, as rows out of sight in a
/// `ScrollArea::show_rows`).
struct Columns {
    /// Each column's width last frame (empty on the first frame for these
    /// columns: every cell is laid out).
    last: Vec<f32>,
    /// Each column's widest cell laid out this frame (`None`: none was).
    now: Vec<Option<f32>>,
    /// The next cell's column.
    col: usize,
}

impl Columns {
    fn load(ui: &egui::Ui, id: egui::Id) -> Self {
        Self {
            last: ui.data(|d| d.get_temp::<Vec<f32>>(id)).unwrap_or_default(),
            now: Vec::new(),
            col: 0,
        }
    }

    /// Keeps this frame's widths: a column none of whose cells was laid
    /// out keeps last frame's.
    fn store(self, ui: &egui::Ui, id: egui::Id) {
        let widths: Vec<f32> = self
            .now
            .iter()
            .enumerate()
            .map(|(col, w)| w.or_else(|| self.last.get(col).copied()).unwrap_or(0.0))
            .collect();
        ui.data_mut(|d| d.insert_temp(id, widths));
    }

    /// The next cell: `text()` laid out as a label where it can be seen,
    /// else empty space as wide as the column was.
    fn cell<T: Into<egui::WidgetText>>(&mut self, ui: &mut egui::Ui, text: impl FnOnce() -> T) {
        if self.now.len() <= self.col {
            self.now.resize(self.col + 1, None);
        }
        let height = ui.spacing().interact_size.y;
        match self.last.get(self.col) {
            Some(&w)
                if !ui.is_rect_visible(egui::Rect::from_min_size(
                    ui.cursor().min,
                    egui::vec2(w, height),
                )) =>
            {
                ui.allocate_space(egui::vec2(w, 0.0));
            }
            _ => {
                let w = ui.label(text()).rect.width();
                let now = &mut self.now[self.col];
                *now = Some(now.map_or(w, |n| n.max(w)));
            }
        }
        self.col += 1;
    }

    fn end_row(&mut self, ui: &mut egui::Ui) {
        ui.end_row();
        self.col = 0;
    }
}

fn row(ui: &mut egui::Ui, columns: &mut Columns, r: &TableRow, oriented: bool) {
    let c = r.cells(false);
    for cell in &c[..8] {
        columns.cell(ui, || cell.as_str());
    }
    columns.cell(ui, || {
        let mean = r.d_mean.iter().sum::<f64>() / r.d_mean.len().max(1) as f64;
        format!("{:.3}", mean * 1e3)
    });
    columns.cell(ui, || {
        format!("{:.2}", r.a_peak.iter().fold(0.0f64, |a, &b| a.max(b)))
    });
    let largest = |v: &[f64]| {
        v.iter()
            .copied()
            .filter(|x| !x.is_nan())
            .fold(0.0f64, f64::max)
    };
    if oriented {
        columns.cell(ui, || format!("{:.4}", r.d_rot_sum));
        columns.cell(ui, || format!("{:.2}", largest(&r.alpha_peak)));
    }
    for d in r.d_mean.iter().chain(&r.e) {
        columns.cell(ui, || format!("{:.3}", d * 1e3));
    }
    if oriented {
        for d in &r.d_rot {
            columns.cell(ui, || format!("{d:.4}"));
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
