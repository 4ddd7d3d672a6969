//! The RL environment of method.md section 8: one demo's DMP (start, goal,
//! unit duration) with gains (D/M, K/M) whose forcing term is the agent's
//! action, integrated exactly as the LfD regeneration (section 4,
//! semi-implicit Euler on the demo's unit-time grid).
//!
//! Choices the method leaves open, fixed here:
//! - **Control step** ([`EnvOptions::decisions`]): the episode's `n - 1`
//!   integration steps (1000 on the 1001-point grid) are split into
//!   decisions, [`DECISIONS`] by default; each action is held over the steps
//!   of its decision (10 by default, 1 with 1000 decisions). The per-step
//!   rewards of a decision are summed into its reward, so the episode's
//!   return is the paper's sum over integration steps either way.
//! - **Action** ([`ActionMode`]): one value per axis, `A = scale * u` with
//!   `u` the policy's output and `scale = ACTION_SCALE * max(|g - y0|, 5
//!   cm)` per axis, so one unit of policy output is a forcing term of the
//!   motion's size (`forcing`, the paper's); or `A = f_fit + scale * u` with
//!   `f_fit` the demo's fitted forcing term at the gains (`residual`).
//! - **Exploration** ([`ExploreScale`]): the policy's initial deviation
//!   per axis is [`crate::rl::ppo::PpoConfig::init_sd`] (0.5) times the RMS of the
//!   demo's own acceleration `y''` (default) or of its fitted forcing term.
//! - **Observation** (7 values): the phase `s` in 0..1, then per axis
//!   `(y - g) / r` and `y' / r` with `r = max(|g - y0|_2, 5 cm)`.
//! - **Rewards**, exactly the paper's: at every integration step
//!   `-1e-3 |y''| - 1e-7 |A|` (Euclidean norms over the three axes, `y''`
//!   the step's acceleration in unit time, m/s^2); after the last step
//!   `-10 |y - g|` (m), `g` the demo's goal.

use serde::{Deserialize, Serialize};

use crate::geom::Vec3;
use crate::rl::policy::Policy;
use crate::rl::task::{Step, Task};
use crate::{Error, Model, Result};

/// Decisions per episode unless told otherwise.
pub const DECISIONS: usize = 100;
/// Policy output to forcing term, per metre of motion (m/s^2 per m).
pub const ACTION_SCALE: f64 = 20.0;
/// Size of an observation.
pub const OBS: usize = 7;
/// Size of an action.
pub const ACT: usize = 3;
/// A goal closer than this to the start (metres) is refused.
pub const MIN_REACH_M: f64 = 1e-3;

/// How the policy's output becomes the forcing term.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ActionMode {
    /// The action is the whole forcing term (the paper).
    #[default]
    Forcing,
    /// The action is added to the demo's fitted forcing term at the gains.
    Residual,
}

impl ActionMode {
    /// Both modes.
    pub const ALL: [Self; 2] = [Self::Forcing, Self::Residual];

    /// The mode's name on the command line and in reports.
    pub fn name(self) -> &'static str {
        match self {
            Self::Forcing => "forcing",
            Self::Residual => "residual",
        }
    }
}

/// What the policy's initial exploration is scaled to
/// ([`Task::action_size`]; the deviation is
/// [`crate::rl::ppo::PpoConfig::init_sd`] times it).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ExploreScale {
    /// The RMS of the demo's own acceleration `y''`: the noise enters `y''`
    /// one for one and the reward charges `|y''|`, so exploring costs the
    /// same share of the demo's acceleration penalty whatever the gains.
    #[default]
    Acceleration,
    /// The RMS of the demo's fitted forcing term at the gains: grows with
    /// K/M (at K/M = 1000 it is mostly `K (y - g)`, about 100x the demo's
    /// acceleration), so stiff gains explore with a noise that costs more
    /// than the whole motion.
    Forcing,
}

impl ExploreScale {
    /// Both scales.
    pub const ALL: [Self; 2] = [Self::Acceleration, Self::Forcing];

    /// The scale's name on the command line and in reports.
    pub fn name(self) -> &'static str {
        match self {
            Self::Acceleration => "acceleration",
            Self::Forcing => "forcing",
        }
    }
}

