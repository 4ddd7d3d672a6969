//! The orientation DMP (method.md section 12): the quaternion form of Ude
//! et al. (2014), movement_primitives' CartesianDMP, in unit time with the
//! position's phase and basis.
//!
//! Preparation ([`PreparedOrientation::new`]): the quaternions in time
//! order are made sign-continuous, slerped onto the uniform grid of
//! section 2, smoothed per component by the same Savitzky-Golay filter as
//! the positions (value, first and second derivative), carried to the
//! unit-time grid like the positions, the smoothed `q` renormalised; the
//! angular velocity and acceleration are `w = 2 vec(q' * conj(q))` and
//! `w' = 2 vec(q'' * conj(q))`. The raw target `q_raw` is slerped onto the
//! unit-time grid.
//!
//! Fit: `f_o = w' + D/M w - K/M 2 log(q_g * conj(q))` is linear in the
//! gains, so the LWR projections are the position's
//! ([`Projections::from_parts`]). Rollout ([`rollout`]):
//! `a_k = -D w_k + K 2 log(q_g * conj(q_k)) + f_o(x_k)`,
//! `w_{k+1} = w_k + a_k dt`, `q_{k+1} = exp(w_{k+1} dt / 2) * q_k`.
//! Error: `d_rot = integral_0^1 2 acos(min(1, |q_new . q_raw|)) ds`.

use crate::fit::basis::Basis;
use crate::fit::lwr::Projections;
use crate::prepare::numeric::trapezoid;
use crate::prepare::orientation::PreparedOrientation;
use crate::rotation;
use crate::rotation::QuatXyzw;

impl PreparedOrientation {
    /// The LWR projections of `f_o = w' + D w - K 2 log(q_g * conj(q))`.
    pub fn projections(&self, basis: &Basis) -> Projections {
        let goal = self.goal;
        let to_goal: Vec<[f64; 3]> = self
            .q
            .iter()
            .map(|&q| rotation::rotation_vector(goal, q))
            .collect();
        let parts = [0, 1, 2].map(|ax| {
            [
                self.wd.iter().map(|v| v[ax]).collect(),
                self.w.iter().map(|v| v[ax]).collect(),
                to_goal.iter().map(|v| -v[ax]).collect(),
            ]
        });
        Projections::from_parts(basis, parts)
    }
}

/// An orientation path on the unit-time grid.
#[derive(Clone, Debug, PartialEq)]
pub struct OrientationRollout {
    /// Orientations, unit quaternions `[x, y, z, w]`.
    pub q: Vec<QuatXyzw>,
    /// Angular velocities, rad per unit time.
    pub w: Vec<[f64; 3]>,
    /// Angular accelerations, rad per unit time squared.
    pub a: Vec<[f64; 3]>,
}

impl OrientationRollout {
    /// The largest angular acceleration norm, `alpha_peak` (NaN once any
    /// step is: a diverged run).
    pub fn alpha_peak(&self) -> f64 {
        self.a
            .iter()
            .map(|a| (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt())
            .fold(0.0, |m, v| {
                if v.is_nan() || m.is_nan() {
                    f64::NAN
                } else {
                    m.max(v)
                }
            })
    }
}

/// Where an orientation rollout starts and ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrientationTarget {
    /// The start orientation.
    pub start: QuatXyzw,
    /// The initial angular velocity, unit time.
    pub w0: [f64; 3],
    /// The goal orientation.
    pub goal: QuatXyzw,
}

/// The fitted forcing term `F0 + D F1 + K F2` on the grid.
pub fn forcing_at(proj: &Projections, dm: f64, km: f64) -> Vec<[f64; 3]> {
    proj.f
        .iter()
        .map(|fk| {
            std::array::from_fn(|ax| {
                let [f0, f1, f2] = fk[ax];
                f0 + dm * f1 + km * f2
            })
        })
        .collect()
}

/// `d_rot`: the angle between a path and a target, integrated over unit
/// time (trapezoid), radians.
pub fn error(path: &[QuatXyzw], target: &[QuatXyzw]) -> f64 {
    let n = path.len().min(target.len());
    let angles = path
        .iter()
        .zip(target)
        .map(|(&a, &b)| rotation::angle(a, b));
    trapezoid(angles, n) / (n.max(2) - 1) as f64
}
