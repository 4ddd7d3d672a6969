//! The figures of `dmpscope rl` runs: one [`Outcome`] per run, the text
//! table (one row per run, then a line per gain set) and the JSON.

use std::fmt::Write as _;

use dmpscope_core::rl::{FirstReach, GreedyRun};
use serde_json::json;

/// One training run's outcome.
pub struct Outcome {
    /// The gain set's name.
    pub name: String,
    /// D/M.
    pub dm: f64,
    /// K/M.
    pub km: f64,
    /// The seed.
    pub seed: u64,
    /// The policy's mean run at the end.
    pub run: GreedyRun,
    /// `d` of that run against the demo, metres.
    pub d: f64,
    /// Whether it ends within 5 mm of the goal.
    pub reached: bool,
    /// Whether the learning curve diverged.
    pub diverged: bool,
    /// When the mean first reached.
    pub first_reach: Option<FirstReach>,
    /// The learning curve.
    pub returns: Vec<f64>,
    /// Training time, seconds.
    pub seconds: f64,
}

impl Outcome {
    /// The run as JSON.
    pub fn json(&self) -> serde_json::Value {
        json!({
            "gains": self.name, "dm": self.dm, "km": self.km, "seed": self.seed,
            "final_error_m": self.run.final_error, "d_m": self.d,
            "a_peak": self.run.a_peak(), "reached": self.reached,
            "diverged": self.diverged,
            "first_reach": self.first_reach.map(|f| json!({"decisions": f.decisions, "seconds": f.seconds})),
            "train_seconds": self.seconds, "returns": self.returns,
            "path": self.run.path,
        })
    }
}

fn curve(returns: &[f64]) -> String {
    if returns.is_empty() {
        return "-".into();
    }
    let at = |f: f64| returns[((returns.len() - 1) as f64 * f) as usize];
    format!("{:.3} -> {:.3} -> {:.3}", at(0.0), at(0.5), at(1.0))
}

/// The table of runs, then one summary line per gain set.
pub fn table(outcomes: &[Outcome]) -> String {
    let mut text = String::new();
    let _ = writeln!(
        text,
        "{:<10} {:>8} {:>9} {:>5} {:>8} {:>9} {:>8} {:>8} {:>11} {:>8} {:>8} {:>6}  learning curve (mean return: first -> middle -> last)",
        "gains", "D/M", "K/M", "seed", "reached", "error mm", "d mm", "a_peak",
        "1st reach", "at s", "train s", "stable"
    );
    for o in outcomes {
        let (fd, fs) = o.first_reach.map_or(("-".to_owned(), "-".to_owned()), |f| {
            (f.decisions.to_string(), format!("{:.1}", f.seconds))
        });
        let _ = writeln!(
            text,
            "{:<10} {:>8.3} {:>9.3} {:>5} {:>8} {:>9.3} {:>8.3} {:>8.2} {:>11} {:>8} {:>8.1} {:>6}  {}",
            o.name,
            o.dm,
            o.km,
            o.seed,
            if o.reached { "yes" } else { "no" },
            o.run.final_error * 1e3,
            o.d * 1e3,
            o.run.a_peak(),
            fd,
            fs,
            o.seconds,
            if o.diverged { "no" } else { "yes" },
            curve(&o.returns)
        );
    }
    let mut names: Vec<&str> = Vec::new();
    for o in outcomes {
        if !names.contains(&o.name.as_str()) {
            names.push(&o.name);
        }
    }
    if outcomes.len() > 1 {
        text.push('\n');
        for name in names {
            let runs: Vec<&Outcome> = outcomes.iter().filter(|o| o.name == name).collect();
            let reached = runs.iter().filter(|o| o.reached).count();
            let stable = runs.iter().filter(|o| !o.diverged).count();
            let mut errs: Vec<f64> = runs.iter().map(|o| o.run.final_error * 1e3).collect();
            errs.sort_by(f64::total_cmp);
            let median = errs[errs.len() / 2];
            let _ = writeln!(
                text,
                "{name:<10} reached {reached}/{n}, stable {stable}/{n}, median final error {median:.2} mm",
                n = runs.len()
            );
        }
    }
    text
}
