//! The figures of `dmpscope rl` runs ([`RunReport`]s): the text table (one
//! row per run, then a line per gain set) and the JSON.

use std::fmt::Write as _;

use dmpscope_core::rl::run::{RunReport, summarise};
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

fn curve(returns: &[f64]) -> String {
    if returns.is_empty() {
        return "-".into();
    }
    let at = |f: f64| returns[((returns.len() - 1) as f64 * f) as usize];
    format!("{:.3} -> {:.3} -> {:.3}", at(0.0), at(0.5), at(1.0))
}

/// The table of runs, then one summary line per gain set.
pub fn table(outcomes: &[RunReport]) -> String {
    let mut text = String::new();
    let _ = writeln!(
        text,
        "{:<10} {:>8} {:>9} {:>5} {:>8} {:>9} {:>8} {:>8} {:>11} {:>6} {:>6} {:>8} {:>6}  learning curve (mean return: first -> middle -> last)",
        "gains",
        "D/M",
        "K/M",
        "seed",
        "reached",
        "error mm",
        "d mm",
        "a_peak",
        "1st reach",
        "at s",
        "held",
        "train s",
        "stable"
    );
    for o in outcomes {
        let (fd, fs) = o.first_reach.map_or(("-".to_owned(), "-".to_owned()), |f| {
            (f.decisions.to_string(), format!("{:.1}", f.seconds))
        });
        let held = o
            .held
            .map_or("-".to_owned(), |h| format!("{:.0}%", 100.0 * h));
        let _ = writeln!(
            text,
            "{:<10} {:>8.3} {:>9.3} {:>5} {:>8} {:>9.3} {:>8.3} {:>8.2} {:>11} {:>6} {:>6} {:>8.1} {:>6}  {}",
            o.name,
            o.dm,
            o.km,
            o.seed,
            if o.reached { "yes" } else { "no" },
            o.greedy.final_error * 1e3,
            o.d * 1e3,
            o.greedy.a_peak(),
            fd,
            fs,
            held,
            o.seconds,
            if o.diverged { "no" } else { "yes" },
            curve(&o.returns)
        );
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
