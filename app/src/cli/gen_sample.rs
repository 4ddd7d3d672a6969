//! `dmpscope gen-sample`: writes the bundled synthetic recordings
//! (`assets/reach10.mcap`; with `--planted`, demos sharing one forcing term
//! at planted gains, `assets/planted8.mcap`), deterministic from a seed.

use std::path::PathBuf;

use anyhow::Context;
use dmpscope_core::export::write::{BulkTopic, TopicSamples, write_pose_stamped_with_bulk};
use dmpscope_core::synth::lab::{CAMERA_TOPIC, LabTake, POSE_TOPIC, write_lab_take};
use dmpscope_core::synth::planted::planted_demos;
use dmpscope_core::synth::planted_forcing::PlantedSpec;
use dmpscope_core::synth::vive::{SynthDemo, reach_demos};

/// Arguments of `gen-sample`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Where to write the MCAP file.
    #[arg(long, short, default_value = "assets/reach10.mcap")]
    out: PathBuf,
    /// Random seed.
    #[arg(long, default_value_t = 42)]
    seed: u64,
    /// Number of demonstrations.
    #[arg(long, default_value_t = 10)]
    demos: usize,
    /// Instead of human-like reaches: demos integrated from one unit-time
    /// DMP with these gains (D/M K/M) and one shared forcing term, goals
    /// and durations varied per demo.
    #[arg(long, num_args = 2, value_names = ["DM", "KM"])]
    planted: Option<Vec<f64>>,
    /// Position noise of the planted demos (standard deviation per axis), mm.
    #[arg(long, default_value_t = 0.1, requires = "planted")]
    noise_mm: f64,
    /// How the planted demos' shared forcing term follows each demo's
    /// goal: absolute (the same term in every demo) or frame (turned and
    /// scaled with the goal, as a frame-independent DMP does).
    #[arg(long, value_enum, default_value_t = ScaleForcing::Absolute, requires = "planted")]
    scale_forcing: ScaleForcing,
    /// Write uncompressed chunks instead of zstd.
    #[arg(long)]
    uncompressed: bool,
    /// Also write this many MB of 1 MB camera frames on `/camera/image_raw`
    /// (a large recording in which the poses are a small part).
    #[arg(long, value_name = "MB", default_value_t = 0)]
    padding_mb: usize,
    /// Instead: a lab take of this many seconds, a tracker's poses
    /// (`/tracker/pose`, 250 Hz) beside a 640x480 rgb8 camera
    /// (`/camera/image_raw`, 30 Hz) in time order, in chunks of
    /// `--chunk-mb` (72 s is about 2 GB).
    #[arg(long, value_name = "SECONDS")]
    lab: Option<f64>,
    /// The lab take's chunk size, MiB.
    #[arg(long, default_value_t = 4, requires = "lab")]
    chunk_mb: u64,
    /// Instead: write the hostile files (decompression bombs, sizes that
    /// lie, floods of indexes) into this folder.
    #[arg(long, value_name = "DIR")]
    hostile: Option<PathBuf>,
}

/// How planted demos share their forcing term.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum ScaleForcing {
    /// One absolute forcing term in every demo.
    Absolute,
    /// Turned and scaled with each demo's goal.
    Frame,
}

/// The start of the first demo's recording (2025-11-22T10:00:00Z).
const EPOCH_NS: i64 = 1_763_805_600_000_000_000;

/// Generates the demos and writes them on `/demo_01`, `/demo_02`, ...
pub fn run(args: Args) -> anyhow::Result<()> {
    if let Some(seconds) = args.lab {
        return write_lab(&args, seconds);
    }
    if let Some(dir) = &args.hostile {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("{}: cannot create", dir.display()))?;
        for h in dmpscope_core::synth::hostile::hostile_files() {
            let path = dir.join(h.name);
            std::fs::write(&path, &h.bytes)
                .with_context(|| format!("{}: cannot write", path.display()))?;
            eprintln!(
                "wrote {} ({} bytes): {}",
                path.display(),
                h.bytes.len(),
                h.what
            );
        }
        return Ok(());
    }
    if args.demos == 0 || args.demos > 99 {
        anyhow::bail!("--demos must be 1 to 99, got {}", args.demos);
    }
    let demos = the_demos(&args)?;
    let topics: Vec<String> = (1..=demos.len()).map(|i| format!("/demo_{i:02}")).collect();
    write_the_demos(&args, &demos, &topics)?;
    print_what_was_written(&args, &demos, &topics);
    Ok(())
}

