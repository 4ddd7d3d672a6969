//! `dmpscope info`: the demonstrations found in recordings.

use std::path::PathBuf;

/// Arguments of `info`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// MCAP files, or folders (every `*.mcap` in them, sorted by name).
    #[arg(required = true, value_name = "FILES")]
    files: Vec<PathBuf>,
    /// Print JSON instead of a table.
    #[arg(long)]
    json: bool,
}

fn xyz(p: [f64; 3]) -> String {
    format!("({:+.3}, {:+.3}, {:+.3})", p[0], p[1], p[2])
}

/// Lists name, samples, duration, median rate, start and goal of every demo.
pub fn run(args: Args) -> anyhow::Result<()> {
    let demos = super::inputs::load_demos(&args.files)?;
    let infos: Vec<_> = demos.iter().map(|d| d.info()).collect();
    if args.json {
        println!("{}", serde_json::to_string_pretty(&infos)?);
        return Ok(());
    }
    let width = infos.iter().map(|i| i.name.len()).max().unwrap_or(4).max(4);
    println!(
        "{:<width$}  {:>7}  {:>8}  {:>8}  {:<26}  goal [m]",
        "demo", "samples", "duration", "rate", "start [m]"
    );
    for i in &infos {
        println!(
            "{:<width$}  {:>7}  {:>7.3}s  {:>6.1}Hz  {:<26}  {}",
            i.name,
            i.n_samples,
            i.duration_s,
            i.median_rate_hz,
            xyz(i.start),
            xyz(i.goal)
        );
    }
    eprintln!("{} demonstrations", infos.len());
    Ok(())
}
