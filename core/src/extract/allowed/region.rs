//! The acceptable region of J (method.md section 11) and what E says over
//! the grid: its depth and how far it exceeds the demos' own errors.

use serde::{Deserialize, Serialize};

use crate::extract::allowed::numbers::num;
use crate::landscape::grid::Landscape;
use crate::landscape::model::zeta;
use crate::landscape::quantity::Quantity;

/// The grid points whose J is within eps of J*.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Acceptable {
    /// The tolerance: `J <= (1 + eps) J*`.
    pub eps: f64,
    /// The share of the grid's points in the region.
    pub fraction: f64,
    /// The least and greatest D/M in it (`None`: the region is empty).
    pub dm: Option<[f64; 2]>,
    /// The least and greatest K/M in it.
    pub km: Option<[f64; 2]>,
    /// The least and greatest zeta in it.
    pub zeta: Option<[f64; 2]>,
    /// Per grid point (row-major `[i_dm][i_km]`), whether it is in.
    #[serde(skip)]
    pub mask: Vec<bool>,
}

impl Acceptable {
    /// The region of `landscape` (complete) for `k` around `j_star`.
    pub fn new(landscape: &Landscape, k: f64, j_star: f64, eps: f64) -> Self {
        let j = landscape.j(k);
        let mask: Vec<bool> = j.iter().map(|&v| v <= (1.0 + eps) * j_star).collect();
        let n_km = landscape.grid.km.n;
        let mut range = [[f64::INFINITY, f64::NEG_INFINITY]; 3];
        let mut count = 0usize;
        for (idx, _) in mask.iter().enumerate().filter(|&(_, &m)| m) {
            count += 1;
            let (dm, km) = (landscape.dm[idx / n_km], landscape.km[idx % n_km]);
            for (r, v) in range.iter_mut().zip([dm, km, zeta(dm, km)]) {
                r[0] = r[0].min(v);
                r[1] = r[1].max(v);
            }
        }
        let some = |r: [f64; 2]| (count > 0).then_some(r);
        Self {
            eps,
            fraction: count as f64 / mask.len().max(1) as f64,
            dm: some(range[0]),
            km: some(range[1]),
            zeta: some(range[2]),
            mask,
        }
    }

    /// `D/M a-b, K/M c-d (zeta e-f)`, or that the region is empty.
    pub fn text(&self) -> String {
        match (self.dm, self.km, self.zeta) {
            (Some(d), Some(k), Some(z)) => format!(
                "D/M {}-{}, K/M {}-{} (zeta {:.2}-{:.2})",
                num(d[0]),
                num(d[1]),
                num(k[0]),
                num(k[1]),
                z[0],
                z[1]
            ),
            _ => "no grid point".to_owned(),
        }
    }
}

/// The depth of E: section 9's depth with E in place of J and E's grid
/// minimum as the reference.
pub fn e_depth(landscape: &Landscape) -> Option<f64> {
    let e = landscape.values(Quantity::ESum);
    let min = e
        .iter()
        .copied()
        .filter(|v| v.is_finite())
        .fold(f64::INFINITY, f64::min);
    if !(min.is_finite() && min > 0.0) {
        return None;
    }
    let (n_dm, n_km) = (landscape.grid.dm.n, landscape.grid.km.n);
    let boundary = (0..n_dm)
        .flat_map(|i| (0..n_km).map(move |j| (i, j)))
        .filter(|&(i, j)| i == 0 || j == 0 || i + 1 == n_dm || j + 1 == n_km)
        .map(|(i, j)| e[landscape.index(i, j)])
        .filter(|v| v.is_finite())
        .fold(f64::INFINITY, f64::min);
    boundary
        .is_finite()
        .then(|| (boundary / min - 1.0).max(0.0))
}

/// The least and greatest `E - sum d` over the grid's points where both
/// are finite.
pub(crate) fn excess(landscape: &Landscape) -> Option<[f64; 2]> {
    let e = landscape.values(Quantity::ESum);
    let d = landscape.values(Quantity::DSum);
    let range = e
        .iter()
        .zip(d)
        .map(|(e, d)| e - d)
        .filter(|v| v.is_finite())
        .fold([f64::INFINITY, f64::NEG_INFINITY], |[lo, hi], v| {
            [lo.min(v), hi.max(v)]
        });
    range[0].is_finite().then_some(range)
}

/// When `E - sum d` varies by less than this share of E's own variation
/// over the grid, E's variation is the DMP's own reproduction error.
pub const EXCESS_SMALL: f64 = 0.1;
