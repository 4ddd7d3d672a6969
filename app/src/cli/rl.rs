//! `dmpscope rl`: train a PPO agent whose action is the DMP forcing term
//! (method.md section 8) for one demo at chosen gains, or `--compare` the
//! extracted gains with the paper's (the paper's Fig. 5 as a table).

use std::fmt::Write as _;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use dmpscope_core::Model;
use dmpscope_core::presets::PAPER_PRESETS;
use dmpscope_core::rl::{DmpEnv, GreedyRun, PpoConfig, REACHED_M, Trainer};
use serde_json::json;

use super::inputs::{InputArgs, load_model};
use super::landscape::{GridArgs, landscape_and_optimum};
use super::output::{progress_bar, write_text};

/// Arguments of `rl`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    input: InputArgs,
    #[command(flatten)]
    grid: GridArgs,
    /// The demo to learn (1-based, in `dmpscope info` order).
    #[arg(long, default_value_t = 1)]
    demo: usize,
    /// D/M of the gains (with --km).
    #[arg(long, requires = "km", conflicts_with_all = ["preset", "extracted", "compare"])]
    dm: Option<f64>,
    /// K/M of the gains (with --dm).
    #[arg(long, requires = "dm")]
    km: Option<f64>,
    /// The gains of a paper preset (Ours, Hrstc1 ... Hrstc4).
    #[arg(long, conflicts_with_all = ["extracted", "compare"])]
    preset: Option<String>,
    /// The gains extracted from the inputs' landscape.
    #[arg(long, conflicts_with = "compare")]
    extracted: bool,
    /// Train for the extracted gains and every paper preset and print the
    /// comparison table.
    #[arg(long)]
    compare: bool,
    /// Environment decisions to train for (100 per episode).
    #[arg(long, default_value_t = dmpscope_core::rl::DEFAULT_DECISIONS)]
    steps: usize,
    /// Seed of the first run.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Runs per gain set with --compare (seeds seed, seed+1, ...).
    #[arg(long, default_value_t = 3)]
    seeds: u64,
    /// Write the results as JSON here.
    #[arg(long, short)]
    out: Option<PathBuf>,
}

/// One training run's outcome.
struct Outcome {
    name: String,
    dm: f64,
    km: f64,
    seed: u64,
    run: GreedyRun,
    d: f64,
    returns: Vec<f64>,
    seconds: f64,
}

impl Outcome {
    fn reached(&self) -> bool {
        self.run.final_error <= REACHED_M
    }

    fn json(&self) -> serde_json::Value {
        json!({
            "gains": self.name, "dm": self.dm, "km": self.km, "seed": self.seed,
            "final_error_m": self.run.final_error, "d_m": self.d,
            "a_peak": self.run.a_peak(), "reached": self.reached(),
            "train_seconds": self.seconds, "returns": self.returns,
            "path": self.run.path,
        })
    }
}

fn train(
    model: &Model,
    demo: usize,
    gains: (&str, f64, f64),
    steps: usize,
    seed: u64,
) -> anyhow::Result<Outcome> {
    let (name, dm, km) = gains;
    let env = DmpEnv::new(&model.demos()[demo], dm, km)?;
    let mut trainer = Trainer::new(env, PpoConfig::default(), seed);
    let bar = progress_bar(steps as u64, &format!("PPO {name} seed {seed}"));
    let start = Instant::now();
    while trainer.decisions() < steps {
        let stats = trainer.iterate();
        bar.set_position(stats.decisions.min(steps) as u64);
    }
    let seconds = start.elapsed().as_secs_f64();
    bar.finish_and_clear();
    let run = trainer.greedy();
    let d = model.path_error(demo, &run.path);
    Ok(Outcome {
        name: name.to_owned(),
        dm,
        km,
        seed,
        d,
        returns: trainer.returns.clone(),
        run,
        seconds,
    })
}

