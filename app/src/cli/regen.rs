//! `dmpscope regen`: demos regenerated at one gain pair, or generalised to
//! a new start, goal and duration (method.md section 10), written as CSV,
//! MCAP (Foxglove poses plus ROS 2 trajectories) or the DMP export of
//! `docs/export.md`.

use dmpscope_core::geom::{Vec3, arrays};
use std::collections::BTreeMap;
use std::fmt::Write;
use std::path::{Path, PathBuf};

use anyhow::Context;
use dmpscope_core::export::dmp_doc::run_document;
use dmpscope_core::export::recording::{
    ExportPath, TopicNames, TrajectoryExport, demo_paths, write_export_mcap,
};
use dmpscope_core::export::ros_traj::{TimedOrientation, TimedPath};
use dmpscope_core::fit::orientation;
use dmpscope_core::generalise::run::{Run, Which, runs, unit_quaternion};
use dmpscope_core::load::formats::ROLE_REGENERATED;
use dmpscope_core::report::text::{pad_right, width};
use dmpscope_core::{Generalised, Model, RawDemo, Scaling, Target, rotation};

use super::inputs::{InputArgs, load_model};
use super::output::{print_notices, write_text};

/// Spatial scaling on the command line.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub enum ScalingArg {
    /// The paper's per-axis factor (g'-y0')/(g-y0).
    Paper,
    /// Frame-independent: rotation and uniform scale of g-y0 onto g'-y0'.
    Frame,
}

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
    /// Only this demo (1-based, in `dmpscope info` order).
    #[arg(long, conflicts_with = "skill")]
    demo: Option<usize>,
    /// The skill of all demos: the mean of their forcing terms in the
    /// scaling's frame, with a band of +-1 SD.
    #[arg(long)]
    skill: bool,
    /// New start, metres (default: the demo's own).
    #[arg(long, num_args = 3, value_names = ["X", "Y", "Z"], allow_negative_numbers = true)]
    start: Option<Vec<f64>>,
    /// New goal, metres (default: the demo's own).
    #[arg(long, num_args = 3, value_names = ["X", "Y", "Z"], allow_negative_numbers = true)]
    goal: Option<Vec<f64>>,
    /// New duration T', seconds (default: the demo's own).
    #[arg(long, allow_negative_numbers = true)]
    duration: Option<f64>,
    /// How the forcing term follows a moved goal.
    #[arg(long, value_enum, default_value = "paper")]
    scaling: ScalingArg,
    /// New goal orientation as a quaternion (default: the demo's own;
    /// needs a recording with orientation). A non-unit one is normalised
    /// with a notice.
    #[arg(long, num_args = 4, value_names = ["QX", "QY", "QZ", "QW"], allow_negative_numbers = true)]
    goal_orientation: Option<Vec<f64>>,
    /// New start orientation as a quaternion (default: the demo's own).
    #[arg(long, num_args = 4, value_names = ["QX", "QY", "QZ", "QW"], allow_negative_numbers = true)]
    start_orientation: Option<Vec<f64>>,
    /// Write the paths here: `.csv` (every path, real-time velocity and
    /// acceleration; `-` for stdout), `.mcap` (demos and paths as
    /// `foxglove.PoseInFrame` JSON, each path also as ROS 2
    /// `nav_msgs/msg/Path` and `trajectory_msgs/msg/MultiDOFJointTrajectory`,
    /// gains as metadata) or `.json` (one DMP a controller can run,
    /// docs/export.md; needs --demo or --skill).
    #[arg(long, short)]
    out: Option<PathBuf>,
}

/// A point argument of three numbers.
pub(super) fn vec3(what: &str, v: &Option<Vec<f64>>) -> anyhow::Result<Option<Vec3>> {
    match v.as_deref() {
        None => Ok(None),
        Some([x, y, z]) => Ok(Some(Vec3::new(*x, *y, *z))),
        Some(other) => anyhow::bail!("{what} takes three numbers X Y Z, got {}", other.len()),
    }
}

/// A quaternion argument, normalised (with a notice on stderr when it was
/// not unit); an error for a zero or non-finite one.
fn quaternion(what: &str, v: &Option<Vec<f64>>) -> anyhow::Result<Option<[f64; 4]>> {
    let Some(v) = v.as_deref() else {
        return Ok(None);
    };
    let &[x, y, z, w] = v else {
        anyhow::bail!("{what} takes four numbers QX QY QZ QW, got {}", v.len());
    };
    let (q, note) = unit_quaternion(what, [x, y, z, w]).map_err(|e| match e {
        dmpscope_core::Error::InvalidSetting(m) => anyhow::anyhow!(m),
        other => other.into(),
    })?;
    print_notices(note.as_slice());
    Ok(Some(q))
}

