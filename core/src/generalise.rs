//! A fitted DMP run somewhere else: a new start, goal and duration
//! (method.md section 10).
//!
//! A [`Primitive`] is a forcing term on the unit-time grid at one gain pair,
//! with the start, goal and initial velocity it was fitted at: one demo's
//! ([`Primitive::of_demo`]) or the skill of many ([`crate::skill`]).
//! [`Primitive::rollout`] maps it to a [`Target`] by the chosen
//! [`Scaling`] and integrates it exactly as [`Model::rollout`] does; at the
//! primitive's own start, goal and duration (the target's defaults) the two
//! give the same bits.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::model::{Model, Rollout};

/// How the forcing term follows a moved goal (method.md section 10).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Scaling {
    /// The paper's per-axis factor `(g'_a - y0'_a) / (g_a - y0_a)`, left at
    /// 1 where `|g_a - y0_a| < 1e-9`.
    #[default]
    Paper,
    /// Frame-independent (Koutras and Doulgeri, 2020): the smallest rotation
    /// taking `g - y0` onto the direction of `g' - y0'`, times the ratio of
    /// their lengths.
    Frame,
}

impl Scaling {
    /// The name used on the command line and in exports.
    pub fn name(self) -> &'static str {
        match self {
            Self::Paper => "paper",
            Self::Frame => "frame",
        }
    }
}

/// Where and how long to run a primitive. `None` keeps the primitive's own.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Target {
    /// New start, absolute metres.
    pub start: Option<[f64; 3]>,
    /// New goal, absolute metres.
    pub goal: Option<[f64; 3]>,
    /// New duration T', seconds.
    pub duration_s: Option<f64>,
    /// Spatial scaling mode.
    pub scaling: Scaling,
}

/// A linear map of forcing terms and velocities from one displacement to
/// another. A diagonal is kept apart so that a factor of exactly 1 changes
/// no bit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Mapping {
    /// Per-axis factors.
    Diagonal([f64; 3]),
    /// A full matrix, row-major.
    Matrix([[f64; 3]; 3]),
}

impl Mapping {
    /// The identity.
    pub const IDENTITY: Self = Self::Diagonal([1.0; 3]);

    /// Applies the map to a vector.
    pub fn apply(&self, v: [f64; 3]) -> [f64; 3] {
        match self {
            Self::Diagonal(d) => std::array::from_fn(|a| d[a] * v[a]),
            Self::Matrix(m) => {
                std::array::from_fn(|a| m[a][0] * v[0] + m[a][1] * v[1] + m[a][2] * v[2])
            }
        }
    }

    /// The map as a row-major matrix.
    pub fn matrix(&self) -> [[f64; 3]; 3] {
        match self {
            Self::Diagonal(d) => {
                std::array::from_fn(|r| std::array::from_fn(|c| if r == c { d[r] } else { 0.0 }))
            }
            Self::Matrix(m) => *m,
        }
    }

