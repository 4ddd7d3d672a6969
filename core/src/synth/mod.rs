//! Synth: demonstrations made here, for the bundled samples, the tests and
//! the bootstrap: tracked reaches as a VIVE records them ([`vive`]) and
//! demos that share one forcing term at planted gains ([`planted`],
//! [`planted_forcing`], [`planted_orientation`]), lab-size takes of
//! poses beside a camera ([`lab`]), and hostile files ([`hostile`]).
//!
//! May use: fit, prepare, load.

pub mod hostile;
pub mod lab;
pub mod planted;
pub mod planted_forcing;
pub mod planted_orientation;
pub mod vive;
