//! RL with DMP (method.md section 8, the paper's section III-D): a PPO agent
//! whose action replaces the DMP's forcing term ([`env`]), with a
//! hand-written MLP and Adam ([`mlp`]) and the PPO trainer ([`ppo`]). No
//! threads: a [`Trainer`] advances one [`Trainer::iterate`] at a time.

pub mod env;
pub mod mlp;
pub mod ppo;

pub use env::DmpEnv;
pub use ppo::{DEFAULT_DECISIONS, GreedyRun, IterStats, PpoConfig, Trainer};

/// Within this distance of the goal an episode "reached" it (issue 6).
pub const REACHED_M: f64 = 0.005;
