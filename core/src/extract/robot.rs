//! Gains as a robot sees them (method.md section 11): the unit-time gains
//! per unit mass turned into real time at a duration T, and the
//! spring-damper's natural frequency, damping ratio and 2 % settling time.

use crate::portable::{cos, exp, ln, sin};
use serde::{Deserialize, Serialize};

/// The band a settled response stays within, as a fraction of the distance
/// it started from.
pub const SETTLE_BAND: f64 = 0.02;

/// One gain pair for a robot running the motion over `duration_s`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct RobotGains {
    /// The duration T the real-time numbers are for, seconds (the demos'
    /// mean duration unless a target says otherwise).
    pub duration_s: f64,
    /// Stiffness per unit mass in real time, `K/M / T^2`, 1/s^2.
    pub stiffness_per_mass: f64,
    /// Damping per unit mass in real time, `D/M / T`, 1/s.
    pub damping_per_mass: f64,
    /// Natural frequency `sqrt(K/M) / T`, rad/s.
    pub natural_frequency_rad_s: f64,
    /// The same in Hz.
    pub natural_frequency_hz: f64,
    /// Damping ratio `D / (2 sqrt(K))` (the same in unit and real time).
    pub zeta: f64,
    /// The time after which the spring-damper released at rest from the
    /// goal's distance stays within 2 % of it, seconds.
    pub settling_time_s: f64,
}

impl RobotGains {
    /// The gains `(dm, km)` of the unit-time DMP run over `duration_s`.
    pub fn new(dm: f64, km: f64, duration_s: f64) -> Self {
        let t = duration_s;
        let wn = km.sqrt();
        Self {
            duration_s: t,
            stiffness_per_mass: km / (t * t),
            damping_per_mass: dm / t,
            natural_frequency_rad_s: wn / t,
            natural_frequency_hz: wn / t / std::f64::consts::TAU,
            zeta: crate::landscape::model::zeta(dm, km),
            settling_time_s: settling_time(dm, km) * t,
        }
    }

    /// One line: `K/M 4.0678 1/s^2, D/M 5.2016 1/s in real time at T = 2.488 s:
    /// natural frequency 2.017 rad/s (0.321 Hz), zeta 1.290, 2 % settling
    /// time 4.347 s`.
    pub fn text(&self) -> String {
        format!(
            "K/M {:.4} 1/s^2, D/M {:.4} 1/s in real time at T = {:.3} s: natural frequency \
             {:.3} rad/s ({:.3} Hz), zeta {:.3}, 2 % settling time {:.3} s",
            self.stiffness_per_mass,
            self.damping_per_mass,
            self.duration_s,
            self.natural_frequency_rad_s,
            self.natural_frequency_hz,
            self.zeta,
            self.settling_time_s
        )
    }
}

