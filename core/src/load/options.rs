//! What the user asks of loading (method.md sections 1, 11 and 13): the
//! CLI's loading flags and the app's Loading section are both
//! [`LoadOptions`]. The readers use the reading part (frames, up axis,
//! fixed frame, which streams); [`crate::arrange`] applies the rest (gaps,
//! what a demo is, segments, rests, units).

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::geom::Quat;

/// Which way is up in the recording.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum UpAxis {
    /// z up, x forward, y left (ROS REP 103, Foxglove): used as is.
    #[default]
    ZUp,
    /// y up, x right, z backward (OpenVR native): turned to z-up as
    /// `(x, y, z) -> (-z, -x, y)`.
    YUp,
}

impl UpAxis {
    /// The position in dmpscope's z-up frame.
    pub fn to_z_up(self, p: [f64; 3]) -> [f64; 3] {
        match self {
            Self::ZUp => p,
            Self::YUp => [-p[2], -p[0], p[1]],
        }
    }

    /// An orientation in dmpscope's z-up frame (the same turn as
    /// [`UpAxis::to_z_up`] applies to positions, then the body's own).
    pub fn orientation_to_z_up(self, q: Quat) -> Quat {
        match self {
            Self::ZUp => q,
            Self::YUp => crate::geom::y_up_to_z_up() * q,
        }
    }
}

/// How to read recordings (method.md sections 1 and 11): the CLI's loading
/// flags and the app's Loading section are both this type.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct LoadOptions {
    /// Keep only these keys (TF child frames, pose-array indices) of
    /// multi-pose topics; empty keeps all.
    pub frames: Vec<String>,
    /// The recording's up axis.
    pub up: UpAxis,
    /// What a demonstration is (applied by [`crate::arrange::streams::load_source`]; the MCAP
    /// reader itself keeps one stream per topic and key).
    pub demos: Grouping,
    /// What to do with a clock jump or a dropout inside a stream (applied
    /// by [`crate::arrange::streams::load_source`] before the grouping).
    pub gaps: GapPolicy,
    /// Which streams are demonstrations: topic patterns and the least
    /// movement (applied by [`crate::arrange::streams::load_source`]).
    pub streams: StreamFilter,
    /// Express every TF frame in this frame, composing `/tf` and
    /// `/tf_static` as a TF buffer does; `None` keeps each transform
    /// relative to its own parent.
    pub fixed_frame: Option<String>,
    /// The length unit of the positions (applied by
    /// [`crate::load::source::load_streams`]).
    pub units: crate::load::units::Units,
    /// Cut each demo's rests at its ends (applied by
    /// [`crate::arrange::streams::load_source`]; measured and reported either way).
    pub trim_rest: bool,
    /// What a rest is, for the end rests (the segmentation's settings).
    pub rest: SegmentSettings,
    /// Cut each demo at its farthest point from its start (`--cut
    /// farthest`; after segmentation and `--segments`): the reach of an
    /// out-and-back with no rest at its far end.
    pub cut: Cut,
    /// An option beyond the method: a stream with an unusable orientation
    /// (zero or not finite) keeps its positions without orientation, with
    /// a warning, instead of the method's error (method.md section 12).
    pub drop_bad_orientation: bool,
}

/// The default least span of a stream's positions, metres (1 cm).
pub const DEFAULT_MIN_EXTENT_M: f64 = 0.01;

/// Which streams are demonstrations.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct StreamFilter {
    /// Keep only streams matching one of these glob patterns (`*`, `?`);
    /// empty keeps all. A pattern matches a stream's topic (`/tf`), its
    /// topic and key (`/tf:hand`) or its key (`hand`).
    pub topics: Vec<String>,
    /// Leave out streams matching one of these patterns (matched the same
    /// way; wins over `topics`).
    pub exclude: Vec<String>,
    /// A stream whose positions span less than this (the diagonal of their
    /// bounding box, metres) does not move and is skipped.
    pub min_extent_m: f64,
}

impl Default for StreamFilter {
    fn default() -> Self {
        Self {
            topics: Vec::new(),
            exclude: Vec::new(),
            min_extent_m: DEFAULT_MIN_EXTENT_M,
        }
    }
}

/// Whether `pattern` matches a stream called `topic` (`/tf:hand`): the
/// whole, the part before the key, or the key.
pub fn matches_stream(pattern: &str, topic: &str) -> bool {
    if glob(pattern, topic) {
        return true;
    }
    match topic.split_once(':') {
        Some((base, key)) => glob(pattern, base) || glob(pattern, key),
        None => false,
    }
}

/// Glob matching with `*` (any run) and `?` (one character).
pub fn glob(pattern: &str, text: &str) -> bool {
    let p: Vec<char> = pattern.chars().collect();
    let t: Vec<char> = text.chars().collect();
    let (mut pi, mut ti) = (0, 0);
    let mut star: Option<(usize, usize)> = None;
    while ti < t.len() {
        if pi < p.len() && (p[pi] == '?' || p[pi] == t[ti]) {
            pi += 1;
            ti += 1;
        } else if pi < p.len() && p[pi] == '*' {
            star = Some((pi, ti));
            pi += 1;
        } else if let Some((sp, st)) = star {
            pi = sp + 1;
            ti = st + 1;
            star = Some((sp, st + 1));
        } else {
            return false;
        }
    }
    p[pi..].iter().all(|&c| c == '*')
}