    /// The map taking displacement `from` (`g - y0`) to `to` (`g' - y0'`)
    /// under `scaling`. Frame-independent scaling needs `from` non-zero.
    pub fn between(from: [f64; 3], to: [f64; 3], scaling: Scaling) -> Result<Self> {
        if from == to {
            return Ok(Self::IDENTITY);
        }
        match scaling {
            Scaling::Paper => Ok(Self::Diagonal(std::array::from_fn(|a| {
                if from[a].abs() < 1e-9 {
                    1.0
                } else {
                    to[a] / from[a]
                }
            }))),
            Scaling::Frame => {
                let (lf, lt) = (norm(from), norm(to));
                if lf < 1e-9 {
                    return Err(Error::InvalidSetting(
                        "frame-independent scaling needs a motion whose goal differs from its \
                         start; this one ends where it starts (use per-axis scaling)"
                            .into(),
                    ));
                }
                let s = lt / lf;
                let r = smallest_rotation(from.map(|v| v / lf), to.map(|v| v / lt.max(1e-300)));
                Ok(match r {
                    None => Self::Diagonal([s; 3]),
                    Some(r) => Self::Matrix(r.map(|row| row.map(|v| s * v))),
                })
            }
        }
    }
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The smallest rotation taking unit vector `a` to unit vector `b`
/// (Rodrigues), `None` when they are parallel (the identity). Vectors
/// within 1e-6 of opposite turn by exactly pi about an axis perpendicular
/// to `a`: near there the smallest rotation's axis depends on the last bits
/// of the inputs, so two implementations would not agree.
fn smallest_rotation(a: [f64; 3], b: [f64; 3]) -> Option<[[f64; 3]; 3]> {
    let c = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let axis = cross(a, b);
    let sin = norm(axis);
    if sin < PARALLEL_SIN && c > 0.0 {
        return None;
    }
    let (k, s, v) = if sin < OPPOSITE_SIN && c <= 0.0 {
        // Opposite: any axis perpendicular to `a`; take the cross product
        // with the (first) coordinate axis least aligned with it.
        let least = (0..3)
            .min_by(|&i, &j| a[i].abs().total_cmp(&a[j].abs()))
            .unwrap_or(0);
        let mut e = [0.0; 3];
        e[least] = 1.0;
        let p = cross(a, e);
        let lp = norm(p);
        (p.map(|v| v / lp), 0.0, 2.0)
    } else {
        let angle = sin.atan2(c);
        (axis.map(|v| v / sin), angle.sin(), 1.0 - angle.cos())
    };
    Some([
        [
            1.0 - v * (k[1] * k[1] + k[2] * k[2]),
            v * k[0] * k[1] - s * k[2],
            v * k[0] * k[2] + s * k[1],
        ],
        [
            v * k[0] * k[1] + s * k[2],
            1.0 - v * (k[0] * k[0] + k[2] * k[2]),
            v * k[1] * k[2] - s * k[0],
        ],
        [
            v * k[0] * k[2] - s * k[1],
            v * k[1] * k[2] + s * k[0],
            1.0 - v * (k[0] * k[0] + k[1] * k[1]),
        ],
    ])
}

/// The shortest duration a target may ask for, seconds.
pub const MIN_DURATION_S: f64 = 1e-3;
/// The longest duration a target may ask for, seconds.
pub const MAX_DURATION_S: f64 = 1e6;

/// Below this `|a x b|` with `a . b > 0`, the directions are the same.
const PARALLEL_SIN: f64 = 1e-15;
/// Below this `|a x b|` with `a . b <= 0`, the directions are opposite.
const OPPOSITE_SIN: f64 = 1e-6;

/// A forcing term at one gain pair with the motion it was fitted to.
#[derive(Clone, Debug, PartialEq)]
pub struct Primitive {
    /// The demo's name, or `skill (N demos)`.
    pub name: String,
    /// D/M the forcing term was fitted at.
    pub dm: f64,
    /// K/M the forcing term was fitted at.
    pub km: f64,
    /// `alpha_x` of the canonical system.
    pub alpha_x: f64,
    /// Origin of the relative coordinates below (absolute metres).
    pub origin: [f64; 3],
    /// Own start, relative to `origin`.
    pub y0: [f64; 3],
    /// Own goal, relative to `origin`.
    pub goal: [f64; 3],
    /// Initial velocity `y'(0)` in unit time.
    pub v0: [f64; 3],
    /// Own duration T, seconds.
    pub duration_s: f64,
    /// LWR weights per axis of the forcing term.
    pub weights: [Vec<f64>; 3],
    /// The forcing term on the grid, times `dt^2` (the integration's form).
    fdt2: Vec<[f64; 3]>,
    /// Skills only: every member's forcing term (times `dt^2`) and initial
    /// velocity, mapped into the skill's frame, for the band.
    members: Vec<(Vec<[f64; 3]>, [f64; 3])>,
}

/// A primitive run at a target: unit-time and real-time kinematics.
#[derive(Clone, Debug, PartialEq)]
pub struct Generalised {
    /// Unit-time path: absolute positions, `y'` and `y''` in unit time.
    pub unit: Rollout,
    /// Real time of each point, seconds (0 to T').
    pub t: Vec<f64>,
    /// Real-time velocity, m/s (`y' / T'`).
    pub v: Vec<[f64; 3]>,
    /// Real-time acceleration, m/s^2 (`y'' / T'^2`).
    pub a: Vec<[f64; 3]>,
    /// Start, absolute.
    pub start: [f64; 3],
    /// Goal, absolute.
    pub goal: [f64; 3],
    /// Duration T', seconds.
    pub duration_s: f64,
    /// The map applied to the forcing term and initial velocity.
    pub mapping: Mapping,
    /// Skills: per-time SD of the members' positions (absolute band
    /// half-width per axis); empty for a demo.
    pub band: Vec<[f64; 3]>,
    /// Largest real-time speed, m/s.
    pub peak_speed: f64,
    /// Largest real-time acceleration norm, m/s^2.
    pub a_peak: f64,
    /// Distance of the last point from the goal, metres.
    pub final_error: f64,
    /// What the user should know (a near-singular axis under per-axis
    /// scaling).
    pub warnings: Vec<String>,
}

impl Primitive {
    /// Demo `i` of `model` at gains `(dm, km)`.
    pub fn of_demo(model: &Model, i: usize, dm: f64, km: f64) -> Result<Self> {
        let Some(demo) = model.demos().get(i) else {
            return Err(Error::InvalidSetting(format!(
                "--demo {} is out of range: there are {} demos (numbered from 1)",
                i + 1,
                model.demos().len()
            )));
        };
        check_gains(dm, km)?;
        let n = demo.len();
        let dt = 1.0 / (n - 1) as f64;
        let dt2 = dt * dt;
        // The same products and sums as the model's kernel and rollout.
        let fdt2 = model
            .projections(i)
            .f
            .iter()
            .map(|fk| {
                std::array::from_fn(|ax| {
                    let [f0, f1, f2] = fk[ax];
                    f0 * dt2 + dm * (f1 * dt2) + km * (f2 * dt2)
                })
            })
            .collect();
        Ok(Self {
            name: demo.name.clone(),
            dm,
            km,
            alpha_x: model.settings().alpha_x,
            origin: demo.p0,
            y0: demo.y_raw[0],
            goal: demo.goal,
            v0: demo.yd[0],
            duration_s: demo.duration_s,
            weights: std::array::from_fn(|ax| model.projections(i).weights_at(ax, dm, km)),
            fdt2,
            members: Vec::new(),
        })
    }

