//! The table of training runs (`dmpscope rl --compare` and the app's RL
//! panel), its columns declared once: per run the gains, seed, whether and
//! how closely the policy's mean reaches the goal, d against the demo,
//! a_peak, when it first reached, how steadily it stayed reached, the
//! training time and whether training stayed stable.

use crate::rl::run::RunReport;

/// A column of the runs' table.
#[derive(Clone, Copy, Debug)]
pub struct RunColumn {
    /// Its title.
    pub title: &'static str,
    /// The terminal's column width.
    pub width: usize,
    /// Whether the terminal aligns it left (the name) or right (numbers).
    pub left: bool,
    /// A run's cell.
    pub cell: fn(&RunReport) -> String,
}

/// The runs' table's columns, in order.
pub const RUN_COLUMNS: [RunColumn; 13] = [
    RunColumn {
        title: "gains",
        width: 10,
        left: true,
        cell: |r| r.name.clone(),
    },
    RunColumn {
        title: "D/M",
        width: 8,
        left: false,
        cell: |r| format!("{:.3}", r.dm),
    },
    RunColumn {
        title: "K/M",
        width: 9,
        left: false,
        cell: |r| format!("{:.3}", r.km),
    },
    RunColumn {
        title: "seed",
        width: 5,
        left: false,
        cell: |r| r.seed.to_string(),
    },
    RunColumn {
        title: "reached",
        width: 8,
        left: false,
        cell: |r| yes_no(r.reached),
    },
    RunColumn {
        title: "error mm",
        width: 9,
        left: false,
        cell: |r| format!("{:.3}", r.greedy.final_error * 1e3),
    },
    RunColumn {
        title: "d mm",
        width: 8,
        left: false,
        cell: |r| format!("{:.3}", r.d * 1e3),
    },
    RunColumn {
        title: "a_peak",
        width: 8,
        left: false,
        cell: |r| format!("{:.2}", r.greedy.a_peak()),
    },
    RunColumn {
        title: "1st reach",
        width: 11,
        left: false,
        cell: |r| {
            r.first_reach
                .map_or("-".to_owned(), |f| f.decisions.to_string())
        },
    },
    RunColumn {
        title: "at s",
        width: 6,
        left: false,
        cell: |r| {
            r.first_reach
                .map_or("-".to_owned(), |f| format!("{:.1}", f.seconds))
        },
    },
    RunColumn {
        title: "held",
        width: 6,
        left: false,
        cell: |r| {
            r.held
                .map_or("-".to_owned(), |h| format!("{:.0}%", 100.0 * h))
        },
    },
    RunColumn {
        title: "train s",
        width: 8,
        left: false,
        cell: |r| format!("{:.1}", r.seconds),
    },
    RunColumn {
        title: "stable",
        width: 6,
        left: false,
        cell: |r| yes_no(!r.diverged),
    },
];

/// The title of the learning curve that follows the columns.
pub const CURVE_TITLE: &str = "learning curve (mean return: first -> middle -> last)";

fn yes_no(b: bool) -> String {
    if b { "yes" } else { "no" }.to_owned()
}

/// A learning curve in three numbers: the mean return first, midway and
/// last (`-` without any).
pub fn curve(returns: &[f64]) -> String {
    if returns.is_empty() {
        return "-".into();
    }
    let at = |f: f64| returns[((returns.len() - 1) as f64 * f) as usize];
    format!("{:.3} -> {:.3} -> {:.3}", at(0.0), at(0.5), at(1.0))
}