/// How loaded streams become demonstrations.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Grouping {
    /// Each topic is a demo; a multi-pose topic gives one per key (TF child
    /// frame, pose index). The default.
    #[default]
    PerTopic,
    /// Each file is a demo: the stream that moves most (the largest span of
    /// its positions; the first in name order of equals).
    PerFile,
    /// Each stream is a continuous recording cut at rest periods.
    Segmented(SegmentSettings),
}

/// What to do with a break inside a stream.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GapPolicy {
    /// Split the stream there: each part is a demo of its own (the
    /// default).
    #[default]
    Split,
    /// Keep the stream whole (preparation bridges a gap by interpolation;
    /// a backwards jump is sorted into place), with a warning.
    Keep,
}

/// Where each demo is cut (method.md section 13).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Cut {
    /// Not cut (the default).
    #[default]
    None,
    /// At its farthest point from its start: the reach of an out-and-back.
    Farthest,
}

/// Which of a recording's segments are demonstrations.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SegmentPick {
    /// Every segment (the default).
    #[default]
    All,
    /// The first movement of each recording (the reach of a
    /// reach-and-return trial).
    First,
    /// The last movement of each recording.
    Last,
    /// The N-th movement (1-based) of each recording.
    Nth(usize),
    /// The movements that leave the recording's home (method.md section
    /// 13): the reaches of a take of reaches and returns.
    Out,
    /// The movements that return to the recording's home: the returns.
    Back,
}

impl SegmentPick {
    /// The segments kept of `all` (in time order).
    pub fn pick<T>(self, mut all: Vec<T>) -> Vec<T> {
        match self {
            Self::All => all,
            Self::First => all.into_iter().take(1).collect(),
            Self::Last => all.pop().into_iter().collect(),
            Self::Nth(n) => all.into_iter().nth(n.wrapping_sub(1)).into_iter().collect(),
            // Chosen by where each segment starts and ends
            // (`arrange::segment::split`), not by its place.
            Self::Out | Self::Back => all,
        }
    }

    /// The choice as on the command line (`all`, `first`, `last`, `N`).
    pub fn name(self) -> String {
        match self {
            Self::All => "all".into(),
            Self::First => "first".into(),
            Self::Last => "last".into(),
            Self::Nth(n) => n.to_string(),
            Self::Out => "out".into(),
            Self::Back => "back".into(),
        }
    }

    /// Parses `all`, `first`, `last`, `out`, `back` or a positive number.
    pub fn parse(text: &str) -> std::result::Result<Self, String> {
        match text {
            "all" => Ok(Self::All),
            "first" => Ok(Self::First),
            "last" => Ok(Self::Last),
            "out" => Ok(Self::Out),
            "back" => Ok(Self::Back),
            n => match n.parse::<usize>() {
                Ok(n) if n >= 1 => Ok(Self::Nth(n)),
                _ => Err(format!(
                    "expected all, first, last, out, back or a segment number from 1, got {text:?}"
                )),
            },
        }
    }
}

/// Settings of the segmentation.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct SegmentSettings {
    /// Speed below which the hand is at rest, m/s.
    pub rest_speed: f64,
    /// Shortest rest that separates two demonstrations, seconds.
    pub min_rest_s: f64,
    /// Shortest demonstration kept, seconds.
    pub min_segment_s: f64,
    /// Width of the window the speed is measured over, seconds (longer is
    /// less sensitive to tracker noise).
    pub speed_window_s: f64,
    /// Which segments of each recording are kept.
    pub keep: SegmentPick,
}

impl Default for SegmentSettings {
    fn default() -> Self {
        Self {
            rest_speed: 0.05,
            min_rest_s: 0.2,
            min_segment_s: 0.4,
            speed_window_s: 0.05,
            keep: SegmentPick::All,
        }
    }
}

impl SegmentSettings {
    /// Checks the settings.
    pub fn validate(&self) -> Result<()> {
        let ok = |v: f64| v.is_finite() && v > 0.0;
        if ok(self.rest_speed)
            && ok(self.min_rest_s)
            && ok(self.min_segment_s)
            && ok(self.speed_window_s)
        {
            Ok(())
        } else {
            Err(Error::InvalidSetting(format!(
                "segmentation settings must be positive: {self:?}"
            )))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn globs_match_topics_keys_and_wildcards() {
        assert!(glob("/vive/*", "/vive/hand"));
        assert!(glob("*hand?", "/left_hand1"));
        assert!(!glob("/vive/*", "/tf"));
        assert!(glob("*", ""));
        assert!(matches_stream("/tf", "/tf:tracker"));
        assert!(matches_stream("track*", "/tf:tracker"));
        assert!(!matches_stream("/tf_static", "/tf:tracker"));
        assert!(glob("/händ", "/händ"));
    }
}
