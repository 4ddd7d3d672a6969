//! The topological similarity `S` of the demos' standardised target forcing
//! terms (method.md section 5).
//!
//! `f_target = y'' + D y' + K (y - g)` is linear in the gains, so each demo
//! and axis keeps its three parts `A = y''`, `B = y'`, `C = y - g`, centred,
//! and their 3 x 3 covariance. At a gain pair a demo's population SD is the
//! quadratic form of that covariance, and its standardised term at grid point
//! k is `(A + D B + K C) / sd`. The cross-demo sample variance is summed over
//! demos after subtracting demo 0's term (so identical demos give exactly 0),
//! then integrated. [`Similarity::evaluate_lanes`] does `L` gain pairs that
//! share D/M at once; every lane does the same arithmetic as a lone pair.

use crate::prepare::demo::PreparedDemo;

/// Below this population SD a demo's standardised term is taken as 0.
pub const SD_FLOOR: f64 = 1e-12;

/// Centred parts of every demo's target forcing term, ready for `S`.
#[derive(Clone, Debug)]
pub struct Similarity {
    n: usize,
    demos: usize,
    /// `parts[(k * 3 + axis) * demos + demo] = [A, B, C]`, centred.
    parts: Vec<[f64; 3]>,
    /// Population (co)variances per axis and demo:
    /// `[vA, vB, vC, cAB, cAC, cBC]` at `[axis * demos + demo]`.
    cov: Vec<[f64; 6]>,
    /// Each axis's SD floored at this fraction of the demo's largest axis
    /// SD (0: the method as written).
    floor: f64,
}

impl Similarity {
    /// Centres the three parts of each demo's target forcing term; `floor`
    /// is [`crate::fit::settings::DmpSettings::axis_sd_floor`] (0: the method).
    pub fn new(demos: &[PreparedDemo], floor: f64) -> Self {
        let n = demos.first().map_or(0, PreparedDemo::len);
        let nd = demos.len();
        let mut parts = vec![[0.0; 3]; n * 3 * nd];
        let mut cov = vec![[0.0; 6]; 3 * nd];
        for (di, d) in demos.iter().enumerate() {
            for axis in 0..3 {
                let raw: [Vec<f64>; 3] = [
                    d.ydd.iter().map(|v| v[axis]).collect(),
                    d.yd.iter().map(|v| v[axis]).collect(),
                    d.y.iter().map(|v| v[axis] - d.goal[axis]).collect(),
                ];
                let centred = raw.map(|v| {
                    let m = v.iter().sum::<f64>() / n as f64;
                    v.into_iter().map(|x| x - m).collect::<Vec<f64>>()
                });
                let dot = |a: &[f64], b: &[f64]| {
                    a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>() / n as f64
                };
                let [a, b, c] = &centred;
                cov[axis * nd + di] = [
                    dot(a, a),
                    dot(b, b),
                    dot(c, c),
                    dot(a, b),
                    dot(a, c),
                    dot(b, c),
                ];
                for k in 0..n {
                    parts[(k * 3 + axis) * nd + di] = [a[k], b[k], c[k]];
                }
            }
        }
        Self {
            n,
            demos: nd,
            parts,
            cov,
            floor,
        }
    }

    /// `1 / sd` of each axis of demo `di` at `(dm, km)` (0 below
    /// [`SD_FLOOR`]), each SD first floored at `floor` times the demo's
    /// largest.
    #[inline]
    fn inverse_sds(&self, di: usize, dm: f64, km: f64) -> [f64; 3] {
        let nd = self.demos;
        let sd = [0, 1, 2].map(|axis| sd_of(&self.cov[axis * nd + di], dm, km));
        let least = self.floor * sd[0].max(sd[1]).max(sd[2]);
        sd.map(|s| {
            let s = s.max(least);
            if s < SD_FLOOR { 0.0 } else { 1.0 / s }
        })
    }

    /// `S` at one gain pair; 0 with fewer than two demos.
    pub fn evaluate(&self, dm: f64, km: f64) -> f64 {
        self.evaluate_lanes(dm, [km])[0]
    }

