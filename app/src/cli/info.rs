//! `dmpscope info`: the demonstrations found in recordings, the topics
//! skipped, and with `--segment` the demonstrations a continuous recording
//! splits into.

use dmpscope_core::arrange::segment::find_segments;
use dmpscope_core::report::text::{pad_right, widest};
use dmpscope_core::{DemoInfo, PrepSettings, prepare};

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
    /// The Savitzky-Golay window as a duration, seconds, for the noise
    /// column (as extract's --sg-seconds; default: the paper's 21 samples).
    #[arg(long, value_name = "S")]
    sg_seconds: Option<f64>,
}

/// A demo's line: what was recorded, and how much of its smoothed
/// acceleration is noise (method.md section 2, "Noise").
#[derive(serde::Serialize)]
struct InfoRow {
    #[serde(flatten)]
    info: DemoInfo,
    /// The noise share of the smoothed acceleration (`None`: not measured).
    acc_noise: Option<f64>,
    /// Where noise dominates, the `--sg-seconds` that smooths it.
    suggested_sg_seconds: Option<f64>,
}

fn rows(demos: &[dmpscope_core::RawDemo], sg_seconds: Option<f64>) -> Vec<InfoRow> {
    let prep = PrepSettings {
        sg_seconds,
        ..PrepSettings::default()
    };
    demos
        .iter()
        .map(|d| {
            let prepared = prepare(d, &prep).ok();
            InfoRow {
                info: d.info(),
                acc_noise: prepared.as_ref().and_then(|p| p.acc_noise),
                suggested_sg_seconds: prepared.and_then(|p| p.suggested_sg_seconds),
            }
        })
        .collect()
}

fn xyz(p: [f64; 3]) -> String {
    format!("({:+.3}, {:+.3}, {:+.3})", p[0], p[1], p[2])
}

/// Lists name, samples, duration, median rate, start, goal, whether it
/// carries orientations and its acceleration's noise share, for every demo.
pub fn run(args: Args) -> anyhow::Result<()> {
    if args.segment {
        return segments(&args);
    }
    let demos = args.load.load_demos()?;
    let rows = rows(&demos, args.sg_seconds);
    if args.json {
        println!("{}", serde_json::to_string_pretty(&rows)?);
        return Ok(());
    }
    let width = widest(rows.iter().map(|r| r.info.name.as_str()), 4);
    println!(
        "{:<width$}  {:>7}  {:>8}  {:>8}  {:<26}  {:<26}  {:<11}  acc. noise",
        "demo", "samples", "duration", "rate", "start [m]", "goal [m]", "orientation"
    );
    for r in &rows {
        let i = &r.info;
        let noise = match (r.acc_noise, r.suggested_sg_seconds) {
            (None, _) => "-".to_owned(),
            (Some(n), None) => format!("{:.0} %", 100.0 * n),
            (Some(n), Some(s)) => format!("{:.0} % (--sg-seconds {s})", 100.0 * n),
        };
        println!(
            "{}  {:>7}  {:>7.3}s  {:>6.1}Hz  {:<26}  {:<26}  {:<11}  {noise}",
            pad_right(&i.name, width),
            i.n_samples,
            i.duration_s,
            i.median_rate_hz,
            xyz(i.start),
            xyz(i.goal),
            if i.orientation { "yes" } else { "none" }
        );
    }
    eprintln!("{} demonstrations", rows.len());
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
