//! Table I as text: one summary row per gain set, then `d_mean` and
//! `a_peak` per demo with one column per gain set.

use std::fmt::Write;

use dmpscope_core::TableRow;

/// Renders the rows for a terminal.
pub fn render(rows: &[TableRow], demo_names: &[String]) -> String {
    let mut s = String::new();
    let name_w = rows.iter().map(|r| r.name.len()).max().unwrap_or(4).max(9);
    let _ = writeln!(
        s,
        "{:<name_w$}  {:>9}  {:>9}  {:>7}  {:>9}  {:>9}  {:>9}",
        "gains", "D/M", "K/M", "zeta", "S", "sum d[m]", "J"
    );
    for r in rows {
        let _ = writeln!(
            s,
            "{:<name_w$}  {:>9.3}  {:>9.3}  {:>7.3}  {:>9.5}  {:>9.5}  {:>9.5}",
            r.name, r.dm, r.km, r.zeta, r.s, r.d_sum, r.j
        );
    }
    let demo_w = demo_names.iter().map(String::len).max().unwrap_or(4).max(8);
    let col_w = name_w.max(9);
    for (title, pick, scale, prec) in [
        (
            "d_mean [mm]",
            (|r: &TableRow| r.d_mean.clone()) as fn(&TableRow) -> Vec<f64>,
            1e3,
            3,
        ),
        ("a_peak [m/s^2]", |r: &TableRow| r.a_peak.clone(), 1.0, 2),
    ] {
        let _ = writeln!(s, "\nTable I: {title}");
        let _ = write!(s, "{:<demo_w$}", "demo");
        for r in rows {
            let _ = write!(s, "  {:>col_w$}", r.name);
        }
        s.push('\n');
        let columns: Vec<Vec<f64>> = rows.iter().map(pick).collect();
        for (i, name) in demo_names.iter().enumerate() {
            let _ = write!(s, "{name:<demo_w$}");
            for c in &columns {
                let _ = write!(s, "  {:>col_w$.prec$}", c[i] * scale);
            }
            s.push('\n');
        }
        let _ = write!(s, "{:<demo_w$}", "mean");
        for c in &columns {
            let mean = c.iter().sum::<f64>() / c.len().max(1) as f64;
            let _ = write!(s, "  {:>col_w$.prec$}", mean * scale);
        }
        s.push('\n');
    }
    s
}