    /// Assembles a skill (used by [`crate::skill`]).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn skill_parts(
        name: String,
        (dm, km, alpha_x): (f64, f64, f64),
        (origin, y0, goal, v0): ([f64; 3], [f64; 3], [f64; 3], [f64; 3]),
        duration_s: f64,
        weights: [Vec<f64>; 3],
        fdt2: Vec<[f64; 3]>,
        members: Vec<(Vec<[f64; 3]>, [f64; 3])>,
    ) -> Self {
        Self {
            name,
            dm,
            km,
            alpha_x,
            origin,
            y0,
            goal,
            v0,
            duration_s,
            weights,
            fdt2,
            members,
        }
    }

    /// Grid points of the unit-time integration.
    pub fn len(&self) -> usize {
        self.fdt2.len()
    }

    /// Whether the grid is empty (never for a built primitive).
    pub fn is_empty(&self) -> bool {
        self.fdt2.is_empty()
    }

    /// The forcing term `f(x_k)` on the grid.
    pub fn forcing(&self) -> Vec<[f64; 3]> {
        let dt2 = self.dt() * self.dt();
        self.fdt2.iter().map(|f| f.map(|v| v / dt2)).collect()
    }

    /// The forcing term times `dt^2`, as integrated.
    pub(crate) fn forcing_dt2(&self) -> &[[f64; 3]] {
        &self.fdt2
    }

    fn dt(&self) -> f64 {
        1.0 / (self.fdt2.len().max(2) - 1) as f64
    }

    /// Own start, absolute.
    pub fn start_abs(&self) -> [f64; 3] {
        std::array::from_fn(|a| self.y0[a] + self.origin[a])
    }

    /// Own goal, absolute.
    pub fn goal_abs(&self) -> [f64; 3] {
        std::array::from_fn(|a| self.goal[a] + self.origin[a])
    }

    /// The diagonal of the bounding box of the start, the goal and the
    /// path at its own target: the motion's extent, metres.
    fn extent(&self) -> f64 {
        let path = self.integrate(self.y0, self.goal, &self.fdt2, self.v0).y;
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for p in path.iter().chain([&self.goal]) {
            for a in 0..3 {
                lo[a] = lo[a].min(p[a]);
                hi[a] = hi[a].max(p[a]);
            }
        }
        norm(std::array::from_fn(|a| hi[a] - lo[a]))
    }

