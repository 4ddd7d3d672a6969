//! The fitted model of a demo set and its evaluation at any gain pair:
//! regeneration (method.md section 4), `d`, `a_peak`, `S` and `J`.
//!
//! All the work that does not depend on the gains happens once, in
//! [`Model::new`]: the basis, the three LWR projections per demo and the
//! centred parts of `S`. A gain pair then costs one integration per demo and
//! one pass of `S`. The kernels are written over `L` gain pairs that share
//! D/M (lanes), which the compiler vectorises; every lane does exactly the
//! same arithmetic, so one pair gives the same bits alone or in a batch.

use serde::Serialize;

use crate::error::{Error, Result};
use crate::fit::basis::Basis;
use crate::fit::lwr::Projections;
use crate::fit::orientation::OrientationRollout;
use crate::fit::settings::DmpSettings;
use crate::geom::Vec3;
use crate::kernels::orientation as orientation_kernel;
use crate::kernels::orientation::RotKernel;
use crate::kernels::position::{DemoKernel, integrate};
use crate::kernels::similarity::Similarity;
use crate::kernels::skill::SkillKernel;
use crate::kernels::skill_error;
use crate::landscape::model_steps::ModelSteps;
use crate::landscape::orientation_point;
use crate::landscape::quantity;
use crate::landscape::quantity::{PointValues, Quantity};
use crate::prepare::demo::PreparedDemo;
use crate::prepare::numeric::trapezoid;

/// Lanes of the batched kernels used by landscapes (gain pairs sharing D/M).
pub const LANES: usize = 16;

/// Everything gain-independent about a set of prepared demos.
#[derive(Clone, Debug)]
pub struct Model {
    demos: Vec<PreparedDemo>,
    settings: DmpSettings,
    basis: Basis,
    projections: Vec<Projections>,
    similarity: Similarity,
    kernels: Vec<DemoKernel>,
    /// The skill run towards each demo (method.md section 11), or why the
    /// skill mode gives none.
    skill: std::result::Result<SkillKernel, String>,
    /// Each demo's orientation projections (method.md section 12), `None`
    /// for a demo without orientation.
    orientation: Vec<Option<Projections>>,
    /// Each demo's orientation kernel (`None` without orientation).
    rot_kernels: Vec<Option<RotKernel>>,
    /// With separate orientation gains: each demo's `(d_rot, alpha_peak)`
    /// at them, the same at every position gain pair.
    rot_fixed: Option<Vec<Option<(f64, f64)>>>,
}

/// The evaluation of one gain pair over all demos.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PointEval {
    /// D/M.
    pub dm: f64,
    /// K/M.
    pub km: f64,
    /// Damping ratio `D / (2 sqrt(K))`.
    pub zeta: f64,
    /// Human-likeness error per demo, metres (= d_mean, m over 1 s).
    pub d: Vec<f64>,
    /// Peak acceleration norm per demo, m/s^2 of the unit-time motion.
    pub a_peak: Vec<f64>,
    /// `sum(d)`.
    pub d_sum: f64,
    /// Similarity `S` (0 for fewer than two demos).
    pub s: f64,
    /// Skill error per demo (method.md section 11), metres; NaN when the
    /// skill mode gives no skill ([`Model::skill_refusal`] says why).
    pub e: Vec<f64>,
    /// `E = sum(e)`.
    pub e_sum: f64,
    /// Orientation error per demo (method.md section 12), radians; NaN
    /// for a demo without orientation.
    pub d_rot: Vec<f64>,
    /// Peak angular acceleration per demo, rad/s^2 of the unit-time
    /// motion; NaN without orientation.
    pub alpha_peak: Vec<f64>,
    /// `sum d_rot` over the demos with orientation, degrees (NaN when none
    /// has one).
    pub d_rot_sum: f64,
    /// The weight of `d_rot_sum` in J ([`DmpSettings::k_rot`]).
    pub k_rot: f64,
}

