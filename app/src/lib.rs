//! The dmpscope app: the GUI ([`gui`]) over the session (the pipeline's
//! state, its own crate `dmpscope-session`, re-exported as [`session`]);
//! the CLI lives in the binary (`src/main.rs` and `src/cli/`) and, in the
//! browser, the entry `web` with the executor over Web Workers.

pub mod gui;
pub use dmpscope_session as session;
#[cfg(target_arch = "wasm32")]
pub mod web;
