//! Fit: the discrete DMP of one demonstration (method.md sections 3, 10
//! and 12): the canonical system and radial basis ([`basis`]), locally
//! weighted regression of the forcing term and the gain-independent
//! projections that make every gain pair a pure integration ([`lwr`]), the
//! model's settings ([`settings`]), how the forcing term follows a moved
//! start and goal ([`mapping`]), and the orientation DMP's form
//! ([`orientation`]).
//!
//! May use: prepare.

pub mod basis;
pub mod lwr;
pub mod mapping;
pub mod orientation;
pub mod settings;
