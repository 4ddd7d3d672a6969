//! Kernels: the landscape's inner loops over lanes of gain pairs, run with
//! the best vector instructions the CPU has ([`dispatch`]): the position
//! DMP's integration with `d` and `a_peak` ([`position`]), `S`
//! ([`similarity`]), the skill error `E` ([`skill_error`], [`skill`]) and
//! the orientation DMP's integration ([`orientation`],
//! [`orientation_poly`]). Every kernel gives the same bits on every
//! instruction set and in the browser.
//!
//! May use: fit, prepare.

pub mod dispatch;
pub mod orientation;
pub mod orientation_poly;
pub mod orientation_run;
pub mod position;
pub mod similarity;
pub mod skill;
pub mod skill_error;
