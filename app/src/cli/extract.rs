//! `dmpscope extract`: the gains minimising J, whether the data determine
//! them (the diagnostics of method.md section 9), and Table I comparing
//! them with the paper's gains.

use dmpscope_core::extract::allowed::{DEFAULT_EPS, PickRule, PickSettings};
use dmpscope_core::extract::diagnostics::{DiagSettings, DiagnosticsJob};
use dmpscope_core::report::extraction::{ExtractSettings, extract_report};
use dmpscope_core::report::summary::LoadingChoices;

use super::inputs::InputArgs;
use super::landscape::{GridArgs, landscape_and_optimum};
use super::output::{print_notices, progress_bar};

/// Arguments of `extract`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    input: InputArgs,
    #[command(flatten)]
    grid: GridArgs,
    /// Print the report as JSON (the shape documented in
    /// `dmpscope_core::report`: k, demos, optimum, table, diagnostics)
    /// instead of text.
    #[arg(long)]
    json: bool,
    /// Skip the diagnostics (depth, shares, leave-one-out, bootstrap).
    #[arg(long)]
    no_diagnostics: bool,
    /// Bootstrap resamples.
    #[arg(long, default_value_t = DiagSettings::default().bootstrap)]
    bootstrap: usize,
    /// The bootstrap's seed.
    #[arg(long, default_value_t = DiagSettings::default().seed)]
    bootstrap_seed: u64,
    /// Points per axis of the leave-one-out and bootstrap extractions' grid
    /// (same box; at most --grid).
    #[arg(long, default_value_t = DiagSettings::default().grid_points)]
    diag_grid: usize,
    /// Also find the least J among the gains whose largest peak
    /// acceleration (any demo) stays within this many m/s^2.
    #[arg(long, value_name = "M_PER_S2")]
    a_peak_limit: Option<f64>,
    /// The acceptable region: the grid points whose J is within this
    /// fraction of the optimum's (method.md section 11).
    #[arg(long, default_value_t = DEFAULT_EPS, value_name = "EPS", value_parser = accept_eps)]
    accept_eps: f64,
    /// How to pick the gains in the acceptable region: optimum (J's),
    /// compliant (least K/M with zeta in [0.7, 1.5]), critical (zeta
    /// nearest 1) or smooth (least peak acceleration). Default: optimum
    /// when J is not flat, compliant when it is.
    #[arg(long, value_parser = pick_rule, value_name = "RULE")]
    pick: Option<PickRule>,
    /// Keep the compliant, critical and smooth picks to gains whose
    /// spring-damper settles (2 %) within this many unit times (method.md
    /// section 11, "Settling"; 1 is the motion's own duration).
    #[arg(long, value_name = "UNIT_TIMES", value_parser = accept_eps)]
    settle_within: Option<f64>,
}

/// A pick rule by name.
fn pick_rule(text: &str) -> Result<PickRule, String> {
    text.parse()
}

/// A tolerance above zero.
fn accept_eps(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!(
            "expected a fraction above 0 (0.02 is 2 %), got {text:?}"
        )),
    }
}

/// Prints `(M:D:K)`, zeta, J, the edge flag, the diagnostics and Table I
/// ([`dmpscope_core::Report::extract_text`]), or the report as JSON.
pub fn run(args: Args) -> anyhow::Result<()> {
    let (_, model, land, optimum) = landscape_and_optimum(&args.input, &args.grid)?;
    let settings = ExtractSettings {
        k: args.grid.k,
        loading: Some(LoadingChoices::of(
            &args.input.load.options(),
            &args.input.prep(),
        )),
        diagnostics: (!args.no_diagnostics).then_some(DiagSettings {
            grid_points: args.diag_grid,
            bootstrap: args.bootstrap,
            seed: args.bootstrap_seed,
        }),
        pick: PickSettings {
            rule: args.pick,
            eps: args.accept_eps,
            a_peak_limit: args.a_peak_limit,
            settle_within: args.settle_within,
        },
    };
    let report = extract_report(
        &model,
        &land,
        &optimum,
        &settings,
        &mut run_the_diagnostics,
        &mut |notice| print_notices(&[notice]),
    )
    .map_err(|e| match e {
        // The a_peak limit's message names its flag: shown as is.
        dmpscope_core::Error::InvalidSetting(m) => anyhow::anyhow!(m),
        other => other.into(),
    })?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
        return Ok(());
    }
    print!("{}", report.extract_text());
    Ok(())
}

/// Runs the diagnostics with a progress bar.
fn run_the_diagnostics(job: &mut DiagnosticsJob) -> dmpscope_core::Result<()> {
    let bar = progress_bar(job.progress().1 as u64, "diagnostics");
    job.run(&|done| bar.set_position(done as u64));
    bar.finish_and_clear();
    Ok(())
}
