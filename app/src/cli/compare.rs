//! `dmpscope compare`: gain sets side by side (Table I's rows by name, or
//! typed `DM:KM`): each set's Table I numbers, settling time and, for a
//! new target, its run there; the best of each column marked; a figure of
//! their regenerations (SVG or PNG).

use std::path::PathBuf;

use anyhow::Context;
use dmpscope_core::extract::allowed::{Allowed, DEFAULT_EPS, PickRule, PickSettings};
use dmpscope_core::generalise::primitive::Target;
use dmpscope_core::report::compare::{CompareRow, Runs, best, compare, resolve};
use dmpscope_core::report::summary::table_rows;
use dmpscope_core::report::table::TableRow;
use dmpscope_core::report::text::{pad_right, widest};
use dmpscope_core::{Model, Scaling};

use super::inputs::InputArgs;
use super::landscape::{GridArgs, landscape_and_optimum};
use super::regen::{ScalingArg, vec3};
use dmpscope::figure::{Figure, svg};

/// Arguments of `compare`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    input: InputArgs,
    #[command(flatten)]
    grid: GridArgs,
    /// The gain sets, comma separated (at most 6): Table I's row names
    /// (extracted, pick, Ours, Hrstc1..Hrstc4; any case) or typed D/M:K/M.
    #[arg(long, default_value = "extracted,pick,Hrstc1")]
    gains: String,
    /// How the pick is made (as extract's --pick; default: optimum when J
    /// is not flat, compliant when it is).
    #[arg(long, value_parser = |s: &str| s.parse::<PickRule>(), value_name = "RULE")]
    pick: Option<PickRule>,
    /// The demo the figure plots against time and the target runs (1-based,
    /// in `dmpscope info` order; default: the first); the figure's 3D panel
    /// shows only it.
    #[arg(long, conflicts_with = "skill")]
    demo: Option<usize>,
    /// The target runs the skill of all demos.
    #[arg(long)]
    skill: bool,
    /// A new start for the target run, metres.
    #[arg(long, num_args = 3, value_names = ["X", "Y", "Z"], allow_negative_numbers = true)]
    start: Option<Vec<f64>>,
    /// A new goal for the target run, metres.
    #[arg(long, num_args = 3, value_names = ["X", "Y", "Z"], allow_negative_numbers = true)]
    goal: Option<Vec<f64>>,
    /// A new duration for the target run, seconds.
    #[arg(long)]
    duration: Option<f64>,
    /// How the forcing term follows a moved goal.
    #[arg(long, value_enum, default_value = "paper")]
    scaling: ScalingArg,
    /// Print JSON (`sets`: each a Table I row with `settling` and
    /// `target`; `best`: the best set of each column) instead of text.
    #[arg(long)]
    json: bool,
    /// Write a figure of the regenerations: `.svg` or `.png`.
    #[arg(long, value_name = "FILE")]
    figure: Option<PathBuf>,
}

/// Prints the sets side by side and writes the figure.
pub fn run(args: Args) -> anyhow::Result<()> {
    let target = the_target(&args)?;
    let (_, model, land, optimum) = landscape_and_optimum(&args.input, &args.grid)?;
    let k = args.grid.k;
    let mut rows = table_rows(&model, Some(&optimum), k, []);
    let allowed = Allowed::new(
        &model,
        &land,
        &optimum,
        PickSettings {
            rule: args.pick,
            eps: DEFAULT_EPS,
            a_peak_limit: None,
            settle_within: None,
        },
    );
    if let Some(p) = &allowed.pick {
        let name = format!("Picked ({})", p.rule.name());
        rows.insert(1, TableRow::from_eval(name, &model.evaluate(p.dm, p.km), k));
    }
    let sets = resolve(&args.gains, &rows)?;
    let n = model.demos().len();
    let selected = match args.demo {
        Some(d) if d == 0 || d > n => anyhow::bail!("--demo {d}: the demos are 1 to {n}"),
        Some(d) => d - 1,
        None => 0,
    };
    let runs = if args.skill {
        Runs::Skill
    } else {
        Runs::Demo(selected)
    };
    let compared = compare(&model, &sets, k, target.as_ref().map(|t| (runs, t)))?;
    if let Some(path) = &args.figure {
        let demos = args.demo.map(|_| vec![selected]).unwrap_or_default();
        write_figure(
            path,
            &Figure::of_model(&model, &Figure::coloured(&sets), &demos, selected),
        )?;
    }
    if args.json {
        let best: serde_json::Map<String, serde_json::Value> = best(&compared)
            .into_iter()
            .map(|(key, i)| (key.to_owned(), compared[i].row.name.clone().into()))
            .collect();
        let doc = serde_json::json!({ "k": k, "sets": compared, "best": best });
        println!("{}", serde_json::to_string_pretty(&doc)?);
    } else {
        print!("{}", text(&model, &compared));
    }
    Ok(())
}

