//! From a raw recording to a demonstration on the unit-time grid
//! (method.md section 2): sort and de-duplicate stamps, resample uniformly,
//! Savitzky-Golay, normalise time, resample onto the integration grid.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Location, Result};
use crate::geom::Vec3;
use crate::load::demo::{RawDemo, median, stamp_intervals_s};
use crate::prepare::noise::acc_noise;
use crate::prepare::numeric::{interp, linspace};
use crate::prepare::orientation::{Grids, PreparedOrientation};
use crate::prepare::savgol::SavGol;

/// The number of points on the unit-time integration grid (method.md section 2.6).
pub const DEFAULT_GRID_POINTS: usize = 1001;

/// The most points a demo is resampled onto (1000 s at 1 kHz): more means
/// stamps with gaps far longer than their interval, not a demonstration.
pub const MAX_RESAMPLED: usize = 1_000_000;

pub use crate::prepare::savgol::MAX_SG_WINDOW;

/// Settings of the preprocessing (method.md section 2; the paper's values
/// are the defaults).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PrepSettings {
    /// Savitzky-Golay window in samples (odd).
    pub sg_window: usize,
    /// Savitzky-Golay polynomial order.
    pub sg_order: usize,
    /// Points of the unit-time integration grid.
    pub grid_points: usize,
    /// An option beyond the method: the window as a duration, seconds,
    /// turned into an odd number of samples at each demo's own resampled
    /// rate (at least `sg_order + 2`, at most [`MAX_SG_WINDOW`]); `None`
    /// uses `sg_window` samples.
    #[serde(default)]
    pub sg_seconds: Option<f64>,
}

impl PrepSettings {
    /// The window in samples for a demo resampled at `spacing` seconds.
    pub fn window_at(&self, spacing: f64) -> usize {
        match self.sg_seconds {
            None => self.sg_window,
            Some(secs) => {
                let least = self.sg_order.saturating_add(2);
                let w = (secs / spacing).round();
                let w = if w.is_finite() && w > 0.0 {
                    (w.min(MAX_SG_WINDOW as f64) as usize).max(least)
                } else {
                    least
                };
                w | 1
            }
        }
    }
}

impl Default for PrepSettings {
    fn default() -> Self {
        Self {
            sg_window: 21,
            sg_order: 3,
            grid_points: DEFAULT_GRID_POINTS,
            sg_seconds: None,
        }
    }
}

/// A demonstration on the unit-time grid `s = t / T`, shifted so that it
/// starts at the origin. Serialisable, so that a model can be rebuilt
/// elsewhere (the browser's workers) from its demos and settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PreparedDemo {
    /// The demo's name, `file:topic`.
    pub name: String,
    /// Samples as recorded (before sorting and de-duplication).
    pub n_samples: usize,
    /// Duration `T` in seconds (the paper's M).
    pub duration_s: f64,
    /// The median sample interval `h`, seconds.
    pub median_interval_s: f64,
    /// Points of the uniform resampling, `n0`.
    pub n0: usize,
    /// The first resampled raw sample, the shift applied to everything.
    pub p0: Vec3,
    /// The goal `g = y_raw(1)`.
    pub goal: Vec3,
    /// The raw (unsmoothed) path, the comparison target of `d`.
    pub y_raw: Vec<Vec3>,
    /// The smoothed path.
    pub y: Vec<Vec3>,
    /// Its derivative with respect to unit time.
    pub yd: Vec<Vec3>,
    /// Its second derivative with respect to unit time.
    pub ydd: Vec<Vec3>,
    /// The orientation (method.md section 12), when the recording has one
    /// that rotates (`None` for a stream without orientation, and for one
    /// whose orientation is one and the same throughout: a tracker that sends
    /// no rotation).
    #[serde(default)]
    pub orientation: Option<PreparedOrientation>,
    /// How much of its smoothed acceleration is noise (method.md section
    /// 2, "Noise"; `None` where a twice-wider window does not fit).
    #[serde(default)]
    pub acc_noise: Option<f64>,
    /// Where noise dominates, the window (seconds) that brings it below
    /// the threshold (`--sg-seconds`).
    #[serde(default)]
    pub suggested_sg_seconds: Option<f64>,
}

