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

use crate::error::{Error, Result};
use crate::fit::mapping::norm;
pub use crate::fit::mapping::{Mapping, Scaling};
use crate::fit::orientation::OrientationRollout;
use crate::geom::Vec3;
use crate::landscape::model::{Model, Rollout};

/// Where and how long to run a primitive. `None` keeps the primitive's own.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Target {
    /// New start, absolute metres.
    pub start: Option<Vec3>,
    /// New goal, absolute metres.
    pub goal: Option<Vec3>,
    /// New duration T', seconds.
    pub duration_s: Option<f64>,
    /// Spatial scaling mode.
    pub scaling: Scaling,
    /// New start orientation, unit `[x, y, z, w]` (method.md section 12).
    pub start_orientation: Option<crate::rotation::QuatXyzw>,
    /// New goal orientation, unit `[x, y, z, w]`.
    pub goal_orientation: Option<crate::rotation::QuatXyzw>,
}

/// The shortest duration a target may ask for, seconds.
pub const MIN_DURATION_S: f64 = 1e-3;
/// The longest duration a target may ask for, seconds.
pub const MAX_DURATION_S: f64 = 1e6;

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
    pub origin: Vec3,
    /// Own start, relative to `origin`.
    pub y0: Vec3,
    /// Own goal, relative to `origin`.
    pub goal: Vec3,
    /// Initial velocity `y'(0)` in unit time.
    pub v0: Vec3,
    /// Own duration T, seconds.
    pub duration_s: f64,
    /// LWR weights per axis of the forcing term.
    pub weights: [Vec<f64>; 3],
    /// The forcing term on the grid, times `dt^2` (the integration's form).
    pub(crate) fdt2: Vec<Vec3>,
    /// Skills only: every member's forcing term (times `dt^2`) and initial
    /// velocity, mapped into the skill's frame, for the band.
    pub(crate) members: Vec<(Vec<Vec3>, Vec3)>,
    /// The diagonal of the bounding box of the start, the goal and the path
    /// at its own target (metres), computed once.
    pub(crate) extent: f64,
    /// The orientation DMP (method.md section 12), for a demo that has
    /// one; a skill has none.
    pub orientation: Option<crate::generalise::orientation::OrientationPrimitive>,
}

