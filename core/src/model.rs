//! The fitted model of a demo set and its evaluation at any gain pair:
//! regeneration (method.md section 4), `d`, `a_peak`, `S` and `J`.
//!
//! All the work that does not depend on the gains happens once, in
//! [`Model::new`]: the basis, the three LWR projections per demo and the
//! centred parts of `S`. A gain pair then costs one integration per demo and
//! one pass of `S`. The integration kernel is written over `L` gain pairs at
//! once (lanes), which the compiler vectorises; every lane does exactly the
//! same arithmetic, so one pair gives the same bits alone or in a batch.

use serde::Serialize;

use crate::dmp::{Basis, DmpSettings, Projections};
use crate::error::{Error, Result};
use crate::prepare::PreparedDemo;
use crate::similarity::{Similarity, SimilarityScratch, trapezoid};

/// Lanes of the batched integration kernel used by landscapes.
pub const LANES: usize = 4;

/// Everything gain-independent about a set of prepared demos.
#[derive(Clone, Debug)]
pub struct Model {
    demos: Vec<PreparedDemo>,
    settings: DmpSettings,
    basis: Basis,
    projections: Vec<Projections>,
    similarity: Similarity,
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
}

impl PointEval {
    /// `J = S + k sum(d)`.
    pub fn j(&self, k: f64) -> f64 {
        self.s + k * self.d_sum
    }
}

/// A regenerated path on the unit-time grid.
#[derive(Clone, Debug, PartialEq)]
pub struct Rollout {
    /// Positions (relative to the demo's start, like [`PreparedDemo::y`]).
    pub y: Vec<[f64; 3]>,
    /// Velocities.
    pub v: Vec<[f64; 3]>,
    /// Accelerations.
    pub a: Vec<[f64; 3]>,
}

/// The damping ratio `zeta = D / (2 sqrt(K))` (method.md section 4).
pub fn zeta(dm: f64, km: f64) -> f64 {
    dm / (2.0 * km.sqrt())
}

