//! `dmpscope regen`: every demo regenerated at one gain pair.

use dmpscope_core::text::{pad_right, width};
use std::fmt::Write;
use std::path::PathBuf;

use std::collections::BTreeMap;

use anyhow::Context;
use dmpscope_core::io::export::{dmp_export, regenerated_paths, write_pose_in_frame_json};
use dmpscope_core::{Model, RawDemo};

use super::inputs::{InputArgs, load_model};
use super::output::write_text;

/// Arguments of `regen`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    input: InputArgs,
    /// D/M.
    #[arg(long)]
    dm: f64,
    /// K/M.
    #[arg(long)]
    km: f64,
    /// Write the paths here: `.csv` (every regenerated path, `-` for stdout),
    /// `.mcap` (demos and regenerated paths as `foxglove.PoseInFrame` JSON,
    /// gains as metadata: opens in Foxglove and Rerun) or `.json` (gains and
    /// DMP weights per demo and axis).
    #[arg(long, short)]
    out: Option<PathBuf>,
}

/// Prints per demo d_mean and a_peak, and writes the paths.
pub fn run(args: Args) -> anyhow::Result<()> {
    for (name, v) in [("--dm", args.dm), ("--km", args.km)] {
        if !(v.is_finite() && v > 0.0) {
            anyhow::bail!("{name} must be a positive number, got {v}");
        }
    }
    let (raw, model) = load_model(&args.input)?;
    let eval = model.evaluate(args.dm, args.km);
    let mut summary = String::new();
    let _ = writeln!(
        summary,
        "D/M = {}, K/M = {}, zeta = {:.4}, S = {:.6}, sum d = {:.6} m",
        args.dm, args.km, eval.zeta, eval.s, eval.d_sum
    );
    let w = model
        .demos()
        .iter()
        .map(|d| d.name.as_str())
        .fold(4, |w, n| w.max(width(n)));
    let _ = writeln!(
        summary,
        "{:<w$}  {:>11}  {:>14}",
        "demo", "d_mean [mm]", "a_peak [m/s^2]"
    );
    for (demo, (d, a)) in model.demos().iter().zip(eval.d.iter().zip(&eval.a_peak)) {
        let _ = writeln!(
            summary,
            "{}  {:>11.4}  {:>14.3}",
            pad_right(&demo.name, w),
            d * 1e3,
            a
        );
    }
    let to_stdout = args
        .out
        .as_deref()
        .is_some_and(|p| p == std::path::Path::new("-"));
    if to_stdout {
        eprint!("{summary}");
    } else {
        print!("{summary}");
    }
    let Some(out) = args.out else {
        eprintln!("note: pass --out F.csv, F.mcap or F.json to write the regenerated paths");
        return Ok(());
    };
    let extension = out
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match extension.as_deref() {
        Some("mcap") => return write_mcap(&out, &raw, &model, args.dm, args.km),
        Some("json") => {
            let doc = dmp_export(&model, args.dm, args.km);
            let mut text = serde_json::to_string_pretty(&doc)?;
            text.push('\n');
            return write_text(Some(&out), &text);
        }
        _ => {}
    }
    let mut csv = String::from("demo,s,t_s,x,y,z,demo_x,demo_y,demo_z,vx,vy,vz,ax,ay,az\n");
    for (i, demo) in model.demos().iter().enumerate() {
        let path = model.rollout(i, args.dm, args.km);
        let n = demo.len();
        for k in 0..n {
            let s = k as f64 / (n - 1) as f64;
            let p: [f64; 3] = std::array::from_fn(|ax| path.y[k][ax] + demo.p0[ax]);
            let q: [f64; 3] = std::array::from_fn(|ax| demo.y_raw[k][ax] + demo.p0[ax]);
            let (v, a) = (path.v[k], path.a[k]);
            let _ = writeln!(
                csv,
                "{},{s},{},{},{},{},{},{},{},{},{},{},{},{},{}",
                demo.name,
                s * demo.duration_s,
                p[0],
                p[1],
                p[2],
                q[0],
                q[1],
                q[2],
                v[0],
                v[1],
                v[2],
                a[0],
                a[1],
                a[2]
            );
        }
    }
    write_text(Some(&out), &csv)
}

/// Writes demos and regenerated paths as `foxglove.PoseInFrame` (JSON) with
/// the gains as metadata.
fn write_mcap(
    out: &std::path::Path,
    raw: &[RawDemo],
    model: &Model,
    dm: f64,
    km: f64,
) -> anyhow::Result<()> {
    let first_stamps: Vec<i64> = raw
        .iter()
        .map(|r| r.stamps_ns.iter().min().copied().unwrap_or(0))
        .collect();
    let paths = regenerated_paths(model, &first_stamps, dm, km);
    let eval = model.evaluate(dm, km);
    let metadata: BTreeMap<String, String> = [
        ("dm", dm.to_string()),
        ("km", km.to_string()),
        ("zeta", eval.zeta.to_string()),
        ("s", eval.s.to_string()),
        ("d_sum", eval.d_sum.to_string()),
        ("demos", model.demos().len().to_string()),
    ]
    .into_iter()
    .map(|(k, v)| (k.to_owned(), v))
    .collect();
    let file =
        std::fs::File::create(out).with_context(|| format!("{}: cannot create", out.display()))?;
    write_pose_in_frame_json(std::io::BufWriter::new(file), &paths, "world", &metadata)
        .with_context(|| format!("{}: cannot write MCAP", out.display()))?;
    eprintln!("wrote {} paths to {}", paths.len(), out.display());
    Ok(())
}
