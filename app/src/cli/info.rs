//! `dmpscope info`: the demonstrations found in recordings, the topics
//! skipped, and with `--segment` the demonstrations a continuous recording
//! splits into.

use dmpscope_core::arrange::segment::find_segments;
use dmpscope_core::report::text::{pad_right, widest};

use super::inputs::LoadArgs;

/// Arguments of `info`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    load: LoadArgs,
    /// Print the segments each stream splits into at rest periods.
    #[arg(long)]
    segment: bool,
    /// Print JSON instead of a table.
    #[arg(long)]
    json: bool,
}

fn xyz(p: [f64; 3]) -> String {
    format!("({:+.3}, {:+.3}, {:+.3})", p[0], p[1], p[2])
}

/// Lists name, samples, duration, median rate, start, goal and whether it
/// carries orientations, for every demo.
pub fn run(args: Args) -> anyhow::Result<()> {
    if args.segment {
        return segments(&args);
    }
    let demos = args.load.load_demos()?;
    let infos: Vec<_> = demos.iter().map(|d| d.info()).collect();
    if args.json {
        println!("{}", serde_json::to_string_pretty(&infos)?);
        return Ok(());
    }
    let width = widest(infos.iter().map(|i| i.name.as_str()), 4);
    println!(
        "{:<width$}  {:>7}  {:>8}  {:>8}  {:<26}  {:<26}  orientation",
        "demo", "samples", "duration", "rate", "start [m]", "goal [m]"
    );
    for i in &infos {
        println!(
            "{}  {:>7}  {:>7.3}s  {:>6.1}Hz  {:<26}  {:<26}  {}",
            pad_right(&i.name, width),
            i.n_samples,
            i.duration_s,
            i.median_rate_hz,
            xyz(i.start),
            xyz(i.goal),
            if i.orientation { "yes" } else { "none" }
        );
    }
    eprintln!("{} demonstrations", infos.len());
    Ok(())
}

/// Prints each stream's segments with their times from the stream's start.
fn segments(args: &Args) -> anyhow::Result<()> {
    let settings = args.load.segment_settings();
    let mut all = Vec::new();
    for stream in args.load.load_streams()? {
        let found = find_segments(&stream, &settings)?;
        let t0 = stream.stamps_ns.iter().min().copied().unwrap_or(0);
        if !args.json {
            println!("{} ({} segments)", stream.name, found.len());
            println!(
                "  {:>3}  {:>9}  {:>9}  {:>9}  {:>7}",
                "#", "start [s]", "end [s]", "length", "samples"
            );
        }
        for (i, s) in found.iter().enumerate() {
            let start = (s.start_ns - t0) as f64 * 1e-9;
            let end = (s.end_ns - t0) as f64 * 1e-9;
            if !args.json {
                println!(
                    "  {:>3}  {start:>9.3}  {end:>9.3}  {:>8.3}s  {:>7}",
                    i + 1,
                    end - start,
                    s.last - s.first + 1
                );
            }
            all.push(serde_json::json!({
                "stream": stream.name, "index": i + 1, "start_s": start, "end_s": end,
                "samples": s.last - s.first + 1,
            }));
        }
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&all)?);
    }
    Ok(())
}
