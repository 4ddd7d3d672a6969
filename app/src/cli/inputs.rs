//! From command-line paths to a fitted model, through the same core calls
//! the app makes: [`dmpscope_core::arrange::streams::load_source`] for each FILE (a file or
//! a folder) with the loading flags as [`LoadOptions`], demos pooled in
//! command-line order, then [`dmpscope_core::build_model`] with the
//! `--unusable` policy. Every default is the core's.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use dmpscope_core::SkillMode;
use dmpscope_core::arrange::pool::load_demos;
use dmpscope_core::fit::settings::DmpSettings;
use dmpscope_core::load::access::{FileAt, Meter, Metered, block_on};
use dmpscope_core::load::flags::{DemosBy as CoreDemosBy, LoadFlags};
use dmpscope_core::load::options::GapPolicy;
use dmpscope_core::load::options::Grouping;
use dmpscope_core::load::options::LoadOptions;
use dmpscope_core::load::options::StreamFilter;
use dmpscope_core::load::options::{Cut, SegmentPick, SegmentSettings};
use dmpscope_core::load::source::{SourceData, SourceStreams, load_streams, load_streams_at};
use dmpscope_core::load::units::Units;
use dmpscope_core::pipeline::ModelFlags;
use dmpscope_core::{Model, PrepSettings, RawDemo, Unusable, build_model};

use super::output::print_notices;

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

impl DemosBy {
    /// The flag's value for a grouping.
    pub fn of(grouping: &Grouping) -> Self {
        match grouping {
            Grouping::PerTopic => Self::Topic,
            Grouping::PerFile => Self::File,
            Grouping::Segmented(_) => Self::Segment,
        }
    }
}

/// What to do with a break in time inside a stream.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum GapsArg {
    /// Split the stream there: each part is a demo of its own.
    Split,
    /// Keep the stream whole, bridged, with a warning.
    Keep,
}

/// What to do with a demo that cannot be used.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum UnusableArg {
    /// Stop with its error.
    Fail,
    /// Leave it out with a warning; stop only when none is left.
    Skip,
}

/// Files and how to read them.
#[derive(Debug, clap::Args)]
pub struct LoadArgs {
    /// MCAP (`.mcap`, `.mcap.zstd`), ROS 1 bag (`.bag`) or CSV (`t,x,y,z`
    /// or `t,x,y,z,qx,qy,qz,qw`) files, or folders (a rosbag2 folder, or any
    /// folder: every recording in it, sorted by name, and its sub-folders).
    #[arg(required = true, value_name = "FILES")]
    pub files: Vec<PathBuf>,
    /// Keep only these TF child frames / pose indices (repeatable).
    #[arg(long = "frame", value_name = "NAME")]
    pub frames: Vec<String>,
    /// Express every TF frame in this frame: `/tf` and `/tf_static` are
    /// composed as a TF buffer does (dynamic transforms interpolated at each
    /// stamp); without it each transform stays relative to its own parent.
    #[arg(long, value_name = "FRAME")]
    pub fixed_frame: Option<String>,
    /// Use only streams matching this glob (`*`, `?`; repeatable): a
    /// topic (`/vive/*`), a topic and key (`/tf:hand`) or a key (`hand`).
    #[arg(long = "topic", value_name = "PATTERN")]
    pub topics: Vec<String>,
    /// Leave out streams matching this glob (repeatable; wins over --topic).
    #[arg(long = "exclude", value_name = "PATTERN")]
    pub exclude: Vec<String>,
    /// A stream whose positions span less than this (m) does not move and
    /// is skipped.
    #[arg(long, default_value_t = StreamFilter::default().min_extent_m, value_name = "M")]
    pub min_extent: f64,
    /// The recording is y-up (OpenVR native), not z-up (ROS, Foxglove).
    #[arg(long)]
    pub y_up: bool,
    /// What a demonstration is.
    #[arg(long, value_enum, default_value_t = DemosBy::of(&Grouping::default()))]
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
    /// A clock jump or a dropout inside a stream (a step over max(0.1 s,
    /// 10 x the median interval)): split the stream there, or keep it whole
    /// (bridged); a warning names it either way.
    #[arg(long, value_enum, default_value_t = GapsArg::Split)]
    pub gaps: GapsArg,
    /// The length unit of the recordings' positions (motion-capture exports
    /// are often in millimetres); converted to metres at loading.
    #[arg(long, value_enum, default_value_t = UnitsArg::M)]
    pub units: UnitsArg,
    /// Cut each demo's rests at its start and end (speed below
    /// --rest-speed for longer than --min-rest) before preparation; they
    /// are reported either way. Changes what unit time spans.
    #[arg(long)]
    pub trim_rest: bool,
    /// With --demos segment: which movements of each recording are demos
    /// (all, first, last, a number from 1, or out / back: those that leave
    /// the recording's home, or return to it), e.g. `first` keeps the
    /// reach of each reach-and-return trial, `out` the reaches of a take of
    /// reaches and returns.
    #[arg(long, default_value = "all", value_parser = SegmentPick::parse, value_name = "WHICH")]
    pub segments: SegmentPick,
    /// An option beyond the method: a stream with a zero or non-finite
    /// quaternion keeps its positions without orientation, with a warning,
    /// instead of the error naming the sample (method.md section 12).
    #[arg(long)]
    pub drop_bad_orientation: bool,
    /// Cut each demo (after segmentation and --segments): `farthest` keeps
    /// it from its start to its farthest point from the start, the reach of
    /// an out-and-back with no rest at its far end.
    #[arg(long, value_enum, default_value_t = CutArg::None)]
    pub cut: CutArg,
}

