//! The loading choices by name, as the CLI's flags and the Python
//! package's keywords spell them ([`LoadFlags`]): one place turns them into
//! [`LoadOptions`], so `dmpscope extract --demos segment --segments first`
//! and `dmpscope.load(..., demos="segment", segments="first")` load the
//! same demonstrations. Every default is [`LoadOptions`]'.

use std::str::FromStr;

use crate::load::options::{
    Cut, GapPolicy, Grouping, LoadOptions, SegmentPick, SegmentSettings, StreamFilter, UpAxis,
};
use crate::load::units::Units;
use crate::notice::Notice;

/// What a demonstration is, by name (`--demos`, `demos=`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum DemosBy {
    /// One per topic (and per TF child frame / pose index of a multi-pose
    /// topic): `topic`.
    #[default]
    Topic,
    /// One per file: `file`.
    File,
    /// Continuous recordings cut at rest periods: `segment`.
    Segment,
}

impl DemosBy {
    /// Every choice, in the order the CLI lists them.
    pub const ALL: [Self; 3] = [Self::Topic, Self::File, Self::Segment];

    /// Its name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Self::Topic => "topic",
            Self::File => "file",
            Self::Segment => "segment",
        }
    }

    /// The choice a grouping was made by.
    pub fn of(grouping: &Grouping) -> Self {
        match grouping {
            Grouping::PerTopic => Self::Topic,
            Grouping::PerFile => Self::File,
            Grouping::Segmented(_) => Self::Segment,
        }
    }
}

impl FromStr for DemosBy {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        Self::ALL
            .into_iter()
            .find(|d| d.name() == s)
            .ok_or_else(|| format!("unknown demos {s:?}: topic, file or segment"))
    }
}

impl GapPolicy {
    /// Its name on the command line (`split`, `keep`).
    pub fn name(self) -> &'static str {
        match self {
            Self::Split => "split",
            Self::Keep => "keep",
        }
    }
}

impl FromStr for GapPolicy {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "split" => Ok(Self::Split),
            "keep" => Ok(Self::Keep),
            _ => Err(format!("unknown gaps {s:?}: split or keep")),
        }
    }
}

impl Cut {
    /// Its name on the command line (`none`, `farthest`).
    pub fn name(self) -> &'static str {
        match self {
            Self::None => "none",
            Self::Farthest => "farthest",
        }
    }
}

impl FromStr for Cut {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "none" => Ok(Self::None),
            "farthest" => Ok(Self::Farthest),
            _ => Err(format!("unknown cut {s:?}: none or farthest")),
        }
    }
}

impl FromStr for Units {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        Self::ALL
            .into_iter()
            .find(|u| u.name() == s)
            .ok_or_else(|| format!("unknown units {s:?}: m, cm or mm"))
    }
}

impl FromStr for SegmentPick {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        Self::parse(s)
    }
}

/// The loading choices as the CLI's flags name them (`--frame`,
/// `--fixed-frame`, `--topic`, `--exclude`, `--min-extent`, `--y-up`,
/// `--demos`, `--rest-speed`, `--min-rest`, `--min-demo`, `--gaps`,
/// `--units`, `--trim-rest`, `--segments`, `--drop-bad-orientation`,
/// `--cut`), with their defaults.
#[derive(Clone, Debug, PartialEq)]
pub struct LoadFlags {
    /// Keep only these TF child frames / pose indices.
    pub frames: Vec<String>,
    /// Express every TF frame in this frame.
    pub fixed_frame: Option<String>,
    /// Use only streams matching these globs.
    pub topics: Vec<String>,
    /// Leave out streams matching these globs.
    pub exclude: Vec<String>,
    /// A stream spanning less than this (metres) does not move.
    pub min_extent: f64,
    /// The recording is y-up.
    pub y_up: bool,
    /// What a demonstration is.
    pub demos: DemosBy,
    /// Segmentation: the speed below which the hand rests, m/s.
    pub rest_speed: f64,
    /// Segmentation: the shortest rest between two demos, seconds.
    pub min_rest: f64,
    /// Segmentation: the shortest demo kept, seconds.
    pub min_demo: f64,
    /// A break in time inside a stream: split or keep.
    pub gaps: GapPolicy,
    /// The positions' length unit.
    pub units: Units,
    /// Cut each demo's rests at its ends.
    pub trim_rest: bool,
    /// With segmentation: which movements of each recording are demos.
    pub segments: SegmentPick,
    /// A stream with an unusable quaternion keeps its positions.
    pub drop_bad_orientation: bool,
    /// Where each demo is cut.
    pub cut: Cut,
}

