//! `dmpscope bench`: medians of the two speeds that matter, the full
//! landscape and one operating point (what a drag on the map costs).

use std::path::PathBuf;
use std::time::Instant;

use dmpscope_core::arrange::streams::load_source;
use dmpscope_core::fit::settings::DmpSettings;
use dmpscope_core::kernels::dispatch::{instruction_set, set_avx512};
use dmpscope_core::landscape::grid as landscape;
use dmpscope_core::landscape::grid::{Axis, Grid};
use dmpscope_core::load::demo::median;
use dmpscope_core::load::options::LoadOptions;
use dmpscope_core::load::source::SourceData;
use dmpscope_core::{PrepSettings, Unusable};

use super::inputs::model_of;

/// Arguments of `bench`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Recordings to measure on.
    #[arg(value_name = "FILES", default_value = "assets/reach10.mcap")]
    files: Vec<PathBuf>,
    /// Points per axis of the landscape.
    #[arg(long, default_value_t = Axis::paper().n)]
    grid: usize,
    /// Landscape repetitions.
    #[arg(long, default_value_t = 7)]
    repeat: usize,
    /// Operating-point repetitions.
    #[arg(long, default_value_t = 500)]
    points: usize,
    /// Instead: measure ingestion of a generated PoseStamped recording of
    /// this many messages (uncompressed and zstd), against mcap's
    /// `MessageStream` on the same bytes.
    #[arg(long, value_name = "MESSAGES")]
    ingest: Option<usize>,
    /// Instead: `dmpscope landscape` on the reach sample against the
    /// vectorised NumPy landscape of `tests/golden/landscape_speed.py`, both
    /// as whole processes, alternated, as a ratio (needs Python with NumPy
    /// and SciPy: `DMPSCOPE_PYTHON`, else `python3`).
    #[arg(long)]
    vs_numpy: bool,
    /// Instead: how fast the demos of this recording are read, against the
    /// PyPI `mcap` reader iterating `--topic` (skipped without `--topic`)
    /// and against reading its bytes once, with the share of the file read
    /// and the peak memory.
    #[arg(long, value_name = "FILE")]
    read: Option<PathBuf>,
    /// The pose topic the PyPI reader iterates (`--read`).
    #[arg(long, requires = "read")]
    topic: Option<String>,
    /// Reads FILE once and prints what it took as JSON (`--read`'s child).
    #[arg(long, value_name = "FILE", hide = true)]
    read_once: Option<PathBuf>,
}

/// Times the landscape and the operating point; prints medians in ms.
pub fn run(args: Args) -> anyhow::Result<()> {
    if let Some(messages) = args.ingest {
        return super::bench_ingest::run(messages, args.repeat);
    }
    if let Some(path) = &args.read_once {
        return super::bench_read::read_once(path);
    }
    if let Some(path) = &args.read {
        let topic = args.topic.as_deref().unwrap_or("");
        return super::bench_read::run(path, topic, args.repeat.clamp(1, 9), args.topic.is_some());
    }
    if args.vs_numpy {
        return vs_numpy(args.grid, args.repeat.clamp(1, 5));
    }
    let (model, load_ms) = load_and_fit(&args.files)?;
    let axis = Axis {
        n: args.grid,
        ..Axis::paper()
    };
    let grid = Grid { dm: axis, km: axis };
    let [land_ms, plain_ms, baseline_ms] = landscape_times(&model, grid, args.repeat.max(1))?;
    let (op_ms, rollout_ms) = operating_point_times(&model, args.points.max(1));
    let threads = std::thread::available_parallelism().map_or(1, usize::from);
    println!(
        "demos: {}, grid: {1}x{1}, threads: {threads}",
        model.demos().len(),
        args.grid
    );
    println!("load + prepare + fit:                 {load_ms:8.2} ms");
    print_landscape_times(
        args.grid,
        args.repeat.max(1),
        &land_ms,
        &plain_ms,
        &baseline_ms,
    );
    print_operating_point_times(&op_ms, &rollout_ms);
    generalise_figures(&model)?;
    orientation_figures(&model, grid, args.repeat.max(1))?;
    diagnostics_figures(&model, grid, args.repeat.max(1))?;
    rl_figures(&model)?;
    println!(
        "elsewhere: the browser's figures (landscape <= 1.0 s, no frame gap > 100 ms while \
         computing, first frame <= 1.5 s, wasm <= 3.5 MB gzipped) in web/tests/browser.mjs; the \
         drag frame (<= 4 ms of app CPU) in tests/frame_time.sh; the NumPy ratio (>= 80x) with \
         --vs-numpy"
    );
    Ok(())
}

