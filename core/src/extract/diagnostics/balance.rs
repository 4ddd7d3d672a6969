//! How well the landscape determines its optimum (method.md section 9):
//! its depth against the box's boundary, and the balance of S against
//! `k sum d` there.

use crate::extract::optimum::Extraction;
use crate::landscape::grid::Landscape;
use crate::load::demo::median;

/// Below this depth an optimum is flat: the data do not determine the gains.
pub const FLAT_DEPTH: f64 = 0.02;

/// `max(0, min(J on the grid's first and last rows and columns) / J* - 1)`,
/// `J*` the refined optimum's J; `None` when J* is not positive or no
/// boundary point is computed.
pub fn depth(landscape: &Landscape, k: f64, j_star: f64) -> Option<f64> {
    let (n_dm, n_km) = (landscape.grid.dm.n, landscape.grid.km.n);
    let j = landscape.j(k);
    let boundary = (0..n_dm)
        .flat_map(|i| (0..n_km).map(move |jj| (i, jj)))
        .filter(|&(i, jj)| i == 0 || jj == 0 || i + 1 == n_dm || jj + 1 == n_km)
        .map(|(i, jj)| j[landscape.index(i, jj)])
        .filter(|v| v.is_finite())
        .fold(f64::INFINITY, f64::min);
    (boundary.is_finite() && j_star > 0.0).then(|| (boundary / j_star - 1.0).max(0.0))
}

/// `k sum d / S` at the optimum; `None` where S is 0 (one demo).
pub fn k_ratio(x: &Extraction) -> Option<f64> {
    (x.eval.s > 0.0).then(|| x.k * x.eval.d_sum / x.eval.s)
}

/// `median(S) / median(sum d)` over every computed grid point: the k that
/// weighs the two terms alike; `None` where S is 0 everywhere.
pub fn balanced_k(landscape: &Landscape) -> Option<f64> {
    let finite = |v: &[f64]| {
        v.iter()
            .copied()
            .filter(|x| x.is_finite())
            .collect::<Vec<_>>()
    };
    let (s, d) = (finite(landscape.s()), finite(landscape.d_sum()));
    if s.is_empty() || d.is_empty() {
        return None;
    }
    let (ms, md) = (median(&s), median(&d));
    (ms > 0.0 && md > 0.0).then(|| ms / md)
}
