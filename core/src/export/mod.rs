//! Export: what leaves dmpscope for a robot or a viewer: the DMP document
//! a controller runs ([`dmp_doc`], `docs/export.md`), demos and regenerated
//! paths as MCAP for Foxglove and Rerun ([`recording`], in Foxglove's schemas:
//! [`foxglove`], [`foxglove_json`]), ROS 2 trajectories
//! ([`ros_traj`]), and recordings written as MCAP ([`write`]).
//!
//! May use: generalise, extract, landscape, fit, load.

pub mod dmp_doc;
pub mod foxglove;
pub mod foxglove_json;
pub mod recording;
pub mod ros_traj;
pub mod write;
