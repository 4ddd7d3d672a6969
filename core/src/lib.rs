#![doc = include_str!("../README.md")]

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