/// The 2 % settling time of `x'' + D x' + K x = 0` from `x = 1`, `x' = 0`,
/// in the time unit of the gains: the last time `|x|` is above
/// [`SETTLE_BAND`] (found on the exact solution, scanned on a fine grid up
/// to where the envelope is inside the band and refined by bisection).
pub fn settling_time(dm: f64, km: f64) -> f64 {
    if !(dm > 0.0 && km > 0.0 && dm.is_finite() && km.is_finite()) {
        return f64::INFINITY;
    }
    let x = Response::new(dm, km);
    let end = x.envelope_end();
    const STEPS: usize = 20_000;
    let h = end / STEPS as f64;
    let mut last_out = None;
    for k in (0..=STEPS).rev() {
        if x.at(k as f64 * h).abs() > SETTLE_BAND {
            last_out = Some(k);
            break;
        }
    }
    let Some(k) = last_out else {
        return 0.0;
    };
    // |x| > band at k h and <= band at (k + 1) h: bisect the crossing.
    let (mut lo, mut hi) = (k as f64 * h, ((k + 1) as f64 * h).min(end));
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if x.at(mid).abs() > SETTLE_BAND {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    hi
}

/// The free response from `x = 1`, `x' = 0`, in closed form.
enum Response {
    /// `zeta < 1`: `e^{-s t} (cos w t + s / w sin w t)`.
    Under { s: f64, w: f64 },
    /// `zeta = 1` (to rounding): `e^{-w t} (1 + w t)`.
    Critical { w: f64 },
    /// `zeta > 1`: `(r2 e^{r1 t} - r1 e^{r2 t}) / (r2 - r1)`, `r1 > r2`.
    Over { r1: f64, r2: f64 },
}

impl Response {
    fn new(dm: f64, km: f64) -> Self {
        let disc = dm * dm - 4.0 * km;
        let scale = dm * dm + 4.0 * km;
        if disc.abs() <= 1e-12 * scale {
            Self::Critical { w: 0.5 * dm }
        } else if disc < 0.0 {
            Self::Under {
                s: 0.5 * dm,
                w: 0.5 * (-disc).sqrt(),
            }
        } else {
            let root = disc.sqrt();
            // r1 = (-D + root) / 2 without cancellation: 2K / (-D - root).
            let r2 = -0.5 * (dm + root);
            Self::Over { r1: km / r2, r2 }
        }
    }

    fn at(&self, t: f64) -> f64 {
        match *self {
            Self::Under { s, w } => exp(-s * t) * (cos(w * t) + s / w * sin(w * t)),
            Self::Critical { w } => exp(-w * t) * (1.0 + w * t),
            Self::Over { r1, r2 } => (r2 * exp(r1 * t) - r1 * exp(r2 * t)) / (r2 - r1),
        }
    }

    /// A time after which the response is surely inside the band.
    fn envelope_end(&self) -> f64 {
        let band = SETTLE_BAND;
        match *self {
            // |x| <= e^{-s t} sqrt(1 + (s/w)^2).
            Self::Under { s, w } => ln((1.0 + (s / w).powi(2)).sqrt() / band) / s,
            // e^{-w t} (1 + w t) <= 2 e^{-w t / 2} (since 1 + u <= 2 e^{u/2}).
            Self::Critical { w } => 2.0 * ln(2.0 / band) / w,
            // Both terms decay at least as e^{r1 t}; the sum of the
            // coefficients' magnitudes bounds the rest.
            Self::Over { r1, r2 } => {
                let c = (r2.abs() + r1.abs()) / (r2 - r1).abs();
                ln(c / band) / -r1
            }
        }
        .max(1e-9)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn settling_time_matches_the_textbook_and_a_fine_integration() {
        // Critically damped: x = e^{-wt}(1 + wt) crosses 0.02 at w t = 5.8335.
        let t = settling_time(2.0, 1.0);
        assert!((t - 5.833_5).abs() < 1e-3, "{t}");
        // Light damping: close to the envelope rule 4 / (zeta wn) in size.
        let (dm, km) = (1.0, 100.0);
        let t = settling_time(dm, km);
        assert!(t > 4.0 && t < 9.0, "{t}");
        // A fine semi-implicit Euler agrees on every case.
        for (dm, km) in [(10.73, 20.71), (25.0, 156.25), (1.0, 100.0), (60.0, 30.0)] {
            let (mut x, mut v, h) = (1.0f64, 0.0f64, 1e-5);
            let (mut t, mut last) = (0.0, 0.0);
            while t < 50.0 {
                v += (-dm * v - km * x) * h;
                x += v * h;
                t += h;
                if x.abs() > SETTLE_BAND {
                    last = t;
                }
            }
            let exact = settling_time(dm, km);
            assert!(
                (exact - last).abs() < 1e-3 * exact.max(1.0),
                "{dm} {km}: {exact} vs {last}"
            );
        }
        let r = RobotGains::new(10.0, 100.0, 2.0);
        assert_eq!(r.stiffness_per_mass, 25.0);
        assert_eq!(r.damping_per_mass, 5.0);
        assert_eq!(r.natural_frequency_rad_s, 5.0);
        assert_eq!(r.zeta, 0.5);
    }
}
