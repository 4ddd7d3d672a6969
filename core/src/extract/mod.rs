//! Extract: the gains a landscape gives (method.md sections 6, 9 and 11):
//! J's optimum refined by Nelder-Mead ([`optimum`], [`nelder_mead`]), the
//! diagnostics of that optimum ([`diagnostics`]), what the demos allow and
//! the pick for the robot ([`allowed`]), and gains as a robot sees them
//! ([`robot`]).
//!
//! May use: landscape, fit, load.

pub mod allowed;
pub mod diagnostics;
pub mod nelder_mead;
pub mod optimum;
pub mod point;
pub mod robot;
