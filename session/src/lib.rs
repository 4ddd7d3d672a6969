#![doc = include_str!("../README.md")]

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
pub use generalise::{GeneraliseSpec, TargetSource, TargetView};
pub use jobs::Runner;
pub use landscape::{Shown, Snapshot};
pub use rl_request::{Progress as RlProgress, RlRequest, RlRun, RunState};
pub use session::Session;
pub use settings::Settings;
pub use sources::{LoadSlot, RemoteFile, RemoteLoad, Source};
pub use state::AllowedView;
pub use state::{DemoEntry, StageRuns};
pub use status::Status;
pub use workers::WorkerStats;