impl PointEval {
    /// `J = S + k sum(d)` (plus `k_rot sum d_rot` when `k_rot` is not 0).
    pub fn j(&self, k: f64) -> f64 {
        j_of(self.s, self.d_sum, self.d_rot_sum, k, self.k_rot)
    }
}

/// `J = S + k sum d`, plus `k_rot sum d_rot` (degrees) when `k_rot` is not
/// 0 (so the paper's J keeps its bits).
pub fn j_of(s: f64, d_sum: f64, d_rot_sum: f64, k: f64, k_rot: f64) -> f64 {
    if k_rot == 0.0 {
        s + k * d_sum
    } else {
        s + k * d_sum + k_rot * d_rot_sum
    }
}

/// A regenerated path on the unit-time grid.
#[derive(Clone, Debug, PartialEq)]
pub struct Rollout {
    /// Positions (relative to the demo's start, like [`PreparedDemo::y`]).
    pub y: Vec<Vec3>,
    /// Velocities.
    pub v: Vec<Vec3>,
    /// Accelerations.
    pub a: Vec<Vec3>,
}

/// The damping ratio `zeta = D / (2 sqrt(K))` (method.md section 4).
pub fn zeta(dm: f64, km: f64) -> f64 {
    dm / (2.0 * km.sqrt())
}

impl Model {
    /// Fits the model. All demos must share one grid length.
    pub fn new(demos: Vec<PreparedDemo>, settings: DmpSettings) -> Result<Self> {
        let mut steps = ModelSteps::new(demos, settings)?;
        while steps.project_next() {}
        steps.finish()
    }

    /// The model from its demos, settings, basis and each demo's
    /// projections ([`ModelSteps::finish`]): the gain-independent rest
    /// (`S`'s centred parts, the kernels, the skill's run).
    pub(super) fn assemble(
        demos: Vec<PreparedDemo>,
        settings: DmpSettings,
        basis: Basis,
        projections: Vec<Projections>,
        orientation: Vec<Option<Projections>>,
    ) -> Result<Self> {
        let similarity = Similarity::new(&demos, settings.axis_sd_floor);
        let kernels = demos
            .iter()
            .zip(&projections)
            .map(|(d, p)| DemoKernel::new(d, p))
            .collect();
        let skill = skill_error::kernels(&demos, &projections, settings.skill_mode);
        let rot_kernels: Vec<Option<RotKernel>> = demos
            .iter()
            .zip(&orientation)
            .map(|(d, p)| Some(RotKernel::new(d.orientation.as_ref()?, p.as_ref()?)))
            .collect();
        check_orientation_settings(&settings, rot_kernels.iter().any(Option::is_some))?;
        let rot_fixed = settings.orientation_gains.map(|[dm, km]| {
            rot_kernels
                .iter()
                .map(|k| {
                    k.as_ref().map(|k| {
                        let (d, a) = orientation_kernel::integrate::<1, true>(k, dm, [km]);
                        (d[0], a[0])
                    })
                })
                .collect()
        });
        Ok(Self {
            demos,
            settings,
            basis,
            projections,
            similarity,
            kernels,
            skill,
            orientation,
            rot_kernels,
            rot_fixed,
        })
    }

    /// The prepared demos, in order.
    pub fn demos(&self) -> &[PreparedDemo] {
        &self.demos
    }

    /// The DMP settings.
    pub fn settings(&self) -> &DmpSettings {
        &self.settings
    }

    /// The basis on the grid.
    pub fn basis(&self) -> &Basis {
        &self.basis
    }

    /// The projections of demo `i`.
    pub fn projections(&self, i: usize) -> &Projections {
        &self.projections[i]
    }

