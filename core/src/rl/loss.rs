//! PPO's losses and their gradients (hand-derived, checked against finite
//! differences in `core/tests/rl.rs`): the clipped surrogate of the
//! Gaussian policy with advantages standardised per minibatch and an
//! optional entropy bonus, and the critic's squared error.

use crate::rl::math;
use crate::rl::mlp::Mlp;

/// Transitions of a batch (the policy's raw outputs as actions).
#[derive(Clone, Debug, Default)]
pub struct Batch {
    /// Observations, normalised as the policy saw them.
    pub obs: Vec<Vec<f64>>,
    /// Actions (policy outputs, before scaling to forcing terms).
    pub act: Vec<Vec<f64>>,
    /// Log-probabilities under the policy that acted.
    pub logp: Vec<f64>,
    /// Advantages (GAE, as computed; standardised per minibatch in the loss).
    pub adv: Vec<f64>,
    /// Returns (value targets).
    pub ret: Vec<f64>,
}

/// The Gaussian log-density of `a` under mean `mu` and log-sd `log_std`.
pub fn log_prob(a: &[f64], mu: &[f64], log_std: &[f64]) -> f64 {
    a.iter()
        .zip(mu)
        .zip(log_std)
        .map(|((a, mu), ls)| {
            let z = (a - mu) / math::exp(*ls);
            -0.5 * z * z - ls - 0.5 * math::ln(2.0 * std::f64::consts::PI)
        })
        .sum()
}

/// The entropy of the Gaussian policy with log-sds `log_std`.
pub fn entropy(log_std: &[f64]) -> f64 {
    let per = 0.5 * (1.0 + math::ln(2.0 * std::f64::consts::PI));
    log_std.iter().map(|ls| ls + per).sum()
}

/// The advantages of samples `idx` standardised to zero mean and unit
/// deviation (left as they are for a single sample).
pub fn standardised(adv: &[f64], idx: &[usize]) -> Vec<f64> {
    let n = idx.len() as f64;
    let raw: Vec<f64> = idx.iter().map(|&i| adv[i]).collect();
    if idx.len() < 2 {
        return raw;
    }
    let mean = raw.iter().sum::<f64>() / n;
    let sd = (raw.iter().map(|a| (a - mean) * (a - mean)).sum::<f64>() / (n - 1.0)).sqrt();
    raw.iter().map(|a| (a - mean) / (sd + 1e-8)).collect()
}

/// The clipped surrogate loss over samples `idx` of `batch` (mean, with
/// the minibatch's advantages standardised) minus `ent_coef` times the
/// entropy, and its gradient: actor parameters then the log-sds.
pub fn actor_loss_grad(
    actor: &Mlp,
    log_std: &[f64],
    batch: &Batch,
    idx: &[usize],
    clip: f64,
    ent_coef: f64,
) -> (f64, Vec<f64>) {
    let np = actor.params.len();
    let mut grad = vec![0.0; np + log_std.len()];
    let mut loss = -ent_coef * entropy(log_std);
    grad[np..].iter_mut().for_each(|g| *g = -ent_coef);
    let scale = 1.0 / idx.len().max(1) as f64;
    let advs = standardised(&batch.adv, idx);
    for (&i, &adv) in idx.iter().zip(&advs) {
        let (mu, trace) = actor.forward(&batch.obs[i]);
        let a = &batch.act[i];
        let ratio = math::exp(log_prob(a, &mu, log_std) - batch.logp[i]);
        let clipped = ratio.clamp(1.0 - clip, 1.0 + clip);
        loss -= scale * (ratio * adv).min(clipped * adv);
        // The gradient flows through the unclipped term when it is the min.
        let active = if adv >= 0.0 {
            ratio <= 1.0 + clip
        } else {
            ratio >= 1.0 - clip
        };
        if !active {
            continue;
        }
        let d_logp = -scale * ratio * adv;
        let mut d_mu = vec![0.0; mu.len()];
        for j in 0..mu.len() {
            let var = math::exp(2.0 * log_std[j]);
            let diff = a[j] - mu[j];
            d_mu[j] = d_logp * diff / var;
            grad[np + j] += d_logp * (diff * diff / var - 1.0);
        }
        actor.backward(&trace, &d_mu, &mut grad[..np]);
    }
    (loss, grad)
}

/// Half the mean squared error of the critic on samples `idx`, and its
/// gradient.
pub fn critic_loss_grad(critic: &Mlp, batch: &Batch, idx: &[usize]) -> (f64, Vec<f64>) {
    let mut grad = vec![0.0; critic.params.len()];
    let mut loss = 0.0;
    let scale = 1.0 / idx.len().max(1) as f64;
    for &i in idx {
        let (v, trace) = critic.forward(&batch.obs[i]);
        let err = v[0] - batch.ret[i];
        loss += 0.5 * scale * err * err;
        critic.backward(&trace, &[scale * err], &mut grad);
    }
    (loss, grad)
}
