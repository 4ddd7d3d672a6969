//! The rules that pick gains in the acceptable region (method.md section
//! 11), how to pick, and a picked gain pair with what a robot needs of it.

use serde::{Deserialize, Serialize};

use crate::extract::point::GainPoint;
use crate::extract::robot::RobotGains;

/// The default eps of the acceptable region (the flatness threshold).
pub const DEFAULT_EPS: f64 = 0.02;

/// The damping ratios a `compliant` pick accepts.
pub const COMPLIANT_ZETA: [f64; 2] = [0.7, 1.5];

/// A rule that picks gains in the acceptable region.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum PickRule {
    /// J's refined optimum (the paper).
    Optimum,
    /// The least K/M with zeta in [0.7, 1.5].
    Compliant,
    /// zeta nearest 1, then the least K/M.
    Critical,
    /// The least max-over-demos a_peak.
    Smooth,
}

impl PickRule {
    /// Every rule, in the order menus list them.
    pub const ALL: [Self; 4] = [Self::Optimum, Self::Compliant, Self::Critical, Self::Smooth];

    /// Its name on the command line and in JSON.
    pub fn name(self) -> &'static str {
        match self {
            Self::Optimum => "optimum",
            Self::Compliant => "compliant",
            Self::Critical => "critical",
            Self::Smooth => "smooth",
        }
    }

    /// What it chooses, in words.
    pub fn rule_text(self) -> &'static str {
        match self {
            Self::Optimum => "J's refined optimum",
            Self::Compliant => "the least K/M with zeta in [0.7, 1.5] (soft and well damped)",
            Self::Critical => "zeta nearest 1 (critically damped), then the least K/M",
            Self::Smooth => "the least peak acceleration of any demo",
        }
    }
}

impl std::str::FromStr for PickRule {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        Self::ALL
            .into_iter()
            .find(|r| r.name() == s)
            .ok_or_else(|| format!("unknown pick {s:?}: optimum, compliant, critical or smooth"))
    }
}

/// A picked gain pair and everything a robot needs to know of it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Pick {
    /// The rule that chose it.
    pub rule: PickRule,
    /// The gains and J, S and sum d there (read through `Deref`:
    /// `pick.dm`).
    #[serde(flatten)]
    pub at: GainPoint,
    /// E there, metres (`None` without a skill error).
    pub e_sum: Option<f64>,
    /// The largest a_peak of any demo there, m/s^2 of unit time.
    pub a_peak_max: f64,
    /// Why this rule and this point, in words.
    pub why: String,
    /// The spring-damper's 2 % settling time there (method.md section 11,
    /// "Settling").
    pub settling: Settling,
    /// Whether it lies on the grid's edge in the direction its rule pushes
    /// (the rule would go further in a wider box).
    pub on_edge: bool,
    /// The sides it lies on in that direction, in words ("" when not).
    pub edge: String,
    /// The gains in real time at the demos' mean duration.
    pub robot: RobotGains,
}

impl Pick {
    /// The pick in one line, as `extract` prints it: `picked by compliant:
    /// D/M 12.3, K/M 45.6 (zeta 0.900)`.
    pub fn headline(&self) -> String {
        format!(
            "picked by {}: D/M {}, K/M {} (zeta {:.3})",
            self.rule.name(),
            crate::extract::allowed::numbers::num(self.dm),
            crate::extract::allowed::numbers::num(self.km),
            self.zeta
        )
    }
}

/// The 2 % settling time of the spring-damper at a gain pair (method.md
/// section 11): `ln(50) / sigma`, `sigma` the decay rate of its slowest
/// mode.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Settling {
    /// In unit time.
    pub unit: f64,
    /// In seconds, at the demos' mean duration.
    pub seconds: f64,
}

impl Settling {
    /// The settling of `(dm, km)` over a motion of `duration` seconds.
    pub fn of(dm: f64, km: f64, duration: f64) -> Self {
        let unit = settling_unit(dm, km);
        Self {
            unit,
            seconds: unit * duration,
        }
    }
}

/// The 2 % settling time in unit time (method.md section 11): the decay
/// rate of the slowest mode is `D/2` when `D^2 < 4 K`, else
/// `(D - sqrt(D^2 - 4 K)) / 2`; infinite without damping or stiffness.
pub fn settling_unit(dm: f64, km: f64) -> f64 {
    if !(dm > 0.0 && km > 0.0) {
        return f64::INFINITY;
    }
    let disc = dm * dm - 4.0 * km;
    let sigma = if disc < 0.0 {
        dm / 2.0
    } else {
        (dm - disc.sqrt()) / 2.0
    };
    crate::portable::ln(50.0) / sigma
}

/// How to pick.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PickSettings {
    /// The rule; `None`: `optimum` when J is not flat, `compliant` when it
    /// is.
    pub rule: Option<PickRule>,
    /// The region's eps.
    pub eps: f64,
    /// An a_peak limit (m/s^2 of unit time) every pick keeps to.
    pub a_peak_limit: Option<f64>,
    /// A settling limit (unit time) the `compliant`, `critical` and
    /// `smooth` picks keep to (`--settle-within`; off by default).
    pub settle_within: Option<f64>,
}

impl Default for PickSettings {
    fn default() -> Self {
        Self {
            rule: None,
            eps: DEFAULT_EPS,
            a_peak_limit: None,
            settle_within: None,
        }
    }
}

impl Pick {
    /// The pick with its reason in words.
    pub(crate) fn with_why(mut self, why: String) -> Self {
        self.why = why;
        self
    }
}

impl std::ops::Deref for Pick {
    type Target = GainPoint;

    fn deref(&self) -> &GainPoint {
        &self.at
    }
}
