//! The planted demos' orientation (method.md section 12): one orientation
//! forcing term, fitted at the planted gains to a nominal minimum-jerk turn,
//! run from each demo's start orientation towards its own goal orientation
//! (the nominal turn stretched 0.5 to 1.5 times and its axis turned up to
//! 0.8 rad about the vertical) with the orientation DMP, integrated with
//! the positions' substeps. Deterministic from the spec's seed, on a
//! generator of its own so the positions do not change.

use crate::rng::Rng;
use crate::rotation;
use crate::rotation::QuatXyzw;
use crate::synth::planted_forcing::{Forcing, GRID, PlantedSpec, SUBSTEPS, forcing_towards, turn};

/// The nominal turn as a rotation vector (radians times the axis).
const NOMINAL_TURN: [f64; 3] = [0.25, 0.45, 0.75];

/// Where every demo's orientation starts before its own small offset.
const START: [f64; 3] = [0.1, -0.2, 0.3];

/// The generator of the demos' orientation paths.
pub(crate) struct Turns {
    rng: Rng,
    forcing: Forcing,
    dm: f64,
    km: f64,
}

impl Turns {
    /// The generator for `spec`.
    pub(crate) fn new(spec: &PlantedSpec) -> Self {
        Self {
            rng: Rng::new(spec.seed ^ 0x6f72_6965_6e74),
            forcing: forcing_towards(spec.dm, spec.km, NOMINAL_TURN),
            dm: spec.dm,
            km: spec.km,
        }
    }

    /// The next demo's orientation path on the fine unit-time grid.
    pub(crate) fn next_path(&mut self) -> Vec<QuatXyzw> {
        let stretch = self.rng.range(0.5, 1.5);
        let angle = self.rng.range(-0.8, 0.8);
        let offset: [f64; 3] = std::array::from_fn(|_| 0.05 * self.rng.normal());
        let start = rotation::exp(std::array::from_fn(|i| 0.5 * (START[i] + offset[i])));
        let turn_vector = turn(NOMINAL_TURN.map(|v| v * stretch), angle);
        let goal = rotation::mul(rotation::exp(turn_vector.map(|v| 0.5 * v)), start);
        integrate(&self.forcing, self.dm, self.km, start, goal)
    }
}

/// The orientation DMP from rest at `start` towards `goal` on the fine grid.
fn integrate(f: &Forcing, dm: f64, km: f64, start: QuatXyzw, goal: QuatXyzw) -> Vec<QuatXyzw> {
    let steps = (GRID - 1) * SUBSTEPS;
    let dt = 1.0 / steps as f64;
    let alpha = crate::fit::settings::DmpSettings::default().alpha_x;
    let (mut q, mut w) = (start, [0.0; 3]);
    let mut path = Vec::with_capacity(steps + 1);
    path.push(q);
    for k in 0..steps {
        let x = (-alpha * k as f64 * dt).exp();
        let fx = f.at(x);
        let r = rotation::rotation_vector(goal, q);
        for ax in 0..3 {
            w[ax] += (-dm * w[ax] + km * r[ax] + fx[ax]) * dt;
        }
        q = rotation::normalised(rotation::mul(rotation::exp(w.map(|v| 0.5 * v * dt)), q));
        path.push(q);
    }
    path
}

/// Slerp of a fine path at unit time `s` in [0, 1].
pub(crate) fn sample(path: &[QuatXyzw], s: f64) -> QuatXyzw {
    let last = path.len() - 1;
    let pos = s.clamp(0.0, 1.0) * last as f64;
    let i = (pos.floor() as usize).min(last.saturating_sub(1));
    rotation::slerp(path[i], path[(i + 1).min(last)], pos - i as f64)
}