/// The environment's options.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct EnvOptions {
    /// Decisions per episode (1 ..= the integration steps).
    pub decisions: usize,
    /// What the action is.
    pub mode: ActionMode,
    /// What the initial exploration is scaled to.
    #[serde(default)]
    pub explore: ExploreScale,
}

impl Default for EnvOptions {
    fn default() -> Self {
        Self {
            decisions: DECISIONS,
            mode: ActionMode::Forcing,
            explore: ExploreScale::Acceleration,
        }
    }
}

/// The environment for one demo and one gain pair.
#[derive(Clone, Debug)]
pub struct DmpEnv {
    /// D/M.
    pub dm: f64,
    /// K/M.
    pub km: f64,
    mode: ActionMode,
    y0: [f64; 3],
    v0: [f64; 3],
    goal: [f64; 3],
    steps: usize,
    hold: usize,
    scale: [f64; 3],
    norm: f64,
    /// The fitted forcing term on the grid, at the gains.
    fitted: Vec<[f64; 3]>,
    /// [`Task::action_size`], policy units.
    explore: [f64; 3],
    // State.
    y: [f64; 3],
    v: [f64; 3],
    k: usize,
    record: Option<(Vec<Vec3>, Vec<f64>)>,
}

/// A deterministic run of the policy's mean.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GreedyRun {
    /// Positions on the demo's grid (start included), demo coordinates.
    pub path: Vec<Vec3>,
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

impl DmpEnv {
    /// The environment of demo `demo` of `model` at gains (`dm`, `km`).
    pub fn new(model: &Model, demo: usize, dm: f64, km: f64, options: EnvOptions) -> Result<Self> {
        let d = model
            .demos()
            .get(demo)
            .ok_or_else(|| Error::InvalidSetting(format!("no demo {}", demo + 1)))?;
        let n = d.len();
        let bad = |why: String| Err(Error::InvalidSetting(format!("{}: {why}", d.name)));
        if n < 2 {
            return bad(format!(
                "RL needs a demo of at least 2 grid points, it has {n}"
            ));
        }
        if !(dm.is_finite() && km.is_finite() && dm >= 0.0 && km >= 0.0) {
            return bad(format!(
                "RL needs finite, non-negative gains, got D/M {dm}, K/M {km}"
            ));
        }
        let steps = n - 1;
        if options.decisions == 0 || options.decisions > steps {
            return bad(format!(
                "decisions per episode must be 1 to {steps} (the integration steps), got {}",
                options.decisions
            ));
        }
        // The environment keeps its state as plain arrays (its own
        // arithmetic, bit for bit the same natively and in the browser).
        let y0: [f64; 3] = d.y_raw[0].into();
        let goal: [f64; 3] = d.goal.into();
        let delta: [f64; 3] = std::array::from_fn(|a| goal[a] - y0[a]);
        let reach = norm3(delta);
        if reach.is_nan() || reach < MIN_REACH_M {
            return bad(format!(
                "its goal is {:.3} mm from its start (at least {} mm is needed): there is no motion to learn",
                reach * 1e3,
                MIN_REACH_M * 1e3
            ));
        }
        let arrays = |v: &[Vec3]| -> Vec<[f64; 3]> { v.iter().map(|p| (*p).into()).collect() };
        let fitted = arrays(&model.forcing(demo, dm, km));
        let ydd = arrays(&d.ydd);
        if fitted.iter().flatten().any(|f| !f.is_finite()) {
            return bad(format!(
                "its fitted forcing term is not finite at D/M {dm}, K/M {km}"
            ));
        }
        let scale = delta.map(|d| ACTION_SCALE * d.abs().max(0.05));
        let sized = match options.explore {
            ExploreScale::Acceleration => &ydd,
            ExploreScale::Forcing => &fitted,
        };
        let explore = std::array::from_fn(|a| {
            let ms = sized.iter().map(|f| f[a] * f[a]).sum::<f64>() / sized.len().max(1) as f64;
            (ms.sqrt() / scale[a]).max(1e-3)
        });
        let mut env = Self {
            dm,
            km,
            mode: options.mode,
            y0,
            v0: d.yd[0].into(),
            goal,
            steps,
            hold: steps.div_ceil(options.decisions),
            scale,
            norm: reach.max(0.05),
            fitted,
            explore,
            y: y0,
            v: d.yd[0].into(),
            k: 0,
            record: None,
        };
        env.reset();
        Ok(env)
    }

