//! RL with DMP (method.md section 8, the paper's section III-D): a PPO agent
//! whose action is the DMP's forcing term ([`env`]), with a hand-written
//! MLP and Adam ([`mlp`]), running normalisers ([`norm`]), the losses
//! ([`loss`]), the trainer ([`ppo`]) over any [`Task`] ([`task`]), the
//! trained [`Policy`] ([`policy`]), the learner's sanity task
//! ([`point_mass`]), the stability figure ([`outcome`]) and a training run
//! with its figures ([`run`]). No threads: a
//! [`Trainer`] advances one [`Trainer::step`] at a time.
//!
//! May use: landscape.

pub mod env;
pub mod loss;
pub mod math;
pub mod mlp;
pub mod norm;
pub mod outcome;
pub mod point_mass;
pub mod policy;
pub mod ppo;
pub mod run;
pub mod table;
pub mod task;

pub use env::{ActionMode, DmpEnv, EnvOptions, ExploreScale, GreedyRun};
pub use outcome::diverged;
pub use point_mass::PointMass;
pub use policy::Policy;
pub use ppo::{DEFAULT_DECISIONS, IterStats, PpoConfig, Trainer};
pub use run::{FirstReach, REACHED_M, RunReport, SetSummary, TrainingRun, summarise};
pub use task::{Step, Task};
