//! Savitzky-Golay smoothing and differentiation (method.md section 2.4):
//! a least-squares polynomial over a sliding window, evaluated at the
//! window's centre, and over the first and last windows at the edges (SciPy's
//! `savgol_filter(..., mode="interp")`).

use crate::error::{Error, Result};

/// The widest window `sg_seconds` gives, samples (its kernels grow with the
/// square of the width: 501 samples are 0.5 s at 1 kHz).
pub const MAX_SG_WINDOW: usize = 501;

/// Smoothed values and first and second derivatives of one signal.
#[derive(Clone, Debug, PartialEq)]
pub struct Smoothed {
    /// The smoothed signal.
    pub value: Vec<f64>,
    /// Its first derivative (per second, with the given sample spacing).
    pub d1: Vec<f64>,
    /// Its second derivative.
    pub d2: Vec<f64>,
}

/// A Savitzky-Golay filter of one window length and polynomial order: the
/// evaluation kernels for every offset in the window, for derivatives 0..=2.
#[derive(Clone, Debug)]
pub struct SavGol {
    window: usize,
    /// `kernels[d][t]`: weights over the window's samples that give the
    /// d-th derivative (unit spacing) of the fit at window position `t`.
    kernels: [Vec<Vec<f64>>; 3],
}

impl SavGol {
    /// A filter of an odd `window` and a polynomial `order` < `window`.
    pub fn new(window: usize, order: usize) -> Result<Self> {
        if window.is_multiple_of(2) || window < 3 {
            return Err(Error::InvalidSetting(format!(
                "Savitzky-Golay window must be odd and at least 3, got {window}"
            )));
        }
        if order >= window || order < 2 {
            return Err(Error::InvalidSetting(format!(
                "Savitzky-Golay order must be at least 2 (for the second derivative) and below the window {window}, got {order}"
            )));
        }
        let half = (window / 2) as f64;
        // Least squares in the scaled coordinate u = j / half, j = -half..=half,
        // which keeps the normal matrix well conditioned: L = (X^T X)^-1 X^T.
        let us: Vec<f64> = (0..window).map(|i| (i as f64 - half) / half).collect();
        let p = order + 1;
        let mut normal = vec![vec![0.0; p]; p];
        for a in 0..p {
            for b in 0..p {
                normal[a][b] = us.iter().map(|u| u.powi((a + b) as i32)).sum();
            }
        }
        let rhs: Vec<Vec<f64>> = (0..p)
            .map(|a| us.iter().map(|u| u.powi(a as i32)).collect())
            .collect();
        let lsq = solve(normal, rhs)?; // p x window: coefficient q of the fit
        let kernels = [0, 1, 2].map(|d| {
            (0..window)
                .map(|t| {
                    let u = us[t];
                    (0..window)
                        .map(|j| {
                            (d..p)
                                .map(|q| {
                                    let falling = (q - d + 1..=q).product::<usize>() as f64;
                                    falling * u.powi((q - d) as i32) * lsq[q][j]
                                })
                                .sum::<f64>()
                                / half.powi(d as i32)
                        })
                        .collect()
                })
                .collect()
        });
        Ok(Self { window, kernels })
    }

    /// The window length.
    pub fn window(&self) -> usize {
        self.window
    }

    /// The weights that give derivative `deriv` (0..=2, unit spacing) at the
    /// centre of the window.
    pub fn centre_kernel(&self, deriv: usize) -> &[f64] {
        &self.kernels[deriv][self.window / 2]
    }

    /// Smooths `signal` sampled every `spacing` seconds. The signal must be
    /// at least one window long.
    pub fn apply(&self, signal: &[f64], spacing: f64) -> Result<Smoothed> {
        let n = signal.len();
        let w = self.window;
        if n < w {
            return Err(Error::InvalidSetting(format!(
                "signal of {n} samples is shorter than the Savitzky-Golay window {w}"
            )));
        }
        let half = w / 2;
        let mut out = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
        for (d, o) in out.iter_mut().enumerate() {
            let scale = spacing.powi(d as i32);
            for (k, slot) in o.iter_mut().enumerate() {
                // The window holding k, and k's position inside it.
                let start = k.saturating_sub(half).min(n - w);
                let kernel = &self.kernels[d][k - start];
                let dot: f64 = kernel
                    .iter()
                    .zip(&signal[start..start + w])
                    .map(|(c, y)| c * y)
                    .sum();
                *slot = dot / scale;
            }
        }
        let [value, d1, d2] = out;
        Ok(Smoothed { value, d1, d2 })
    }
}

/// Solves `a x = b` for every right-hand side row of `b` (Gauss-Jordan with
/// partial pivoting); `b` is `p` rows of length `m`, so is the result.
fn solve(mut a: Vec<Vec<f64>>, mut b: Vec<Vec<f64>>) -> Result<Vec<Vec<f64>>> {
    let p = a.len();
    for col in 0..p {
        let pivot = (col..p)
            .max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))
            .unwrap_or(col);
        if a[pivot][col].abs() < 1e-300 {
            return Err(Error::InvalidSetting(
                "Savitzky-Golay normal equations are singular".into(),
            ));
        }
        a.swap(col, pivot);
        b.swap(col, pivot);
        let inv = 1.0 / a[col][col];
        for row in 0..p {
            if row == col {
                continue;
            }
            let factor = a[row][col] * inv;
            if factor == 0.0 {
                continue;
            }
            for c in 0..p {
                a[row][c] -= factor * a[col][c];
            }
            let (pivot_row, target) = if row < col {
                let (lo, hi) = b.split_at_mut(col);
                (&hi[0], &mut lo[row])
            } else {
                let (lo, hi) = b.split_at_mut(row);
                (&lo[col], &mut hi[0])
            };
            for (t, s) in target.iter_mut().zip(pivot_row) {
                *t -= factor * s;
            }
        }
    }
    for (i, row) in b.iter_mut().enumerate() {
        let inv = 1.0 / a[i][i];
        row.iter_mut().for_each(|v| *v *= inv);
    }
    Ok(b)
}