/// The target run asked for (none without --start, --goal or --duration).
fn the_target(args: &Args) -> anyhow::Result<Option<Target>> {
    if args.start.is_none() && args.goal.is_none() && args.duration.is_none() {
        return Ok(None);
    }
    if let Some(d) = args.duration
        && !(d.is_finite() && d > 0.0)
    {
        anyhow::bail!("--duration must be a positive number of seconds, got {d}");
    }
    Ok(Some(Target {
        start: vec3("--start", &args.start)?,
        goal: vec3("--goal", &args.goal)?,
        duration_s: args.duration,
        scaling: match args.scaling {
            ScalingArg::Paper => Scaling::Paper,
            ScalingArg::Frame => Scaling::Frame,
        },
        ..Target::default()
    }))
}

/// Writes the figure as its extension says.
fn write_figure(path: &std::path::Path, figure: &Figure) -> anyhow::Result<()> {
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let bytes = match extension.as_deref() {
        Some("svg") => svg(figure)?.into_bytes(),
        Some("png") => dmpscope::figure::png(figure)?,
        _ => anyhow::bail!(
            "--figure {}: the figure is written as .svg or .png",
            path.display()
        ),
    };
    std::fs::write(path, bytes).with_context(|| format!("writing {}", path.display()))?;
    eprintln!("wrote {}", path.display());
    Ok(())
}

/// The sets as a text table, the best of each column marked with `*`.
fn text(model: &Model, rows: &[CompareRow]) -> String {
    let best = best(rows);
    let star = |key: &str, i: usize| if best.contains(&(key, i)) { "*" } else { " " };
    let width = widest(rows.iter().map(|r| r.row.name.as_str()), 4);
    let mut out = format!(
        "{}  {:>8}  {:>8}  {:>6}  {:>9}  {:>9}  {:>11}  {:>10}  {:>10}  {:>11}",
        pad_right("gains", width),
        "D/M",
        "K/M",
        "zeta",
        "t_s [s]",
        "S",
        "sum d [m]",
        "J",
        "E [m]",
        "a_peak max"
    );
    let targeted = rows.iter().any(|r| r.target.is_some());
    if targeted {
        out.push_str("  target: end err [mm]  a_peak");
    }
    out.push('\n');
    for (i, r) in rows.iter().enumerate() {
        let a_peak = r.row.a_peak.iter().copied().fold(f64::NAN, f64::max);
        out.push_str(&format!(
            "{}  {:>8.3}  {:>8.3}  {:>6.3}  {:>8.3}{}  {:>8.5}{}  {:>10.5}{}  {:>9.5}{}  {:>9.5}{}  {:>10.2}{}",
            pad_right(&r.row.name, width),
            r.row.dm,
            r.row.km,
            r.row.zeta,
            r.settling.seconds,
            star("settling", i),
            r.row.s,
            star("s", i),
            r.row.d_sum,
            star("d_sum", i),
            r.row.j,
            star("j", i),
            r.row.e_sum,
            star("e_sum", i),
            a_peak,
            star("a_peak", i),
        ));
        if let Some(t) = r.target {
            out.push_str(&format!(
                "  {:>19.3}{}  {:>6.2}{}",
                t.end_error_m * 1000.0,
                star("target_end_error_m", i),
                t.a_peak,
                star("target_a_peak", i)
            ));
        }
        out.push('\n');
    }
    out.push_str(&format!(
        "* the best of the column (least); t_s: 2 % settling at the demos' mean duration ({:.2} s)\n",
        dmpscope_core::extract::allowed::mean_duration(model)
    ));
    out
}
