//! A demo's orientation on the unit-time grid (method.md section 12): the
//! quaternions in time order made sign-continuous, slerped onto the
//! uniform grid of section 2, smoothed per component by the positions'
//! Savitzky-Golay filter (value, first and second derivative), carried to
//! the unit-time grid like the positions, the smoothed `q` renormalised;
//! the angular velocity and acceleration are `w = 2 vec(q' * conj(q))` and
//! `w' = 2 vec(q'' * conj(q))`. The raw target `q_raw` is slerped onto the
//! unit-time grid.

use crate::error::Result;
use crate::prepare::numeric::interp;
use crate::prepare::savgol::SavGol;
use crate::rotation;
use crate::rotation::QuatXyzw;

/// A demo's orientation on the unit-time grid.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PreparedOrientation {
    /// The raw orientation slerped onto the grid: the error's target.
    pub q_raw: Vec<QuatXyzw>,
    /// The smoothed orientation, unit norm.
    pub q: Vec<QuatXyzw>,
    /// Angular velocity in unit time (space frame), rad per unit time.
    pub w: Vec<[f64; 3]>,
    /// Angular acceleration in unit time.
    pub wd: Vec<[f64; 3]>,
    /// The goal orientation `q_raw(1)`.
    pub goal: QuatXyzw,
}

/// Where to sample: the recorded times, the uniform grid and the
/// unit-time grid (as times), the filter and the duration.
pub struct Grids<'a> {
    /// Sorted unique sample times, seconds from the first.
    pub t: &'a [f64],
    /// The uniform grid of section 2, seconds.
    pub uniform: &'a [f64],
    /// The unit-time grid as times, seconds.
    pub unit: &'a [f64],
    /// The Savitzky-Golay filter of the positions.
    pub sg: &'a SavGol,
    /// The duration T, seconds.
    pub total: f64,
}

/// Slerp of the samples `qs` at times `t` onto `at` (clamped at the ends).
fn slerp_onto(at: &[f64], t: &[f64], qs: &[QuatXyzw]) -> Vec<QuatXyzw> {
    let last = t.len() - 1;
    at.iter()
        .map(|&x| {
            if x <= t[0] {
                return qs[0];
            }
            if x >= t[last] {
                return qs[last];
            }
            let j = t.partition_point(|&p| p <= x) - 1;
            if t[j] == x {
                return qs[j];
            }
            rotation::slerp(qs[j], qs[j + 1], (x - t[j]) / (t[j + 1] - t[j]))
        })
        .collect()
}

impl PreparedOrientation {
    /// Prepares the quaternions `qs` (one per sorted unique sample, unit
    /// norm) on `grids`.
    pub fn new(qs: &[QuatXyzw], grids: &Grids<'_>) -> Result<Self> {
        let mut qs = qs.to_vec();
        rotation::sign_continuous(&mut qs);
        let uniform = slerp_onto(grids.uniform, grids.t, &qs);
        let spacing = grids.total / (grids.uniform.len().max(2) - 1) as f64;
        let (total, total2) = (grids.total, grids.total * grids.total);
        let mut parts: [[Vec<f64>; 4]; 3] = Default::default();
        for c in 0..4 {
            let column: Vec<f64> = uniform.iter().map(|q| q[c]).collect();
            let s = grids.sg.apply(&column, spacing)?;
            let d1: Vec<f64> = s.d1.iter().map(|v| v * total).collect();
            let d2: Vec<f64> = s.d2.iter().map(|v| v * total2).collect();
            parts[0][c] = interp(grids.unit, grids.uniform, &s.value);
            parts[1][c] = interp(grids.unit, grids.uniform, &d1);
            parts[2][c] = interp(grids.unit, grids.uniform, &d2);
        }
        let n = grids.unit.len();
        let at = |p: &[Vec<f64>; 4], k: usize| -> QuatXyzw { std::array::from_fn(|c| p[c][k]) };
        let q: Vec<QuatXyzw> = (0..n)
            .map(|k| rotation::normalised(at(&parts[0], k)))
            .collect();
        let vec2 = |d: QuatXyzw, q: QuatXyzw| {
            let p = rotation::mul(d, rotation::conj(q));
            [2.0 * p[0], 2.0 * p[1], 2.0 * p[2]]
        };
        let w = (0..n).map(|k| vec2(at(&parts[1], k), q[k])).collect();
        let wd = (0..n).map(|k| vec2(at(&parts[2], k), q[k])).collect();
        let q_raw = slerp_onto(grids.unit, grids.uniform, &uniform);
        let goal = q_raw[n - 1];
        Ok(Self {
            q_raw,
            q,
            w,
            wd,
            goal,
        })
    }
}