impl Model {
    /// Fits the model. All demos must share one grid length.
    pub fn new(demos: Vec<PreparedDemo>, settings: DmpSettings) -> Result<Self> {
        let Some(first) = demos.first() else {
            return Err(Error::InvalidSetting("no demonstrations to fit".into()));
        };
        let n = first.len();
        if let Some(other) = demos.iter().find(|d| d.len() != n) {
            return Err(Error::InvalidSetting(format!(
                "{} has {} grid points, {} has {n}",
                other.name,
                other.len(),
                first.name
            )));
        }
        let basis = Basis::new(&settings, n)?;
        let projections = demos.iter().map(|d| Projections::new(&basis, d)).collect();
        let similarity = Similarity::new(&demos);
        Ok(Self {
            demos,
            settings,
            basis,
            projections,
            similarity,
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
    pub fn forcing(&self, i: usize, dm: f64, km: f64) -> Vec<[f64; 3]> {
        self.projections[i]
            .f
            .iter()
            .map(|fk| [0, 1, 2].map(|ax| fk[ax][0] + dm * fk[ax][1] + km * fk[ax][2]))
            .collect()
    }

    /// `d` and `a_peak` of every demo and `S` at one gain pair.
    pub fn evaluate(&self, dm: f64, km: f64) -> PointEval {
        let mut d = Vec::with_capacity(self.demos.len());
        let mut a_peak = Vec::with_capacity(self.demos.len());
        for i in 0..self.demos.len() {
            let (di, ai) = self.integrate::<1>(i, [dm], [km]);
            d.push(di[0]);
            a_peak.push(ai[0]);
        }
        let d_sum = d.iter().sum();
        let s = self
            .similarity
            .evaluate(dm, km, &mut SimilarityScratch::default());
        PointEval {
            dm,
            km,
            zeta: zeta(dm, km),
            d,
            a_peak,
            d_sum,
            s,
        }
    }

    /// `(sum d, S)` at [`LANES`] gain pairs; the landscape's unit of work.
    /// Each lane's numbers equal [`Model::evaluate`]'s to the bit.
    pub fn evaluate_lanes(
        &self,
        dm: [f64; LANES],
        km: [f64; LANES],
        scratch: &mut SimilarityScratch,
    ) -> [(f64, f64); LANES] {
        let mut d_sum = [0.0; LANES];
        for i in 0..self.demos.len() {
            let (d, _) = self.integrate::<LANES>(i, dm, km);
            for l in 0..LANES {
                d_sum[l] += d[l];
            }
        }
        std::array::from_fn(|l| (d_sum[l], self.similarity.evaluate(dm[l], km[l], scratch)))
    }

    /// Integrates demo `i` at `L` gain pairs (method.md section 4) and returns
    /// `d` and `a_peak` per lane.
    fn integrate<const L: usize>(
        &self,
        i: usize,
        dm: [f64; L],
        km: [f64; L],
    ) -> ([f64; L], [f64; L]) {
        let demo = &self.demos[i];
        let proj = &self.projections[i].f;
        let n = demo.len();
        let dt = 1.0 / (n - 1) as f64;
        let g = demo.goal;
        let mut y: [[f64; L]; 3] = std::array::from_fn(|ax| [demo.y_raw[0][ax]; L]);
        let mut v: [[f64; L]; 3] = std::array::from_fn(|ax| [demo.yd[0][ax]; L]);
        let mut err_sum = [0.0; L];
        let mut a2_max = [0.0f64; L];
        for k in 0..n {
            let fk = &proj[k];
            let yr = demo.y_raw[k];
            let mut acc = [[0.0; L]; 3];
            let mut e2 = [0.0; L];
            let mut a2 = [0.0; L];
            for ax in 0..3 {
                for l in 0..L {
                    let f = fk[ax][0] + dm[l] * fk[ax][1] + km[l] * fk[ax][2];
                    let a = -dm[l] * v[ax][l] - km[l] * (y[ax][l] - g[ax]) + f;
                    acc[ax][l] = a;
                    let e = y[ax][l] - yr[ax];
                    e2[l] += e * e;
                    a2[l] += a * a;
                }
            }
            let w = if k == 0 || k + 1 == n { 0.5 } else { 1.0 };
            for l in 0..L {
                err_sum[l] += w * e2[l].sqrt();
                a2_max[l] = a2_max[l].max(a2[l]);
            }
            if k + 1 < n {
                for ax in 0..3 {
                    for l in 0..L {
                        v[ax][l] += acc[ax][l] * dt;
                        y[ax][l] += v[ax][l] * dt;
                    }
                }
            }
        }
        (err_sum.map(|e| e * dt), a2_max.map(f64::sqrt))
    }

    /// The full regenerated path of demo `i` at `(dm, km)`, for plots and
    /// export; the same recurrence as [`Model::evaluate`].
    pub fn rollout(&self, i: usize, dm: f64, km: f64) -> Rollout {
        let demo = &self.demos[i];
        let proj = &self.projections[i].f;
        let n = demo.len();
        let dt = 1.0 / (n - 1) as f64;
        let g = demo.goal;
        let mut y = demo.y_raw[0];
        let mut v = demo.yd[0];
        let mut out = Rollout {
            y: Vec::with_capacity(n),
            v: Vec::with_capacity(n),
            a: Vec::with_capacity(n),
        };
        for fk in proj.iter().take(n) {
            let a: [f64; 3] = std::array::from_fn(|ax| {
                let f = fk[ax][0] + dm * fk[ax][1] + km * fk[ax][2];
                -dm * v[ax] - km * (y[ax] - g[ax]) + f
            });
            out.y.push(y);
            out.v.push(v);
            out.a.push(a);
            for ax in 0..3 {
                v[ax] += a[ax] * dt;
                y[ax] += v[ax] * dt;
            }
        }
        out
    }

    /// `d` of a path against demo `i`'s raw target (trapezoid over unit time).
    pub fn path_error(&self, i: usize, path: &[[f64; 3]]) -> f64 {
        let target = &self.demos[i].y_raw;
        let n = target.len().min(path.len());
        let errs = path.iter().zip(target).map(|(p, t)| {
            let e2: f64 = (0..3).map(|ax| (p[ax] - t[ax]) * (p[ax] - t[ax])).sum();
            e2.sqrt()
        });
        trapezoid(errs, n) / (n.max(2) - 1) as f64
    }
}