    /// The fitted forcing term of demo `i` at `(dm, km)` on the grid.
    pub fn forcing(&self, i: usize, dm: f64, km: f64) -> Vec<Vec3> {
        self.projections[i]
            .f
            .iter()
            .map(|fk| Vec3::from_fn(|ax, _| fk[ax][0] + dm * fk[ax][1] + km * fk[ax][2]))
            .collect()
    }

    /// The same model without its skill error (E is NaN and costs
    /// nothing): what `dmpscope bench` compares the landscape with.
    pub fn without_skill_error(&self) -> Self {
        Self {
            skill: Err("the skill error is switched off".to_owned()),
            ..self.clone()
        }
    }

    /// The same model without its orientation error (d_rot is NaN and
    /// costs nothing): what `dmpscope bench` compares the landscape with.
    pub fn without_orientation_error(&self) -> Self {
        Self {
            rot_kernels: vec![None; self.demos.len()],
            rot_fixed: None,
            ..self.clone()
        }
    }

    /// The orientation projections of demo `i` (`None`: no orientation).
    pub fn orientation_projections(&self, i: usize) -> Option<&Projections> {
        self.orientation.get(i).and_then(Option::as_ref)
    }

    /// Whether any demo has an orientation.
    pub fn has_orientation(&self) -> bool {
        self.orientation.iter().any(Option::is_some)
    }

    /// The gains the orientation DMP runs at when the position's are
    /// `(dm, km)`: the separate orientation gains where set, else the same.
    pub fn orientation_gains(&self, dm: f64, km: f64) -> (f64, f64) {
        self.settings
            .orientation_gains
            .map_or((dm, km), |[d, k]| (d, k))
    }

    /// Demo `i`'s orientation regenerated at the position gains `(dm, km)`
    /// (the orientation's own where set) from its own start to its own
    /// goal (method.md section 12); `None` without orientation.
    pub fn orientation_rollout(&self, i: usize, dm: f64, km: f64) -> Option<OrientationRollout> {
        let prepared = self.demos.get(i)?.orientation.as_ref()?;
        let proj = self.orientation_projections(i)?;
        let target = crate::fit::orientation::OrientationTarget {
            start: prepared.q[0],
            w0: prepared.w[0],
            goal: prepared.goal,
        };
        let (dm, km) = self.orientation_gains(dm, km);
        Some(crate::kernels::orientation_run::rollout(
            proj, dm, km, target,
        ))
    }

    /// `d_rot` (radians) and `alpha_peak` of demo `i` at the position gains
    /// `(dm, km)` (method.md section 12); `None` without orientation.
    pub fn rotation_error(&self, i: usize, dm: f64, km: f64) -> Option<(f64, f64)> {
        if let Some(fixed) = &self.rot_fixed {
            return fixed.get(i).copied().flatten();
        }
        let kernel = self.rot_kernels.get(i)?.as_ref()?;
        let (d, a) = orientation_kernel::integrate::<1, true>(kernel, dm, [km]);
        Some((d[0], a[0]))
    }

    /// The landscape's `sum d_rot` at `(dm, km[l])`: NaN when the map is
    /// off ([`DmpSettings::orientation_map`] and no `k_rot`).
    fn d_rot_map_lanes<const L: usize>(&self, dm: f64, km: [f64; L]) -> [f64; L] {
        if self.settings.orientation_map || self.settings.k_rot != 0.0 {
            self.d_rot_sum_of(dm, km)
        } else {
            [f64::NAN; L]
        }
    }

    /// `sum d_rot` in degrees at the gain pairs `(dm, km[l])` (NaN when no
    /// demo has an orientation).
    fn d_rot_sum_of<const L: usize>(&self, dm: f64, km: [f64; L]) -> [f64; L] {
        if let Some(fixed) = &self.rot_fixed {
            return [degrees_sum(fixed.iter().map(|r| r.map(|r| r.0))); L];
        }
        let mut sum = [0.0; L];
        let mut any = false;
        for kernel in self.rot_kernels.iter().flatten() {
            any = true;
            let d = orientation_kernel::integrate::<L, false>(kernel, dm, km).0;
            for l in 0..L {
                sum[l] += d[l];
            }
        }
        if any {
            sum.map(f64::to_degrees)
        } else {
            [f64::NAN; L]
        }
    }