    /// Runs the primitive at `target`: from its start to its goal over its
    /// duration, the forcing term and initial velocity mapped by the
    /// scaling. Errors name the argument at fault.
    pub fn rollout(&self, target: &Target) -> Result<Generalised> {
        let start = target.start.unwrap_or_else(|| self.start_abs());
        let goal = target.goal.unwrap_or_else(|| self.goal_abs());
        let duration = target.duration_s.unwrap_or(self.duration_s);
        for (what, v) in [("--start", start), ("--goal", goal)] {
            if v.iter().any(|c| !c.is_finite()) {
                return Err(Error::InvalidSetting(format!(
                    "the {} ({what}) must be three finite numbers, got {v:?}",
                    what.trim_start_matches('-')
                )));
            }
        }
        if !(duration.is_finite() && duration > 0.0) {
            return Err(Error::InvalidSetting(format!(
                "the duration (--duration) must be a positive number of seconds, got {duration}"
            )));
        }
        if !(MIN_DURATION_S..=MAX_DURATION_S).contains(&duration) {
            return Err(Error::InvalidSetting(format!(
                "the duration (--duration) must be between {MIN_DURATION_S} s and \
                 {MAX_DURATION_S} s, got {duration}"
            )));
        }
        if start == goal {
            return Err(Error::InvalidSetting(format!(
                "the goal (--goal) equals the start (--start), {start:?}: a point-to-point \
                 motion needs them apart"
            )));
        }
        // Relative coordinates: the defaults keep the primitive's own bits.
        let y0 = match target.start {
            Some(s) => std::array::from_fn(|a| s[a] - self.origin[a]),
            None => self.y0,
        };
        let g = match target.goal {
            Some(s) => std::array::from_fn(|a| s[a] - self.origin[a]),
            None => self.goal,
        };
        // The map from the absolute numbers an export holds (docs/export.md),
        // so a runner computes the same one; at the defaults from == to.
        let (own_start, own_goal) = (self.start_abs(), self.goal_abs());
        let from: [f64; 3] = std::array::from_fn(|a| own_goal[a] - own_start[a]);
        let to: [f64; 3] = std::array::from_fn(|a| goal[a] - start[a]);
        let mapping = Mapping::between(from, to, target.scaling).map_err(|e| match e {
            Error::InvalidSetting(m) => Error::InvalidSetting(format!("{}: {m}", self.name)),
            other => other,
        })?;
        let mut warnings = Vec::new();
        if let (Scaling::Paper, Mapping::Diagonal(factors)) = (target.scaling, mapping) {
            let extent = self.extent();
            for (a, axis) in ["x", "y", "z"].iter().enumerate() {
                // Only where the factor does something.
                if from[a].abs() < 0.05 * extent && (factors[a] - 1.0).abs() > 1e-6
                    || from[a].abs() < 1e-9 && to[a].abs() >= 1e-9
                {
                    warnings.push(format!(
                        "{}: start and goal differ by {:.1} mm on {axis}, under 5 % of the \
                         motion's {:.0} mm; per-axis scaling {} there (try --scaling frame)",
                        self.name,
                        from[a].abs() * 1e3,
                        extent * 1e3,
                        if from[a].abs() < 1e-9 {
                            "leaves that axis's forcing term unscaled".to_owned()
                        } else {
                            format!("multiplies that axis's forcing term by {:.3}", factors[a])
                        }
                    ));
                }
            }
        }
        let n = self.fdt2.len();
        let dt = self.dt();
        let fdt2: Vec<[f64; 3]> = if mapping == Mapping::IDENTITY {
            self.fdt2.clone()
        } else {
            self.fdt2.iter().map(|f| mapping.apply(*f)).collect()
        };
        let v0 = mapping.apply(self.v0);
        let mut unit = self.integrate(y0, g, &fdt2, v0);
        for p in &mut unit.y {
            *p = std::array::from_fn(|a| p[a] + self.origin[a]);
        }
        if let Some(s) = target.start {
            // The state at step 0 is the start, exactly.
            unit.y[0] = s;
        }
        let band = self.band(y0, g, &mapping, &unit.y);
        let t: Vec<f64> = (0..n).map(|k| duration * k as f64 * dt).collect();
        let v: Vec<[f64; 3]> = unit.v.iter().map(|v| v.map(|c| c / duration)).collect();
        let dur2 = duration * duration;
        let a: Vec<[f64; 3]> = unit.a.iter().map(|a| a.map(|c| c / dur2)).collect();
        let finite = |rows: &[[f64; 3]]| rows.iter().flatten().all(|c| c.is_finite());
        if !(finite(&unit.y) && finite(&v) && finite(&a) && finite(&band)) {
            return Err(Error::InvalidSetting(format!(
                "{}: the motion diverges at D/M {} and K/M {} over {duration} s (its numbers \
                 overflow): nothing to run or export",
                self.name, self.dm, self.km
            )));
        }
        let peak_speed = v.iter().map(|v| norm(*v)).fold(0.0, f64::max);
        let a_peak = a.iter().map(|a| norm(*a)).fold(0.0, f64::max);
        let last = unit.y[n - 1];
        let final_error = norm(std::array::from_fn(|c| last[c] - goal[c]));
        Ok(Generalised {
            unit,
            t,
            v,
            a,
            start,
            goal,
            duration_s: duration,
            mapping,
            band,
            peak_speed,
            a_peak,
            final_error,
            warnings,
        })
    }

