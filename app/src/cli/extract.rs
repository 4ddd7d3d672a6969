//! `dmpscope extract`: the gains minimising J, and Table I comparing them
//! with the paper's gains.

use dmpscope_core::Report;

use super::inputs::InputArgs;
use super::landscape::{GridArgs, landscape_and_optimum};

/// Arguments of `extract`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    input: InputArgs,
    #[command(flatten)]
    grid: GridArgs,
    /// Print the report as JSON (the shape documented in
    /// `dmpscope_core::report`: k, demos, optimum, table) instead of text.
    #[arg(long)]
    json: bool,
}

/// Prints `(M:D:K)`, zeta, J, the edge flag and Table I.
pub fn run(args: Args) -> anyhow::Result<()> {
    let (_, model, _, optimum) = landscape_and_optimum(&args.input, &args.grid)?;
    let report = Report::new(&model, Some(&optimum), args.grid.k);
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
        return Ok(());
    }
    print!("{}", report.optimum_text());
    println!();
    print!("{}", report.table_text());
    Ok(())
}
