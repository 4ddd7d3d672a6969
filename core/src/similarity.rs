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

use crate::prepare::PreparedDemo;

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
}

impl Similarity {
    /// Centres the three parts of each demo's target forcing term.
    pub fn new(demos: &[PreparedDemo]) -> Self {
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
        }
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
        for (slot, c) in inv.iter_mut().zip(&self.cov) {
            let [va, vb, vc, cab, cac, cbc] = *c;
            for l in 0..L {
                let k = km[l];
                let var = va
                    + dm * dm * vb
                    + k * k * vc
                    + 2.0 * dm * cab
                    + 2.0 * k * cac
                    + 2.0 * dm * k * cbc;
                let sd = var.max(0.0).sqrt();
                slot[l] = if sd < SD_FLOOR { 0.0 } else { 1.0 / sd };
            }
        }
        let inv_nd = 1.0 / nd as f64;
        let inv_nd1 = 1.0 / (nd - 1) as f64;
        let mut total = [0.0; L];
        for k in 0..n {
            let mut var_sum = [0.0; L];
            for axis in 0..3 {
                let row = &self.parts[(k * 3 + axis) * nd..(k * 3 + axis + 1) * nd];
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
                total[l] += w * var_sum[l].max(0.0).sqrt();
            }
        }
        let dt = 1.0 / (n - 1) as f64;
        total.map(|t| t * dt)
    }
}

/// The trapezoid sum `sum_k w_k v_k` with `w = 1/2` at both ends, for unit spacing.
pub fn trapezoid(values: impl Iterator<Item = f64>, n: usize) -> f64 {
    let mut total = 0.0;
    for (k, v) in values.enumerate() {
        total += if k == 0 || k + 1 == n { 0.5 * v } else { v };
    }
    total
}