    /// Why the model has no skill error (a frame skill whose demos' mean
    /// displacement is zero); `None` when it has one.
    pub fn skill_refusal(&self) -> Option<&str> {
        self.skill.as_ref().err().map(String::as_str)
    }

    /// `d`, `a_peak` and `e` of every demo and `S` at one gain pair.
    pub fn evaluate(&self, dm: f64, km: f64) -> PointEval {
        let rot = (0..self.demos.len())
            .map(|i| {
                self.rotation_error(i, dm, km)
                    .unwrap_or((f64::NAN, f64::NAN))
            })
            .collect();
        self.evaluate_with_rot(dm, km, rot)
    }

    /// [`Model::evaluate`] and every demo's [`Model::orientation_rollout`]
    /// at `(dm, km)`, each demo's orientation integrated once for both (the
    /// operating point, every frame a gain is dragged): the same numbers as
    /// the two apart, to the bit.
    pub fn evaluate_with_turns(
        &self,
        dm: f64,
        km: f64,
    ) -> (PointEval, Vec<Option<OrientationRollout>>) {
        let (rot, turns) = match &self.rot_fixed {
            // Every demo with an orientation, four at a time, one per lane.
            None => orientation_point::evaluate(&self.rot_kernels, dm, km, |i| {
                self.orientation_rollout(i, dm, km)
            }),
            // With separate orientation gains d_rot is fixed and the path
            // runs at those gains.
            Some(_) => (0..self.demos.len())
                .map(|i| {
                    let error = self.rotation_error(i, dm, km);
                    (
                        error.unwrap_or((f64::NAN, f64::NAN)),
                        self.orientation_rollout(i, dm, km),
                    )
                })
                .unzip(),
        };
        (self.evaluate_with_rot(dm, km, rot), turns)
    }

    /// Each demo's `[d, a_peak, E]` at `(dm, km[l])` (E NaN without a
    /// skill error): the regenerations, with E read off the skill's run
    /// inside them.
    fn regenerations<const L: usize>(&self, dm: f64, km: [f64; L]) -> Vec<[[f64; L]; 3]> {
        match &self.skill {
            Ok(skill) => skill.regenerate_lanes(&self.kernels, dm, km),
            Err(_) => self
                .kernels
                .iter()
                .map(|kernel| {
                    let (d, a) = integrate::<L, true>(kernel, dm, km);
                    [d, a, [f64::NAN; L]]
                })
                .collect(),
        }
    }

    /// [`Model::evaluate`] given each demo's `(d_rot, alpha_peak)`.
    fn evaluate_with_rot(&self, dm: f64, km: f64, rot: Vec<(f64, f64)>) -> PointEval {
        let each = self.regenerations(dm, [km]);
        let d: Vec<f64> = each.iter().map(|[d, _, _]| d[0]).collect();
        let a_peak: Vec<f64> = each.iter().map(|[_, a, _]| a[0]).collect();
        let e: Vec<f64> = each.iter().map(|[_, _, e]| e[0]).collect();
        let d_sum = d.iter().sum();
        let d_rot: Vec<f64> = rot.iter().map(|r| r.0).collect();
        // Over the demos with orientation, in order, as the lanes sum.
        let d_rot_sum = degrees_sum(
            self.rot_kernels
                .iter()
                .zip(&d_rot)
                .map(|(k, d)| k.as_ref().map(|_| *d)),
        );
        PointEval {
            dm,
            km,
            zeta: zeta(dm, km),
            d,
            a_peak,
            d_sum,
            s: self.similarity.evaluate(dm, km),
            e_sum: e.iter().sum(),
            e,
            alpha_peak: rot.iter().map(|r| r.1).collect(),
            d_rot,
            d_rot_sum,
            k_rot: self.settings.k_rot,
        }
    }

