//! The topological similarity `S` of the demos' standardised target forcing
//! terms (method.md section 5).
//!
//! `f_target = y'' + D y' + K (y - g)` is linear in the gains, so the three
//! parts are centred once; at each gain pair a demo's standardised term is
//! `(A + D B + K C) / sd`, then the cross-demo sample SD is integrated.

use crate::prepare::PreparedDemo;

/// Below this population SD a demo's standardised term is taken as 0.
pub const SD_FLOOR: f64 = 1e-12;

/// Centred parts of every demo's target forcing term, ready for `S`.
#[derive(Clone, Debug)]
pub struct Similarity {
    n: usize,
    demos: usize,
    /// `parts[axis][demo][j]`: the centred part j (`y''`, `y'`, `y - g`), n values.
    parts: Vec<Vec<[Vec<f64>; 3]>>,
}

/// Reusable buffers for [`Similarity::evaluate`], one per thread.
#[derive(Clone, Debug, Default)]
pub struct SimilarityScratch {
    f: Vec<f64>,
    mean: Vec<f64>,
    sig2: Vec<f64>,
}

impl Similarity {
    /// Centres the three parts of each demo's target forcing term.
    pub fn new(demos: &[PreparedDemo]) -> Self {
        let n = demos.first().map_or(0, PreparedDemo::len);
        let centre = |v: Vec<f64>| {
            let m = v.iter().sum::<f64>() / v.len() as f64;
            v.into_iter().map(|x| x - m).collect::<Vec<f64>>()
        };
        let parts = (0..3)
            .map(|axis| {
                demos
                    .iter()
                    .map(|d| {
                        [
                            centre(d.ydd.iter().map(|v| v[axis]).collect()),
                            centre(d.yd.iter().map(|v| v[axis]).collect()),
                            centre(d.y.iter().map(|v| v[axis] - d.goal[axis]).collect()),
                        ]
                    })
                    .collect()
            })
            .collect();
        Self {
            n,
            demos: demos.len(),
            parts,
        }
    }

    /// `S` at gains `(dm, km)`; 0 with fewer than two demos.
    pub fn evaluate(&self, dm: f64, km: f64, scratch: &mut SimilarityScratch) -> f64 {
        let (n, nd) = (self.n, self.demos);
        if nd < 2 || n < 2 {
            return 0.0;
        }
        scratch.f.resize(nd * n, 0.0);
        scratch.mean.resize(n, 0.0);
        scratch.sig2.clear();
        scratch.sig2.resize(n, 0.0);
        let inv_nd = 1.0 / nd as f64;
        let inv_nd1 = 1.0 / (nd - 1) as f64;
        for axis_parts in &self.parts {
            scratch.mean.iter_mut().for_each(|m| *m = 0.0);
            for (demo, [a, b, c]) in axis_parts.iter().enumerate() {
                let f = &mut scratch.f[demo * n..(demo + 1) * n];
                let mut ss = 0.0;
                for k in 0..n {
                    let v = a[k] + dm * b[k] + km * c[k];
                    f[k] = v;
                    ss += v * v;
                }
                let sd = (ss / n as f64).sqrt();
                let inv = if sd < SD_FLOOR { 0.0 } else { 1.0 / sd };
                for (fk, mk) in f.iter_mut().zip(scratch.mean.iter_mut()) {
                    *fk *= inv;
                    *mk += *fk;
                }
            }
            scratch.mean.iter_mut().for_each(|m| *m *= inv_nd);
            for demo in 0..nd {
                let f = &scratch.f[demo * n..(demo + 1) * n];
                for ((s2, fk), mk) in scratch.sig2.iter_mut().zip(f).zip(&scratch.mean) {
                    let dev = fk - mk;
                    *s2 += dev * dev * inv_nd1;
                }
            }
        }
        let dt = 1.0 / (n - 1) as f64;
        trapezoid(scratch.sig2.iter().map(|v| v.sqrt()), n) * dt
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
