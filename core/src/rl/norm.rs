//! Running normalisation (Stable-Baselines3's `VecNormalize`): the running
//! mean and variance of every observation component, and of the discounted
//! return, whose deviation rewards are divided by. The observation
//! statistics belong to the policy: a policy is only meaningful with the
//! normaliser it was trained with, so [`crate::rl::policy::Policy`] carries them.

use serde::{Deserialize, Serialize};

/// Normalised values are clipped to +-this.
pub const CLIP: f64 = 10.0;
const EPS: f64 = 1e-8;

/// Running mean and (population) variance per component, started as
/// Stable-Baselines3 does: mean 0, variance 1, a weight of 1e-4.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunningStat {
    /// The running mean.
    pub mean: Vec<f64>,
    /// The running variance.
    pub var: Vec<f64>,
    /// The weight of what was seen.
    pub count: f64,
}

impl RunningStat {
    /// Statistics for `dim` components.
    pub fn new(dim: usize) -> Self {
        Self {
            mean: vec![0.0; dim],
            var: vec![1.0; dim],
            count: 1e-4,
        }
    }

    /// Takes one more sample into account (Chan et al.'s parallel update
    /// with a batch of one).
    pub fn update(&mut self, x: &[f64]) {
        let total = self.count + 1.0;
        for ((m, v), &x) in self.mean.iter_mut().zip(&mut self.var).zip(x) {
            let delta = x - *m;
            *m += delta / total;
            *v = (*v * self.count + delta * delta * self.count / total) / total;
        }
        self.count = total;
    }

    /// `x` standardised by the statistics, clipped to +-[`CLIP`].
    pub fn normalise(&self, x: &[f64]) -> Vec<f64> {
        x.iter()
            .zip(self.mean.iter().zip(&self.var))
            .map(|(x, (m, v))| ((x - m) / (v + EPS).sqrt()).clamp(-CLIP, CLIP))
            .collect()
    }
}

/// Reward scaling by the running deviation of the discounted return.
#[derive(Clone, Debug, PartialEq)]
pub struct ReturnScale {
    stat: RunningStat,
    ret: f64,
    gamma: f64,
}

impl ReturnScale {
    /// A scaler for discount `gamma`.
    pub fn new(gamma: f64) -> Self {
        Self {
            stat: RunningStat::new(1),
            ret: 0.0,
            gamma,
        }
    }

    /// The scaled reward of one decision (`done` ends the episode's return).
    pub fn scale(&mut self, reward: f64, done: bool) -> f64 {
        self.ret = self.ret * self.gamma + reward;
        self.stat.update(&[self.ret]);
        if done {
            self.ret = 0.0;
        }
        (reward / (self.stat.var[0] + EPS).sqrt()).clamp(-CLIP, CLIP)
    }
}
