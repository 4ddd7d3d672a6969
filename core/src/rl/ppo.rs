//! PPO (Schulman et al. 2017) for the [`DmpEnv`]: a Gaussian policy whose
//! mean is an actor MLP (hidden 64, 64, tanh) and whose log standard
//! deviation is a learned vector, a critic MLP of the same shape, GAE, the
//! clipped surrogate objective, Adam. Everything is seeded: the same seed on
//! the same machine gives the same numbers. One [`Trainer::iterate`]
//! collects a batch of episodes and updates; the app calls it from a thread
//! natively and in slices in the browser.

use super::env::{ACT, DmpEnv, OBS};
use super::mlp::{Adam, Mlp};
use crate::synth::Rng;

/// PPO's settings (the defaults are what the note of issue 6 reports).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PpoConfig {
    /// Episodes collected per iteration.
    pub episodes: usize,
    /// Passes over the batch per iteration.
    pub epochs: usize,
    /// Samples per gradient step.
    pub minibatch: usize,
    /// Discount.
    pub gamma: f64,
    /// GAE's lambda.
    pub lambda: f64,
    /// The ratio clip.
    pub clip: f64,
    /// Adam's step size.
    pub lr: f64,
    /// The initial log standard deviation of the policy.
    pub init_log_std: f64,
}

impl Default for PpoConfig {
    fn default() -> Self {
        Self {
            episodes: 4,
            epochs: 8,
            minibatch: 100,
            gamma: 0.99,
            lambda: 0.95,
            clip: 0.2,
            lr: 1e-3,
            init_log_std: -1.0,
        }
    }
}

/// Decisions a training run takes unless told otherwise (the CLI's
/// `--steps`, the app's RL panel).
pub const DEFAULT_DECISIONS: usize = 100_000;

/// Hidden layer sizes of the actor and the critic.
pub const HIDDEN: [usize; 2] = [64, 64];

/// One iteration's summary.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IterStats {
    /// Mean undiscounted return of the iteration's episodes.
    pub mean_return: f64,
    /// Mean distance to the goal at the episodes' ends, metres.
    pub mean_final_error: f64,
    /// Decisions taken so far in training.
    pub decisions: usize,
}

/// A deterministic run of the policy's mean.
#[derive(Clone, Debug, PartialEq)]
pub struct GreedyRun {
    /// Positions on the demo's grid (start included), demo coordinates.
    pub path: Vec<[f64; 3]>,
    /// |y''| of every integration step.
    pub accel: Vec<f64>,
    /// Distance to the goal at the end, metres.
    pub final_error: f64,
    /// The episode's return.
    pub ret: f64,
}

impl GreedyRun {
    /// The peak acceleration, m/s^2 in unit time.
    pub fn a_peak(&self) -> f64 {
        self.accel.iter().fold(0.0, |a, &b| a.max(b))
    }
}

/// Transitions of a batch (the policy's raw outputs as actions).
#[derive(Clone, Debug, Default)]
pub struct Batch {
    /// Observations.
    pub obs: Vec<[f64; OBS]>,
    /// Actions (policy outputs, before scaling to forcing terms).
    pub act: Vec<[f64; ACT]>,
    /// Log-probabilities under the policy that acted.
    pub logp: Vec<f64>,
    /// Advantages (normalised).
    pub adv: Vec<f64>,
    /// Returns (value targets).
    pub ret: Vec<f64>,
}

/// The Gaussian log-density of `a` under mean `mu` and log-sd `log_std`.
pub fn log_prob(a: &[f64; ACT], mu: &[f64], log_std: &[f64; ACT]) -> f64 {
    (0..ACT)
        .map(|j| {
            let z = (a[j] - mu[j]) / log_std[j].exp();
            -0.5 * z * z - log_std[j] - 0.5 * (2.0 * std::f64::consts::PI).ln()
        })
        .sum()
}

