//! The RL environment of method.md section 8: one demo's DMP (start, goal,
//! unit duration) with gains (D/M, K/M) whose forcing term is the agent's
//! action, integrated exactly as the LfD regeneration (section 4,
//! semi-implicit Euler on the demo's unit-time grid).
//!
//! Choices the method leaves open, fixed here:
//! - **Control step**: the episode's `n - 1` integration steps (1000 on the
//!   1001-point grid) are split into [`DECISIONS`] decisions; each action is
//!   held over the steps of its decision (10 on the default grid).
//! - **Action**: one value per axis, `A = scale * u` with `u` the policy's
//!   output and `scale = ACTION_SCALE * max(|g - y0|, 5 cm)` per axis, so
//!   one unit of policy output is a forcing term of the motion's size.
//! - **Observation** (7 values): the phase `s` in 0..1, then per axis
//!   `(y - g) / r` and `y' / r` with `r = max(|g - y0|_2, 5 cm)`.
//! - **Rewards**, exactly the paper's: at every integration step
//!   `-1e-3 |y''| - 1e-7 |A|` (Euclidean norms over the three axes, `y''`
//!   the step's acceleration in unit time, m/s^2), summed over the steps of
//!   a decision; after the last step `-10 |y - g|` (m), `g` the demo's goal.

use crate::{Error, PreparedDemo, Result};

/// Decisions per episode.
pub const DECISIONS: usize = 100;
/// Policy output to forcing term, per metre of motion (m/s^2 per m).
pub const ACTION_SCALE: f64 = 20.0;
/// Size of an observation.
pub const OBS: usize = 7;
/// Size of an action.
pub const ACT: usize = 3;

/// The environment for one demo and one gain pair.
#[derive(Clone, Debug)]
pub struct DmpEnv {
    /// D/M.
    pub dm: f64,
    /// K/M.
    pub km: f64,
    y0: [f64; 3],
    v0: [f64; 3],
    goal: [f64; 3],
    steps: usize,
    scale: [f64; 3],
    norm: f64,
    // State.
    y: [f64; 3],
    v: [f64; 3],
    k: usize,
}

/// What one decision gave.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Step {
    /// The reward of the decision (the terminal reward included on the last).
    pub reward: f64,
    /// Whether the episode ended.
    pub done: bool,
}

impl DmpEnv {
    /// The environment of `demo` at gains (`dm`, `km`).
    pub fn new(demo: &PreparedDemo, dm: f64, km: f64) -> Result<Self> {
        let n = demo.len();
        if n < DECISIONS + 1 || !(dm.is_finite() && km.is_finite()) {
            return Err(Error::InvalidSetting(format!(
                "RL needs a demo of at least {} grid points and finite gains (got {n}, D/M {dm}, K/M {km})",
                DECISIONS + 1
            )));
        }
        let y0 = demo.y_raw[0];
        let goal = demo.goal;
        let delta: [f64; 3] = std::array::from_fn(|a| goal[a] - y0[a]);
        let norm = delta.iter().map(|d| d * d).sum::<f64>().sqrt().max(0.05);
        let mut env = Self {
            dm,
            km,
            y0,
            v0: demo.yd[0],
            goal,
            steps: n - 1,
            scale: delta.map(|d| ACTION_SCALE * d.abs().max(0.05)),
            norm,
            y: y0,
            v: demo.yd[0],
            k: 0,
        };
        env.reset();
        Ok(env)
    }

    /// Back to the start; returns the first observation.
    pub fn reset(&mut self) -> [f64; OBS] {
        self.y = self.y0;
        self.v = self.v0;
        self.k = 0;
        self.observe()
    }

    /// The current observation.
    pub fn observe(&self) -> [f64; OBS] {
        let s = self.k as f64 / self.steps as f64;
        let mut o = [s, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
        for a in 0..3 {
            o[1 + a] = (self.y[a] - self.goal[a]) / self.norm;
            o[4 + a] = self.v[a] / self.norm;
        }
        o
    }

    /// The position now.
    pub fn position(&self) -> [f64; 3] {
        self.y
    }

    /// The distance to the goal now, metres.
    pub fn goal_error(&self) -> f64 {
        norm3(std::array::from_fn(|a| self.y[a] - self.goal[a]))
    }

    /// The forcing term for a policy output `u`.
    pub fn forcing(&self, u: &[f64; ACT]) -> [f64; 3] {
        std::array::from_fn(|a| self.scale[a] * u[a])
    }

    /// Applies policy output `u` for one decision; `path` and `accel`, when
    /// given, receive the positions after and accelerations of each step.
    pub fn step(
        &mut self,
        u: &[f64; ACT],
        mut path: Option<&mut Vec<[f64; 3]>>,
        mut accel: Option<&mut Vec<f64>>,
    ) -> Step {
        let f = self.forcing(u);
        let f_norm = norm3(f);
        let dt = 1.0 / self.steps as f64;
        let end = ((self.k / self.hold() + 1) * self.hold()).min(self.steps);
        let mut reward = 0.0;
        while self.k < end {
            let acc: [f64; 3] = std::array::from_fn(|a| {
                -self.dm * self.v[a] - self.km * (self.y[a] - self.goal[a]) + f[a]
            });
            for a in 0..3 {
                self.v[a] += acc[a] * dt;
                self.y[a] += self.v[a] * dt;
            }
            let a_norm = norm3(acc);
            reward += -1e-3 * a_norm - 1e-7 * f_norm;
            if let Some(p) = path.as_deref_mut() {
                p.push(self.y);
            }
            if let Some(acc_out) = accel.as_deref_mut() {
                acc_out.push(a_norm);
            }
            self.k += 1;
        }
        let done = self.k >= self.steps;
        if done {
            reward += -10.0 * self.goal_error();
        }
        Step { reward, done }
    }

    /// Integration steps per decision.
    fn hold(&self) -> usize {
        self.steps.div_ceil(DECISIONS)
    }

    /// The start.
    pub fn start(&self) -> [f64; 3] {
        self.y0
    }
}

fn norm3(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}
