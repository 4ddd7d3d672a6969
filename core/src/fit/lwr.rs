//! Locally weighted regression of a forcing term onto the basis, and the
//! three gain-independent projections per demo (method.md section 3).

use crate::fit::basis::Basis;
use crate::prepare::demo::PreparedDemo;

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

/// [`fit_weights`] of `T` targets in one pass over the basis, to the bit:
/// each weight's sums run over the grid in the same order, and the
/// denominator, the same for every target, is summed once.
pub fn fit_weights_many<const T: usize>(basis: &Basis, targets: [&[f64]; T]) -> [Vec<f64>; T] {
    let b = basis.len();
    // `num[i][t]`: the targets side by side, so each step is one vector
    // operation across them (their sums stay apart, each in grid order).
    let mut num = vec![[0.0; T]; b];
    let mut den = vec![0.0; b];
    // As `fit_weights`' zip: the grid points both the basis and every
    // target have.
    let n = targets
        .iter()
        .fold(basis.grid_points(), |n, t| n.min(t.len()));
    for k in 0..n {
        let (x, row) = (basis.x[k], basis.row(k));
        let f: [f64; T] = std::array::from_fn(|t| targets[t][k]);
        for (acc, &p) in num.iter_mut().zip(row) {
            let xp = x * p;
            for t in 0..T {
                acc[t] += xp * f[t];
            }
        }
        for (acc, &p) in den.iter_mut().zip(row) {
            *acc += x * x * p;
        }
    }
    std::array::from_fn(|t| {
        num.iter()
            .zip(&den)
            .map(|(n, d)| if *d < 1e-300 { 0.0 } else { n[t] / d })
            .collect()
    })
}

/// [`forcing_from_weights`] of `T` weight vectors, to the bit: each grid
/// point's basis row is read once and its `T` sums run side by side, each
/// over the basis functions in order from `-0.0` (as `Iterator::sum`).
pub fn forcing_many<const T: usize>(basis: &Basis, weights: [&[f64]; T]) -> [Vec<f64>; T] {
    let n = basis.grid_points();
    let mut out: [Vec<f64>; T] = std::array::from_fn(|_| Vec::with_capacity(n));
    let b = weights.iter().fold(basis.len(), |b, w| b.min(w.len()));
    // `wt[i][t]`: the weight vectors side by side, so the `T` sums of a
    // row are one vector operation per basis function.
    let wt: Vec<[f64; T]> = (0..b)
        .map(|i| std::array::from_fn(|t| weights[t][i]))
        .collect();
    for k in 0..n {
        let mut dot = [-0.0f64; T];
        for (&p, w) in basis.row(k)[..b].iter().zip(&wt) {
            for t in 0..T {
                dot[t] += p * w[t];
            }
        }
        for (out, dot) in out.iter_mut().zip(dot) {
            out.push(basis.x[k] * dot / basis.psi_sum[k]);
        }
    }
    out
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
        // The nine fits in one pass over the basis, then the nine forcing
        // terms in another: the bits of nine calls of `fit_weights` and
        // `forcing_from_weights`, with the basis read twice instead of 18
        // times and nine independent sums per row instead of one.
        let targets: [&[f64]; 9] = std::array::from_fn(|t| parts[t / 3][t % 3].as_slice());
        let fitted = fit_weights_many(basis, targets);
        let fitted_refs: [&[f64]; 9] = std::array::from_fn(|t| fitted[t].as_slice());
        let forcing = forcing_many(basis, fitted_refs);
        let mut f = vec![[[0.0; 3]; 3]; n];
        for (t, fj) in forcing.iter().enumerate() {
            for (k, &v) in fj.iter().enumerate() {
                f[k][t / 3][t % 3] = v;
            }
        }
        let [a0, a1, a2, b0, b1, b2, c0, c1, c2] = fitted;
        Self {
            f,
            weights: [[a0, a1, a2], [b0, b1, b2], [c0, c1, c2]],
        }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fit::settings::DmpSettings;

    #[test]
    fn the_batched_fit_gives_the_bits_of_one_fit_at_a_time() {
        let basis = Basis::new(&DmpSettings::default(), 301).expect("basis");
        // Nine targets of different shapes, one with signed zeros and one
        // zero throughout.
        let targets: [Vec<f64>; 9] = std::array::from_fn(|t| {
            (0..301)
                .map(|k| {
                    let s = k as f64 / 300.0;
                    match t {
                        0 => 0.0,
                        1 => -0.0,
                        _ => (s * (t as f64 + 0.3)).sin() * (1.0 + t as f64 * s * s) - 0.2,
                    }
                })
                .collect()
        });
        let refs: [&[f64]; 9] = std::array::from_fn(|t| targets[t].as_slice());
        let many = fit_weights_many(&basis, refs);
        let many_refs: [&[f64]; 9] = std::array::from_fn(|t| many[t].as_slice());
        let forcing = forcing_many(&basis, many_refs);
        for t in 0..9 {
            let one = fit_weights(&basis, &targets[t]);
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&many[t]), bits(&one), "weights of target {t}");
            let f = forcing_from_weights(&basis, &one);
            assert_eq!(bits(&forcing[t]), bits(&f), "forcing of target {t}");
        }
    }
}
