//! Table I, live: one row per gain set (extracted, picked, the paper's,
//! the operating point) with D/M, K/M, zeta, S, sum d, J, the skill error
//! E, the mean d_mean, the largest a_peak, each demo's d_mean and each
//! demo's e (method.md section 11); with orientation, the summed d_rot, the
//! largest alpha_peak and each demo's d_rot in degrees (section 12); copied
//! as Markdown or CSV (the core's report renders both).

use dmpscope_core::report::table::{PER_DEMO, PerDemo, SUMMARY, TableRow, parts};
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
    if cx.view.compare_table {
        super::compare_table::compare_table_ui(ui, cx);
        return;
    }
    let rows = cx.session.table_rows();
    ui.horizontal(|ui| {
        if cx.view.pins.is_empty() {
            ui.label(egui::RichText::new("Table I").strong());
        } else {
            ui.selectable_value(&mut cx.view.compare_table, false, "Table I");
            ui.selectable_value(&mut cx.view.compare_table, true, "Pinned sets");
        }
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
            header(ui, &mut columns, &names, oriented);
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

/// The header: the name, the summary columns with the app's two extra
/// (the mean d_mean, the largest a_peak; with orientation the largest
/// alpha_peak), then a column per demo of each group the app shows.
fn header(ui: &mut egui::Ui, columns: &mut Columns, names: &[&str], oriented: bool) {
    let strong = |t: &str| egui::RichText::new(t).strong();
    columns.cell(ui, || strong("gains"));
    for &part in parts(oriented) {
        for c in SUMMARY.iter().filter(|c| c.orientation == part) {
            columns.cell(ui, || strong(c.title));
        }
        let extra: &[&str] = if part {
            &["max alpha_peak"]
        } else {
            &["mean d_mean [mm]", "max a_peak"]
        };
        for &h in extra {
            columns.cell(ui, || strong(h));
        }
    }
    for g in in_app(oriented) {
        for (i, name) in names.iter().enumerate() {
            columns.cell(ui, || {
                strong(&format!("{} {} [{}]", g.short, short(name, i), g.unit))
            });
        }
    }
}

/// The per-demo groups the app shows a column per demo of.
fn in_app(oriented: bool) -> impl Iterator<Item = &'static PerDemo> {
    PER_DEMO
        .iter()
        .filter(move |g| g.in_app && (oriented || !g.orientation))
}

fn row(ui: &mut egui::Ui, columns: &mut Columns, r: &TableRow, oriented: bool) {
    columns.cell(ui, || r.name.as_str());
    let largest = |v: &[f64]| {
        v.iter()
            .copied()
            .filter(|x| !x.is_nan())
            .fold(0.0f64, f64::max)
    };
    for &part in parts(oriented) {
        for c in SUMMARY.iter().filter(|c| c.orientation == part) {
            columns.cell(ui, || c.cell(r));
        }
        if part {
            columns.cell(ui, || format!("{:.2}", largest(&r.alpha_peak)));
        } else {
            columns.cell(ui, || {
                let mean = r.d_mean.iter().sum::<f64>() / r.d_mean.len().max(1) as f64;
                format!("{:.3}", mean * 1e3)
            });
            columns.cell(ui, || {
                format!("{:.2}", r.a_peak.iter().fold(0.0f64, |a, &b| a.max(b)))
            });
        }
    }
    for g in in_app(oriented) {
        for &v in (g.values)(r) {
            columns.cell(ui, || g.cell(v));
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
