//! The comparison of gain sets as a table of text cells, declared once for
//! the app's grid, CSV and Markdown: the summary columns, each demo's
//! d_mean, and the target run's columns where there is one; the best
//! (least) value of each marked column flagged.

use crate::report::compare::{BETTER, CompareRow, best};

/// A column of the comparison: its title, its key in [`BETTER`] (when the
/// best is marked) and its cell.
struct Col {
    title: String,
    key: Option<&'static str>,
    cell: Box<dyn Fn(&CompareRow) -> String>,
}

fn fixed(v: f64, decimals: usize) -> String {
    if v.is_finite() {
        format!("{v:.decimals$}")
    } else {
        "-".to_owned()
    }
}

fn columns(rows: &[CompareRow], demos: &[String]) -> Vec<Col> {
    let col =
        |title: &str, key: Option<&'static str>, cell: Box<dyn Fn(&CompareRow) -> String>| Col {
            title: title.to_owned(),
            key,
            cell,
        };
    let mut cols = vec![
        col("gains", None, Box::new(|r| r.row.name.clone())),
        col("D/M", None, Box::new(|r| fixed(r.row.dm, 3))),
        col("K/M", None, Box::new(|r| fixed(r.row.km, 3))),
        col("zeta", None, Box::new(|r| fixed(r.row.zeta, 3))),
        col(
            "t_s [s]",
            Some("settling"),
            Box::new(|r| fixed(r.settling.seconds, 3)),
        ),
        col("S", Some("s"), Box::new(|r| fixed(r.row.s, 5))),
        col(
            "sum d [m]",
            Some("d_sum"),
            Box::new(|r| fixed(r.row.d_sum, 5)),
        ),
        col("J", Some("j"), Box::new(|r| fixed(r.row.j, 5))),
        col("E [m]", Some("e_sum"), Box::new(|r| fixed(r.row.e_sum, 5))),
        col(
            "a_peak max",
            Some("a_peak"),
            Box::new(|r| fixed(r.row.a_peak.iter().copied().fold(f64::NAN, f64::max), 2)),
        ),
    ];
    for (i, name) in demos.iter().enumerate() {
        cols.push(col(
            &format!("d_mean {name} [mm]"),
            None,
            Box::new(move |r| fixed(r.row.d_mean.get(i).map_or(f64::NAN, |d| d * 1000.0), 2)),
        ));
    }
    if rows.iter().any(|r| r.target.is_some()) {
        cols.push(col(
            "target end error [mm]",
            Some("target_end_error_m"),
            Box::new(|r| fixed(r.target.map_or(f64::NAN, |t| t.end_error_m * 1000.0), 3)),
        ));
        cols.push(col(
            "target a_peak [m/s²]",
            Some("target_a_peak"),
            Box::new(|r| fixed(r.target.map_or(f64::NAN, |t| t.a_peak), 2)),
        ));
    }
    cols
}

/// The comparison as text cells: the titles, each row's cells, and per
/// row and column whether it is the column's best.
pub struct CompareTable {
    /// The column titles.
    pub titles: Vec<String>,
    /// Each set's cells.
    pub cells: Vec<Vec<String>>,
    /// Each set's flags: the column's best (least).
    pub best: Vec<Vec<bool>>,
}

impl CompareTable {
    /// The table of `rows` over `demos` (their names).
    pub fn new(rows: &[CompareRow], demos: &[String]) -> Self {
        let cols = columns(rows, demos);
        let winners = best(rows);
        debug_assert!(
            winners
                .iter()
                .all(|(k, _)| BETTER.iter().any(|b| b.key == *k))
        );
        Self {
            titles: cols.iter().map(|c| c.title.clone()).collect(),
            cells: rows
                .iter()
                .map(|r| cols.iter().map(|c| (c.cell)(r)).collect())
                .collect(),
            best: (0..rows.len())
                .map(|i| {
                    cols.iter()
                        .map(|c| c.key.is_some_and(|k| winners.contains(&(k, i))))
                        .collect()
                })
                .collect(),
        }
    }

    /// As Markdown, the best of each column in bold.
    pub fn markdown(&self) -> String {
        let mut out = format!("| {} |\n", self.titles.join(" | "));
        out.push_str(&format!("|{}\n", "---|".repeat(self.titles.len())));
        for (cells, best) in self.cells.iter().zip(&self.best) {
            let shown: Vec<String> = cells
                .iter()
                .zip(best)
                .map(|(c, &b)| if b { format!("**{c}**") } else { c.clone() })
                .collect();
            out.push_str(&format!("| {} |\n", shown.join(" | ")));
        }
        out
    }

    /// As CSV; a last row `best` names each marked column's best set.
    pub fn csv(&self) -> String {
        let quote = |s: &str| {
            if s.contains([',', '"', '\n']) {
                format!("\"{}\"", s.replace('"', "\"\""))
            } else {
                s.to_owned()
            }
        };
        let line = |cells: &[String]| cells.iter().map(|c| quote(c)).collect::<Vec<_>>().join(",");
        let mut out = line(&self.titles) + "\n";
        for cells in &self.cells {
            out.push_str(&line(cells));
            out.push('\n');
        }
        let best: Vec<String> = (0..self.titles.len())
            .map(|c| {
                if c == 0 {
                    return "best".to_owned();
                }
                self.best
                    .iter()
                    .position(|row| row[c])
                    .map_or(String::new(), |i| self.cells[i][0].clone())
            })
            .collect();
        out.push_str(&line(&best));
        out.push('\n');
        out
    }
}
