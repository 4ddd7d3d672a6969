#![doc = include_str!("../README.md")]

pub mod figure;
pub mod gui;
pub use dmpscope_session as session;
#[cfg(target_arch = "wasm32")]
pub mod web;
