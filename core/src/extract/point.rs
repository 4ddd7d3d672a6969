//! A gain pair and what J, S and sum d are there: the part the optimum
//! (`report::summary::Optimum`) and the pick (`extract::allowed::Pick`)
//! share, flattened into both in JSON. (The operating point's evaluation,
//! `landscape::model::PointEval`, holds every demo's numbers instead, and
//! its J follows k.)

use serde::{Deserialize, Serialize};

use crate::landscape::model::PointEval;

/// A gain pair with its damping ratio and J, S and sum d there.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct GainPoint {
    /// D/M.
    pub dm: f64,
    /// K/M.
    pub km: f64,
    /// Damping ratio.
    pub zeta: f64,
    /// J there, for the extraction's k.
    pub j: f64,
    /// S there.
    pub s: f64,
    /// sum d there, metres.
    pub d_sum: f64,
}

impl GainPoint {
    /// The point of an evaluation, J for `k`.
    pub fn of(eval: &PointEval, k: f64) -> Self {
        Self {
            dm: eval.dm,
            km: eval.km,
            zeta: eval.zeta,
            j: eval.j(k),
            s: eval.s,
            d_sum: eval.d_sum,
        }
    }
}
