//! PPO (Schulman et al. 2017) for any [`Task`]: a Gaussian policy whose mean
//! is an actor MLP (hidden 64, 64, tanh) and whose log standard deviation
//! is a learned vector, a critic MLP of the same shape, GAE, the clipped
//! surrogate objective, Adam; with the implementation details that make
//! PPO train reliably (Huang et al. 2022, Stable-Baselines3's defaults):
//! orthogonal initialisation with a small last policy layer, observation
//! and reward normalisation by running statistics, advantages standardised
//! per minibatch, gradient-norm clipping, a linearly annealed step size,
//! an initial policy deviation scaled to the task's own action size, and an
//! optional entropy bonus (method.md section 8 says which and why).
//!
//! Everything is seeded: the same seed on the same machine gives the same
//! numbers. One [`Trainer::iterate`] collects a batch of episodes and
//! updates; [`Trainer::step`] does a few milliseconds of it, so the app
//! trains on a thread natively and in slices in the browser.

use crate::rl::env::DmpEnv;
use crate::rl::loss::{Batch, actor_loss_grad, critic_loss_grad, log_prob};
use crate::rl::math;
use crate::rl::mlp::{Adam, Mlp, clip_grad_norm};
use crate::rl::norm::{ReturnScale, RunningStat};
use crate::rl::policy::Policy;
use crate::rl::task::Task;
use crate::rng::Rng;
use crate::{Error, Result};

/// PPO's settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PpoConfig {
    /// Episodes collected per iteration.
    pub episodes: usize,
    /// Passes over the batch per iteration.
    pub epochs: usize,
    /// Samples per gradient step.
    pub minibatch: usize,
    /// Discount per decision.
    pub gamma: f64,
    /// GAE's lambda per decision.
    pub lambda: f64,
    /// The ratio clip.
    pub clip: f64,
    /// Adam's initial step size.
    pub lr: f64,
    /// The step size falls linearly to 0 over this many decisions of
    /// training (0: constant).
    pub anneal_over: usize,
    /// Each network's gradient is scaled down to at most this norm.
    pub max_grad_norm: f64,
    /// Weight of the policy's entropy in the actor's loss.
    pub ent_coef: f64,
    /// The policy's initial standard deviation as a fraction of the task's
    /// action size ([`Task::action_size`]).
    pub init_sd: f64,
    /// Observations standardised by running statistics.
    pub norm_obs: bool,
    /// Rewards divided by the running deviation of the discounted return.
    pub norm_reward: bool,
}

/// Decisions per episode the default discounting is set for.
pub const REFERENCE_DECISIONS: usize = 100;

impl Default for PpoConfig {
    fn default() -> Self {
        Self {
            episodes: 4,
            epochs: 8,
            minibatch: 100,
            gamma: 0.999,
            lambda: 0.98,
            clip: 0.2,
            lr: 1e-3,
            anneal_over: DEFAULT_DECISIONS,
            max_grad_norm: 0.5,
            ent_coef: 0.0,
            init_sd: 0.5,
            norm_obs: true,
            norm_reward: true,
        }
    }
}