/// Where demos are cut, on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum CutArg {
    /// Not cut.
    None,
    /// At the farthest point from the start.
    Farthest,
}

/// Length units on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum UnitsArg {
    /// Metres.
    M,
    /// Centimetres.
    Cm,
    /// Millimetres.
    Mm,
}

impl LoadArgs {
    /// The flags as the core names them.
    pub fn flags(&self) -> LoadFlags {
        LoadFlags {
            frames: self.frames.clone(),
            fixed_frame: self.fixed_frame.clone(),
            topics: self.topics.clone(),
            exclude: self.exclude.clone(),
            min_extent: self.min_extent,
            y_up: self.y_up,
            demos: match self.demos {
                DemosBy::Topic => CoreDemosBy::Topic,
                DemosBy::File => CoreDemosBy::File,
                DemosBy::Segment => CoreDemosBy::Segment,
            },
            rest_speed: self.rest_speed,
            min_rest: self.min_rest,
            min_demo: self.min_demo,
            gaps: match self.gaps {
                GapsArg::Split => GapPolicy::Split,
                GapsArg::Keep => GapPolicy::Keep,
            },
            units: match self.units {
                UnitsArg::M => Units::M,
                UnitsArg::Cm => Units::Cm,
                UnitsArg::Mm => Units::Mm,
            },
            trim_rest: self.trim_rest,
            segments: self.segments,
            drop_bad_orientation: self.drop_bad_orientation,
            cut: match self.cut {
                CutArg::None => Cut::None,
                CutArg::Farthest => Cut::Farthest,
            },
        }
    }

    /// The segmentation settings.
    pub fn segment_settings(&self) -> SegmentSettings {
        self.flags().segment_settings()
    }

    /// The loading options these flags describe.
    pub fn options(&self) -> LoadOptions {
        self.flags().options()
    }

    /// The streams of every file, before grouping (`info --segment`).
    pub fn load_streams(&self) -> anyhow::Result<Vec<RawDemo>> {
        self.warn_of_ignored_segments();
        let options = self.options();
        let mut demos = Vec::new();
        for path in &self.files {
            let name = path.display().to_string();
            let loaded = read_streams(&name, path, &options)?;
            print_notices(&loaded.notices);
            demos.extend(loaded.demos);
        }
        Ok(demos)
    }

    /// The demonstrations, grouped as asked, their names unique.
    pub fn load_demos(&self) -> anyhow::Result<Vec<RawDemo>> {
        self.warn_of_ignored_segments();
        Ok(load_demos(
            &self.files,
            &self.options(),
            &mut read_streams,
            &mut print_notices,
        )?)
    }

    /// Warns that `--segments` does nothing without `--demos segment`.
    fn warn_of_ignored_segments(&self) {
        if let Some(notice) = self.flags().segments_notice() {
            print_notices(&[notice]);
        }
    }
}

/// Input files and the settings that turn them into a model.
#[derive(Debug, clap::Args)]
pub struct InputArgs {
    #[command(flatten)]
    pub load: LoadArgs,
    /// Savitzky-Golay window (samples, odd).
    #[arg(long, default_value_t = PrepSettings::default().sg_window)]
    pub sg_window: usize,
    /// Savitzky-Golay polynomial order.
    #[arg(long, default_value_t = PrepSettings::default().sg_order)]
    pub sg_order: usize,
    /// Number of DMP basis functions.
    #[arg(long, default_value_t = DmpSettings::default().basis_functions)]
    pub basis: usize,
    /// An option beyond the method: floor each axis's SD in S's
    /// standardisation at this fraction of the demo's largest axis SD (0:
    /// the method as written; method.md section 5).
    #[arg(long, default_value_t = DmpSettings::default().axis_sd_floor, value_name = "FRACTION")]
    pub axis_sd_floor: f64,
    /// How the one skill of all demos follows each demo's start and goal
    /// in the skill error E (method.md section 11): frame (turn and
    /// scale), per-axis (the paper's factors) or none (one absolute
    /// forcing term).
    #[arg(long, default_value = "frame", value_parser = skill_mode, value_name = "MODE")]
    pub skill_mode: SkillMode,
    /// A demo that cannot be used (too few samples, non-finite values):
    /// leave it out with a warning naming it and why (stop only when none
    /// is left), or stop at the first.
    #[arg(long, value_enum, default_value_t = UnusableArg::Skip)]
    pub unusable: UnusableArg,
    /// An option beyond the method: the Savitzky-Golay window as a
    /// duration in seconds, an odd number of samples at each demo's own
    /// rate (at least --sg-order + 2); overrides --sg-window.
    #[arg(long, value_name = "S", value_parser = positive_seconds)]
    pub sg_seconds: Option<f64>,
    /// An option beyond the paper: add k_rot times the demos' summed
    /// orientation error (degrees) to J (method.md section 12; 0, the
    /// default, keeps the paper's J on positions).
    #[arg(long, default_value_t = 0.0, value_name = "K_ROT")]
    pub k_rot: f64,
    /// Separate gains for the orientation DMP (default: the position's, one
    /// pair for the pose as movement_primitives' CartesianDMP has).
    #[arg(long, num_args = 2, value_names = ["DM", "KM"], allow_negative_numbers = true)]
    pub orientation_gains: Option<Vec<f64>>,
}

