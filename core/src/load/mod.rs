//! Load: recordings read into raw demonstrations (method.md sections 1,
//! 12 and 13). A source (a file, a folder, bytes) is recognised by
//! [`formats`], read by its reader ([`mcap`], [`rosbag1`], [`rosbag2`],
//! [`csv`], OptiTrack Motive's CSV export [`motive`]), each message decoded by [`decode`] into pose samples, and the
//! samples gathered by [`collect`] into one [`demo::RawDemo`] per topic and
//! key, with TF ([`tf`]), units ([`units`]) and orientation checks
//! ([`orientation_check`]) applied. [`options`] is what the user asks of
//! loading, [`flags`] the same by the CLI's names. Turning streams into
//! demos is [`crate::arrange`]'s.
//!
//! May use: nothing.

pub mod access;
pub mod collect;
pub mod csv;
pub mod decode;
pub mod demo;
pub mod flags;
pub mod formats;
pub mod mcap;
pub mod motive;
pub mod options;
pub mod orientation_check;
pub mod rosbag1;
pub mod rosbag2;
pub mod source;
pub mod streams;
pub mod tf;
pub mod units;
