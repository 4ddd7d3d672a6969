//! A demonstration as it was recorded: stamps and positions, before any
//! processing (method.md section 1).

use std::ops::Range;

use serde::Serialize;

use crate::geom::{Quat, Vec3};

/// Which clock a demo's stamps came from (method.md section 2.1).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum TimeSource {
    /// The message's own stamp (ROS header stamp, Foxglove `timestamp`).
    HeaderStamp,
    /// The MCAP log time, used when stamps are missing or all zero.
    LogTime,
}

/// One recorded demonstration: samples in file order, as decoded.
#[derive(Clone, Debug, PartialEq)]
pub struct RawDemo {
    /// The display name, `file:topic`.
    pub name: String,
    /// The file the demo came from, as the user named it.
    pub file: String,
    /// The topic (or other source key) inside the file.
    pub topic: String,
    /// Time stamps in integer nanoseconds, file order.
    pub stamps_ns: Vec<i64>,
    /// Positions in metres, one per stamp.
    pub positions: Vec<Vec3>,
    /// Orientations, one per stamp, in the same frame as the positions;
    /// `None` when the source has none (a point, a CSV without `qx..qw`)
    /// or when any sample's quaternion is unusable (not finite, zero).
    pub orientations: Option<Vec<Quat>>,
    /// Where the stamps came from.
    pub time_source: TimeSource,
}

/// A summary of a demo for listings (`dmpscope info`, the demos panel).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DemoInfo {
    /// The display name, `file:topic`.
    pub name: String,
    /// Number of samples as recorded.
    pub n_samples: usize,
    /// Last stamp minus first stamp, seconds.
    pub duration_s: f64,
    /// Median sampling rate in Hz (0 when undefined).
    pub median_rate_hz: f64,
    /// The position of the earliest sample.
    pub start: [f64; 3],
    /// The position of the latest sample.
    pub goal: [f64; 3],
    /// Where the stamps came from.
    pub time_source: TimeSource,
    /// Whether the demo carries orientations.
    pub orientation: bool,
}

impl RawDemo {
    /// The sample indices in time order, equal stamps reduced to the first
    /// in file order (method.md section 2.2).
    pub fn unique_order(&self) -> Vec<usize> {
        let mut order: Vec<usize> = (0..self.stamps_ns.len()).collect();
        // `sort_by_key` is stable: of equal stamps the first in file order stays first.
        order.sort_by_key(|&i| self.stamps_ns[i]);
        order.dedup_by_key(|i| self.stamps_ns[*i]);
        order
    }

    /// The samples in time order, equal stamps reduced to the first in file
    /// order (method.md section 2.2). Returns `(stamps_ns, positions)`.
    pub fn sorted_unique(&self) -> (Vec<i64>, Vec<Vec3>) {
        let order = self.unique_order();
        (
            order.iter().map(|&i| self.stamps_ns[i]).collect(),
            order.iter().map(|&i| self.positions[i]).collect(),
        )
    }

    /// The demo with its samples in time order and equal stamps reduced,
    /// as [`RawDemo::sorted_unique`], orientations included.
    pub fn sorted(&self) -> RawDemo {
        let order = self.unique_order();
        RawDemo {
            stamps_ns: order.iter().map(|&i| self.stamps_ns[i]).collect(),
            positions: order.iter().map(|&i| self.positions[i]).collect(),
            orientations: self
                .orientations
                .as_ref()
                .map(|q| order.iter().map(|&i| q[i]).collect()),
            ..self.without_samples()
        }
    }

    /// The samples in `range` (in the demo's own order) as a demo of their
    /// own, with this demo's file and clock, named `name` and `topic`.
    pub fn part(&self, range: Range<usize>, name: String, topic: String) -> RawDemo {
        RawDemo {
            name,
            topic,
            stamps_ns: self.stamps_ns[range.clone()].to_vec(),
            positions: self.positions[range.clone()].to_vec(),
            orientations: self.orientations.as_ref().map(|q| q[range].to_vec()),
            ..self.without_samples()
        }
    }

    /// Appends `other`'s samples (a later file of the same recording); the
    /// orientations stay only if both have them.
    pub fn extend(&mut self, other: RawDemo) {
        self.stamps_ns.extend(other.stamps_ns);
        self.positions.extend(other.positions);
        self.orientations = match (self.orientations.take(), other.orientations) {
            (Some(mut a), Some(b)) => {
                a.extend(b);
                Some(a)
            }
            _ => None,
        };
    }

    /// The demo's name, file, topic and clock with no samples.
    fn without_samples(&self) -> RawDemo {
        RawDemo {
            name: self.name.clone(),
            file: self.file.clone(),
            topic: self.topic.clone(),
            stamps_ns: Vec::new(),
            positions: Vec::new(),
            orientations: None,
            time_source: self.time_source,
        }
    }

    /// Last minus first stamp in seconds (0 for fewer than two samples),
    /// without sorting: the same as [`RawDemo::info`]'s duration.
    pub fn duration_s(&self) -> f64 {
        match (self.stamps_ns.iter().min(), self.stamps_ns.iter().max()) {
            (Some(a), Some(b)) => (b - a) as f64 * 1e-9,
            _ => 0.0,
        }
    }

    /// How far the positions spread: the diagonal of their bounding box,
    /// metres (0 for fewer than two samples).
    pub fn extent_m(&self) -> f64 {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for p in &self.positions {
            for a in 0..3 {
                lo[a] = lo[a].min(p[a]);
                hi[a] = hi[a].max(p[a]);
            }
        }
        if self.positions.len() < 2 {
            return 0.0;
        }
        (0..3).map(|a| (hi[a] - lo[a]).powi(2)).sum::<f64>().sqrt()
    }

    /// A summary for listings.
    pub fn info(&self) -> DemoInfo {
        let (stamps, positions) = self.sorted_unique();
        let duration_s = match (stamps.first(), stamps.last()) {
            (Some(a), Some(b)) => (b - a) as f64 * 1e-9,
            _ => 0.0,
        };
        let intervals = stamp_intervals_s(&stamps);
        let h = median(&intervals);
        DemoInfo {
            name: self.name.clone(),
            n_samples: self.stamps_ns.len(),
            duration_s,
            median_rate_hz: if h > 0.0 { 1.0 / h } else { 0.0 },
            start: positions.first().map_or([0.0; 3], |p| (*p).into()),
            goal: positions.last().map_or([0.0; 3], |p| (*p).into()),
            time_source: self.time_source,
            orientation: self.orientations.is_some(),
        }
    }
}

/// Successive differences of sorted integer stamps, in seconds.
pub fn stamp_intervals_s(stamps_ns: &[i64]) -> Vec<f64> {
    stamps_ns
        .windows(2)
        .map(|w| (w[1] - w[0]) as f64 * 1e-9)
        .collect()
}

/// The median (the mean of the two middle values for an even count, as
/// NumPy's); 0 for an empty slice.
pub fn median(values: &[f64]) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    let m = v.len() / 2;
    if !v.len().is_multiple_of(2) {
        v[m]
    } else {
        (v[m - 1] + v[m]) / 2.0
    }
}