impl PpoConfig {
    /// The defaults for episodes of `decisions` decisions: gamma and lambda
    /// taken to the power `100 / decisions`, so that the discount over a
    /// unit of the episode's time is the default's whatever the control
    /// step; the step size anneals over `train` decisions.
    pub fn for_episode(decisions: usize, train: usize) -> Self {
        let d = Self::default();
        let p = REFERENCE_DECISIONS as f64 / decisions.max(1) as f64;
        Self {
            gamma: math::pow(d.gamma, p),
            lambda: math::pow(d.lambda, p),
            anneal_over: train,
            ..d
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
    /// Mean undiscounted return of the iteration's episodes (the task's
    /// own rewards, not the normalised ones).
    pub mean_return: f64,
    /// Mean distance to the goal at the episodes' ends.
    pub mean_final_error: f64,
    /// Decisions taken so far in training.
    pub decisions: usize,
}

/// A PPO agent learning on one task.
pub struct Trainer<T: Task = DmpEnv> {
    task: T,
    config: PpoConfig,
    policy: Policy,
    critic: Mlp,
    actor_opt: Adam,
    critic_opt: Adam,
    rng: Rng,
    reward_scale: ReturnScale,
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

impl<T: Task> Trainer<T> {
    /// A fresh agent for `task`, everything drawn from `seed`.
    pub fn new(task: T, config: PpoConfig, seed: u64) -> Self {
        let mut rng = Rng::new(seed);
        let (n_obs, n_act) = (task.obs_dim(), task.act_dim());
        let sizes = |out| [n_obs, HIDDEN[0], HIDDEN[1], out];
        let gain = std::f64::consts::SQRT_2;
        let actor = Mlp::orthogonal(&sizes(n_act), &mut rng, gain, 0.01);
        let critic = Mlp::orthogonal(&sizes(1), &mut rng, gain, 1.0);
        let log_std = task
            .action_size()
            .iter()
            .map(|s| math::ln((config.init_sd * s).max(1e-6)))
            .collect();
        Self {
            actor_opt: Adam::new(actor.params.len() + n_act, config.lr),
            critic_opt: Adam::new(critic.params.len(), config.lr),
            policy: Policy {
                actor,
                log_std,
                obs_norm: RunningStat::new(n_obs),
            },
            critic,
            reward_scale: ReturnScale::new(config.gamma),
            task,
            config,
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

    /// Whether an iteration is under way (collected or updating, not yet
    /// summarised).
    pub fn mid_iteration(&self) -> bool {
        self.pending.is_some()
    }

    /// The task.
    pub fn task(&self) -> &T {
        &self.task
    }

    /// The policy as trained so far.
    pub fn policy(&self) -> &Policy {
        &self.policy
    }

    /// The settings.
    pub fn config(&self) -> &PpoConfig {
        &self.config
    }

    /// Collects `config.episodes` episodes, then updates actor and critic
    /// (all the [`Self::step`]s of one iteration).
    pub fn iterate(&mut self) -> Result<IterStats> {
        loop {
            if let Some(stats) = self.step()? {
                return Ok(stats);
            }
        }
    }

    /// A small piece of an iteration (one episode, or one minibatch update
    /// of both networks: a few milliseconds), so a browser can train between
    /// frames; returns the iteration's summary when it completes. A run of
    /// `step`s gives exactly the numbers of the same run of `iterate`s. A
    /// non-finite action, reward or loss stops training with an error.
    pub fn step(&mut self) -> Result<Option<IterStats>> {
        let c = self.config;
        let mut pending = self.pending.take().unwrap_or_default();
        if pending.episodes < c.episodes {
            let (ret, err) = self.collect_episode(&mut pending.batch)?;
            pending.episodes += 1;
            pending.sum_ret += ret;
            pending.sum_err += err;
            self.decisions += self.task.decisions();
            if pending.episodes == c.episodes {
                pending.order = (0..pending.batch.adv.len()).collect();
                let lr = c.lr * self.lr_fraction(pending.order.len());
                self.actor_opt.lr = lr;
                self.critic_opt.lr = lr;
            }
            self.pending = Some(pending);
            return Ok(None);
        }
        let mb = c.minibatch.max(1);
        let per_epoch = pending.order.len().div_ceil(mb);
        if pending.update < c.epochs * per_epoch {
            self.update(&mut pending, per_epoch)?;
            if pending.update < c.epochs * per_epoch {
                self.pending = Some(pending);
                return Ok(None);
            }
        }
        let stats = IterStats {
            mean_return: pending.sum_ret / c.episodes as f64,
            mean_final_error: pending.sum_err / c.episodes as f64,
            decisions: self.decisions,
        };
        self.returns.push(stats.mean_return);
        Ok(Some(stats))
    }

    /// The step size's share left when the iteration whose batch holds
    /// `batch` decisions updates.
    fn lr_fraction(&self, batch: usize) -> f64 {
        let total = self.config.anneal_over;
        if total == 0 {
            return 1.0;
        }
        let before = self.decisions.saturating_sub(batch) as f64;
        (1.0 - before / total as f64).max(0.0)
    }

    /// One minibatch update of both networks.
    fn update(&mut self, pending: &mut Pending, per_epoch: usize) -> Result<()> {
        let c = self.config;
        let mb = c.minibatch.max(1);
        let chunk = pending.update % per_epoch;
        if chunk == 0 {
            for i in (1..pending.order.len()).rev() {
                let j = (self.rng.next_u64() % (i as u64 + 1)) as usize;
                pending.order.swap(i, j);
            }
        }
        let end = ((chunk + 1) * mb).min(pending.order.len());
        let idx = &pending.order[chunk * mb..end];
        let p = &mut self.policy;
        let (loss, mut g) = actor_loss_grad(
            &p.actor,
            &p.log_std,
            &pending.batch,
            idx,
            c.clip,
            c.ent_coef,
        );
        let (vloss, mut vg) = critic_loss_grad(&self.critic, &pending.batch, idx);
        if !(loss.is_finite() && vloss.is_finite()) {
            return Err(Error::Training(format!(
                "the loss is not finite after {} decisions of training",
                self.decisions
            )));
        }
        clip_grad_norm(&mut g, c.max_grad_norm);
        clip_grad_norm(&mut vg, c.max_grad_norm);
        let mut params = std::mem::take(&mut p.actor.params);
        params.extend_from_slice(&p.log_std);
        self.actor_opt.step(&mut params, &g);
        let split = params.len() - p.log_std.len();
        for (ls, v) in p.log_std.iter_mut().zip(&params[split..]) {
            *ls = v.clamp(-12.0, 2.0);
        }
        params.truncate(split);
        p.actor.params = params;
        self.critic_opt.step(&mut self.critic.params, &vg);
        pending.update += 1;
        Ok(())
    }

    /// Runs one exploring episode into `batch` (GAE advantages on the
    /// scaled rewards); returns its return and final distance to the goal.
    fn collect_episode(&mut self, batch: &mut Batch) -> Result<(f64, f64)> {
        let c = self.config;
        let mut raw = self.task.reset();
        let (mut rewards, mut values, mut ret) = (Vec::new(), Vec::new(), 0.0);
        loop {
            if c.norm_obs {
                self.policy.obs_norm.update(&raw);
            }
            let obs = self.policy.obs_norm.normalise(&raw);
            let p = &self.policy;
            let (mu, _) = p.actor.forward(&obs);
            let act: Vec<f64> = mu
                .iter()
                .zip(&p.log_std)
                .map(|(m, ls)| m + math::exp(*ls) * math::normal(&mut self.rng))
                .collect();
            if act.iter().any(|a| !a.is_finite()) {
                return Err(Error::Training(format!(
                    "the policy's action is not finite at decision {} of an episode, after {} decisions of training",
                    rewards.len() + 1,
                    self.decisions
                )));
            }
            batch.logp.push(log_prob(&act, &mu, &p.log_std));
            values.push(self.critic.forward(&obs).0[0]);
            let step = self.task.act(&act);
            if !step.reward.is_finite() {
                return Err(Error::Training(format!(
                    "the reward is not finite at decision {} of an episode, after {} decisions of training",
                    rewards.len() + 1,
                    self.decisions
                )));
            }
            batch.obs.push(obs);
            batch.act.push(act);
            ret += step.reward;
            rewards.push(if c.norm_reward {
                self.reward_scale.scale(step.reward, step.done)
            } else {
                step.reward
            });
            raw = self.task.observe();
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
        Ok((ret, self.task.goal_error()))
    }
}