/// Loads, prepares and fits the recordings with the defaults; the model and
/// the time it took in ms.
fn load_and_fit(files: &[PathBuf]) -> anyhow::Result<(std::sync::Arc<dmpscope_core::Model>, f64)> {
    let t0 = Instant::now();
    let mut raw = Vec::new();
    for path in files {
        let name = path.display().to_string();
        raw.extend(load_source(&name, SourceData::Path(path), &LoadOptions::default())?.demos);
    }
    let (_, model) = model_of(
        raw,
        &PrepSettings::default(),
        DmpSettings::default(),
        Unusable::Fail,
    )?;
    let load_ms = t0.elapsed().as_secs_f64() * 1e3;
    Ok((model, load_ms))
}

/// The operating point's times in ms at `n` points: the evaluation, and
/// every demo's full path.
fn operating_point_times(model: &dmpscope_core::Model, n: usize) -> (Vec<f64>, Vec<f64>) {
    // Operating points along a path across the default box, as a drag would visit.
    let mut op_ms = Vec::new();
    let mut rollout_ms = Vec::new();
    for i in 0..n {
        let u = i as f64 / n as f64;
        let (dm, km) = (10f64.powf(-1.0 + 4.0 * u), 10f64.powf(3.0 - 4.0 * u));
        let t = Instant::now();
        let eval = model.evaluate(dm, km);
        op_ms.push(t.elapsed().as_secs_f64() * 1e3);
        let t = Instant::now();
        for demo in 0..model.demos().len() {
            std::hint::black_box(model.rollout(demo, dm, km));
        }
        rollout_ms.push(t.elapsed().as_secs_f64() * 1e3);
        std::hint::black_box(eval);
    }
    (op_ms, rollout_ms)
}

/// Prints the landscape's medians, with E and without, and the kernels'
/// instruction set (with the AVX2 baseline's time where it was measured).
fn print_landscape_times(
    n: usize,
    repeat: usize,
    land_ms: &[f64],
    plain_ms: &[f64],
    baseline_ms: &[f64],
) {
    let lm = median(land_ms);
    let pm = median(plain_ms);
    println!(
        "landscape {0}x{0} with E (median of {1}): {lm:8.2} ms   (with E / without: {2:.2}, goal <= 2)",
        n,
        repeat,
        lm / pm
    );
    println!(
        "landscape {0}x{0} without E (median):    {pm:8.2} ms   (position-only kernel, goal 150 ms: {1:.2}x)",
        n,
        pm / 150.0
    );
    let isa = instruction_set();
    if baseline_ms.is_empty() {
        println!("kernels: {isa} (the build's baseline)");
    } else {
        println!(
            "kernels: {isa}; without E on the AVX2 baseline (DMPSCOPE_SIMD=baseline): {:.2} ms, {:.2}x slower",
            median(baseline_ms),
            median(baseline_ms) / pm
        );
    }
}

/// Prints the operating point's medians: the evaluation and the full paths.
fn print_operating_point_times(op_ms: &[f64], rollout_ms: &[f64]) {
    let om = median(op_ms);
    let rm = median(rollout_ms);
    println!(
        "operating point: d, a_peak, S (median): {om:8.3} ms   (goal 0.5 ms: {:.2}x)",
        om / 0.5
    );
    println!("operating point: full paths (median):  {rm:8.3} ms");
}

