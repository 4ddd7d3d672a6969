//! # dmpscope-core
//!
//! Pure computation behind dmpscope: reading hand-tracker recordings, preparing
//! each demonstration, fitting Dynamic Movement Primitives, and mapping the
//! human-likeness error `d`, the cross-demo similarity `S` and the objective
//! `J = S + k * sum(d)` over a grid of gain ratios (D/M, K/M).
//!
//! The method, every number of it, is fixed in `docs/method.md`; each module
//! names the section it implements. Data flows one way:
//!
//! ```text
//! file, folder or bytes -> RawDemo (io::load_source, group)
//!       -> PreparedDemo (prepare) -> Model (pipeline, dmp, similarity)
//!       -> Landscape (landscape) -> Extraction (extract)
//!       -> Report: Table I (report, presets)
//! ```
//!
//! Both front ends (the CLI and the app's session) load with
//! [`io::load_source`] and build the model with [`build_model`], and tell
//! the user what happened with [`Notice`]s.
//!
//! Nothing here needs threads, a GPU or a file system: the loaders take any
//! [`std::io::Read`], the landscape engine runs in slices when asked to, and
//! rayon is used only behind the `parallel` feature.

pub mod allowed;
pub mod arrange;
pub mod demo;
pub mod diagnostics;
pub mod dmp;
pub mod error;
pub mod extract;
pub mod gaps;
pub mod generalise;
pub mod geom;
pub mod group;
pub mod io;
pub mod kernel_dispatch;
pub mod landscape;
pub mod mapping;
pub mod model;
pub mod nelder_mead;
pub mod notice;
pub mod orientation;
mod orientation_kernel;
mod orientation_point;
mod orientation_poly;
pub mod pipeline;
pub mod planted;
mod planted_orientation;
pub mod portable;
mod position_kernel;
pub mod prepare;
pub mod presets;
pub mod quantity;
pub mod report;
pub mod rest;
pub mod rl;
pub mod robot;
pub mod rotation;
pub mod savgol;
pub mod segment;
pub mod similarity;
pub mod skill;
pub mod skill_error;
mod skill_kernel;
pub mod synth;
pub mod table_text;
pub mod text;
pub mod tf;
pub mod units;

pub use demo::{DemoInfo, RawDemo, TimeSource};
pub use error::{Error, Result};
pub use extract::{Extraction, extract};
pub use generalise::{Generalised, Mapping, Primitive, Scaling, Target};
pub use landscape::{Axis, AxisScale, Grid, Landscape, LandscapeJob};
pub use model::{Model, PointEval, Rollout};
pub use notice::{Level, Notice};
pub use pipeline::{Built, Unusable, build_model};
pub use prepare::{PrepSettings, PreparedDemo, prepare};
pub use presets::{PAPER_PRESETS, Preset};
pub use quantity::{PointValues, Quantity};
pub use report::{Report, TableRow};
pub use skill::Skill;
pub use skill_error::SkillMode;

/// The number of points on the unit-time integration grid (method.md section 2.6).
pub const DEFAULT_GRID_POINTS: usize = 1001;
/// The paper's weight of the summed human-likeness error in J (method.md section 6).
pub const DEFAULT_K: f64 = 20.0;
