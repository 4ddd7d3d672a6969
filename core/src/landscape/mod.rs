//! Landscape: the fitted model of a demo set ([`model`], fitted in steps
//! by [`model_steps`]) evaluated at any
//! gain pair and over a grid of them ([`grid`]): `sum d`, `S`, `J`, `E`,
//! `a_peak` and `d_rot`, each declared once in [`quantity`]; the
//! operating point's orientation ([`orientation_point`]).
//!
//! May use: kernels, fit, prepare.

pub mod grid;
pub mod model;
pub mod model_steps;
pub mod orientation_point;
pub mod quantity;
