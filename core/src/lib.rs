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

pub mod arrange;
pub mod error;
pub mod export;
pub mod extract;
pub mod fit;
pub mod generalise;
pub mod geom;
pub mod kernels;
pub mod landscape;
pub mod load;
pub mod notice;
pub mod pipeline;
pub mod portable;
pub mod prepare;
pub mod report;
pub mod rl;
pub mod rng;
pub mod rotation;
pub mod synth;

pub use arrange::streams::load_source;
pub use error::{Error, Result};
pub use extract::optimum::{Extraction, extract};
pub use fit::mapping::{Mapping, Scaling};
pub use fit::settings::SkillMode;
pub use generalise::primitive::{Generalised, Primitive, Target};
pub use generalise::skill::Skill;
pub use landscape::grid::{Axis, AxisScale, DEFAULT_K, Grid, Landscape, LandscapeJob};
pub use landscape::model::{Model, PointEval, Rollout};
pub use landscape::quantity::{PointValues, Quantity};
pub use load::demo::{DemoInfo, RawDemo, TimeSource};
pub use notice::{Level, Notice};
pub use pipeline::{Built, Unusable, build_model};
pub use prepare::demo::{DEFAULT_GRID_POINTS, PrepSettings, PreparedDemo, prepare};
pub use report::presets::{PAPER_PRESETS, Preset};
pub use report::summary::Report;
pub use report::table::TableRow;
