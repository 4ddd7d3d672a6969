//! The app's state, without egui: the recordings opened, their demos, the
//! messages, the model, the landscape, the extraction, Table I, the
//! operating point's paths and the RL run (ARCHITECTURE.md, "The data
//! path").
//!
//! Two inputs change it: [`Settings`] (whatever set them: a widget, a reset,
//! a test, an imported file) and [`Command`]s. [`Session::update`] is the one
//! place that decides what to recompute: each stage keeps the typed key it
//! was computed for and is redone only when its key changes:
//!
//! ```text
//! stream options (frames, up axis)            -> a source's streams (a load job)
//! + grouping                                  -> its demos
//! demos + included + preprocessing + DMP      -> the model
//! model + grid                                -> the landscape (a job)
//! landscape + k                               -> the extraction (a job, one at a time)
//! extraction + diagnostics settings           -> the diagnostics (a job, progressive)
//! extraction + a_peak limit                   -> the constrained optimum (a job)
//! extraction + pick rule, eps, a_peak limit   -> the acceptable region, E's verdict
//!                                                and the pick (a job)
//! model + k                                   -> the paper's rows of Table I
//! model + operating point (+ k for its J)     -> the operating point's paths (and row),
//!                                                its forcing terms and S shares
//! model                                       -> the RL run stays or goes
//! ```
//!
//! Background work runs through one [`jobs::Runner`] on the
//! [`executor::Executor`] the platform hands the session (threads natively,
//! Web Workers in the browser, a fake in tests); with
//! [`jobs::Runner::inline`] every job finishes inside `update`, so tests
//! drive the session synchronously, without egui and without sleeps. This
//! crate names no GUI and no platform: cargo refuses it egui, eframe, wgpu
//! and web-sys.

mod allowed;
mod commands;
pub mod diagnostics;
pub mod executor;
pub mod generalise;
pub mod jobs;
pub mod landscape;
pub mod messages;
pub mod pooled;
pub mod rl;
pub mod rl_board;
pub mod rl_request;
pub mod session;
pub mod settings;
pub mod sources;
pub mod stage;
mod stages;
pub mod state;
mod status;
pub mod tiles;
pub mod worker_side;
pub mod workers;

pub use commands::Command;
pub use diagnostics::DiagSnapshot;
pub use executor::{Executor, PageTime};
pub use generalise::{GenSource, GenView, GeneraliseSpec};
pub use jobs::Runner;
pub use landscape::{Shown, Snapshot};
pub use rl_request::{Progress as RlProgress, RlRequest, RlRun, RunState};
pub use session::Session;
pub use settings::Settings;
pub use sources::Source;
pub use state::AllowedView;
pub use state::{DemoEntry, StageRuns};
pub use status::Status;
pub use workers::WorkerStats;
