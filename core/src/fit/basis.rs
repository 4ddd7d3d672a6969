//! The canonical system `x(s) = exp(-alpha_x s)` and the Gaussian basis
//! `psi_i(x) = exp(-h_i (x - c_i)^2)` on the integration grid.

use crate::error::{Error, Result};
use crate::fit::settings::DmpSettings;

/// The basis evaluated on a unit-time grid of `n` points.
#[derive(Clone, Debug)]
pub struct Basis {
    /// Centres `c_i`.
    pub centres: Vec<f64>,
    /// Widths `h_i`.
    pub widths: Vec<f64>,
    /// The phase `x(s_k)` at each grid point.
    pub x: Vec<f64>,
    /// `psi[k][i] = psi_i(x(s_k))`, row-major, `n` rows of `B`.
    pub psi: Vec<f64>,
    /// `sum_i psi_i(x(s_k))` per grid point.
    pub psi_sum: Vec<f64>,
}

impl Basis {
    /// The basis on the grid `s_k = k / (n - 1)`, `k = 0..n`.
    pub fn new(settings: &DmpSettings, n: usize) -> Result<Self> {
        let b = settings.basis_functions;
        if b < 2 {
            return Err(Error::InvalidSetting(format!(
                "a DMP needs at least 2 basis functions, got {b}"
            )));
        }
        if !(settings.alpha_x.is_finite() && settings.alpha_x > 0.0) {
            return Err(Error::InvalidSetting(format!(
                "alpha_x must be positive, got {}",
                settings.alpha_x
            )));
        }
        let alpha = settings.alpha_x;
        let centres: Vec<f64> = (0..b)
            .map(|i| crate::portable::exp(-alpha * i as f64 / (b - 1) as f64))
            .collect();
        let mut widths: Vec<f64> = centres
            .windows(2)
            .map(|c| 1.0 / ((c[1] - c[0]) * (c[1] - c[0])))
            .collect();
        widths.push(widths[b - 2]);
        let s = crate::prepare::numeric::linspace(1.0, n);
        let x: Vec<f64> = s
            .iter()
            .map(|&s| crate::portable::exp(-alpha * s))
            .collect();
        let mut psi = Vec::with_capacity(n * b);
        let mut psi_sum = Vec::with_capacity(n);
        for &xk in &x {
            let row_start = psi.len();
            psi.extend(
                centres
                    .iter()
                    .zip(&widths)
                    .map(|(c, h)| crate::portable::exp(-h * (xk - c) * (xk - c))),
            );
            psi_sum.push(psi[row_start..].iter().sum());
        }
        Ok(Self {
            centres,
            widths,
            x,
            psi,
            psi_sum,
        })
    }

    /// Number of basis functions.
    pub fn len(&self) -> usize {
        self.centres.len()
    }

    /// Whether there are no basis functions (never for a built basis).
    pub fn is_empty(&self) -> bool {
        self.centres.is_empty()
    }

    /// Number of grid points.
    pub fn grid_points(&self) -> usize {
        self.x.len()
    }

    /// `psi_i(x(s_k))` for all i at grid point k.
    pub fn row(&self, k: usize) -> &[f64] {
        let b = self.len();
        &self.psi[k * b..(k + 1) * b]
    }
}