    /// `S` at `(dm, km[l])` for every lane `l`.
    pub fn evaluate_lanes<const L: usize>(&self, dm: f64, km: [f64; L]) -> [f64; L] {
        let (n, nd) = (self.n, self.demos);
        if nd < 2 || n < 2 {
            return [0.0; L];
        }
        // 1 / sd per axis, demo and lane, from the covariance quadratic form.
        let mut inv = vec![[0.0; L]; 3 * nd];
        for di in 0..nd {
            for l in 0..L {
                let per_axis = self.inverse_sds(di, dm, km[l]);
                for (axis, v) in per_axis.into_iter().enumerate() {
                    inv[axis * nd + di][l] = v;
                }
            }
        }
        crate::kernels::dispatch::run(Lanes {
            similarity: self,
            dm,
            km,
            inv: &inv,
        })
    }
}

/// [`Similarity::evaluate_lanes`]'s integral over the grid, given each
/// demo's `1 / sd` per axis and lane, as a call the dispatch compiles per
/// instruction set (compiled for the baseline it spilled its lanes and
/// took about as long as the regenerations' kernels).
struct Lanes<'a, const L: usize> {
    similarity: &'a Similarity,
    dm: f64,
    km: [f64; L],
    /// `inv[axis * demos + demo][lane]`.
    inv: &'a [[f64; L]],
}

impl<const L: usize> crate::kernels::dispatch::Kernel for Lanes<'_, L> {
    type Output = [f64; L];

    #[inline(always)]
    fn call(self) -> [f64; L] {
        let Self {
            similarity,
            dm,
            km,
            inv,
        } = self;
        let (n, nd) = (similarity.n, similarity.demos);
        let inv_nd = 1.0 / nd as f64;
        let inv_nd1 = 1.0 / (nd - 1) as f64;
        let mut total = [0.0; L];
        for k in 0..n {
            let mut var_sum = [0.0; L];
            for axis in 0..3 {
                let row = &similarity.parts[(k * 3 + axis) * nd..(k * 3 + axis + 1) * nd];
                let inv_row = &inv[axis * nd..(axis + 1) * nd];
                let [a0, b0, c0] = row[0];
                let p0 = a0 + dm * b0;
                let mut f0 = [0.0; L];
                for l in 0..L {
                    f0[l] = (p0 + km[l] * c0) * inv_row[0][l];
                }
                let mut sum = [0.0; L];
                let mut sumsq = [0.0; L];
                for (&[a, b, c], inv_d) in row[1..].iter().zip(&inv_row[1..]) {
                    let p = a + dm * b;
                    for l in 0..L {
                        let dev = (p + km[l] * c) * inv_d[l] - f0[l];
                        sum[l] += dev;
                        sumsq[l] += dev * dev;
                    }
                }
                for l in 0..L {
                    var_sum[l] += (sumsq[l] - sum[l] * sum[l] * inv_nd) * inv_nd1;
                }
            }
            let w = if k == 0 || k + 1 == n { 0.5 } else { 1.0 };
            for l in 0..L {
                // max(var, 0), NaN giving 0.
                let v = crate::kernels::dispatch::larger(0.0, var_sum[l]);
                total[l] += w * v.sqrt();
            }
        }
        let dt = 1.0 / (n - 1) as f64;
        total.map(|t| t * dt)
    }
}

/// Every demo's standardised target forcing term at one gain pair, and the
/// integrand of `S` (method.md sections 5 and 9).
#[derive(Clone, Debug, PartialEq)]
pub struct Standardised {
    /// `f[demo][k][axis]`: `f_stand` on the grid.
    pub f: Vec<Vec<[f64; 3]>>,
    /// `sqrt(sigma_fx^2 + sigma_fy^2 + sigma_fz^2)` per grid point (0 with
    /// fewer than two demos): `S` is its trapezoid integral.
    pub sigma: Vec<f64>,
    /// Each demo's `q_i` of [`Standardised::shares`], summed in the same
    /// pass as `sigma`: the shares are those of `f` as computed, not of
    /// later edits to it.
    q: Vec<f64>,
}

