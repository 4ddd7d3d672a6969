//! The canonical system `x(s) = exp(-alpha_x s)` and the Gaussian basis
//! `psi_i(x) = exp(-h_i (x - c_i)^2)` on the integration grid.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};

/// DMP settings (method.md section 3; the paper's values are the defaults).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct DmpSettings {
    /// Number of basis functions `B`.
    pub basis_functions: usize,
    /// Decay of the canonical system, `alpha_x` (ln 100 puts x(1) at 0.01).
    pub alpha_x: f64,
    /// S's standardisation, an option beyond the method (method.md section
    /// 5): each axis's SD of a demo's target forcing term is floored at
    /// this fraction of that demo's largest axis SD, so an axis that barely
    /// moves is not blown up to unit variance. 0 (the default) is the
    /// method as written.
    #[serde(default)]
    pub axis_sd_floor: f64,
    /// How the skill error E follows each demo's start and goal (method.md
    /// section 11).
    #[serde(default)]
    pub skill_mode: crate::skill_error::SkillMode,
    /// The weight of the orientation error in J, per degree: `J = S + k
    /// sum d + k_rot sum d_rot` with `d_rot` in degrees (an option beyond
    /// the method, `--k-rot`; 0, the default, leaves J the paper's).
    #[serde(default)]
    pub k_rot: f64,
    /// Separate gains `[D/M, K/M]` for the orientation DMP (`None`, the
    /// default: the position's, one pair for the pose as method.md section
    /// 12 says); `--orientation-gains`.
    #[serde(default)]
    pub orientation_gains: Option<[f64; 2]>,
    /// Whether the landscape maps `sum d_rot` (method.md section 12):
    /// the orientation's kernel costs about twice the position's, so the
    /// app computes the map when it is shown (or `k_rot` needs it); the
    /// CLI always. Each evaluated point (Table I, the operating point) has
    /// its d_rot either way.
    /// (Settings saved before the option read as off, as the app's default.)
    #[serde(default)]
    pub orientation_map: bool,
}

impl Default for DmpSettings {
    fn default() -> Self {
        Self {
            basis_functions: 100,
            alpha_x: crate::portable::ln(100.0),
            axis_sd_floor: 0.0,
            skill_mode: crate::skill_error::SkillMode::Frame,
            k_rot: 0.0,
            orientation_gains: None,
            orientation_map: true,
        }
    }
}

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
        let s = crate::prepare::linspace(1.0, n);
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