impl PreparedDemo {
    /// Points on the unit-time grid.
    pub fn len(&self) -> usize {
        self.y.len()
    }

    /// Whether the grid is empty (never, for a prepared demo).
    pub fn is_empty(&self) -> bool {
        self.y.is_empty()
    }
}

fn column(v: &[Vec3], axis: usize) -> Vec<f64> {
    v.iter().map(|p| p[axis]).collect()
}

fn zip3(cols: [Vec<f64>; 3]) -> Vec<Vec3> {
    let [x, y, z] = cols;
    x.into_iter()
        .zip(y)
        .zip(z)
        .map(|((x, y), z)| Vec3::new(x, y, z))
        .collect()
}

/// The demo's orientation on `grids` (method.md section 12), `None` when
/// it has none, or one constant orientation (a tracker that sends no
/// rotation).
fn prepare_orientation(
    raw: &RawDemo,
    samples: usize,
    grids: &Grids<'_>,
) -> Result<Option<PreparedOrientation>> {
    let Some(all) = &raw.orientations else {
        return Ok(None);
    };
    let qs: Vec<crate::rotation::QuatXyzw> = raw
        .unique_order()
        .iter()
        .filter_map(|&i| all.get(i))
        .map(crate::geom::xyzw)
        .collect();
    // Exactly one orientation throughout (the identity, or what the up
    // axis made of it, either sign): a tracker that sends no rotation.
    let constant = qs
        .first()
        .is_some_and(|&f| qs.iter().all(|q| *q == f || q.map(|c| -c) == f));
    if qs.len() != samples || constant {
        return Ok(None);
    }
    PreparedOrientation::new(&qs, grids).map(Some)
}

/// Prepares one demonstration (method.md sections 2.2-2.7).
pub fn prepare(raw: &RawDemo, settings: &PrepSettings) -> Result<PreparedDemo> {
    let sg = SavGol::new(settings.sg_window, settings.sg_order)?;
    check(raw, settings)?;
    let (stamps, positions) = raw.sorted_unique();
    if stamps.len() < 2 {
        return Err(Error::TooFewSamples {
            demo: raw.name.clone(),
            n0: stamps.len(),
            min: sg.window(),
        });
    }
    let first = stamps[0];
    let t: Vec<f64> = stamps.iter().map(|s| (s - first) as f64 * 1e-9).collect();
    let total = t[t.len() - 1];
    let h = median(&stamp_intervals_s(&stamps));
    let n0 = uniform_points(raw, total, h)?;
    // A window given as a duration is known in samples only now.
    let sg = match settings.sg_seconds {
        None => sg,
        Some(_) => SavGol::new(
            settings.window_at(total / (n0.max(2) - 1) as f64),
            settings.sg_order,
        )?,
    };
    if n0 < sg.window() {
        return Err(Error::TooFewSamples {
            demo: raw.name.clone(),
            n0,
            min: sg.window(),
        });
    }
    let grid_t = linspace(total, n0);
    let s = linspace(1.0, settings.grid_points);
    let query_t: Vec<f64> = s.iter().map(|s| s * total).collect();
    let on = Grids {
        t: &t,
        uniform: &grid_t,
        unit: &query_t,
        sg: &sg,
        total,
    };
    let (p0, cols, resampled) = smooth_axes(&positions, &on)?;
    let spacing = total / (n0 - 1) as f64;
    let (acc_noise, wider) = acc_noise(&resampled, sg.window(), settings.sg_order, spacing)?;
    let orientation = prepare_orientation(raw, stamps.len(), &on)?;
    let [c_raw, c_y, c_yd, c_ydd] = cols;
    let y_raw = zip3(c_raw);
    let goal = y_raw[y_raw.len() - 1];
    Ok(PreparedDemo {
        name: raw.name.clone(),
        n_samples: raw.stamps_ns.len(),
        duration_s: total,
        median_interval_s: h,
        n0,
        p0,
        goal,
        y_raw,
        y: zip3(c_y),
        yd: zip3(c_yd),
        ydd: zip3(c_ydd),
        orientation,
        acc_noise,
        suggested_sg_seconds: wider.map(|w| ((w as f64 * spacing) * 1000.0).ceil() / 1000.0),
    })
}

