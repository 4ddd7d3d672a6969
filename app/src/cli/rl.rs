//! `dmpscope rl`: train a PPO agent whose action is the DMP forcing term
//! (method.md section 8) for one demo at chosen gains, or `--compare` the
//! extracted gains with the paper's (the paper's Fig. 5 as a table; the
//! runs share the machine's cores, `--jobs`).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Instant;

use dmpscope_core::Model;
use dmpscope_core::report::presets::PAPER_PRESETS;
use dmpscope_core::rl::env::{ActionMode, EnvOptions, ExploreScale};
use dmpscope_core::rl::run::{RunReport, TrainingRun};
use serde_json::json;

use super::inputs::{InputArgs, load_model};
use super::landscape::{GridArgs, landscape_and_optimum};
use super::output::{progress_bar, write_text};
use super::rl_table::{json as run_json, table};

/// What the action is (method.md section 8).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum Mode {
    /// The action is the whole forcing term (the paper).
    Forcing,
    /// The action is added to the demo's fitted forcing term at the gains.
    Residual,
}

/// What the policy's initial exploration is scaled to (method.md
/// section 8).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum Explore {
    /// The demo's own acceleration (its RMS per axis).
    Acceleration,
    /// The demo's fitted forcing term at the gains (its RMS per axis).
    Forcing,
}

impl From<Explore> for ExploreScale {
    fn from(e: Explore) -> Self {
        match e {
            Explore::Acceleration => Self::Acceleration,
            Explore::Forcing => Self::Forcing,
        }
    }
}

impl From<Mode> for ActionMode {
    fn from(m: Mode) -> Self {
        match m {
            Mode::Forcing => Self::Forcing,
            Mode::Residual => Self::Residual,
        }
    }
}

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
    /// What the action is.
    #[arg(long, value_enum, default_value_t = Mode::Forcing)]
    mode: Mode,
    /// What the policy's initial deviation (0.5 of it) is scaled to.
    #[arg(long, value_enum, default_value_t = Explore::Acceleration)]
    explore: Explore,
    /// Decisions per episode: 100 (each held 10 integration steps) or 1000
    /// (one per integration step); any count from 1 to the demo's
    /// integration steps works (each held ceil(steps / decisions)).
    #[arg(long, default_value_t = dmpscope_core::rl::env::DECISIONS)]
    decisions: usize,
    /// Environment decisions to train for.
    #[arg(long, default_value_t = dmpscope_core::rl::ppo::DEFAULT_DECISIONS)]
    steps: usize,
    /// Seed of the first run.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Runs per gain set, seeds seed, seed+1, ... (default: 3 with
    /// --compare, else 1).
    #[arg(long)]
    seeds: Option<u64>,
    /// Runs trained at once when there are several (--compare, --seeds;
    /// default: the machine's cores).
    #[arg(long)]
    jobs: Option<usize>,
    /// Write the results as JSON here.
    #[arg(long, short)]
    out: Option<PathBuf>,
    /// Write the trained policy (network, log-sds, observation normaliser,
    /// the environment's scales) as JSON here (the last seed's).
    #[arg(long, conflicts_with = "compare")]
    save_policy: Option<PathBuf>,
}

/// A finished run: its figures and the run (for `--save-policy`).
type Trained = anyhow::Result<(RunReport, TrainingRun)>;

/// A run to do.
struct Job {
    name: String,
    gains: (f64, f64),
    seed: u64,
}

fn train(
    model: &Model,
    demo: usize,
    job: &Job,
    options: EnvOptions,
    steps: usize,
    bar: &indicatif::ProgressBar,
) -> Trained {
    let mut run = TrainingRun::new(model, demo, job.gains, options, steps, job.seed)
        .map_err(|e| anyhow::anyhow!("{} gains: {e}", job.name))?;
    let start = Instant::now();
    let mut last = 0;
    while !run.done() {
        let stats = run
            .step(start.elapsed().as_secs_f64())
            .map_err(|e| anyhow::anyhow!("{} gains, seed {}: {e}", job.name, job.seed))?;
        if let Some(s) = stats {
            bar.inc((s.decisions.min(steps) - last) as u64);
            last = s.decisions.min(steps);
        }
    }
    let outcome = run
        .report(model, &job.name, start.elapsed().as_secs_f64())
        .ok_or_else(|| anyhow::anyhow!("training ended before its first iteration"))?;
    Ok((outcome, run))
}

/// The gain sets the arguments ask for.
fn gain_sets(
    args: &Args,
    extracted: Option<(f64, f64)>,
) -> anyhow::Result<Vec<(String, f64, f64)>> {
    let mut sets = Vec::new();
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
    Ok(sets)
}

/// The model, and the landscape's optimum `(D/M, K/M)` where it was needed.
type ModelAndOptimum = (Arc<Model>, Option<(f64, f64)>);

/// Loads the model, and the landscape's optimum when the gains need it.
fn model_and_extracted(args: &Args) -> anyhow::Result<ModelAndOptimum> {
    let input = &args.input;
    let needs_landscape = args.extracted || args.compare;
    Ok(if needs_landscape {
        let (_, model, _, x) = landscape_and_optimum(input, &args.grid)?;
        (model, Some((x.eval.dm, x.eval.km)))
    } else {
        (load_model(input)?.1, None)
    })
}