/// The demos: planted at the given gains (checked, with the noise), else
/// human-like reaches.
fn the_demos(args: &Args) -> anyhow::Result<Vec<SynthDemo>> {
    Ok(match args.planted.as_deref() {
        Some(&[dm, km]) => {
            let valid = |v: f64| v.is_finite() && v > 0.0;
            if !(valid(dm) && valid(km)) {
                anyhow::bail!("--planted gains must be positive, got {dm} {km}");
            }
            if !(args.noise_mm.is_finite() && args.noise_mm >= 0.0) {
                anyhow::bail!("--noise-mm must be >= 0, got {}", args.noise_mm);
            }
            let spec = PlantedSpec {
                dm,
                km,
                noise_m: args.noise_mm * 1e-3,
                demos: args.demos,
                seed: args.seed,
                scale_forcing: match args.scale_forcing {
                    ScaleForcing::Absolute => None,
                    ScaleForcing::Frame => Some(dmpscope_core::fit::mapping::Scaling::Frame),
                },
            };
            planted_demos(&spec, EPOCH_NS)
        }
        Some(other) => anyhow::bail!("--planted takes two gains, got {other:?}"),
        None => reach_demos(args.seed, args.demos, EPOCH_NS),
    })
}

/// Writes each demo on its topic (with the camera frames asked for) to `--out`.
fn write_the_demos(args: &Args, demos: &[SynthDemo], topics: &[String]) -> anyhow::Result<()> {
    let samples: Vec<TopicSamples<'_>> = demos
        .iter()
        .zip(topics)
        .map(|(d, t)| TopicSamples {
            orientations: d.orientations.as_deref(),
            topic: t,
            frame_id: "world",
            samples: &d.samples,
        })
        .collect();
    let file = std::fs::File::create(&args.out)
        .with_context(|| format!("{}: cannot create", args.out.display()))?;
    let bulk = (args.padding_mb > 0).then_some(BulkTopic {
        topic: "/camera/image_raw",
        message_bytes: 1_000_000,
        messages: args.padding_mb,
    });
    write_pose_stamped_with_bulk(
        std::io::BufWriter::new(file),
        &samples,
        !args.uncompressed,
        bulk,
    )
    .with_context(|| format!("{}: cannot write MCAP", args.out.display()))?;
    Ok(())
}

/// Says what was written: the planted gains and noise, or which reaches
/// hesitate and correct.
fn print_what_was_written(args: &Args, demos: &[SynthDemo], topics: &[String]) {
    let corrected: Vec<&str> = demos
        .iter()
        .zip(topics)
        .filter(|(d, _)| d.corrected)
        .map(|(_, t)| t.as_str())
        .collect();
    if let Some(g) = &args.planted {
        eprintln!(
            "wrote {} demos planted at D/M {} K/M {} ({} mm noise) to {}",
            demos.len(),
            g[0],
            g[1],
            args.noise_mm,
            args.out.display()
        );
        return;
    }
    eprintln!(
        "wrote {} demos to {} (hesitation and correction in: {})",
        demos.len(),
        args.out.display(),
        if corrected.is_empty() {
            "none".to_owned()
        } else {
            corrected.join(", ")
        }
    );
}

/// Writes a lab take to `--out`.
fn write_lab(args: &Args, seconds: f64) -> anyhow::Result<()> {
    if !(seconds.is_finite() && seconds > 0.0 && seconds <= 3600.0) {
        anyhow::bail!("--lab takes 0 to 3600 seconds, got {seconds}");
    }
    let take = LabTake {
        seconds,
        zstd: !args.uncompressed,
        chunk_size: args.chunk_mb.clamp(1, 256) << 20,
        seed: args.seed,
        ..LabTake::default()
    };
    let file = std::fs::File::create(&args.out)
        .with_context(|| format!("{}: cannot create", args.out.display()))?;
    let out = std::io::BufWriter::with_capacity(8 << 20, file);
    write_lab_take(out, &take).with_context(|| format!("{}: cannot write", args.out.display()))?;
    let size = std::fs::metadata(&args.out).map_or(0, |m| m.len());
    eprintln!(
        "wrote {} ({:.2} GB): {seconds} s of {POSE_TOPIC} at 250 Hz beside {CAMERA_TOPIC} at 30 Hz",
        args.out.display(),
        size as f64 * 1e-9
    );
    Ok(())
}
