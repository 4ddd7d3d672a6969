//! From command-line paths to a fitted model: folders expanded to their
//! `*.mcap` files, demos pooled in command-line order then topic name,
//! grouped (per topic, per file, segmented), and the preprocessing and DMP
//! settings shared by every subcommand.

use std::path::PathBuf;
use std::sync::Arc;

use anyhow::{Context, bail};
use dmpscope_core::dmp::DmpSettings;
use dmpscope_core::group::{Grouping, group};
use dmpscope_core::io::{LoadOptions, UpAxis, csv::load_csv, load_path_with};
use dmpscope_core::segment::SegmentSettings;
use dmpscope_core::{Model, PrepSettings, RawDemo, prepare};

/// What a demonstration is, on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum DemosBy {
    /// One per topic (and per TF child frame / pose index in multi-pose topics).
    Topic,
    /// One per file (its first stream; narrow with --frame).
    File,
    /// Cut continuous recordings at rest periods.
    Segment,
}

/// Files and how to read them.
#[derive(Debug, clap::Args)]
pub struct LoadArgs {
    /// MCAP or CSV (`t,x,y,z`) files, or folders (every `*.mcap` in them,
    /// sorted by name).
    #[arg(required = true, value_name = "FILES")]
    pub files: Vec<PathBuf>,
    /// Keep only these TF child frames / pose indices (repeatable).
    #[arg(long = "frame", value_name = "NAME")]
    pub frames: Vec<String>,
    /// The recording is y-up (OpenVR native), not z-up (ROS, Foxglove).
    #[arg(long)]
    pub y_up: bool,
    /// What a demonstration is.
    #[arg(long, value_enum, default_value_t = DemosBy::Topic)]
    pub demos: DemosBy,
    /// Segmentation: speed below which the hand rests, m/s.
    #[arg(long, default_value_t = SegmentSettings::default().rest_speed)]
    pub rest_speed: f64,
    /// Segmentation: shortest rest between two demos, s.
    #[arg(long, default_value_t = SegmentSettings::default().min_rest_s)]
    pub min_rest: f64,
    /// Segmentation: shortest demo kept, s.
    #[arg(long, default_value_t = SegmentSettings::default().min_segment_s)]
    pub min_demo: f64,
}

impl LoadArgs {
    /// The segmentation settings.
    pub fn segment_settings(&self) -> SegmentSettings {
        SegmentSettings {
            rest_speed: self.rest_speed,
            min_rest_s: self.min_rest,
            min_segment_s: self.min_demo,
            ..SegmentSettings::default()
        }
    }

    /// The streams of every file, before grouping.
    pub fn load_streams(&self) -> anyhow::Result<Vec<RawDemo>> {
        let options = LoadOptions {
            frames: self.frames.clone(),
            up: if self.y_up { UpAxis::YUp } else { UpAxis::ZUp },
        };
        let mut demos = Vec::new();
        for path in expand(&self.files)? {
            if path
                .extension()
                .is_some_and(|e| e.eq_ignore_ascii_case("csv"))
            {
                let text = std::fs::read_to_string(&path)
                    .with_context(|| format!("{}: cannot read", path.display()))?;
                let mut demo = load_csv(&path.display().to_string(), &text)?;
                for p in &mut demo.positions {
                    *p = options.up.to_z_up(*p);
                }
                demos.push(demo);
                continue;
            }
            let loaded = load_path_with(&path, &options)?;
            for (topic, schema) in &loaded.skipped {
                eprintln!("note: {}: skipped topic {topic} ({schema})", path.display());
            }
            for warning in &loaded.warnings {
                eprintln!("warning: {warning}");
            }
            demos.extend(loaded.demos);
        }
        Ok(demos)
    }

    /// The demonstrations, grouped as asked.
    pub fn load_demos(&self) -> anyhow::Result<Vec<RawDemo>> {
        let grouping = match self.demos {
            DemosBy::Topic => Grouping::PerTopic,
            DemosBy::File => Grouping::PerFile,
            DemosBy::Segment => Grouping::Segmented(self.segment_settings()),
        };
        let demos = group(self.load_streams()?, &grouping)?;
        if demos.is_empty() {
            bail!("no demonstration found (segmentation found no movement between rests?)");
        }
        Ok(demos)
    }
}

/// Input files and the settings that turn them into a model.
#[derive(Debug, clap::Args)]
pub struct InputArgs {
    #[command(flatten)]
    pub load: LoadArgs,
    /// Savitzky-Golay window (samples, odd).
    #[arg(long, default_value_t = 21)]
    pub sg_window: usize,
    /// Savitzky-Golay polynomial order.
    #[arg(long, default_value_t = 3)]
    pub sg_order: usize,
    /// Number of DMP basis functions.
    #[arg(long, default_value_t = 100)]
    pub basis: usize,
}

impl InputArgs {
    fn prep(&self) -> PrepSettings {
        PrepSettings {
            sg_window: self.sg_window,
            sg_order: self.sg_order,
            ..PrepSettings::default()
        }
    }

    fn dmp(&self) -> DmpSettings {
        DmpSettings {
            basis_functions: self.basis,
            ..DmpSettings::default()
        }
    }
}

/// The files named, folders expanded.
pub fn expand(paths: &[PathBuf]) -> anyhow::Result<Vec<PathBuf>> {
    let mut out = Vec::new();
    for path in paths {
        if path.is_dir() {
            let mut found: Vec<PathBuf> = std::fs::read_dir(path)
                .with_context(|| format!("{}: cannot list folder", path.display()))?
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| {
                    p.extension()
                        .is_some_and(|e| e.eq_ignore_ascii_case("mcap"))
                })
                .collect();
            found.sort();
            if found.is_empty() {
                bail!("{}: folder holds no .mcap file", path.display());
            }
            out.extend(found);
        } else {
            out.push(path.clone());
        }
    }
    Ok(out)
}

/// The model of every demo in the inputs.
pub fn load_model(args: &InputArgs) -> anyhow::Result<(Vec<RawDemo>, Arc<Model>)> {
    let raw = args.load.load_demos()?;
    model_of(raw, &args.prep(), args.dmp())
}

/// The model of the given demos with explicit settings.
pub fn model_of(
    raw: Vec<RawDemo>,
    prep: &PrepSettings,
    dmp: DmpSettings,
) -> anyhow::Result<(Vec<RawDemo>, Arc<Model>)> {
    let prepared = raw
        .iter()
        .map(|r| prepare(r, prep))
        .collect::<Result<Vec<_>, _>>()?;
    if prepared.len() < 2 {
        eprintln!(
            "note: only {} demonstration: S needs two or more and is 0 here",
            prepared.len()
        );
    }
    let model = Model::new(prepared, dmp)?;
    Ok((raw, Arc::new(model)))
}
