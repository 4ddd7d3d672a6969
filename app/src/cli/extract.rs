//! `dmpscope extract`: the gains minimising J, and Table I comparing them
//! with the paper's gains.

use dmpscope_core::TableRow;
use dmpscope_core::presets::preset_rows;
use serde_json::json;

use super::inputs::InputArgs;
use super::landscape::{GridArgs, landscape_and_optimum};

/// Arguments of `extract`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    input: InputArgs,
    #[command(flatten)]
    grid: GridArgs,
    /// Print JSON (the extraction and Table I rows) instead of text.
    #[arg(long)]
    json: bool,
}

/// Prints `(M:D:K)`, zeta, J, the edge flag and Table I.
pub fn run(args: Args) -> anyhow::Result<()> {
    let (_, model, _, optimum) = landscape_and_optimum(&args.input, &args.grid)?;
    let k = args.grid.k;
    let mut rows = vec![TableRow::from_eval("Extracted", &optimum.eval, k)];
    rows.extend(preset_rows(&model, k));
    if args.json {
        let doc = json!({ "extraction": optimum, "table": rows });
        println!("{}", serde_json::to_string_pretty(&doc)?);
        return Ok(());
    }
    let e = &optimum.eval;
    println!("(M:D:K) = 1 : {:.4} : {:.4}", e.dm, e.km);
    println!("zeta    = {:.4}", e.zeta);
    println!(
        "J       = {:.6}  (S = {:.6}, sum d = {:.6} m, k = {k})",
        optimum.j, e.s, e.d_sum
    );
    if optimum.on_edge() {
        println!(
            "on edge = yes: {} (widen the range)",
            optimum.edges.describe()
        );
    } else {
        println!("on edge = no");
    }
    println!();
    let names: Vec<String> = model.demos().iter().map(|d| d.name.clone()).collect();
    print!("{}", super::table::render(&rows, &names));
    Ok(())
}
