//! The dmpscope app: the GUI over `dmpscope-core` (the CLI lives in the
//! binary, `src/main.rs` and `src/cli/`) and, in the browser, the entry
//! [`web`].

pub mod gui;
#[cfg(target_arch = "wasm32")]
pub mod web;