/// Checks the gains are positive numbers.
fn check_the_gains(args: &Args) -> anyhow::Result<()> {
    for (name, v) in [("--dm", args.dm), ("--km", args.km)] {
        if !(v.is_finite() && v > 0.0) {
            anyhow::bail!("{name} must be a positive number, got {v}");
        }
    }
    Ok(())
}

/// The new start, goal, duration, scaling and orientations; the duration checked.
fn the_target(args: &Args) -> anyhow::Result<Target> {
    let scaling = match args.scaling {
        ScalingArg::Paper => Scaling::Paper,
        ScalingArg::Frame => Scaling::Frame,
    };
    let target = Target {
        start: vec3("--start", &args.start)?,
        goal: vec3("--goal", &args.goal)?,
        duration_s: args.duration,
        scaling,
        start_orientation: quaternion("--start-orientation", &args.start_orientation)?,
        goal_orientation: quaternion("--goal-orientation", &args.goal_orientation)?,
    };
    if let Some(d) = target.duration_s
        && !(d.is_finite() && d > 0.0)
    {
        anyhow::bail!("--duration must be a positive number of seconds, got {d}");
    }
    Ok(target)
}

/// The output's extension in lower case; a `.json` one needs one DMP chosen.
fn the_extension(args: &Args) -> anyhow::Result<Option<String>> {
    let extension = args
        .out
        .as_deref()
        .and_then(|p| p.extension())
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    if extension.as_deref() == Some("json") && args.demo.is_none() && !args.skill {
        anyhow::bail!(
            "a .json export holds one DMP: pass --demo N (1-based) or --skill to choose it"
        );
    }
    Ok(extension)
}

/// Prints the runs' warnings, then the summary (on stderr when the paths go to stdout).
fn print_the_summary(model: &Model, args: &Args, runs: &[Run]) {
    for r in runs {
        for w in &r.out.warnings {
            eprintln!("warning: {w}");
        }
    }
    let summary = summary(model, args, runs);
    let to_stdout = args.out.as_deref().is_some_and(|p| p == Path::new("-"));
    if to_stdout {
        eprint!("{summary}");
    } else {
        print!("{summary}");
    }
}

/// Writes one run as the DMP export of `docs/export.md`.
fn write_json(
    out: &Path,
    model: &Model,
    args: &Args,
    r: &Run,
    frame_id: String,
    scaling: Scaling,
) -> anyhow::Result<()> {
    let doc = run_document(model, r, frame_id, scaling, args.input.load.options().units)
        .with_context(|| format!("{}: not written", out.display()))?;
    let mut text = serde_json::to_string(&doc)?;
    text.push('\n');
    write_text(Some(out), &text)?;
    eprintln!("wrote the DMP of {} to {}", r.primitive.name, out.display());
    Ok(())
}

/// Prints per path d_mean, a_peak, peak speed and final error, and writes
/// the paths.
pub fn run(args: Args) -> anyhow::Result<()> {
    check_the_gains(&args)?;
    let target = the_target(&args)?;
    let extension = the_extension(&args)?;
    let (raw, model) = load_model(&args.input)?;
    let n = model.demos().len();
    if let Some(d) = args.demo
        && (d == 0 || d > n)
    {
        anyhow::bail!("--demo must be between 1 and {n}, got {d}");
    }
    let runs = make_runs(&model, &args, &target)?;
    print_the_summary(&model, &args, &runs);
    let Some(out) = args.out.as_deref() else {
        eprintln!("note: pass --out F.csv, F.mcap or F.json to write the paths");
        return Ok(());
    };
    let frame_id = args
        .input
        .load
        .fixed_frame
        .clone()
        .unwrap_or_else(|| "world".to_owned());
    match extension.as_deref() {
        Some("mcap") => write_mcap(out, &raw, &model, &args, &runs, &frame_id),
        Some("json") => write_json(out, &model, &args, &runs[0], frame_id, target.scaling),
        _ => write_text(Some(out), &csv(&model, &runs, own_target(&args))),
    }
}

fn make_runs(model: &Model, args: &Args, target: &Target) -> anyhow::Result<Vec<Run>> {
    let which = match (args.skill, args.demo) {
        (true, _) => Which::Skill,
        (false, Some(d)) => Which::Demo(d - 1),
        (false, None) => Which::All,
    };
    Ok(runs(model, args.dm, args.km, which, target)?)
}

/// Whether a run is at its demo's own start, goal and duration.
fn own_target(args: &Args) -> bool {
    args.start.is_none() && args.goal.is_none() && args.duration.is_none()
}

