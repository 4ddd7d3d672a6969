//! The dmpscope app: the GUI over `dmpscope-core` (the CLI lives in the
//! binary, `src/main.rs` and `src/cli/`).

pub mod gui;
