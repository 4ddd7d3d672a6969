//! The dmpscope app: the [`session`] (the pipeline's state, no egui), the
//! GUI over it ([`gui`]; the CLI lives in the binary, `src/main.rs` and
//! `src/cli/`) and, in the browser, the entry `web`.

pub mod gui;
pub mod session;
#[cfg(target_arch = "wasm32")]
pub mod web;
