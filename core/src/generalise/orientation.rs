//! A demo's orientation DMP run at a new start and goal orientation
//! (method.md section 12: the forcing term unchanged).

use crate::fit::orientation::{OrientationRollout, OrientationTarget, forcing_at};
use crate::kernels::orientation_run::rollout_forcing;
use crate::landscape::model::Model;
use crate::rotation;
use crate::rotation::QuatXyzw;

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
    pub start: QuatXyzw,
    /// Its own initial angular velocity, unit time.
    pub w0: [f64; 3],
    /// Its own goal orientation.
    pub goal: QuatXyzw,
}

impl OrientationPrimitive {
    /// Demo `i`'s orientation DMP at the position gains `(dm, km)` (the
    /// orientation's own where the model has them); `None` without one.
    pub fn of_demo(model: &Model, i: usize, dm: f64, km: f64) -> Option<Self> {
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
    pub fn ends(&self, start: Option<QuatXyzw>, goal: Option<QuatXyzw>) -> (QuatXyzw, QuatXyzw) {
        let towards = |q: QuatXyzw, other: QuatXyzw| {
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
    pub fn rollout(&self, start: Option<QuatXyzw>, goal: Option<QuatXyzw>) -> OrientationRollout {
        let (start, goal) = self.ends(start, goal);
        let target = OrientationTarget {
            start,
            w0: self.w0,
            goal,
        };
        rollout_forcing(&self.forcing, self.gains.0, self.gains.1, target)
    }
}