    /// The current observation.
    pub fn observation(&self) -> [f64; OBS] {
        let s = self.k as f64 / self.steps as f64;
        let mut o = [s, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
        for a in 0..3 {
            o[1 + a] = (self.y[a] - self.goal[a]) / self.norm;
            o[4 + a] = self.v[a] / self.norm;
        }
        o
    }

    /// What the action is.
    pub fn mode(&self) -> ActionMode {
        self.mode
    }

    /// The position now.
    pub fn position(&self) -> [f64; 3] {
        self.y
    }

    /// The start.
    pub fn start(&self) -> [f64; 3] {
        self.y0
    }

    /// The goal.
    pub fn goal(&self) -> [f64; 3] {
        self.goal
    }

    /// The forcing term one unit of policy output is, per axis (m/s^2).
    pub fn action_scale(&self) -> [f64; 3] {
        self.scale
    }

    /// The length `r` positions and velocities are observed in, metres.
    pub fn observation_scale(&self) -> f64 {
        self.norm
    }

    /// The forcing term for a policy output `u` at integration step `k`.
    pub fn forcing(&self, u: &[f64], k: usize) -> [f64; 3] {
        std::array::from_fn(|a| {
            let base = match self.mode {
                ActionMode::Forcing => 0.0,
                ActionMode::Residual => self.fitted.get(k).map_or(0.0, |f| f[a]),
            };
            base + self.scale[a] * u.get(a).copied().unwrap_or(0.0)
        })
    }

    /// Integration steps per decision.
    pub fn hold(&self) -> usize {
        self.hold
    }

    /// Applies policy output `u` for one decision.
    pub fn step(&mut self, u: &[f64]) -> Step {
        let dt = 1.0 / self.steps as f64;
        let end = (self.k + self.hold).min(self.steps);
        let mut reward = 0.0;
        while self.k < end {
            let f = self.forcing(u, self.k);
            let acc: [f64; 3] = std::array::from_fn(|a| {
                -self.dm * self.v[a] - self.km * (self.y[a] - self.goal[a]) + f[a]
            });
            for a in 0..3 {
                self.v[a] += acc[a] * dt;
                self.y[a] += self.v[a] * dt;
            }
            let a_norm = norm3(acc);
            reward += -1e-3 * a_norm - 1e-7 * norm3(f);
            if let Some((path, accel)) = &mut self.record {
                path.push(self.y.into());
                accel.push(a_norm);
            }
            self.k += 1;
        }
        let done = self.k >= self.steps;
        if done {
            reward += -10.0 * self.goal_error();
        }
        Step { reward, done }
    }

    /// Runs `policy`'s mean once (no exploration), recording the path.
    pub fn greedy(&self, policy: &Policy) -> Result<GreedyRun> {
        let mut env = self.clone();
        env.record = Some((Vec::with_capacity(self.steps + 1), Vec::new()));
        let episode = policy.run(&mut env)?;
        let (mut path, accel) = env.record.take().unwrap_or_default();
        path.insert(0, self.y0.into());
        Ok(GreedyRun {
            path,
            accel,
            final_error: episode.final_error,
            ret: episode.ret,
        })
    }
}

impl Task for DmpEnv {
    fn obs_dim(&self) -> usize {
        OBS
    }

    fn act_dim(&self) -> usize {
        ACT
    }

    fn decisions(&self) -> usize {
        self.steps.div_ceil(self.hold)
    }

    fn reset(&mut self) -> Vec<f64> {
        self.y = self.y0;
        self.v = self.v0;
        self.k = 0;
        if let Some((p, a)) = &mut self.record {
            p.clear();
            a.clear();
        }
        self.observe()
    }

    fn observe(&self) -> Vec<f64> {
        self.observation().to_vec()
    }

    fn act(&mut self, u: &[f64]) -> Step {
        self.step(u)
    }

    fn goal_error(&self) -> f64 {
        norm3(std::array::from_fn(|a| self.y[a] - self.goal[a]))
    }

    /// The RMS over the grid, per axis, of the demo's acceleration or of
    /// its fitted forcing term ([`ExploreScale`]), in policy units
    /// (divided by the action scale).
    fn action_size(&self) -> Vec<f64> {
        self.explore.to_vec()
    }
}

fn norm3(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}
