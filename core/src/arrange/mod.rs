//! Arrange: a source's streams turned into its demonstrations (method.md
//! sections 1 and 13): the streams the user chose ([`streams`]), split at
//! breaks in time ([`gaps`]), grouped one per topic, file or segment
//! ([`group`], [`segment`]), cut at their farthest point if asked and
//! their loops said ([`shape`]), their end rests measured or trimmed
//! ([`rest`]). [`pool`] loads several sources into one list of demos.
//!
//! May use: load.

pub mod gaps;
pub mod group;
pub mod pool;
pub mod rest;
pub mod segment;
pub mod shape;
pub mod streams;