/// An error for a grid too small to integrate on, or a position that is
/// not finite (naming its sample).
fn check(raw: &RawDemo, settings: &PrepSettings) -> Result<()> {
    if settings.grid_points < 3 {
        return Err(Error::InvalidSetting(format!(
            "the integration grid needs at least 3 points, got {}",
            settings.grid_points
        )));
    }
    for (i, p) in raw.positions.iter().enumerate() {
        if let Some(axis) = p.iter().position(|v| !v.is_finite()) {
            return Err(Error::NonFinite {
                at: Location::file(&raw.file).topic(&raw.topic).sample(i),
                field: ["position.x", "position.y", "position.z"][axis],
            });
        }
    }
    Ok(())
}

/// The number of points of the uniform grid (section 2.3): the duration
/// over the median interval, rounded, plus one; an error when the stamps
/// would ask for more than [`MAX_RESAMPLED`].
fn uniform_points(raw: &RawDemo, total: f64, h: f64) -> Result<usize> {
    let ratio = total / h;
    if !ratio.is_finite() || ratio > MAX_RESAMPLED as f64 {
        return Err(Error::BadTiming {
            demo: raw.name.clone(),
            reason: format!(
                "duration {total} s over median interval {h} s would need {ratio:.0} resampled points \
                 (at most {MAX_RESAMPLED}): the stamps have gaps far longer than the sampling interval"
            ),
        });
    }
    Ok(ratio.round_ties_even() as usize + 1)
}

/// What [`smooth_axes`] gives: the start, the raw, smoothed, velocity and
/// acceleration columns on the unit-time grid, the uniformly resampled axes.
type SmoothedAxes = (Vec3, [[Vec<f64>; 3]; 4], [Vec<f64>; 3]);

/// Each axis resampled uniformly, smoothed and differentiated, shifted to
/// start at 0 and carried to the unit-time grid: the start `p0`, the
/// columns of the raw, smoothed, velocity and acceleration paths, and the
/// uniformly resampled positions (the noise measure's input).
fn smooth_axes(positions: &[Vec3], on: &Grids<'_>) -> Result<SmoothedAxes> {
    let (total, grid_t, query_t) = (on.total, on.uniform, on.unit);
    let spacing = total / (grid_t.len() - 1) as f64;
    let mut p0 = Vec3::zeros();
    let mut cols: [[Vec<f64>; 3]; 4] = Default::default();
    let mut uniform: [Vec<f64>; 3] = Default::default();
    for axis in 0..3 {
        let resampled = interp(grid_t, on.t, &column(positions, axis));
        p0[axis] = resampled[0];
        let smooth = on.sg.apply(&resampled, spacing)?;
        let shifted: Vec<f64> = resampled.iter().map(|v| v - p0[axis]).collect();
        let smooth_shifted: Vec<f64> = smooth.value.iter().map(|v| v - p0[axis]).collect();
        let vel: Vec<f64> = smooth.d1.iter().map(|v| v * total).collect();
        let acc: Vec<f64> = smooth.d2.iter().map(|v| v * total * total).collect();
        cols[0][axis] = interp(query_t, grid_t, &shifted);
        cols[1][axis] = interp(query_t, grid_t, &smooth_shifted);
        cols[2][axis] = interp(query_t, grid_t, &vel);
        cols[3][axis] = interp(query_t, grid_t, &acc);
        uniform[axis] = resampled;
    }
    Ok((p0, cols, uniform))
}
