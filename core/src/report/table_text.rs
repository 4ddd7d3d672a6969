//! Table I rendered for people and spreadsheets: the terminal's text, the
//! Markdown and the CSV of a [`Report`] (method.md section 7), each from
//! the columns [`crate::report::table`] declares. The JSON is the report's
//! own serde shape ([`crate::report::summary`]).

use std::fmt::Write as _;

use crate::report::summary::Report;
use crate::report::table::{PER_DEMO, SUMMARY, TableRow, parts};
use crate::report::text::{pad_left, pad_right, widest};

impl Report {
    /// Table I for a terminal: one summary row per gain set, then each
    /// per-demo group with a column per gain set.
    pub fn table_text(&self) -> String {
        let rows = &self.table;
        let mut s = String::new();
        let name_w = widest(rows.iter().map(|r| r.name.as_str()), 9);
        let shown: Vec<_> = SUMMARY
            .iter()
            .filter(|c| self.oriented() || !c.orientation)
            .collect();
        let _ = write!(s, "{:<name_w$}", "gains");
        for c in &shown {
            let _ = write!(s, "  {:>w$}", c.short, w = c.width);
        }
        s.push('\n');
        for r in rows {
            s.push_str(&pad_right(&r.name, name_w));
            for c in &shown {
                let _ = write!(s, "  {:>w$}", c.cell(r), w = c.width);
            }
            s.push('\n');
        }
        let names = self.demo_names();
        let demo_w = widest(names.iter().map(String::as_str), 8);
        let col_w = name_w.max(9);
        for group in PER_DEMO
            .iter()
            .filter(|g| self.oriented() || !g.orientation)
        {
            let _ = writeln!(s, "\nTable I: {}", group.section);
            let _ = write!(s, "{:<demo_w$}", "demo");
            for r in rows {
                let _ = write!(s, "  {}", pad_left(&r.name, col_w));
            }
            s.push('\n');
            for (i, name) in names.iter().enumerate() {
                let _ = write!(s, "{}", pad_right(name, demo_w));
                for r in rows {
                    let v = (group.values)(r).get(i).copied().unwrap_or(f64::NAN);
                    let _ = write!(s, "  {:>col_w$}", group.cell(v));
                }
                s.push('\n');
            }
            let _ = write!(s, "{:<demo_w$}", "mean");
            for r in rows {
                let c = (group.values)(r);
                let mean = c.iter().sum::<f64>() / c.len().max(1) as f64;
                let _ = write!(s, "  {:>col_w$}", group.cell(mean));
            }
            s.push('\n');
        }
        s
    }

    /// Whether any row has an orientation error (the orientation's
    /// columns are shown).
    pub fn oriented(&self) -> bool {
        self.table.iter().any(TableRow::oriented)
    }

    /// The column titles in [`TableRow::cells`]' order: `gains`, then each
    /// summary column's `title` and each per-demo column's `demo` title.
    fn head(
        &self,
        title: impl Fn(&crate::report::table::Column) -> String,
        demo: impl Fn(&crate::report::table::PerDemo, &str) -> String,
    ) -> Vec<String> {
        let names = self.demo_names();
        let mut head = vec!["gains".to_owned()];
        for &part in parts(self.oriented()) {
            head.extend(SUMMARY.iter().filter(|c| c.orientation == part).map(&title));
            for g in PER_DEMO.iter().filter(|g| g.orientation == part) {
                head.extend(names.iter().map(|d| demo(g, d)));
            }
        }
        head
    }

    /// Table I as Markdown (`|` in names escaped).
    pub fn markdown(&self) -> String {
        let cell = |t: &str| t.replace('|', "\\|");
        let head = self.head(|c| c.title.to_owned(), |g, d| g.title(&cell(d)));
        let oriented = self.oriented();
        let mut out = format!("| {} |\n|{}\n", head.join(" | "), "---|".repeat(head.len()));
        for r in &self.table {
            let cells: Vec<String> = r.cells(oriented).iter().map(|c| cell(c)).collect();
            let _ = writeln!(out, "| {} |", cells.join(" | "));
        }
        out
    }

    /// Table I as CSV (RFC 4180: a field with a comma, quote or line break
    /// is quoted).
    pub fn csv(&self) -> String {
        let head = self.head(|c| c.key.to_owned(), |g, d| format!("{}:{d}", g.key));
        let oriented = self.oriented();
        let line = |fields: &[String]| {
            let quoted: Vec<String> = fields.iter().map(|f| csv_field(f)).collect();
            quoted.join(",") + "\n"
        };
        let mut out = line(&head);
        for r in &self.table {
            out.push_str(&line(&r.cells(oriented)));
        }
        out
    }
}

/// A CSV field, quoted when it holds a comma, a quote or a line break.
fn csv_field(f: &str) -> String {
    if f.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", f.replace('"', "\"\""))
    } else {
        f.to_owned()
    }
}