    /// Every quantity of the table ([`crate::quantity`]) at the gain pairs
    /// `(dm, km[l])`; the landscape's unit of work. Each lane's numbers equal
    /// [`Model::evaluate`]'s to the bit (`max a_peak` is the largest of its
    /// per-demo `a_peak`).
    pub fn evaluate_lanes<const L: usize>(&self, dm: f64, km: [f64; L]) -> [PointValues; L] {
        let mut d_sum = [0.0; L];
        let mut peak = [0.0f64; L];
        // NaN without a skill error: the sum stays NaN.
        let mut e_sum = [0.0; L];
        for [d, a, e] in self.regenerations(dm, km) {
            for l in 0..L {
                d_sum[l] += d[l];
                peak[l] = crate::kernels::dispatch::larger(peak[l], a[l]);
                e_sum[l] += e[l];
            }
        }
        let s = self.similarity.evaluate_lanes(dm, km);
        let d_rot_sum = self.d_rot_map_lanes(dm, km);
        std::array::from_fn(|l| {
            let mut point = [0.0; quantity::COUNT];
            point[Quantity::DSum.index()] = d_sum[l];
            point[Quantity::S.index()] = s[l];
            point[Quantity::APeak.index()] = peak[l];
            point[Quantity::ESum.index()] = e_sum[l];
            point[Quantity::DRotSum.index()] = d_rot_sum[l];
            point
        })
    }

    /// `J` at one gain pair ([`j_of`]), the same bits as
    /// `evaluate(dm, km).j(k)` without the per-demo lists and `a_peak`.
    pub fn j(&self, dm: f64, km: f64, k: f64) -> f64 {
        let mut d_sum = 0.0;
        for kernel in &self.kernels {
            d_sum += integrate::<1, false>(kernel, dm, [km]).0[0];
        }
        let k_rot = self.settings.k_rot;
        let d_rot_sum = if k_rot == 0.0 {
            0.0
        } else {
            self.d_rot_sum_of(dm, [km])[0]
        };
        j_of(self.similarity.evaluate(dm, km), d_sum, d_rot_sum, k, k_rot)
    }

    /// `S` alone at one gain pair (no integration).
    pub fn s(&self, dm: f64, km: f64) -> f64 {
        self.similarity.evaluate(dm, km)
    }

    /// The similarity parts (standardised forcing terms, shares of S).
    pub fn similarity(&self) -> &Similarity {
        &self.similarity
    }

    /// The model of the demos at `indices` (in that order, repeats allowed:
    /// a bootstrap resample), reusing every per-demo fit: no demo is
    /// prepared or fitted again. A resample's extraction needs J only, so
    /// its skill error is not computed ([`Model::skill_refusal`] says so
    /// and E is NaN): that halves the resampled landscapes' cost.
    pub fn subset(&self, indices: &[usize]) -> Result<Self> {
        if let Some(&bad) = indices.iter().find(|&&i| i >= self.demos.len()) {
            return Err(Error::InvalidSetting(format!(
                "no demo {bad} in a model of {}",
                self.demos.len()
            )));
        }
        if indices.is_empty() {
            return Err(Error::NoUsableDemo {
                reasons: Vec::new(),
            });
        }
        let demos: Vec<PreparedDemo> = indices.iter().map(|&i| self.demos[i].clone()).collect();
        let projections: Vec<Projections> = indices
            .iter()
            .map(|&i| self.projections[i].clone())
            .collect();
        let skill = Err("a resample's model: its skill error is not computed".to_owned());
        let rot_kernels: Vec<Option<RotKernel>> = indices
            .iter()
            .map(|&i| self.rot_kernels[i].clone())
            .collect();
        // A resample without an oriented demo has no d_rot to weigh.
        let mut settings = self.settings;
        if rot_kernels.iter().all(Option::is_none) {
            settings.k_rot = 0.0;
        }
        Ok(Self {
            demos,
            settings,
            basis: self.basis.clone(),
            projections,
            similarity: self.similarity.subset(indices),
            kernels: indices.iter().map(|&i| self.kernels[i].clone()).collect(),
            skill,
            orientation: indices
                .iter()
                .map(|&i| self.orientation[i].clone())
                .collect(),
            rot_kernels,
            rot_fixed: self
                .rot_fixed
                .as_ref()
                .map(|f| indices.iter().map(|&i| f[i]).collect()),
        })
    }