/// A skill mode by name.
fn skill_mode(text: &str) -> Result<SkillMode, String> {
    text.parse()
}

/// A duration in seconds above zero.
fn positive_seconds(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!(
            "expected a duration in seconds above 0, got {text:?}"
        )),
    }
}

impl InputArgs {
    /// The model's flags as the core names them.
    pub fn model_flags(&self) -> ModelFlags {
        ModelFlags {
            sg_window: self.sg_window,
            sg_order: self.sg_order,
            basis: self.basis,
            axis_sd_floor: self.axis_sd_floor,
            skill_mode: self.skill_mode,
            unusable: self.unusable(),
            sg_seconds: self.sg_seconds,
            k_rot: self.k_rot,
            orientation_gains: self
                .orientation_gains
                .as_deref()
                .and_then(|g| Some([*g.first()?, *g.get(1)?])),
        }
    }

    /// The preprocessing settings.
    pub fn prep(&self) -> PrepSettings {
        self.model_flags().prep()
    }

    /// The DMP settings.
    pub fn dmp(&self) -> DmpSettings {
        self.model_flags().dmp()
    }

    /// The policy for unusable demos.
    pub fn unusable(&self) -> Unusable {
        match self.unusable {
            UnusableArg::Fail => Unusable::Fail,
            UnusableArg::Skip => Unusable::Skip,
        }
    }
}

/// The model of every demo in the inputs, and the raw demos it was built
/// from (in the model's order).
pub fn load_model(args: &InputArgs) -> anyhow::Result<(Vec<RawDemo>, Arc<Model>)> {
    let raw = args.load.load_demos()?;
    model_of(raw, &args.prep(), args.dmp(), args.unusable())
}

/// The model of the given demos with explicit settings; notices go to
/// stderr.
pub fn model_of(
    raw: Vec<RawDemo>,
    prep: &PrepSettings,
    dmp: DmpSettings,
    unusable: Unusable,
) -> anyhow::Result<(Vec<RawDemo>, Arc<Model>)> {
    let built = build_model(&raw, prep, dmp, unusable)?;
    print_notices(&built.notices);
    let mut raw: Vec<Option<RawDemo>> = raw.into_iter().map(Some).collect();
    let used = built
        .used
        .iter()
        .filter_map(|&i| raw.get_mut(i).and_then(Option::take))
        .collect();
    Ok((used, Arc::new(built.model)))
}

/// Files at least this large are read with a progress bar on stderr.
const PROGRESS_FROM: u64 = 64 << 20;

/// The streams of `path` (a file or a folder), as the core's
/// `load_streams`; a file of [`PROGRESS_FROM`] bytes or more is read with
/// a progress bar on stderr (drawn only where stderr is a terminal).
fn read_streams(
    name: &str,
    path: &Path,
    options: &LoadOptions,
) -> dmpscope_core::Result<SourceStreams> {
    let size = std::fs::metadata(path)
        .ok()
        .filter(|m| m.is_file())
        .map(|m| m.len());
    let Some(size) = size.filter(|&s| s >= PROGRESS_FROM) else {
        return load_streams(name, SourceData::Path(path), options);
    };
    let file = FileAt::open(path).map_err(|reason| dmpscope_core::Error::Io {
        file: name.to_owned(),
        reason,
    })?;
    let meter = Arc::new(Meter::default());
    let mut access = Metered::new(file, Arc::clone(&meter));
    let bar = super::output::byte_bar(size, name);
    let result = std::thread::scope(|scope| {
        let reading = scope.spawn(|| block_on(load_streams_at(name, &mut access, options)));
        while !reading.is_finished() {
            bar.set_position(meter.bytes_read());
            std::thread::sleep(std::time::Duration::from_millis(100));
        }
        reading.join()
    });
    bar.finish_and_clear();
    result.unwrap_or_else(|_| {
        Err(dmpscope_core::Error::Source {
            path: name.to_owned(),
            reason: "the reader stopped unexpectedly".to_owned(),
        })
    })
}
