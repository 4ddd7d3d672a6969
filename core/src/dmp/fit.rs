//! Locally weighted regression of a forcing term onto the basis, and the
//! three gain-independent projections per demo (method.md section 3).

use super::basis::Basis;
use crate::prepare::PreparedDemo;

/// LWR weights `w_i = sum_k x psi_i f / sum_k x^2 psi_i` of a target sampled
/// on the basis grid (0 where the denominator is below 1e-300).
pub fn fit_weights(basis: &Basis, target: &[f64]) -> Vec<f64> {
    let b = basis.len();
    let mut num = vec![0.0; b];
    let mut den = vec![0.0; b];
    for (k, (&x, &f)) in basis.x.iter().zip(target).enumerate() {
        for (i, &p) in basis.row(k).iter().enumerate() {
            num[i] += x * p * f;
            den[i] += x * x * p;
        }
    }
    num.iter()
        .zip(&den)
        .map(|(n, d)| if *d < 1e-300 { 0.0 } else { n / d })
        .collect()
}

/// The forcing term `f(x_k) = x_k sum_i psi_i w_i / sum_i psi_i` on the grid.
pub fn forcing_from_weights(basis: &Basis, weights: &[f64]) -> Vec<f64> {
    (0..basis.grid_points())
        .map(|k| {
            let dot: f64 = basis.row(k).iter().zip(weights).map(|(p, w)| p * w).sum();
            basis.x[k] * dot / basis.psi_sum[k]
        })
        .collect()
}

/// The fitted forcing term of one demo as a linear function of the gains:
/// since `f_target = y'' + D y' + K (y - g)` and LWR is linear, the fit is
/// `F0 + D F1 + K F2` with `Fj` the fits of `y''`, `y'`, `y - g`.
#[derive(Clone, Debug)]
pub struct Projections {
    /// Per grid point `[F0, F1, F2]` for each axis: `f[k][axis][j]`.
    pub f: Vec<[[f64; 3]; 3]>,
    /// LWR weights per axis of the three parts: `weights[axis][j]`.
    pub weights: [[Vec<f64>; 3]; 3],
}

impl Projections {
    /// Fits the three parts of one prepared demo.
    pub fn new(basis: &Basis, demo: &PreparedDemo) -> Self {
        let parts = [0, 1, 2].map(|axis| {
            [
                demo.ydd.iter().map(|v| v[axis]).collect(),
                demo.yd.iter().map(|v| v[axis]).collect(),
                demo.y.iter().map(|v| v[axis] - demo.goal[axis]).collect(),
            ]
        });
        Self::from_parts(basis, parts)
    }

    /// Fits any forcing target that is `P0 + D P1 + K P2`: `parts[axis]`
    /// holds `[P0, P1, P2]` on the grid (the orientation DMP's, method.md
    /// section 12, as well as the position's).
    pub fn from_parts(basis: &Basis, parts: [[Vec<f64>; 3]; 3]) -> Self {
        let n = basis.grid_points();
        let mut f = vec![[[0.0; 3]; 3]; n];
        let weights = parts.map(|axis| axis.map(|part| fit_weights(basis, &part)));
        for axis in 0..3 {
            for j in 0..3 {
                let fj = forcing_from_weights(basis, &weights[axis][j]);
                for (k, v) in fj.into_iter().enumerate() {
                    f[k][axis][j] = v;
                }
            }
        }
        Self { f, weights }
    }

    /// The LWR weights of one axis at gains `(dm, km)`.
    pub fn weights_at(&self, axis: usize, dm: f64, km: f64) -> Vec<f64> {
        let [w0, w1, w2] = &self.weights[axis];
        w0.iter()
            .zip(w1)
            .zip(w2)
            .map(|((a, b), c)| a + dm * b + km * c)
            .collect()
    }
}