impl Similarity {
    /// The similarity of the demos at `indices` (repeats allowed), from the
    /// parts already centred.
    pub fn subset(&self, indices: &[usize]) -> Self {
        let (n, nd, m) = (self.n, self.demos, indices.len());
        let mut parts = Vec::with_capacity(n * 3 * m);
        for row in self.parts.chunks(nd.max(1)) {
            parts.extend(indices.iter().map(|&i| row[i]));
        }
        let mut cov = Vec::with_capacity(3 * m);
        for axis in 0..3 {
            cov.extend(indices.iter().map(|&i| self.cov[axis * nd + i]));
        }
        Self {
            n,
            demos: m,
            parts,
            cov,
            floor: self.floor,
        }
    }

    /// Every demo's `f_stand` and the integrand of `S` at `(dm, km)`, with
    /// each demo's share of it, in one pass over the grid.
    pub fn standardised(&self, dm: f64, km: f64) -> Standardised {
        let (n, nd) = (self.n, self.demos);
        let mut inv = vec![0.0; 3 * nd];
        for di in 0..nd {
            for (axis, v) in self.inverse_sds(di, dm, km).into_iter().enumerate() {
                inv[axis * nd + di] = v;
            }
        }
        let mut f = vec![vec![[0.0; 3]; n]; nd];
        let mut sigma = vec![0.0; n];
        let mut q = vec![0.0; nd];
        // One grid point's values across the demos, for one axis.
        let mut across = vec![0.0; nd];
        for k in 0..n {
            let w = if k == 0 || k + 1 == n { 0.5 } else { 1.0 };
            let mut var = [0.0; 3];
            for (axis, var) in var.iter_mut().enumerate() {
                let parts = &self.parts[(k * 3 + axis) * nd..][..nd];
                for (di, &[a, b, c]) in parts.iter().enumerate() {
                    let v = (a + dm * b + km * c) * inv[axis * nd + di];
                    f[di][k][axis] = v;
                    across[di] = v;
                }
                if nd < 2 {
                    continue;
                }
                let mean = across.iter().sum::<f64>() / nd as f64;
                let mut sq = 0.0;
                for (qi, &v) in q.iter_mut().zip(&across) {
                    let e = v - mean;
                    sq += e * e;
                    *qi += w * e * e;
                }
                *var = sq / (nd - 1) as f64;
            }
            if nd >= 2 {
                sigma[k] = var.iter().sum::<f64>().sqrt();
            }
        }
        Standardised { f, sigma, q }
    }

    /// Each demo's share of S at `(dm, km)` ([`Standardised::shares`]).
    pub fn shares(&self, dm: f64, km: f64) -> Option<Vec<f64>> {
        self.standardised(dm, km).shares()
    }
}

impl Standardised {
    /// Each demo's share of S (method.md section 9):
    /// `q_i = integral sum_axes (f_stand(i) - mean_j f_stand(j))^2`,
    /// `share_i = q_i / sum_j q_j`; `None` with fewer than two demos, equal
    /// shares when every demo's term is the same. The `q_i` were summed
    /// when [`Similarity::standardised`] computed `f`.
    pub fn shares(&self) -> Option<Vec<f64>> {
        let nd = self.f.len();
        let n = self.sigma.len();
        if nd < 2 || n < 2 {
            return None;
        }
        let dt = 1.0 / (n - 1) as f64;
        let total: f64 = self.q.iter().map(|v| v * dt).sum();
        if total <= 0.0 {
            return Some(vec![1.0 / nd as f64; nd]);
        }
        Some(self.q.iter().map(|v| v * dt / total).collect())
    }
}

/// The population SD of a demo's axis at `(dm, km)` from its covariance
/// `[vA, vB, vC, cAB, cAC, cBC]`.
#[inline]
fn sd_of(c: &[f64; 6], dm: f64, km: f64) -> f64 {
    let [va, vb, vc, cab, cac, cbc] = *c;
    let var =
        va + dm * dm * vb + km * km * vc + 2.0 * dm * cab + 2.0 * km * cac + 2.0 * dm * km * cbc;
    var.max(0.0).sqrt()
}