fn curve(returns: &[f64]) -> String {
    let at = |f: f64| returns[((returns.len() - 1) as f64 * f) as usize];
    if returns.is_empty() {
        return "-".into();
    }
    format!("{:.3} -> {:.3} -> {:.3}", at(0.0), at(0.5), at(1.0))
}

/// Trains and prints the outcome (or the comparison table).
pub fn run(args: Args) -> anyhow::Result<()> {
    if args.steps == 0 || args.seeds == 0 {
        anyhow::bail!("--steps and --seeds must be at least 1");
    }
    let input = &args.input;
    let needs_landscape = args.extracted || args.compare;
    let (model, extracted): (Arc<Model>, Option<(f64, f64)>) = if needs_landscape {
        let (_, model, _, x) = landscape_and_optimum(input, &args.grid)?;
        (model, Some((x.eval.dm, x.eval.km)))
    } else {
        (load_model(input)?.1, None)
    };
    let n = model.demos().len();
    if args.demo == 0 || args.demo > n {
        anyhow::bail!("--demo must be between 1 and {n}, got {}", args.demo);
    }
    let demo = args.demo - 1;
    let mut sets: Vec<(String, f64, f64)> = Vec::new();
    if let (Some(dm), Some(km)) = (args.dm, args.km) {
        for (flag, v) in [("--dm", dm), ("--km", km)] {
            if !(v.is_finite() && v > 0.0) {
                anyhow::bail!("{flag} must be a positive number, got {v}");
            }
        }
        sets.push(("given".into(), dm, km));
    } else if let Some(name) = &args.preset {
        let p = PAPER_PRESETS
            .iter()
            .find(|p| p.name.eq_ignore_ascii_case(name))
            .ok_or_else(|| {
                let names: Vec<_> = PAPER_PRESETS.iter().map(|p| p.name).collect();
                anyhow::anyhow!("no preset {name:?}; the presets are {}", names.join(", "))
            })?;
        sets.push((p.name.into(), p.dm, p.km));
    } else if let Some((dm, km)) = extracted {
        sets.push(("Extracted".into(), dm, km));
        if args.compare {
            sets.extend(
                PAPER_PRESETS
                    .iter()
                    .map(|p| (p.name.to_owned(), p.dm, p.km)),
            );
        }
    } else {
        anyhow::bail!("choose the gains: --dm X --km Y, --preset NAME, --extracted or --compare");
    }
    let seeds: Vec<u64> = if args.compare {
        (0..args.seeds).map(|i| args.seed + i).collect()
    } else {
        vec![args.seed]
    };
    let mut outcomes = Vec::new();
    for (name, dm, km) in &sets {
        for &seed in &seeds {
            outcomes.push(train(&model, demo, (name, *dm, *km), args.steps, seed)?);
        }
    }
    let mut text = String::new();
    let _ = writeln!(
        text,
        "RL with DMP on {} ({} decisions of training per run)",
        model.demos()[demo].name,
        args.steps
    );
    let _ = writeln!(
        text,
        "{:<10} {:>8} {:>9} {:>5} {:>8} {:>15} {:>9} {:>8} {:>9}  learning curve (mean return: first -> middle -> last)",
        "gains", "D/M", "K/M", "seed", "reached", "final error mm", "d mm", "a_peak", "train s"
    );
    for o in &outcomes {
        let _ = writeln!(
            text,
            "{:<10} {:>8.3} {:>9.3} {:>5} {:>8} {:>15.3} {:>9.3} {:>8.2} {:>9.2}  {}",
            o.name,
            o.dm,
            o.km,
            o.seed,
            if o.reached() { "yes" } else { "no" },
            o.run.final_error * 1e3,
            o.d * 1e3,
            o.run.a_peak(),
            o.seconds,
            curve(&o.returns)
        );
    }
    print!("{text}");
    if let Some(out) = &args.out {
        let value = if outcomes.len() == 1 {
            outcomes[0].json()
        } else {
            json!({ "runs": outcomes.iter().map(Outcome::json).collect::<Vec<_>>() })
        };
        write_text(Some(out), &serde_json::to_string_pretty(&value)?)?;
    }
    Ok(())
}