/// One run per gain set and seed, in the order of the table.
fn the_jobs(args: &Args, extracted: Option<(f64, f64)>, n_seeds: u64) -> anyhow::Result<Vec<Job>> {
    let seeds: Vec<u64> = (0..n_seeds).map(|i| args.seed + i).collect();
    let jobs: Vec<Job> = gain_sets(args, extracted)?
        .into_iter()
        .flat_map(|(name, dm, km)| {
            seeds.iter().map(move |&seed| Job {
                name: name.clone(),
                gains: (dm, km),
                seed,
            })
        })
        .collect();
    Ok(jobs)
}

/// Trains the jobs on `workers` threads; their figures in job order, and the last run.
fn train_all(
    model: &Model,
    demo: usize,
    jobs: &[Job],
    options: EnvOptions,
    steps: usize,
    workers: usize,
) -> anyhow::Result<(Vec<RunReport>, Option<TrainingRun>)> {
    let bar = progress_bar((steps * jobs.len()) as u64, "PPO");
    let next = AtomicUsize::new(0);
    let results: Mutex<Vec<Option<Trained>>> = Mutex::new((0..jobs.len()).map(|_| None).collect());
    std::thread::scope(|scope| {
        for _ in 0..workers {
            scope.spawn(|| {
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    let Some(job) = jobs.get(i) else { break };
                    let r = train(model, demo, job, options, steps, &bar);
                    if let Ok(mut all) = results.lock() {
                        all[i] = Some(r);
                    }
                }
            });
        }
    });
    bar.finish_and_clear();
    let results = results
        .into_inner()
        .map_err(|_| anyhow::anyhow!("a training thread panicked"))?;
    let mut outcomes = Vec::new();
    let mut last_run = None;
    for r in results {
        let (o, run) = r.ok_or_else(|| anyhow::anyhow!("a training run did not finish"))??;
        outcomes.push(o);
        last_run = Some(run);
    }
    Ok((outcomes, last_run))
}

/// Prints what was trained and the outcome table.
fn print_the_outcomes(args: &Args, demo_name: &str, workers: usize, outcomes: &[RunReport]) {
    let mut text = String::new();
    let _ = writeln!(
        text,
        "RL with DMP on {} ({} decisions of training per run, {} decisions per episode, action: {}, exploration: {}, {} run(s) at once)",
        demo_name,
        args.steps,
        args.decisions,
        ActionMode::from(args.mode).name(),
        ExploreScale::from(args.explore).name(),
        workers
    );
    text.push_str(&table(outcomes));
    print!("{text}");
}

/// Writes the outcomes as JSON to `out`: the one run, or every run under `runs`.
fn write_the_outcomes(out: &Path, outcomes: &[RunReport]) -> anyhow::Result<()> {
    let value = if outcomes.len() == 1 {
        run_json(&outcomes[0])
    } else {
        json!({ "runs": outcomes.iter().map(run_json).collect::<Vec<_>>() })
    };
    write_text(Some(out), &serde_json::to_string_pretty(&value)?)
}

/// Writes the run's trained policy, with the environment's scales, as JSON to `path`.
fn save_the_policy(path: &Path, demo_name: &str, run: &TrainingRun) -> anyhow::Result<()> {
    let env = run.trainer().task();
    let value = json!({
        "format": "dmpscope.policy",
        "version": 1,
        "demo": demo_name,
        "dm": env.dm, "km": env.km,
        "mode": env.mode().name(),
        "decisions_per_episode": dmpscope_core::rl::task::Task::decisions(env),
        "integration_steps_per_decision": env.hold(),
        "start": env.start(), "goal": env.goal(),
        "action_scale": env.action_scale(),
        "observation_scale_m": env.observation_scale(),
        "observation": "phase s, then (y - g) / r per axis, then y' / r per axis (unit time); normalised by obs_norm, clipped to +-10",
        "action": "u = actor(normalised observation); forcing term A = action_scale * u (+ the fitted forcing term in residual mode)",
        "policy": run.trainer().policy(),
    });
    write_text(Some(path), &serde_json::to_string_pretty(&value)?)
}

/// Trains and prints the outcome (or the comparison table).
pub fn run(args: Args) -> anyhow::Result<()> {
    let n_seeds = args.seeds.unwrap_or(if args.compare { 3 } else { 1 });
    if args.steps == 0 || n_seeds == 0 || args.jobs == Some(0) {
        anyhow::bail!("--steps, --seeds and --jobs must be at least 1");
    }
    let (model, extracted) = model_and_extracted(&args)?;
    let n = model.demos().len();
    if args.demo == 0 || args.demo > n {
        anyhow::bail!("--demo must be between 1 and {n}, got {}", args.demo);
    }
    let demo = args.demo - 1;
    let options = EnvOptions {
        decisions: args.decisions,
        mode: args.mode.into(),
        explore: args.explore.into(),
    };
    let jobs = the_jobs(&args, extracted, n_seeds)?;
    let workers = args
        .jobs
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, usize::from))
        .min(jobs.len());
    let (outcomes, last_run) = train_all(&model, demo, &jobs, options, args.steps, workers)?;
    let demo_name = &model.demos()[demo].name;
    print_the_outcomes(&args, demo_name, workers, &outcomes);
    if let Some(out) = &args.out {
        write_the_outcomes(out, &outcomes)?;
    }
    if let (Some(path), Some(run)) = (&args.save_policy, &last_run) {
        save_the_policy(path, demo_name, run)?;
    }
    Ok(())
}
