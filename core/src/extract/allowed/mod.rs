//! What the demos determine, and gains for the robot where they do not
//! (method.md section 11): the acceptable region of J and E's depth
//! ([`region`]), the identifiability verdict ([`verdict`]), and a gain pair
//! picked in the region by a named rule ([`rule`], [`pick`]).

pub mod numbers;
pub mod pick;
pub mod region;
pub mod rule;
pub mod verdict;

pub use numbers::{num, percent};
pub use region::{Acceptable, EXCESS_SMALL, e_depth};
pub use rule::{
    COMPLIANT_ZETA, DEFAULT_EPS, Pick, PickRule, PickSettings, Settling, settling_unit,
};
pub use verdict::{Allowed, mean_duration};