fn summary(model: &Model, args: &Args, runs: &[Run]) -> String {
    let eval = model.evaluate(args.dm, args.km);
    let mut s = String::new();
    let _ = writeln!(
        s,
        "D/M = {}, K/M = {}, zeta = {:.4}, S = {:.6}, sum d = {:.6} m",
        args.dm, args.km, eval.zeta, eval.s, eval.d_sum
    );
    let w = runs
        .iter()
        .map(|r| r.primitive.name.as_str())
        .fold(4, |w, n| w.max(width(n)));
    let _ = writeln!(
        s,
        "{:<w$}  {:>11}  {:>14}  {:>7}  {:>10}  {:>15}  {:>9}",
        "path",
        "d_mean [mm]",
        "a_peak [m/s^2]",
        "T' [s]",
        "v_max [m/s]",
        "a_max [m/s^2]",
        "end [mm]"
    );
    for r in runs {
        let d = match (r.demo, own_target(args)) {
            (Some(i), true) => format!("{:.4}", eval.d[i] * 1e3),
            _ => "-".to_owned(),
        };
        let unit_peak = r
            .out
            .unit
            .a
            .iter()
            .map(|a| (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt())
            .fold(0.0, f64::max);
        let _ = writeln!(
            s,
            "{}  {d:>11}  {unit_peak:>14.3}  {:>7.3}  {:>10.4}  {:>15.4}  {:>9.3}",
            pad_right(&r.primitive.name, w),
            r.out.duration_s,
            r.out.peak_speed,
            r.out.a_peak,
            r.out.final_error * 1e3
        );
    }
    let _ = writeln!(
        s,
        "(a_peak in unit time as in Table I; v_max, a_max in real time over T'; end: distance of the last point from the goal)"
    );
    orientation_summary(&mut s, model, args, runs);
    s
}

/// One line per path with an orientation: its error against the demo (at
/// the demo's own target), its angle from the goal orientation at the
/// end and its peak angular acceleration.
fn orientation_summary(s: &mut String, model: &Model, args: &Args, runs: &[Run]) {
    let goal_arg = quaternion("--goal-orientation", &args.goal_orientation)
        .ok()
        .flatten();
    let own =
        own_target(args) && args.goal_orientation.is_none() && args.start_orientation.is_none();
    for r in runs {
        let (Some(path), Some(prim)) = (&r.out.orientation, &r.primitive.orientation) else {
            continue;
        };
        let goal = goal_arg.unwrap_or(prim.goal);
        let end = path
            .q
            .last()
            .map_or(f64::NAN, |q| rotation::angle(*q, goal).to_degrees());
        let d_rot = match (r.demo, own) {
            (Some(i), true) => model.demos()[i]
                .orientation
                .as_ref()
                .map_or("-".to_owned(), |o| {
                    format!(
                        "{:.4} deg",
                        orientation::error(&path.q, &o.q_raw).to_degrees()
                    )
                }),
            _ => "-".to_owned(),
        };
        let _ = writeln!(
            s,
            "{} orientation: d_rot {d_rot}, end {end:.4} deg from the goal orientation, \
             alpha_peak {:.3} rad per unit time squared",
            r.primitive.name,
            path.alpha_peak()
        );
    }
}

/// The paths as CSV; the demo's own samples beside a path only when it
/// runs at the demo's own target.
fn csv(model: &Model, runs: &[Run], own: bool) -> String {
    let mut csv =
        String::from("demo,s,t_s,x,y,z,demo_x,demo_y,demo_z,vx,vy,vz,ax,ay,az,sd_x,sd_y,sd_z\n");
    for r in runs {
        let demo = r.demo.filter(|_| own).map(|i| &model.demos()[i]);
        let n = r.out.t.len();
        for k in 0..n {
            let s = k as f64 / (n - 1) as f64;
            let p = r.out.unit.y[k];
            let (v, a) = (r.out.v[k], r.out.a[k]);
            let target = match demo {
                Some(d) if k < d.y_raw.len() => {
                    let q = d.y_raw[k];
                    format!("{},{},{}", q[0] + d.p0[0], q[1] + d.p0[1], q[2] + d.p0[2])
                }
                _ => ",,".to_owned(),
            };
            let band = match r.out.band.get(k) {
                Some(b) => format!("{},{},{}", b[0], b[1], b[2]),
                None => ",,".to_owned(),
            };
            let _ = writeln!(
                csv,
                "{},{s},{},{},{},{},{target},{},{},{},{},{},{},{band}",
                r.primitive.name, r.out.t[k], p[0], p[1], p[2], v[0], v[1], v[2], a[0], a[1], a[2]
            );
        }
    }
    csv
}

/// Writes the demos and each path as `foxglove.PoseInFrame` (JSON), each
/// path also as ROS 2 `nav_msgs/msg/Path` and `MultiDOFJointTrajectory`,
/// with the gains as metadata.
fn write_mcap(
    out: &Path,
    raw: &[RawDemo],
    model: &Model,
    args: &Args,
    runs: &[Run],
    frame_id: &str,
) -> anyhow::Result<()> {
    let (paths, trajectories) = paths_and_trajectories(raw, model, runs, frame_id);
    let metadata = gains_metadata(model, args);
    let file =
        std::fs::File::create(out).with_context(|| format!("{}: cannot create", out.display()))?;
    write_export_mcap(
        std::io::BufWriter::new(file),
        &paths,
        &trajectories,
        frame_id,
        &metadata,
    )
    .with_context(|| format!("{}: cannot write MCAP", out.display()))?;
    eprintln!(
        "wrote {} demos and {} paths (each also as nav_msgs/Path and MultiDOFJointTrajectory) to {}",
        model.demos().len(),
        runs.len(),
        out.display()
    );
    Ok(())
}

/// The demos' paths then each run's, and each run's ROS trajectory, stamped
/// from its demo's first stamp.
fn paths_and_trajectories(
    raw: &[RawDemo],
    model: &Model,
    runs: &[Run],
    frame_id: &str,
) -> (Vec<ExportPath>, Vec<TrajectoryExport>) {
    let first_stamp = |i: usize| {
        raw.get(i)
            .and_then(|r| r.stamps_ns.iter().min().copied())
            .unwrap_or(0)
    };
    let firsts: Vec<i64> = (0..model.demos().len()).map(first_stamp).collect();
    let mut names = TopicNames::default();
    let (mut paths, shorts) = demo_paths(model, &firsts, &mut names);
    let mut trajectories = Vec::new();
    for r in runs {
        let start = first_stamp(r.demo.unwrap_or(0));
        let short = match r.demo {
            Some(i) => shorts[i].clone(),
            None => names.unique(&r.primitive.name),
        };
        paths.push(regenerated_path(r, &short, start));
        trajectories.push(ros_trajectory(r, &short, start, frame_id));
    }
    (paths, trajectories)
}

/// A run's path as poses on `/regen/<short>`, from `start` (ns).
fn regenerated_path(r: &Run, short: &str, start: i64) -> ExportPath {
    ExportPath {
        topic: format!("/regen/{short}"),
        name: r.primitive.name.clone(),
        role: ROLE_REGENERATED,
        samples: r
            .out
            .t
            .iter()
            .zip(&r.out.unit.y)
            .map(|(t, p)| (start + (t * 1e9).round() as i64, (*p).into()))
            .collect(),
    }
}

/// A run as ROS 2 trajectories under `/dmp/<short>`, from `start` (ns).
fn ros_trajectory(r: &Run, short: &str, start: i64, frame_id: &str) -> TrajectoryExport {
    TrajectoryExport {
        prefix: format!("/dmp/{short}"),
        name: r.primitive.name.clone(),
        path: TimedPath {
            frame_id: frame_id.to_owned(),
            joint: "end_effector".to_owned(),
            stamp_ns: start,
            t: r.out.t.clone(),
            y: arrays(&r.out.unit.y),
            v: arrays(&r.out.v),
            a: arrays(&r.out.a),
            orientation: timed_orientation(&r.out),
        },
    }
}

/// The MCAP's metadata: the gains, their figures, the demos, the scaling, the duration.
fn gains_metadata(model: &Model, args: &Args) -> BTreeMap<String, String> {
    let eval = model.evaluate(args.dm, args.km);
    let mut metadata: BTreeMap<String, String> = [
        ("dm", args.dm.to_string()),
        ("km", args.km.to_string()),
        ("zeta", eval.zeta.to_string()),
        ("s", eval.s.to_string()),
        ("d_sum", eval.d_sum.to_string()),
        ("demos", model.demos().len().to_string()),
        ("scaling", args.scaling_name().to_owned()),
    ]
    .into_iter()
    .map(|(k, v)| (k.to_owned(), v))
    .collect();
    if let Some(d) = args.duration {
        metadata.insert("duration_s".into(), d.to_string());
    }
    metadata
}

/// A generalised run's orientation in real time (unit-time rates over the
/// run's duration), for the ROS trajectories.
fn timed_orientation(out: &Generalised) -> Option<TimedOrientation> {
    let o = out.orientation.as_ref()?;
    let duration = out.t.last().copied().filter(|d| *d > 0.0)?;
    Some(TimedOrientation {
        q: o.q.clone(),
        w: o.w.iter().map(|w| w.map(|c| c / duration)).collect(),
        alpha: o
            .a
            .iter()
            .map(|a| a.map(|c| c / (duration * duration)))
            .collect(),
    })
}

impl Args {
    fn scaling_name(&self) -> &'static str {
        match self.scaling {
            ScalingArg::Paper => "paper",
            ScalingArg::Frame => "frame",
        }
    }
}