/// The landscape's wall times in ms: with E, without E, and without E on
/// the AVX2 baseline where the kernels run on AVX-512 (else empty);
/// alternated so that all see the same machine.
fn landscape_times(
    model: &std::sync::Arc<dmpscope_core::Model>,
    grid: Grid,
    repeat: usize,
) -> anyhow::Result<[Vec<f64>; 3]> {
    let cancel = std::sync::atomic::AtomicBool::new(false);
    let without_e = std::sync::Arc::new(model.without_skill_error());
    let (mut land_ms, mut plain_ms, mut baseline_ms) = (Vec::new(), Vec::new(), Vec::new());
    let faster = instruction_set() == "AVX-512";
    let time = |m: &std::sync::Arc<dmpscope_core::Model>, into: &mut Vec<f64>| {
        let t = Instant::now();
        let land = landscape::compute(m.clone(), grid, &cancel, &mut |_, _| {});
        into.push(t.elapsed().as_secs_f64() * 1e3);
        land.map(std::hint::black_box).map(|_| ())
    };
    for _ in 0..repeat {
        if faster {
            // The same landscape on the build's baseline, for CPUs without
            // AVX-512 (the numbers are the same bits).
            set_avx512(false);
            let r = time(&without_e, &mut baseline_ms);
            set_avx512(true);
            r?;
        }
        time(model, &mut land_ms)?;
        time(&without_e, &mut plain_ms)?;
    }
    Ok([land_ms, plain_ms, baseline_ms])
}

/// The landscape with the orientation error `d_rot` (method.md section 12)
/// against the same landscape without it, alternated, and the operating
/// point with every demo's orientation path (a drag's work per frame)
/// against the evaluation and the paths computed apart: on `model` when
/// its demos have orientations, else on the bundled planted sample.
fn orientation_figures(
    model: &std::sync::Arc<dmpscope_core::Model>,
    grid: Grid,
    repeat: usize,
) -> anyhow::Result<()> {
    let (model, on) = if model.has_orientation() {
        (model.clone(), "these demos")
    } else {
        let path = PathBuf::from("assets/planted8.mcap");
        let raw = load_source(
            "planted8.mcap",
            SourceData::Path(&path),
            &LoadOptions::default(),
        )?
        .demos;
        let (_, m) = model_of(
            raw,
            &PrepSettings::default(),
            DmpSettings::default(),
            Unusable::Fail,
        )?;
        (m, "planted8")
    };
    let without = std::sync::Arc::new(model.without_orientation_error());
    let cancel = std::sync::atomic::AtomicBool::new(false);
    let (mut with_ms, mut without_ms) = (Vec::new(), Vec::new());
    for _ in 0..repeat {
        let t = Instant::now();
        std::hint::black_box(landscape::compute(
            model.clone(),
            grid,
            &cancel,
            &mut |_, _| {},
        )?);
        with_ms.push(t.elapsed().as_secs_f64() * 1e3);
        let t = Instant::now();
        std::hint::black_box(landscape::compute(
            without.clone(),
            grid,
            &cancel,
            &mut |_, _| {},
        )?);
        without_ms.push(t.elapsed().as_secs_f64() * 1e3);
    }
    let (w, wo) = (median(&with_ms), median(&without_ms));
    println!(
        "landscape {0}x{0} with d_rot, {on} (median): {w:8.2} ms   (without: {wo:.2} ms; ratio {1:.2}, goal <= 1.6)",
        grid.dm.n,
        w / wo
    );
    // The operating point (a drag's work per frame): every demo's numbers
    // and orientation path in one pass, four demos a lane each, against
    // the evaluation and each demo's rollout apart (two integrations of
    // each demo's orientation, one lane each).
    let (dm, km) = (25.0, 156.25);
    let (mut one_ms, mut apart_ms) = (Vec::new(), Vec::new());
    for _ in 0..50 * repeat {
        let t = Instant::now();
        std::hint::black_box(model.evaluate_with_turns(dm, km));
        one_ms.push(t.elapsed().as_secs_f64() * 1e3);
        let t = Instant::now();
        std::hint::black_box(model.evaluate(dm, km));
        for i in 0..model.demos().len() {
            std::hint::black_box(model.orientation_rollout(i, dm, km));
        }
        apart_ms.push(t.elapsed().as_secs_f64() * 1e3);
    }
    println!(
        "operating point with orientation, {on} (median): {:8.3} ms   (with the paths; evaluation and paths apart: {:.3} ms)",
        median(&one_ms),
        median(&apart_ms)
    );
    Ok(())
}

