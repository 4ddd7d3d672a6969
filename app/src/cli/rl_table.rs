//! The figures of `dmpscope rl` runs ([`RunReport`]s): the text table (one
//! row per run, then a line per gain set) and the JSON.

use std::fmt::Write as _;

use dmpscope_core::rl::run::{RunReport, summarise};
use dmpscope_core::rl::table::{CURVE_TITLE, RUN_COLUMNS, curve};
use serde_json::json;

/// A run as JSON.
pub fn json(o: &RunReport) -> serde_json::Value {
    json!({
        "gains": o.name, "dm": o.dm, "km": o.km, "seed": o.seed,
        "final_error_m": o.greedy.final_error, "d_m": o.d,
        "a_peak": o.greedy.a_peak(), "reached": o.reached,
        "diverged": o.diverged,
        "first_reach": o.first_reach.map(|f| json!({"decisions": f.decisions, "seconds": f.seconds})),
        "held_after_first_reach": o.held,
        "train_seconds": o.seconds, "returns": o.returns,
        "path": o.greedy.path,
    })
}

/// The table of runs, then one summary line per gain set.
pub fn table(outcomes: &[RunReport]) -> String {
    let mut text = String::new();
    let line = |cells: Vec<String>, last: &str| {
        let parts: Vec<String> = RUN_COLUMNS
            .iter()
            .zip(cells)
            .map(|(c, cell)| {
                if c.left {
                    format!("{cell:<w$}", w = c.width)
                } else {
                    format!("{cell:>w$}", w = c.width)
                }
            })
            .collect();
        format!("{}  {last}\n", parts.join(" "))
    };
    text.push_str(&line(
        RUN_COLUMNS.iter().map(|c| c.title.to_owned()).collect(),
        CURVE_TITLE,
    ));
    for o in outcomes {
        let cells = RUN_COLUMNS.iter().map(|c| (c.cell)(o)).collect();
        text.push_str(&line(cells, &curve(&o.returns)));
    }
    if outcomes.len() > 1 {
        text.push('\n');
        for set in summarise(outcomes) {
            let _ = writeln!(
                text,
                "{:<10} reached {}/{n}, stable {}/{n}, median final error {:.2} mm",
                set.name,
                set.reached,
                set.stable,
                set.median_final_error * 1e3,
                n = set.runs
            );
        }
    }
    text
}
