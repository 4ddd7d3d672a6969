//! Table I rendered for people and spreadsheets: the terminal's text, the
//! Markdown and the CSV of a [`Report`] (method.md section 7). The JSON is
//! the report's own serde shape ([`crate::report`]).

use std::fmt::Write as _;

use crate::report::summary::{Report, TableRow};
use crate::report::text::{pad_left, pad_right, widest};

impl Report {
    /// Table I for a terminal: one summary row per gain set, then
    /// `d_mean` and `a_peak` per demo with a column per gain set.
    pub fn table_text(&self) -> String {
        let rows = &self.table;
        let mut s = String::new();
        let name_w = widest(rows.iter().map(|r| r.name.as_str()), 9);
        let oriented = self.oriented();
        let _ = write!(
            s,
            "{:<name_w$}  {:>9}  {:>9}  {:>7}  {:>9}  {:>9}  {:>9}  {:>9}",
            "gains", "D/M", "K/M", "zeta", "S", "sum d[m]", "J", "E[m]"
        );
        if oriented {
            let _ = write!(s, "  {:>14}", "sum d_rot[deg]");
        }
        s.push('\n');
        for r in rows {
            let _ = write!(
                s,
                "{}  {:>9.3}  {:>9.3}  {:>7.3}  {:>9.5}  {:>9.5}  {:>9.5}  {:>9.5}",
                pad_right(&r.name, name_w),
                r.dm,
                r.km,
                r.zeta,
                r.s,
                r.d_sum,
                r.j,
                r.e_sum
            );
            if oriented {
                let _ = write!(s, "  {:>14.4}", r.d_rot_sum);
            }
            s.push('\n');
        }
        let names = self.demo_names();
        let demo_w = widest(names.iter().map(String::as_str), 8);
        let col_w = name_w.max(9);
        type Pick = fn(&TableRow) -> &[f64];
        let mut parts: Vec<(&str, Pick, f64, usize)> = vec![
            ("d_mean [mm]", |r| &r.d_mean, 1e3, 3),
            ("a_peak [m/s^2]", |r| &r.a_peak, 1.0, 2),
            ("e, the skill's error [mm]", |r| &r.e, 1e3, 3),
        ];
        if self.oriented() {
            parts.push(("d_rot, the orientation's error [deg]", |r| &r.d_rot, 1.0, 4));
            parts.push(("alpha_peak [rad/s^2]", |r| &r.alpha_peak, 1.0, 2));
        }
        for (title, pick, scale, prec) in parts {
            let _ = writeln!(s, "\nTable I: {title}");
            let _ = write!(s, "{:<demo_w$}", "demo");
            for r in rows {
                let _ = write!(s, "  {}", pad_left(&r.name, col_w));
            }
            s.push('\n');
            for (i, name) in names.iter().enumerate() {
                let _ = write!(s, "{}", pad_right(name, demo_w));
                for r in rows {
                    let v = pick(r).get(i).copied().unwrap_or(f64::NAN);
                    let _ = write!(s, "  {:>col_w$.prec$}", v * scale);
                }
                s.push('\n');
            }
            let _ = write!(s, "{:<demo_w$}", "mean");
            for r in rows {
                let c = pick(r);
                let mean = c.iter().sum::<f64>() / c.len().max(1) as f64;
                let _ = write!(s, "  {:>col_w$.prec$}", mean * scale);
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

    /// The column titles: `fixed`, then one `d_mean`, `a_peak` and `e`
    /// column per demo, each titled by its function of the demo's name;
    /// with orientation, `rot_sum` and one `d_rot` and `alpha_peak` column
    /// per demo.
    fn head(
        &self,
        fixed: [&str; 8],
        per_demo: [&dyn Fn(&str) -> String; 3],
        rot_sum: &str,
        rot_per_demo: [&dyn Fn(&str) -> String; 2],
    ) -> Vec<String> {
        let names = self.demo_names();
        let mut head: Vec<String> = fixed.map(str::to_owned).into();
        for title in per_demo {
            head.extend(names.iter().map(|d| title(d)));
        }
        if self.oriented() {
            head.push(rot_sum.to_owned());
            for title in rot_per_demo {
                head.extend(names.iter().map(|d| title(d)));
            }
        }
        head
    }

    /// Table I as Markdown (`|` in names escaped).
    pub fn markdown(&self) -> String {
        let fixed = [
            "gains",
            "D/M",
            "K/M",
            "zeta",
            "S",
            "sum d [m]",
            "J",
            "E [m]",
        ];
        let cell = |t: &str| t.replace('|', "\\|");
        let head = self.head(
            fixed,
            [
                &|d| format!("d_mean {} [mm]", cell(d)),
                &|d| format!("a_peak {}", cell(d)),
                &|d| format!("e {} [mm]", cell(d)),
            ],
            "sum d_rot [deg]",
            [&|d| format!("d_rot {} [deg]", cell(d)), &|d| {
                format!("alpha_peak {}", cell(d))
            }],
        );
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
        let fixed = ["gains", "dm", "km", "zeta", "s", "d_sum", "j", "e_sum"];
        let head = self.head(
            fixed,
            [
                &|d| format!("d_mean_mm:{d}"),
                &|d| format!("a_peak:{d}"),
                &|d| format!("e_mm:{d}"),
            ],
            "d_rot_sum_deg",
            [&|d| format!("d_rot_deg:{d}"), &|d| {
                format!("alpha_peak:{d}")
            }],
        );
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
