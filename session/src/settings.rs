//! The user's settings, persisted between runs (the app's storage, the
//! browser's local storage): the core's own serde types for loading,
//! preprocessing, the DMP and the grid, so the app has every option the CLI
//! has and every default is the core's.

use dmpscope_core::extract::diagnostics::DiagSettings;
use dmpscope_core::fit::settings::DmpSettings;
use dmpscope_core::landscape::grid::{AxisScale, Grid};
use dmpscope_core::load::options::LoadOptions;
use dmpscope_core::report::presets::PAPER_PRESETS;
use dmpscope_core::{DEFAULT_K, PrepSettings};
use serde::{Deserialize, Serialize};

/// Everything the user chose.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct Settings {
    /// How recordings are read (up axis, frame filter, what a demo is).
    pub load: LoadOptions,
    /// Preprocessing (Savitzky-Golay window and order).
    pub prep: PrepSettings,
    /// The DMP (basis functions).
    pub dmp: DmpSettings,
    /// The gain grid of the landscape.
    pub grid: Grid,
    /// Weight k of sum d in J.
    pub k: f64,
    /// The operating point (D/M, K/M).
    pub op: (f64, f64),
    /// Colour heat maps on a log scale.
    pub log_colour: bool,
    /// How the diagnostics are computed (resampled grid, bootstrap).
    pub diagnostics: DiagSettings,
    /// The largest peak acceleration allowed, m/s^2 (masks the J map and
    /// gives the constrained optimum); `None`: no limit.
    pub a_peak_limit: Option<f64>,
    /// How the gains are picked in the acceptable region (method.md
    /// section 11); `None`: optimum when J is not flat, compliant when it
    /// is.
    pub pick: Option<dmpscope_core::extract::allowed::PickRule>,
    /// The acceptable region's eps: J within this fraction of J*.
    pub accept_eps: f64,
    /// The settling limit (unit time) of the compliant, critical and
    /// smooth picks (`None`: off).
    #[serde(default)]
    pub settle_within: Option<f64>,
}

impl Default for Settings {
    fn default() -> Self {
        // The paper's Hrstc1, a gain pair inside the default box.
        let start = PAPER_PRESETS[1];
        let op = (start.dm, start.km);
        Self {
            load: LoadOptions::default(),
            prep: PrepSettings::default(),
            // The d_rot map when it is shown (it costs about twice the
            // position's kernel): the app turns it on from the map chooser.
            dmp: DmpSettings {
                orientation_map: false,
                ..DmpSettings::default()
            },
            grid: Grid::default(),
            k: DEFAULT_K,
            op,
            log_colour: true,
            diagnostics: DiagSettings::default(),
            a_peak_limit: None,
            pick: None,
            accept_eps: dmpscope_core::extract::allowed::DEFAULT_EPS,
            settle_within: None,
        }
    }
}

impl Settings {
    /// The defaults with `n` x `n` grid points (tests, quick looks).
    pub fn with_grid_points(n: usize) -> Self {
        let mut s = Self::default();
        s.set_grid_points(n);
        s
    }

    /// Points per grid axis (both axes share it in the app).
    pub fn grid_points(&self) -> usize {
        self.grid.dm.n
    }

    /// Sets the points of both grid axes.
    pub fn set_grid_points(&mut self, n: usize) {
        self.grid.dm.n = n;
        self.grid.km.n = n;
    }

    /// Whether the grid's axes are log-spaced.
    pub fn log_axes(&self) -> bool {
        self.grid.dm.scale == AxisScale::Log
    }

    /// Sets both axes' spacing.
    pub fn set_log_axes(&mut self, log: bool) {
        let scale = if log {
            AxisScale::Log
        } else {
            AxisScale::Linear
        };
        self.grid.dm.scale = scale;
        self.grid.km.scale = scale;
    }
}
