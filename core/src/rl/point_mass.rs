//! The learner's sanity task: a 1-D unit point mass at rest at 0 driven to
//! 1 in one second by a piecewise-constant force, under a quadratic effort
//! cost. Its optimum is known in closed form, so a PPO that trains (the
//! same code that trains the DMP agent) must come close to it within a
//! fixed budget, and a broken one cannot.
//!
//! Dynamics, exact for a force `u` held over a decision of length `dt =
//! 1/N`: `x' = x + v dt + u dt^2 / 2`, `v' = v + u dt`. Reward of a decision
//! `-RHO u^2 dt`; after the last, `-W (x - 1)^2`. Observation: the phase
//! `k/N`, `x - 1`, `v`.
//!
//! The end position is linear in the forces, `x_N = b . u` with `b_k =
//! dt^2 (N - k - 1/2)`, so the least cost is `W RHO dt / (RHO dt + W b.b)`,
//! at `u = b W / (RHO dt + W b.b)` ([`PointMass::optimal_cost`]).

use crate::rl::task::{Step, Task};

/// Effort weight.
pub const RHO: f64 = 1.0;
/// Terminal weight.
pub const W: f64 = 10.0;

/// The point-mass task with `n` decisions.
#[derive(Clone, Debug)]
pub struct PointMass {
    n: usize,
    k: usize,
    x: f64,
    v: f64,
}

impl PointMass {
    /// The task with `n` decisions per episode (at least 1).
    pub fn new(n: usize) -> Self {
        Self {
            n: n.max(1),
            k: 0,
            x: 0.0,
            v: 0.0,
        }
    }

    fn dt(&self) -> f64 {
        1.0 / self.n as f64
    }

    /// The least total cost (minus the best return) and the forces that
    /// give it.
    pub fn optimal_cost(&self) -> (f64, Vec<f64>) {
        let dt = self.dt();
        let b: Vec<f64> = (0..self.n)
            .map(|k| dt * dt * (self.n as f64 - k as f64 - 0.5))
            .collect();
        let bb: f64 = b.iter().map(|v| v * v).sum();
        let c = W / (RHO * dt + W * bb);
        (
            W * RHO * dt / (RHO * dt + W * bb),
            b.iter().map(|v| c * v).collect(),
        )
    }
}

impl Task for PointMass {
    fn obs_dim(&self) -> usize {
        3
    }

    fn act_dim(&self) -> usize {
        1
    }

    fn decisions(&self) -> usize {
        self.n
    }

    fn reset(&mut self) -> Vec<f64> {
        (self.k, self.x, self.v) = (0, 0.0, 0.0);
        self.observe()
    }

    fn observe(&self) -> Vec<f64> {
        vec![self.k as f64 / self.n as f64, self.x - 1.0, self.v]
    }

    fn act(&mut self, u: &[f64]) -> Step {
        let u = u.first().copied().unwrap_or(0.0);
        let dt = self.dt();
        self.x += self.v * dt + 0.5 * u * dt * dt;
        self.v += u * dt;
        self.k += 1;
        let done = self.k >= self.n;
        let mut reward = -RHO * u * u * dt;
        if done {
            reward -= W * (self.x - 1.0) * (self.x - 1.0);
        }
        Step { reward, done }
    }

    fn goal_error(&self) -> f64 {
        (self.x - 1.0).abs()
    }

    fn action_size(&self) -> Vec<f64> {
        vec![1.0]
    }
}
