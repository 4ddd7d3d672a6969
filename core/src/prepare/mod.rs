//! Prepare: a raw demonstration put on the unit-time grid (method.md
//! section 2): stamps sorted, resampled, smoothed and differentiated by
//! Savitzky-Golay ([`savgol`]), time normalised ([`demo`]), the orientation
//! likewise ([`orientation`]), how much of its acceleration is noise
//! ([`noise`]), with the small numeric helpers every later stage shares
//! ([`numeric`]).
//!
//! May use: load.

pub mod demo;
pub mod noise;
pub mod numeric;
pub mod orientation;
pub mod savgol;
