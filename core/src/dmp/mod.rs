//! The discrete DMP of method.md section 3: the canonical system and radial
//! basis ([`basis`]), locally weighted regression of the forcing term
//! ([`fit`]), and the gain-independent projections that make every grid point
//! of a landscape a pure integration ([`fit::Projections`]).

pub mod basis;
pub mod fit;

pub use basis::{Basis, DmpSettings};
pub use fit::{Projections, fit_weights, forcing_from_weights};
