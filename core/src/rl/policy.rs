//! The trained policy as a robot would run it: the actor network, its
//! log standard deviations and the observation normaliser it was trained
//! with (without which the network's inputs mean nothing). Serialisable, so
//! `dmpscope rl --save-policy` writes it whole.

use serde::{Deserialize, Serialize};

use crate::rl::mlp::Mlp;
use crate::rl::norm::RunningStat;
use crate::rl::task::Task;
use crate::{Error, Result};

/// A Gaussian policy: `u ~ N(actor(normalise(obs)), exp(log_std)^2)`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Policy {
    /// The mean's network.
    pub actor: Mlp,
    /// Log standard deviation per action component.
    pub log_std: Vec<f64>,
    /// The observation normaliser (frozen outside training).
    pub obs_norm: RunningStat,
}

/// One deterministic episode of a policy's mean.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Episode {
    /// Its return.
    pub ret: f64,
    /// The task's distance to the goal at the end.
    pub final_error: f64,
}

impl Policy {
    /// The policy's mean action for a raw observation.
    pub fn mean(&self, obs: &[f64]) -> Vec<f64> {
        self.actor.forward(&self.obs_norm.normalise(obs)).0
    }

    /// Runs the mean once on `task` from its start. A non-finite action
    /// ends the run with an error.
    pub fn run<T: Task>(&self, task: &mut T) -> Result<Episode> {
        let mut obs = task.reset();
        let mut ret = 0.0;
        for k in 0.. {
            let u = self.mean(&obs);
            if u.iter().any(|v| !v.is_finite()) {
                return Err(Error::Training(format!(
                    "the policy's action at decision {} is not finite",
                    k + 1
                )));
            }
            let step = task.act(&u);
            ret += step.reward;
            obs = task.observe();
            if step.done {
                break;
            }
        }
        Ok(Episode {
            ret,
            final_error: task.goal_error(),
        })
    }
}
