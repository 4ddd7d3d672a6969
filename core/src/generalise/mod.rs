//! Generalise: a fitted DMP run somewhere else (method.md section 10): a
//! new start, goal and duration for one demo's DMP ([`primitive`]) and its
//! orientation ([`orientation`]), and one skill from many demos
//! ([`skill`]).
//!
//! May use: landscape, kernels, fit.

pub mod orientation;
pub mod primitive;
pub mod skill;