    /// The full regenerated path of demo `i` at `(dm, km)`, for plots and
    /// export: the same recurrence and arithmetic as [`Model::evaluate`].
    pub fn rollout(&self, i: usize, dm: f64, km: f64) -> Rollout {
        let kernel = &self.kernels[i];
        let g = self.demos[i].goal;
        let n = kernel.steps.len();
        let dt = 1.0 / (n - 1) as f64;
        let dt2 = dt * dt;
        let (ddt, kdt2) = (dm * dt, km * dt2);
        let (mut z, mut u) = (kernel.z0, kernel.u0);
        let mut out = Rollout {
            y: Vec::with_capacity(n),
            v: Vec::with_capacity(n),
            a: Vec::with_capacity(n),
        };
        for step in &kernel.steps {
            let mut a = [0.0; 3];
            out.y.push(Vec3::from_fn(|ax, _| z[ax] + g[ax]));
            out.v.push(u.map(|u| u / dt).into());
            for ax in 0..3 {
                let [f0, f1, f2, _] = step[ax];
                let du = f0 + dm * f1 + km * f2 - kdt2 * z[ax] - ddt * u[ax];
                a[ax] = du / dt2;
                u[ax] += du;
                z[ax] += u[ax];
            }
            out.a.push(a.into());
        }
        out
    }

    /// `d` of a path against demo `i`'s raw target (trapezoid over unit time).
    pub fn path_error(&self, i: usize, path: &[Vec3]) -> f64 {
        let target = &self.demos[i].y_raw;
        let n = target.len().min(path.len());
        let errs = path.iter().zip(target).map(|(p, t)| {
            let e2: f64 = (0..3).map(|ax| (p[ax] - t[ax]) * (p[ax] - t[ax])).sum();
            e2.sqrt()
        });
        trapezoid(errs, n) / (n.max(2) - 1) as f64
    }
}

/// The sum in degrees of the values present (radians), in order; NaN when
/// none is: `sum d_rot` over the demos with orientation.
fn degrees_sum(values: impl Iterator<Item = Option<f64>>) -> f64 {
    let mut any = false;
    let sum: f64 = values.flatten().inspect(|_| any = true).sum();
    if any { sum.to_degrees() } else { f64::NAN }
}

/// Checks `k_rot` and the orientation gains: finite, `k_rot >= 0`, gains
/// positive, and `k_rot > 0` only with an orientation to weigh.
fn check_orientation_settings(settings: &DmpSettings, any_orientation: bool) -> Result<()> {
    let k_rot = settings.k_rot;
    if !(k_rot.is_finite() && k_rot >= 0.0) {
        return Err(Error::InvalidSetting(format!(
            "k_rot must be a finite number >= 0, got {k_rot}"
        )));
    }
    if k_rot > 0.0 && !any_orientation {
        return Err(Error::InvalidSetting(
            "k_rot weighs the orientation error, but no demo has an orientation".into(),
        ));
    }
    if let Some([dm, km]) = settings.orientation_gains
        && !(dm.is_finite() && km.is_finite() && dm > 0.0 && km > 0.0)
    {
        return Err(Error::InvalidSetting(format!(
            "the orientation gains must be positive numbers, got D/M {dm}, K/M {km}"
        )));
    }
    Ok(())
}