/// A primitive run at a target: unit-time and real-time kinematics.
#[derive(Clone, Debug, PartialEq)]
pub struct Generalised {
    /// Unit-time path: absolute positions, `y'` and `y''` in unit time.
    pub unit: Rollout,
    /// Real time of each point, seconds (0 to T').
    pub t: Vec<f64>,
    /// Real-time velocity, m/s (`y' / T'`).
    pub v: Vec<Vec3>,
    /// Real-time acceleration, m/s^2 (`y'' / T'^2`).
    pub a: Vec<Vec3>,
    /// Start, absolute.
    pub start: Vec3,
    /// Goal, absolute.
    pub goal: Vec3,
    /// Duration T', seconds.
    pub duration_s: f64,
    /// The map applied to the forcing term and initial velocity.
    pub mapping: Mapping,
    /// Skills: per-time SD of the members' positions (absolute band
    /// half-width per axis); empty for a demo.
    pub band: Vec<Vec3>,
    /// Largest real-time speed, m/s.
    pub peak_speed: f64,
    /// Largest real-time acceleration norm, m/s^2.
    pub a_peak: f64,
    /// Distance of the last point from the goal, metres.
    pub final_error: f64,
    /// What the user should know (a near-singular axis under per-axis
    /// scaling).
    pub warnings: Vec<String>,
    /// The orientation path in unit time, when the primitive has one.
    pub orientation: Option<OrientationRollout>,
    /// The goal orientation it ran to (its own when none was asked for; a
    /// new one with the sign the run took), with an orientation DMP.
    pub orientation_goal: Option<crate::rotation::QuatXyzw>,
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
                Vec3::from_fn(|ax, _| {
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
            extent: 0.0,
            orientation: crate::generalise::orientation::OrientationPrimitive::of_demo(
                model, i, dm, km,
            ),
        }
        .with_extent())
    }

    /// Sets [`Self::extent`] from the primitive's own run (every
    /// constructor ends here; the per-axis warning reads it).
    pub(crate) fn with_extent(mut self) -> Self {
        let path = self.integrate(self.y0, self.goal, &self.fdt2, self.v0).y;
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for p in path.iter().chain([&self.goal]) {
            for a in 0..3 {
                lo[a] = lo[a].min(p[a]);
                hi[a] = hi[a].max(p[a]);
            }
        }
        self.extent = norm(Vec3::from_fn(|a, _| hi[a] - lo[a]));
        self
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
    pub fn forcing(&self) -> Vec<Vec3> {
        let dt2 = self.dt() * self.dt();
        self.fdt2.iter().map(|f| f.map(|v| v / dt2)).collect()
    }

    fn dt(&self) -> f64 {
        1.0 / (self.fdt2.len().max(2) - 1) as f64
    }

    /// Own start, absolute.
    pub fn start_abs(&self) -> Vec3 {
        Vec3::from_fn(|a, _| self.y0[a] + self.origin[a])
    }

    /// Own goal, absolute.
    pub fn goal_abs(&self) -> Vec3 {
        Vec3::from_fn(|a, _| self.goal[a] + self.origin[a])
    }

    /// Runs the primitive at `target`: from its start to its goal over its
    /// duration, the forcing term and initial velocity mapped by the
    /// scaling. Errors name the argument at fault.
    pub fn rollout(&self, target: &Target) -> Result<Generalised> {
        let start = target.start.unwrap_or_else(|| self.start_abs());
        let goal = target.goal.unwrap_or_else(|| self.goal_abs());
        let duration = target.duration_s.unwrap_or(self.duration_s);
        check_target(start, goal, duration)?;
        // Relative coordinates: the defaults keep the primitive's own bits.
        let relative = |p: Option<Vec3>, own: Vec3| {
            p.map_or(own, |s| Vec3::from_fn(|a, _| s[a] - self.origin[a]))
        };
        let (y0, g) = (
            relative(target.start, self.y0),
            relative(target.goal, self.goal),
        );
        let (mapping, warnings) = self.mapping_to(start, goal, target.scaling)?;
        let fdt2: Vec<Vec3> = if mapping == Mapping::IDENTITY {
            self.fdt2.clone()
        } else {
            self.fdt2.iter().map(|f| mapping.apply(*f)).collect()
        };
        let mut unit = self.integrate(y0, g, &fdt2, mapping.apply(self.v0));
        for p in &mut unit.y {
            *p = Vec3::from_fn(|a, _| p[a] + self.origin[a]);
        }
        if let Some(s) = target.start {
            // The state at step 0 is the start, exactly.
            unit.y[0] = s;
        }
        let band = self.band(y0, g, &mapping, &unit.y);
        let n = self.fdt2.len();
        let dt = self.dt();
        let t: Vec<f64> = (0..n).map(|k| duration * k as f64 * dt).collect();
        let v: Vec<Vec3> = unit.v.iter().map(|v| v.map(|c| c / duration)).collect();
        let dur2 = duration * duration;
        let a: Vec<Vec3> = unit.a.iter().map(|a| a.map(|c| c / dur2)).collect();
        self.check_finite([&unit.y, &v, &a, &band], duration)?;
        let orientation = self.orientation_rollout(target)?;
        let peak_speed = v.iter().map(|v| norm(*v)).fold(0.0, f64::max);
        let a_peak = a.iter().map(|a| norm(*a)).fold(0.0, f64::max);
        let last = unit.y[n - 1];
        let final_error = norm(Vec3::from_fn(|c, _| last[c] - goal[c]));
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
            orientation,
            orientation_goal: self
                .orientation
                .as_ref()
                .map(|o| o.ends(target.start_orientation, target.goal_orientation).1),
        })
    }

    /// The map from the primitive's own displacement to `goal - start`, from
    /// the absolute numbers an export holds (docs/export.md, so a runner
    /// computes the same one; at the defaults from == to), and the warnings
    /// of a per-axis map where an axis barely moves.
    fn mapping_to(
        &self,
        start: Vec3,
        goal: Vec3,
        scaling: Scaling,
    ) -> Result<(Mapping, Vec<String>)> {
        let (own_start, own_goal) = (self.start_abs(), self.goal_abs());
        let from: Vec3 = Vec3::from_fn(|a, _| own_goal[a] - own_start[a]);
        let to: Vec3 = Vec3::from_fn(|a, _| goal[a] - start[a]);
        let mapping = Mapping::between(from, to, scaling).map_err(|e| match e {
            Error::InvalidSetting(m) => Error::InvalidSetting(format!("{}: {m}", self.name)),
            other => other,
        })?;
        let mut warnings = Vec::new();
        if let (Scaling::Paper, Mapping::Diagonal(factors)) = (scaling, mapping) {
            let extent = self.extent;
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
        Ok((mapping, warnings))
    }

    /// An error when any of the run's numbers overflowed.
    fn check_finite(&self, rows: [&[Vec3]; 4], duration: f64) -> Result<()> {
        let finite = |rows: &[Vec3]| {
            rows.iter()
                .all(|r| r.x.is_finite() && r.y.is_finite() && r.z.is_finite())
        };
        if rows.iter().all(|r| finite(r)) {
            return Ok(());
        }
        Err(Error::InvalidSetting(format!(
            "{}: the motion diverges at D/M {} and K/M {} over {duration} s (its numbers \
             overflow): nothing to run or export",
            self.name, self.dm, self.km
        )))
    }

    /// The orientation's run at the target's start and goal orientations;
    /// an error when they are given without an orientation to run.
    fn orientation_rollout(&self, target: &Target) -> Result<Option<OrientationRollout>> {
        match &self.orientation {
            Some(o) => Ok(Some(
                o.rollout(target.start_orientation, target.goal_orientation),
            )),
            None if target.start_orientation.is_some() || target.goal_orientation.is_some() => {
                Err(Error::InvalidSetting(format!(
                    "{}: no orientation to run to a new start or goal orientation (its \
                     recording has none, or the skill of several demos)",
                    self.name
                )))
            }
            None => Ok(None),
        }
    }

    /// Per-time SD (N - 1) of the members' positions at the target.
    fn band(&self, y0: Vec3, g: Vec3, mapping: &Mapping, mean: &[Vec3]) -> Vec<Vec3> {
        let m = self.members.len();
        if m < 2 {
            return if m == 1 {
                vec![Vec3::zeros(); mean.len()]
            } else {
                Vec::new()
            };
        }
        let mut sum2 = vec![Vec3::zeros(); mean.len()];
        for (fdt2, v0) in &self.members {
            let mapped: Vec<Vec3> = fdt2.iter().map(|f| mapping.apply(*f)).collect();
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
    fn integrate(&self, y0: Vec3, g: Vec3, fdt2: &[Vec3], v0: Vec3) -> Rollout {
        let n = fdt2.len();
        let dt = self.dt();
        let dt2 = dt * dt;
        let (ddt, kdt2) = (self.dm * dt, self.km * dt2);
        // The state as plain arrays: the loop then compiles as the model's.
        let g: [f64; 3] = g.into();
        let mut z: [f64; 3] = std::array::from_fn(|a| y0[a] - g[a]);
        let mut u: [f64; 3] = v0.map(|v| v * dt).into();
        let mut out = Rollout {
            y: Vec::with_capacity(n),
            v: Vec::with_capacity(n),
            a: Vec::with_capacity(n),
        };
        for f in fdt2 {
            let f: [f64; 3] = (*f).into();
            let mut acc = [0.0; 3];
            out.y.push(Vec3::new(z[0] + g[0], z[1] + g[1], z[2] + g[2]));
            out.v.push(Vec3::new(u[0] / dt, u[1] / dt, u[2] / dt));
            for a in 0..3 {
                let du = f[a] - kdt2 * z[a] - ddt * u[a];
                acc[a] = du / dt2;
                u[a] += du;
                z[a] += u[a];
            }
            out.a.push(acc.into());
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

/// An error naming the argument at fault when the start or goal is not
/// finite, the duration is out of range, or the goal equals the start.
fn check_target(start: Vec3, goal: Vec3, duration: f64) -> Result<()> {
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
    Ok(())
}
