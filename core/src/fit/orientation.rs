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
use crate::rotation::Q;

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
    pub q: Vec<Q>,
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
    pub start: Q,
    /// The initial angular velocity, unit time.
    pub w0: [f64; 3],
    /// The goal orientation.
    pub goal: Q,
}

/// Integrates the orientation DMP with the fitted forcing term of `proj`
/// at `(dm, km)` from `target` (method.md section 12).
pub fn rollout(
    proj: &Projections,
    dm: f64,
    km: f64,
    target: OrientationTarget,
) -> OrientationRollout {
    rollout_forcing(&forcing_at(proj, dm, km), dm, km, target)
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

/// Integrates the orientation DMP with a forcing term on the grid (the
/// kernel's steps: [`crate::orientation_kernel`]).
pub fn rollout_forcing(
    forcing: &[[f64; 3]],
    dm: f64,
    km: f64,
    target: OrientationTarget,
) -> OrientationRollout {
    use crate::kernels::orientation::{KeepPath, Lanes, Observe as _, Start};
    let n = forcing.len();
    let dt = 1.0 / (n.max(2) - 1) as f64;
    let mut lanes = Lanes::<1>::new(Start::new(target.start, target.w0, target.goal));
    let mut keep = KeepPath::new(target.start, target.goal, n);
    for (k, f) in forcing.iter().enumerate() {
        keep.before(k, &lanes);
        // -0.0, not 0.0: `v + D (-0) + K (-0)` is `v` to the bit, a `-0`
        // included, as the kernel's `F0 + D F1 + K F2` with the same sum.
        let parts = f.map(|v| [v, -0.0, -0.0]);
        let a = lanes.step(&parts, dm, &[wide::f64x4::splat(km)], dt);
        keep.after(&a);
    }
    keep.into_path()
}

/// A demo's orientation DMP at one gain pair, to run at a new start and
/// goal orientation (method.md section 12: the forcing term unchanged).
#[derive(Clone, Debug, PartialEq)]
pub struct OrientationPrimitive {
    /// The forcing term on the grid.
    pub forcing: Vec<[f64; 3]>,
    /// LWR weights per axis at the primitive's gains.
    pub weights: [Vec<f64>; 3],
    /// The gains `(D/M, K/M)` it runs at: the position's, or the model's
    /// separate orientation gains ([`crate::fit::settings::DmpSettings::orientation_gains`]).
    pub gains: (f64, f64),
    /// Its own start orientation (the smoothed `q(0)`).
    pub start: Q,
    /// Its own initial angular velocity, unit time.
    pub w0: [f64; 3],
    /// Its own goal orientation.
    pub goal: Q,
}

impl OrientationPrimitive {
    /// Demo `i`'s orientation DMP at the position gains `(dm, km)` (the
    /// orientation's own where the model has them); `None` without one.
    pub fn of_demo(model: &crate::Model, i: usize, dm: f64, km: f64) -> Option<Self> {
        let prepared = model.demos().get(i)?.orientation.as_ref()?;
        let proj = model.orientation_projections(i)?;
        let (dm, km) = model.orientation_gains(dm, km);
        Some(Self {
            forcing: forcing_at(proj, dm, km),
            weights: std::array::from_fn(|ax| proj.weights_at(ax, dm, km)),
            gains: (dm, km),
            start: prepared.q[0],
            w0: prepared.w[0],
            goal: prepared.goal,
        })
    }

    /// The start and goal a run from `start` to `goal` (its own where
    /// `None`) takes. A quaternion and its negative are one orientation, so
    /// a new one is taken with the sign that keeps the rotation the demo
    /// makes: a new start in its own start's hemisphere, a new goal in the
    /// start's (the shorter way round). The demo's own goal keeps its sign:
    /// a demo may turn further than 180 degrees.
    pub fn ends(&self, start: Option<Q>, goal: Option<Q>) -> (Q, Q) {
        let towards = |q: Q, other: Q| {
            if rotation::dot(q, other) < 0.0 {
                q.map(|c| -c)
            } else {
                q
            }
        };
        let start = start.map_or(self.start, |s| towards(s, self.start));
        let goal = goal.map_or(self.goal, |g| towards(g, start));
        (start, goal)
    }

    /// Runs it at its gains from `start` to `goal` (its own where `None`;
    /// signs as [`OrientationPrimitive::ends`] takes them).
    pub fn rollout(&self, start: Option<Q>, goal: Option<Q>) -> OrientationRollout {
        let (start, goal) = self.ends(start, goal);
        let target = OrientationTarget {
            start,
            w0: self.w0,
            goal,
        };
        rollout_forcing(&self.forcing, self.gains.0, self.gains.1, target)
    }
}

/// `d_rot`: the angle between a path and a target, integrated over unit
/// time (trapezoid), radians.
pub fn error(path: &[Q], target: &[Q]) -> f64 {
    let n = path.len().min(target.len());
    let angles = path
        .iter()
        .zip(target)
        .map(|(&a, &b)| rotation::angle(a, b));
    trapezoid(angles, n) / (n.max(2) - 1) as f64
}