impl Default for LoadFlags {
    fn default() -> Self {
        let options = LoadOptions::default();
        let segments = SegmentSettings::default();
        Self {
            frames: Vec::new(),
            fixed_frame: None,
            topics: Vec::new(),
            exclude: Vec::new(),
            min_extent: StreamFilter::default().min_extent_m,
            y_up: options.up == UpAxis::YUp,
            demos: DemosBy::of(&options.demos),
            rest_speed: segments.rest_speed,
            min_rest: segments.min_rest_s,
            min_demo: segments.min_segment_s,
            gaps: options.gaps,
            units: options.units,
            trim_rest: options.trim_rest,
            segments: segments.keep,
            drop_bad_orientation: options.drop_bad_orientation,
            cut: options.cut,
        }
    }
}

impl LoadFlags {
    /// The segmentation settings.
    pub fn segment_settings(&self) -> SegmentSettings {
        SegmentSettings {
            rest_speed: self.rest_speed,
            min_rest_s: self.min_rest,
            min_segment_s: self.min_demo,
            keep: self.segments,
            ..SegmentSettings::default()
        }
    }

    /// The loading options these flags describe.
    pub fn options(&self) -> LoadOptions {
        LoadOptions {
            frames: self.frames.clone(),
            up: if self.y_up { UpAxis::YUp } else { UpAxis::ZUp },
            demos: match self.demos {
                DemosBy::Topic => Grouping::PerTopic,
                DemosBy::File => Grouping::PerFile,
                DemosBy::Segment => Grouping::Segmented(self.segment_settings()),
            },
            gaps: self.gaps,
            fixed_frame: self.fixed_frame.clone(),
            streams: StreamFilter {
                topics: self.topics.clone(),
                exclude: self.exclude.clone(),
                min_extent_m: self.min_extent,
            },
            units: self.units,
            trim_rest: self.trim_rest,
            rest: SegmentSettings {
                keep: SegmentPick::All,
                ..self.segment_settings()
            },
            drop_bad_orientation: self.drop_bad_orientation,
            cut: self.cut,
        }
    }

    /// The warning that `--segments` is ignored without `--demos segment`.
    pub fn segments_notice(&self) -> Option<Notice> {
        (self.segments != SegmentPick::All && self.demos != DemosBy::Segment).then(|| {
            Notice::warning(format!(
                "--segments {} applies only with --demos segment: every demo is kept",
                self.segments.name()
            ))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_flags_are_the_default_options() {
        assert_eq!(LoadFlags::default().options(), LoadOptions::default());
        assert!(LoadFlags::default().segments_notice().is_none());
    }

    #[test]
    fn names_parse_back() {
        for d in DemosBy::ALL {
            assert_eq!(d.name().parse::<DemosBy>(), Ok(d));
        }
        for u in Units::ALL {
            assert_eq!(u.name().parse::<Units>(), Ok(u));
        }
        for g in [GapPolicy::Split, GapPolicy::Keep] {
            assert_eq!(g.name().parse::<GapPolicy>(), Ok(g));
        }
        for c in [Cut::None, Cut::Farthest] {
            assert_eq!(c.name().parse::<Cut>(), Ok(c));
        }
        assert!("segments".parse::<DemosBy>().is_err());
        assert_eq!("2".parse::<SegmentPick>(), Ok(SegmentPick::Nth(2)));
    }

    #[test]
    fn segments_without_segmentation_warn() {
        let flags = LoadFlags {
            segments: SegmentPick::First,
            ..LoadFlags::default()
        };
        let notice = flags.segments_notice().map(|n| n.to_string());
        assert_eq!(
            notice.as_deref(),
            Some("warning: --segments first applies only with --demos segment: every demo is kept")
        );
    }
}
