//! Generalise: a fitted DMP run somewhere else (method.md section 10): a
//! new start, goal and duration for one demo's DMP ([`primitive`]) and its
//! orientation ([`orientation`]), and one skill from many demos
//! ([`skill`]); which of them a caller runs, and their runs ([`run`]).
//!
//! May use: landscape, kernels, fit.

pub mod orientation;
pub mod primitive;
pub mod run;
pub mod skill;
