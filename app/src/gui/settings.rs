//! What the app remembers between runs (eframe storage).

use dmpscope_core::landscape::{Axis, AxisScale, Grid};
use serde::{Deserialize, Serialize};

/// The user's settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct Settings {
    /// Points per grid axis.
    pub grid_n: usize,
    /// D/M range.
    pub dm_range: (f64, f64),
    /// K/M range.
    pub km_range: (f64, f64),
    /// Log-spaced axes (else linear).
    pub log_axes: bool,
    /// Colour heat maps on a log scale.
    pub log_colour: bool,
    /// Weight k of sum d in J.
    pub k: f64,
    /// Savitzky-Golay window.
    pub sg_window: usize,
    /// Savitzky-Golay order.
    pub sg_order: usize,
    /// DMP basis functions.
    pub basis: usize,
    /// The operating point (D/M, K/M).
    pub op: (f64, f64),
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            grid_n: 128,
            dm_range: (0.1, 1000.0),
            km_range: (0.1, 1000.0),
            log_axes: true,
            log_colour: true,
            k: dmpscope_core::DEFAULT_K,
            sg_window: 21,
            sg_order: 3,
            basis: 100,
            op: (25.0, 156.25),
        }
    }
}

impl Settings {
    /// The gain grid these settings describe.
    pub fn grid(&self) -> Grid {
        let scale = if self.log_axes {
            AxisScale::Log
        } else {
            AxisScale::Linear
        };
        let axis = |(lo, hi): (f64, f64)| Axis {
            lo,
            hi,
            n: self.grid_n,
            scale,
        };
        Grid {
            dm: axis(self.dm_range),
            km: axis(self.km_range),
        }
    }
}
