//! What PPO learns on: a [`Task`] is an episodic environment with a fixed
//! number of decisions, continuous observations and actions, and a measure
//! of how far from its goal an episode ended. The DMP environment
//! ([`crate::rl::env::DmpEnv`]) and the sanity task ([`crate::rl::point_mass::PointMass`]) are the
//! two.

/// What one decision gave.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Step {
    /// The reward of the decision (the terminal reward included on the last).
    pub reward: f64,
    /// Whether the episode ended.
    pub done: bool,
}

/// An episodic environment PPO can train on.
pub trait Task {
    /// Size of an observation.
    fn obs_dim(&self) -> usize;
    /// Size of an action (the policy's output).
    fn act_dim(&self) -> usize;
    /// Decisions in one episode.
    fn decisions(&self) -> usize;
    /// Back to the start; the first observation.
    fn reset(&mut self) -> Vec<f64>;
    /// The current observation.
    fn observe(&self) -> Vec<f64>;
    /// Applies the policy's output `u` for one decision.
    fn act(&mut self, u: &[f64]) -> Step;
    /// How far from the goal the state is now (metres for the DMP).
    fn goal_error(&self) -> f64;
    /// The size of the action the task needs, per action component, in the
    /// policy's output units: the initial policy standard deviation is a
    /// fraction of it ([`crate::rl::ppo::PpoConfig::init_sd`]).
    fn action_size(&self) -> Vec<f64>;
}
