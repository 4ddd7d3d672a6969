//! Splitting one continuous recording into demonstrations at rest periods:
//! where the hand's speed stays below a threshold for long enough, one
//! demonstration ends and the next begins. Fragments too short to be a
//! demonstration are dropped.

use serde::Serialize;

use crate::error::Result;
use crate::geom::Vec3;
use crate::load::demo::RawDemo;
use crate::load::options::{SegmentPick, SegmentSettings};

/// One demonstration found in a recording, as stamps of the recording.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Segment {
    /// The first sample's stamp, ns.
    pub start_ns: i64,
    /// The last sample's stamp, ns.
    pub end_ns: i64,
    /// Index of the first sample in time order (after de-duplication).
    pub first: usize,
    /// Index of the last sample, inclusive.
    pub last: usize,
}

/// The hand's speed at each sample (time order), m/s, as the distance
/// travelled over a window of about `window_s` centred on the sample.
pub fn speeds(stamps_ns: &[i64], positions: &[Vec3], window_s: f64) -> Vec<f64> {
    let half = (window_s * 0.5e9) as i64;
    let n = stamps_ns.len();
    let (mut lo, mut hi) = (0, 0);
    (0..n)
        .map(|i| {
            while stamps_ns[i] - stamps_ns[lo] > half {
                lo += 1;
            }
            hi = hi.max(i);
            while hi + 1 < n && stamps_ns[hi + 1] - stamps_ns[i] <= half {
                hi += 1;
            }
            let (a, b) = if hi > lo {
                (lo, hi)
            } else {
                (i.saturating_sub(1), (i + 1).min(n - 1))
            };
            let dt = (stamps_ns[b] - stamps_ns[a]) as f64 * 1e-9;
            if dt <= 0.0 {
                return 0.0;
            }
            let d2: f64 = (0..3)
                .map(|ax| (positions[b][ax] - positions[a][ax]).powi(2))
                .sum();
            d2.sqrt() / dt
        })
        .collect()
}

/// The demonstrations in one recording: the stretches between rest periods
/// of at least `min_rest_s`, each from the last sample of the rest before it
/// to the first sample of the rest after it, at least `min_segment_s` long.
pub fn find_segments(demo: &RawDemo, settings: &SegmentSettings) -> Result<Vec<Segment>> {
    settings.validate()?;
    let (stamps, positions) = demo.sorted_unique();
    if stamps.len() < 2 {
        return Ok(Vec::new());
    }
    let rests = rest_runs(&stamps, &positions, settings);
    // Motion lies between rests, and before the first / after the last.
    let mut bounds = Vec::new();
    let mut from = 0;
    for &(rest_start, rest_end) in &rests {
        if rest_start > from {
            bounds.push((from, rest_start));
        }
        from = rest_end;
    }
    if from + 1 < stamps.len() {
        bounds.push((from, stamps.len() - 1));
    }
    let min_len = (settings.min_segment_s * 1e9) as i64;
    Ok(bounds
        .into_iter()
        .filter(|&(a, b)| stamps[b] - stamps[a] >= min_len)
        .map(|(first, last)| Segment {
            start_ns: stamps[first],
            end_ns: stamps[last],
            first,
            last,
        })
        .collect())
}

/// The rests of a recording in time order (sorted, unique stamps): maximal
/// runs of samples slower than the rest speed lasting at least the
/// shortest rest, as `(first, last)` sample indices.
fn rest_runs(
    stamps: &[i64],
    positions: &[Vec3],
    settings: &SegmentSettings,
) -> Vec<(usize, usize)> {
    let speed = speeds(stamps, positions, settings.speed_window_s);
    let min_rest = (settings.min_rest_s * 1e9) as i64;
    let mut rests = Vec::new();
    let mut i = 0;
    while i < stamps.len() {
        if speed[i] >= settings.rest_speed {
            i += 1;
            continue;
        }
        let start = i;
        while i + 1 < stamps.len() && speed[i + 1] < settings.rest_speed {
            i += 1;
        }
        if stamps[i] - stamps[start] >= min_rest {
            rests.push((start, i));
        }
        i += 1;
    }
    rests
}

/// How near a rest must be to the home to count as being at home, metres.
pub const HOME_RADIUS_M: f64 = 0.05;

/// A recording's home (method.md section 13): the place it rests at most.
/// Each rest's mean position is gathered with the rests within
/// [`HOME_RADIUS_M`] of the first of their group; the group whose rests
/// last longest in all is home (the earliest on ties), its first rest's
/// mean position. `None` without rests.
pub fn home(demo: &RawDemo, settings: &SegmentSettings) -> Option<Vec3> {
    let (stamps, positions) = demo.sorted_unique();
    let rests = rest_runs(&stamps, &positions, settings);
    let mean = |(a, b): (usize, usize)| {
        let n = (b - a + 1) as f64;
        Vec3::from_fn(|ax, _| positions[a..=b].iter().map(|p| p[ax]).sum::<f64>() / n)
    };
    let mut groups: Vec<(Vec3, i64)> = Vec::new();
    for &r in &rests {
        let at = mean(r);
        let lasts = stamps[r.1] - stamps[r.0];
        match groups
            .iter_mut()
            .find(|(g, _)| (g - at).norm() <= HOME_RADIUS_M)
        {
            Some((_, total)) => *total += lasts,
            None => groups.push((at, lasts)),
        }
    }
    groups
        .iter()
        .fold(None::<(Vec3, i64)>, |best, &(at, total)| match best {
            Some((_, b)) if b >= total => best,
            _ => Some((at, total)),
        })
        .map(|(at, _)| at)
}

/// The recording cut into its segments, named `name#1`, `name#2`, ...
/// (`--segments out` and `back` keep those that leave the recording's
/// home, or return to it; the others are chosen by `SegmentSettings::keep`
/// afterwards).
pub fn split(demo: &RawDemo, settings: &SegmentSettings) -> Result<Vec<RawDemo>> {
    split_counted(demo, settings).map(|(kept, _)| kept)
}

/// [`split`], with the number of segments found before `out` or `back`
/// chose.
pub fn split_counted(demo: &RawDemo, settings: &SegmentSettings) -> Result<(Vec<RawDemo>, usize)> {
    let sorted = demo.sorted();
    let segments = find_segments(demo, settings)?;
    let found = segments.len();
    let home = match settings.keep {
        SegmentPick::Out | SegmentPick::Back => home(demo, settings),
        _ => None,
    };
    let (_, positions) = demo.sorted_unique();
    let near = |i: usize, h: Vec3| (positions[i] - h).norm() <= HOME_RADIUS_M;
    Ok(segments
        .into_iter()
        .enumerate()
        .filter(|(_, s)| match (settings.keep, home) {
            (SegmentPick::Out, Some(h)) => near(s.first, h) && !near(s.last, h),
            (SegmentPick::Back, Some(h)) => !near(s.first, h) && near(s.last, h),
            (SegmentPick::Out | SegmentPick::Back, None) => false,
            _ => true,
        })
        .map(|(i, s)| {
            sorted.part(
                s.first..s.last + 1,
                format!("{}#{}", demo.name, i + 1),
                format!("{}#{}", demo.topic, i + 1),
            )
        })
        .collect::<Vec<_>>())
    .map(|kept| (kept, found))
}