    /// Per-time SD (N - 1) of the members' positions at the target.
    fn band(
        &self,
        y0: [f64; 3],
        g: [f64; 3],
        mapping: &Mapping,
        mean: &[[f64; 3]],
    ) -> Vec<[f64; 3]> {
        let m = self.members.len();
        if m < 2 {
            return if m == 1 {
                vec![[0.0; 3]; mean.len()]
            } else {
                Vec::new()
            };
        }
        let mut sum2 = vec![[0.0; 3]; mean.len()];
        for (fdt2, v0) in &self.members {
            let mapped: Vec<[f64; 3]> = fdt2.iter().map(|f| mapping.apply(*f)).collect();
            let path = self.integrate(y0, g, &mapped, mapping.apply(*v0)).y;
            for (k, p) in path.iter().enumerate() {
                for a in 0..3 {
                    let e = p[a] + self.origin[a] - mean[k][a];
                    sum2[k][a] += e * e;
                }
            }
        }
        sum2.iter()
            .map(|s| s.map(|v| (v / (m - 1) as f64).sqrt()))
            .collect()
    }

    /// The full unit-time rollout (relative positions) of an already
    /// mapped forcing term: the arithmetic of [`Model::rollout`].
    fn integrate(&self, y0: [f64; 3], g: [f64; 3], fdt2: &[[f64; 3]], v0: [f64; 3]) -> Rollout {
        let n = fdt2.len();
        let dt = self.dt();
        let dt2 = dt * dt;
        let (ddt, kdt2) = (self.dm * dt, self.km * dt2);
        let mut z: [f64; 3] = std::array::from_fn(|a| y0[a] - g[a]);
        let mut u: [f64; 3] = v0.map(|v| v * dt);
        let mut out = Rollout {
            y: Vec::with_capacity(n),
            v: Vec::with_capacity(n),
            a: Vec::with_capacity(n),
        };
        for f in fdt2 {
            let mut acc = [0.0; 3];
            out.y.push(std::array::from_fn(|a| z[a] + g[a]));
            out.v.push(u.map(|u| u / dt));
            for a in 0..3 {
                let du = f[a] - kdt2 * z[a] - ddt * u[a];
                acc[a] = du / dt2;
                u[a] += du;
                z[a] += u[a];
            }
            out.a.push(acc);
        }
        out
    }
}

/// Gains must be positive and finite.
pub(crate) fn check_gains(dm: f64, km: f64) -> Result<()> {
    for (name, v) in [("D/M", dm), ("K/M", km)] {
        if !(v.is_finite() && v > 0.0) {
            return Err(Error::InvalidSetting(format!(
                "{name} must be a positive number, got {v}"
            )));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_smallest_rotation_takes_a_to_b() {
        let a = [1.0, 0.0, 0.0];
        for b in [
            [0.0, 1.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.6, 0.0, 0.8],
            [-0.36, 0.48, 0.8],
        ] {
            let r = smallest_rotation(a, b).expect("not parallel");
            let got = Mapping::Matrix(r).apply(a);
            for c in 0..3 {
                assert!((got[c] - b[c]).abs() < 1e-15, "{got:?} vs {b:?}");
            }
            // Orthonormal.
            for i in 0..3 {
                for j in 0..3 {
                    let dot: f64 = (0..3).map(|k| r[i][k] * r[j][k]).sum();
                    let want = if i == j { 1.0 } else { 0.0 };
                    assert!((dot - want).abs() < 1e-15);
                }
            }
        }
        assert!(smallest_rotation(a, a).is_none());
        // Within 1e-6 rad of opposite: exactly the pi turn, whatever the
        // last bits.
        let near = [-1.0, 1e-8, 0.0];
        let len = norm(near);
        let r = smallest_rotation(a, near.map(|v| v / len)).expect("opposite");
        let exact = smallest_rotation(a, [-1.0, 0.0, 0.0]).expect("opposite");
        assert_eq!(r, exact);
        assert_eq!(Mapping::Matrix(r).apply(a), [-1.0, 0.0, 0.0]);
    }

    #[test]
    fn per_axis_factors_leave_a_still_axis_alone() {
        let m =
            Mapping::between([0.2, 0.0, 1e-12], [0.4, 0.3, 0.1], Scaling::Paper).expect("paper");
        assert_eq!(m, Mapping::Diagonal([2.0, 1.0, 1.0]));
        assert!(Mapping::between([0.0; 3], [0.1, 0.0, 0.0], Scaling::Frame).is_err());
    }
}
