//! `dmpscope extract`: the gains minimising J, whether the data determine
//! them (the diagnostics of method.md section 9), and Table I comparing
//! them with the paper's gains.

use std::sync::Arc;

use dmpscope_core::extract::allowed::{Allowed, DEFAULT_EPS, PickRule, PickSettings};
use dmpscope_core::extract::diagnostics::{DiagSettings, DiagnosticsJob};
use dmpscope_core::landscape::grid::Landscape;
use dmpscope_core::report::summary::{Constrained, LoadingChoices};
use dmpscope_core::report::table::TableRow;
use dmpscope_core::{Extraction, Model, Report};

use super::inputs::InputArgs;
use super::landscape::{GridArgs, landscape_and_optimum};
use super::output::progress_bar;

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

/// Prints `(M:D:K)`, zeta, J, the edge flag, the diagnostics and Table I.
pub fn run(args: Args) -> anyhow::Result<()> {
    let (_, model, land, optimum) = landscape_and_optimum(&args.input, &args.grid)?;
    let mut report = Report::new(&model, Some(&optimum), args.grid.k);
    report.loading = Some(LoadingChoices::of(
        &args.input.load.options(),
        &args.input.prep(),
    ));
    if !args.no_diagnostics {
        report = add_the_diagnostics(&args, report, &model, &land, &optimum);
    }
    if let Some(limit) = args.a_peak_limit {
        if !(limit.is_finite() && limit > 0.0) {
            anyhow::bail!("--a-peak-limit must be a positive number of m/s^2, got {limit}");
        }
        report.constrained = Some(Constrained::compute(&model, &land, args.grid.k, limit));
    }
    add_the_allowed(&args, &mut report, &model, &land, &optimum);
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
        return Ok(());
    }
    print_the_report(&report, optimum.j);
    Ok(())
}

/// Runs the diagnostics (with a progress bar, and a note when J is flat)
/// and adds them to the report.
fn add_the_diagnostics(
    args: &Args,
    report: Report,
    model: &Arc<Model>,
    land: &Landscape,
    optimum: &Extraction,
) -> Report {
    let settings = DiagSettings {
        grid_points: args.diag_grid,
        bootstrap: args.bootstrap,
        seed: args.bootstrap_seed,
    };
    let mut job = DiagnosticsJob::new(Arc::clone(model), land, optimum, settings);
    let bar = progress_bar(job.progress().1 as u64, "diagnostics");
    job.run(&|done| bar.set_position(done as u64));
    bar.finish_and_clear();
    if job.diagnostics().flat {
        eprintln!(
            "note: J is flat (depth below {}): J alone does not determine the gains; the \
             output says what the data allow and which gains are picked in it",
            dmpscope_core::extract::diagnostics::balance::FLAT_DEPTH
        );
    }
    report.with_diagnostics(job.diagnostics().clone(), job.about().clone())
}

/// Adds what the data allow and the gains picked in it (a row of Table I),
/// warning of a missing skill error or a failed pick.
fn add_the_allowed(
    args: &Args,
    report: &mut Report,
    model: &Model,
    land: &Landscape,
    optimum: &Extraction,
) {
    let allowed = Allowed::new(
        model,
        land,
        optimum,
        PickSettings {
            rule: args.pick,
            eps: args.accept_eps,
            a_peak_limit: args.a_peak_limit,
            settle_within: args.settle_within,
        },
    );
    if let Some(why) = model.skill_refusal() {
        eprintln!("warning: no skill error E: {why}");
    }
    if let Some(failure) = &allowed.pick_failure {
        eprintln!("warning: {failure}");
    }
    if let Some(p) = &allowed.pick {
        let eval = model.evaluate(p.dm, p.km);
        let name = format!("Picked ({})", p.rule.name());
        report
            .table
            .insert(1, TableRow::from_eval(name, &eval, args.grid.k));
    }
    report.allowed = Some(allowed);
}

/// Prints the report as text: the optimum (after what the data allow when J
/// is flat), the constrained optimum, the diagnostics and Table I.
fn print_the_report(report: &Report, optimum_j: f64) {
    // A flat J leads with what the data allow and the pick (never a dead
    // end); a determined one with its optimum.
    let flat = report.allowed.as_ref().is_some_and(|a| a.j_flat);
    if flat && let Some(a) = &report.allowed {
        print!("{}", a.text());
        println!();
    }
    print!("{}", report.optimum_text());
    if let Some(c) = &report.constrained {
        print!("{}", c.text(Some(optimum_j)));
    }
    if let Some(a) = &report.allowed {
        println!("for the robot: {}", a.optimum_robot.text());
        if !flat {
            println!();
            print!("{}", a.text());
        }
    }
    println!();
    let diag = report.diagnostics_text();
    if !diag.is_empty() {
        print!("{diag}");
        println!();
    }
    print!("{}", report.table_text());
}