/// A new target (method.md section 10): one generalised rollout of a demo
/// (1001 steps), and what a drag of the goal costs the app per frame (the
/// session's stage: a demo, and the skill of all demos with its band).
fn generalise_figures(model: &std::sync::Arc<dmpscope_core::Model>) -> anyhow::Result<()> {
    use dmpscope::session::{
        Command, GeneraliseSpec, Runner, Session, Settings, Source, TargetSource,
    };
    use dmpscope_core::{Primitive, Scaling, Target};
    let (dm, km) = (25.0, 156.25);
    let p = Primitive::of_demo(model, 0, dm, km)?;
    let goal = p.goal_abs();
    let mut one_ms = Vec::new();
    for i in 0..2000 {
        let target = Target {
            goal: Some(dmpscope_core::geom::Vec3::new(
                goal[0] - 1e-4 * i as f64,
                goal[1],
                goal[2],
            )),
            scaling: if i % 2 == 0 {
                Scaling::Paper
            } else {
                Scaling::Frame
            },
            ..Target::default()
        };
        let t = Instant::now();
        std::hint::black_box(p.rollout(&target)?);
        one_ms.push(t.elapsed().as_secs_f64() * 1e3);
    }
    let m = median(&one_ms);
    println!(
        "new target: one rollout, 1001 steps (median): {m:8.4} ms   (goal 0.05 ms: {:.2}x)",
        m / 0.05
    );
    let mut settings = Settings::with_grid_points(8);
    settings.op = (dm, km);
    let mut session = Session::new(Runner::inline());
    session.apply(Command::AddSources(vec![Source::sample()]));
    session.update(&settings);
    for (what, source) in [
        ("demo", TargetSource::Demo(0)),
        ("skill", TargetSource::Skill),
    ] {
        let mut spec = GeneraliseSpec {
            source,
            target: Target::default(),
        };
        let mut frame_ms = Vec::new();
        for i in 0..500 {
            spec.target.goal = Some(dmpscope_core::geom::Vec3::new(
                goal[0] - 1e-4 * i as f64,
                goal[1],
                goal[2],
            ));
            let t = Instant::now();
            session.apply(Command::SetGeneralise(Some(spec)));
            session.update(&settings);
            frame_ms.push(t.elapsed().as_secs_f64() * 1e3);
        }
        println!(
            "new target: a goal drag's frame, {what:<5} (median): {:8.4} ms   (session stage; 16.7 ms is a frame at 60 Hz)",
            median(&frame_ms)
        );
    }
    Ok(())
}

/// Every diagnostic of the model's extraction (depth, shares, S minimum,
/// leave-one-out, 100 bootstrap resamples on the default 32 x 32 grid):
/// the median over `repeat` runs, on all cores.
fn diagnostics_figures(
    model: &std::sync::Arc<dmpscope_core::Model>,
    grid: Grid,
    repeat: usize,
) -> anyhow::Result<()> {
    use dmpscope_core::extract::diagnostics::{DiagSettings, DiagnosticsJob};
    let cancel = std::sync::atomic::AtomicBool::new(false);
    let land = landscape::compute(model.clone(), grid, &cancel, &mut |_, _| {})?;
    let x = dmpscope_core::extract(model, &land, dmpscope_core::DEFAULT_K)?;
    let mut times = Vec::new();
    let mut parts = (0, 0);
    for _ in 0..repeat.min(5) {
        let t = Instant::now();
        let mut job = DiagnosticsJob::new(model.clone(), &land, &x, DiagSettings::default());
        parts = job.progress();
        job.run(&|_| {});
        times.push(t.elapsed().as_secs_f64() * 1e3);
        std::hint::black_box(job.diagnostics());
    }
    let m = median(&times);
    println!(
        "diagnostics ({} resampled extractions, median of {}): {m:8.1} ms   (goal 3000 ms: {:.2}x)",
        parts.1,
        times.len(),
        m / 3000.0
    );
    Ok(())
}