/// The clipped surrogate loss over samples `idx` of `batch` (mean) and its
/// gradient: actor parameters then the three log-sds.
pub fn actor_loss_grad(
    actor: &Mlp,
    log_std: &[f64; ACT],
    batch: &Batch,
    idx: &[usize],
    clip: f64,
) -> (f64, Vec<f64>) {
    let mut grad = vec![0.0; actor.params.len() + ACT];
    let mut loss = 0.0;
    let scale = 1.0 / idx.len().max(1) as f64;
    for &i in idx {
        let (mu, trace) = actor.forward(&batch.obs[i]);
        let a = &batch.act[i];
        let ratio = (log_prob(a, &mu, log_std) - batch.logp[i]).exp();
        let adv = batch.adv[i];
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
        let mut d_mu = vec![0.0; ACT];
        for j in 0..ACT {
            let var = (2.0 * log_std[j]).exp();
            let diff = a[j] - mu[j];
            d_mu[j] = d_logp * diff / var;
            grad[actor.params.len() + j] += d_logp * (diff * diff / var - 1.0);
        }
        actor.backward(&trace, &d_mu, &mut grad[..actor.params.len()]);
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

/// A PPO agent learning in one environment.
pub struct Trainer {
    env: DmpEnv,
    config: PpoConfig,
    actor: Mlp,
    critic: Mlp,
    log_std: [f64; ACT],
    actor_opt: Adam,
    critic_opt: Adam,
    rng: Rng,
    decisions: usize,
    pending: Option<Pending>,
    /// Mean return of every iteration so far (the learning curve).
    pub returns: Vec<f64>,
}

/// An iteration under way.
#[derive(Default)]
struct Pending {
    batch: Batch,
    episodes: usize,
    sum_ret: f64,
    sum_err: f64,
    order: Vec<usize>,
    update: usize,
}

/// Runs one exploring episode into `batch` (GAE advantages, not yet
/// normalised); returns its return and final distance to the goal.
fn collect_episode(
    env: &mut DmpEnv,
    actor: &Mlp,
    critic: &Mlp,
    log_std: &[f64; ACT],
    rng: &mut Rng,
    c: PpoConfig,
    batch: &mut Batch,
) -> (f64, f64) {
    let mut obs = env.reset();
    let (mut rewards, mut values, mut ret) = (Vec::new(), Vec::new(), 0.0);
    loop {
        let (mu, _) = actor.forward(&obs);
        let act: [f64; ACT] = std::array::from_fn(|j| mu[j] + log_std[j].exp() * rng.normal());
        batch.obs.push(obs);
        batch.act.push(act);
        batch.logp.push(log_prob(&act, &mu, log_std));
        values.push(critic.forward(&obs).0[0]);
        let step = env.step(&act, None, None);
        rewards.push(step.reward);
        ret += step.reward;
        obs = env.observe();
        if step.done {
            break;
        }
    }
    // GAE over the episode (the last decision is terminal).
    let mut adv = vec![0.0; rewards.len()];
    let mut next = (0.0, 0.0); // (advantage, value) after t
    for t in (0..rewards.len()).rev() {
        let delta = rewards[t] + c.gamma * next.1 - values[t];
        adv[t] = delta + c.gamma * c.lambda * next.0;
        next = (adv[t], values[t]);
    }
    batch
        .ret
        .extend(adv.iter().zip(&values).map(|(a, v)| a + v));
    batch.adv.extend(adv);
    (ret, env.goal_error())
}

/// Advantages to zero mean and unit deviation.
fn normalise(adv: &mut [f64]) {
    let n = adv.len().max(1) as f64;
    let mean = adv.iter().sum::<f64>() / n;
    let sd = (adv.iter().map(|a| (a - mean).powi(2)).sum::<f64>() / n).sqrt();
    adv.iter_mut().for_each(|a| *a = (*a - mean) / (sd + 1e-8));
}

impl Trainer {
    /// A fresh agent for `env`, everything drawn from `seed`.
    pub fn new(env: DmpEnv, config: PpoConfig, seed: u64) -> Self {
        let mut rng = Rng::new(seed);
        let sizes = |out| [OBS, HIDDEN[0], HIDDEN[1], out];
        let actor = Mlp::new(&sizes(ACT), &mut rng, 0.01);
        let critic = Mlp::new(&sizes(1), &mut rng, 1.0);
        Self {
            env,
            config,
            actor_opt: Adam::new(actor.params.len() + ACT, config.lr),
            critic_opt: Adam::new(critic.params.len(), config.lr),
            actor,
            critic,
            log_std: [config.init_log_std; ACT],
            rng,
            decisions: 0,
            pending: None,
            returns: Vec::new(),
        }
    }

    /// Decisions taken in training so far.
    pub fn decisions(&self) -> usize {
        self.decisions
    }

    /// The environment.
    pub fn env(&self) -> &DmpEnv {
        &self.env
    }

    /// Collects `config.episodes` episodes, then updates actor and critic
    /// (all the [`Self::step`]s of one iteration).
    pub fn iterate(&mut self) -> IterStats {
        loop {
            if let Some(stats) = self.step() {
                return stats;
            }
        }
    }

    /// A small piece of an iteration (one episode, or one minibatch update
    /// of both networks: a few milliseconds), so a browser can train between
    /// frames; returns the iteration's summary when it completes. A run of
    /// `step`s gives exactly the numbers of the same run of `iterate`s.
    pub fn step(&mut self) -> Option<IterStats> {
        let c = self.config;
        let pending = self.pending.get_or_insert_with(Pending::default);
        if pending.episodes < c.episodes {
            let (ret, err) = collect_episode(
                &mut self.env,
                &self.actor,
                &self.critic,
                &self.log_std,
                &mut self.rng,
                c,
                &mut pending.batch,
            );
            pending.episodes += 1;
            pending.sum_ret += ret;
            pending.sum_err += err;
            self.decisions += super::env::DECISIONS;
            if pending.episodes == c.episodes {
                normalise(&mut pending.batch.adv);
                pending.order = (0..pending.batch.adv.len()).collect();
            }
            return None;
        }
        let mb = c.minibatch.max(1);
        let per_epoch = pending.order.len().div_ceil(mb);
        if pending.update < c.epochs * per_epoch {
            let chunk = pending.update % per_epoch;
            if chunk == 0 {
                for i in (1..pending.order.len()).rev() {
                    let j = (self.rng.next_u64() % (i as u64 + 1)) as usize;
                    pending.order.swap(i, j);
                }
            }
            let end = ((chunk + 1) * mb).min(pending.order.len());
            let idx = &pending.order[chunk * mb..end];
            let (_, g) = actor_loss_grad(&self.actor, &self.log_std, &pending.batch, idx, c.clip);
            let mut params = std::mem::take(&mut self.actor.params);
            params.extend_from_slice(&self.log_std);
            self.actor_opt.step(&mut params, &g);
            let split = params.len() - ACT;
            for (j, v) in params[split..].iter().enumerate() {
                self.log_std[j] = v.clamp(-5.0, 1.0);
            }
            params.truncate(split);
            self.actor.params = params;
            let (_, g) = critic_loss_grad(&self.critic, &pending.batch, idx);
            self.critic_opt.step(&mut self.critic.params, &g);
            pending.update += 1;
            if pending.update < c.epochs * per_epoch {
                return None;
            }
        }
        let stats = IterStats {
            mean_return: pending.sum_ret / c.episodes as f64,
            mean_final_error: pending.sum_err / c.episodes as f64,
            decisions: self.decisions,
        };
        self.pending = None;
        self.returns.push(stats.mean_return);
        Some(stats)
    }

    /// Runs the policy's mean once (no exploration).
    pub fn greedy(&self) -> GreedyRun {
        let mut env = self.env.clone();
        let mut obs = env.reset();
        let mut path = vec![env.start()];
        let mut accel = Vec::new();
        let mut ret = 0.0;
        loop {
            let (mu, _) = self.actor.forward(&obs);
            let u: [f64; ACT] = std::array::from_fn(|j| mu[j]);
            let step = env.step(&u, Some(&mut path), Some(&mut accel));
            ret += step.reward;
            obs = env.observe();
            if step.done {
                break;
            }
        }
        GreedyRun {
            path,
            accel,
            final_error: env.goal_error(),
            ret,
        }
    }
}