/// RL figures: one minibatch step of the critic (100 samples, 7-64-64-1,
/// forward + backward + Adam, as `/tmp` probes of burn measured it) and one
/// PPO iteration (4 episodes + 8 epochs of updates).
fn rl_figures(model: &dmpscope_core::Model) -> anyhow::Result<()> {
    use dmpscope_core::rl::env::{DmpEnv, EnvOptions};
    use dmpscope_core::rl::loss::{Batch, critic_loss_grad};
    use dmpscope_core::rl::mlp::{Adam, Mlp};
    use dmpscope_core::rl::ppo::{PpoConfig, Trainer};
    let mut rng = dmpscope_core::rng::Rng::new(1);
    let mut critic = Mlp::new(&[7, 64, 64, 1], &mut rng, 1.0);
    let mut adam = Adam::new(critic.params.len(), 1e-3);
    let mut batch = Batch::default();
    for _ in 0..100 {
        batch.obs.push((0..7).map(|_| rng.normal()).collect());
        batch.ret.push(rng.normal());
    }
    let idx: Vec<usize> = (0..100).collect();
    let mut step_ms = Vec::new();
    for _ in 0..500 {
        let t = Instant::now();
        let (_, g) = critic_loss_grad(&critic, &batch, &idx);
        adam.step(&mut critic.params, &g);
        step_ms.push(t.elapsed().as_secs_f64() * 1e3);
    }
    let env = DmpEnv::new(model, 0, 32.6, 1000.0, EnvOptions::default())?;
    let mut trainer = Trainer::new(env, PpoConfig::default(), 1);
    let mut iter_ms = Vec::new();
    for _ in 0..15 {
        let t = Instant::now();
        std::hint::black_box(trainer.iterate()?);
        iter_ms.push(t.elapsed().as_secs_f64() * 1e3);
    }
    println!(
        "RL: critic minibatch step (median):     {:8.3} ms   (100 x 7-64-64-1, forward + backward + Adam)",
        median(&step_ms)
    );
    println!(
        "RL: PPO iteration (median):             {:8.2} ms   (400 decisions, 8 epochs)",
        median(&iter_ms)
    );
    Ok(())
}

/// `dmpscope landscape` against the NumPy reference on the reach sample, as
/// whole processes (start-up, loading and writing included), alternated
/// `repeat` times; medians and their ratio.
fn vs_numpy(grid: usize, repeat: usize) -> anyhow::Result<()> {
    use anyhow::Context;
    use std::process::{Command, Stdio};
    let python = std::env::var("DMPSCOPE_PYTHON").unwrap_or_else(|_| "python3".to_owned());
    let script = PathBuf::from("tests/golden/landscape_speed.py");
    anyhow::ensure!(
        script.exists(),
        "{} not found: run from the repository's root",
        script.display()
    );
    let ok = Command::new(&python)
        .args(["-c", "import numpy, scipy"])
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    anyhow::ensure!(
        ok,
        "{python} cannot import numpy and scipy (pip install numpy scipy)"
    );
    let me = std::env::current_exe().context("the running binary")?;
    let out = std::env::temp_dir().join("dmpscope-bench-landscape.json");
    let n = grid.to_string();
    let time = |cmd: &mut Command| -> anyhow::Result<f64> {
        let t = Instant::now();
        let status = cmd
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .status()
            .context("a benchmark process")?;
        anyhow::ensure!(status.success(), "{cmd:?} failed");
        Ok(t.elapsed().as_secs_f64())
    };
    let (mut ours, mut numpy) = (Vec::new(), Vec::new());
    for _ in 0..repeat {
        ours.push(time(
            Command::new(&me)
                .args(["landscape", "assets/reach10.mcap", "--grid", &n, "--out"])
                .arg(&out),
        )?);
        numpy.push(time(
            Command::new(&python)
                .arg(&script)
                .args(["--set", "reach10", "--grid", &n]),
        )?);
    }
    let (o, p) = (median(&ours), median(&numpy));
    println!("reach10, {grid}x{grid}, whole processes, median of {repeat}, alternated:");
    println!("  dmpscope landscape (d, a_peak, S, E; load, fit, write JSON): {o:8.3} s");
    println!("  NumPy reference (d, a_peak, S; tests/golden/landscape_speed.py): {p:8.3} s");
    println!("  ratio {:.1}x   (goal >= 80x)", p / o);
    Ok(())
}
