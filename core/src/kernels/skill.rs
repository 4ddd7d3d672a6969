//! The skill error's integration (method.md section 11): one run of the
//! skill per gain pair, in the frame of the demos' mean displacement, and
//! every demo's E read off it.
//!
//! The skill run towards demo i integrates the forcing term `P_i G` from
//! `z0_i` with `u0_i = P_i u0`, where `G`, `u0` are the skill's in the
//! mean frame and `P_i` the linear map from the mean displacement to demo
//! i's. The DMP is linear with scalar gains, which commute with `P_i`, so
//! that run is `P_i z(t) + h(t) r_i`: `z` the skill's run in the mean frame
//! from `z0 = -mean_d`, `h` the scalar run from 1 at rest without forcing,
//! and `r_i = z0_i - P_i z0` the part of the start `P_i` does not give
//! (zero in exact arithmetic for frame-independent skills and for per-axis
//! factors; the demos' own offsets without scaling). One integration per
//! gain pair then serves every demo, instead of one per demo: the same E
//! to rounding (the golden tests check it), and a lone demo's E is its d
//! to the bit as before.
//!
//! A frame-independent `P_i` is `s_i R_i`, so demo i's error is
//! `s_i |z - T_i|` with `T_i = R_i^T (y_i - g_i) / s_i`, computed once.

use crate::fit::mapping::Mapping;
use crate::kernels::position::{DemoKernel, StepRead, integrate_reading};

/// How each demo reads its skill run off the mean frame's.
#[derive(Clone, Debug)]
enum Views {
    /// Frame-independent maps `s_i R_i`: demo i's error is
    /// `s_i |z - T_i|`.
    Similar {
        /// `s_i` per demo.
        scale: Vec<f64>,
        /// `T_i` at `[i * n + k]`.
        targets: Vec<[f64; 3]>,
    },
    /// Per-axis maps (per-axis factors, or none): demo i's error is
    /// `|a_i z + h r_i - (y_i - g_i)|`.
    Axes {
        /// `a_i` per demo.
        factors: Vec<[f64; 3]>,
        /// `r_i` per demo, or `None` where every one is exactly 0 (then
        /// `h` is not integrated).
        offsets: Option<Vec<[f64; 3]>>,
        /// `y_i - g_i` at `[i * n + k]`.
        targets: Vec<[f64; 3]>,
    },
}

/// The skill in the mean frame and how each demo reads it.
#[derive(Clone, Debug)]
pub(crate) struct SkillKernel {
    /// The skill's run in the mean frame (its targets unused).
    mean: DemoKernel,
    views: Views,
    demos: usize,
}

impl SkillKernel {
    /// The kernel of the skill `mean` (forcing parts times `dt^2`, `z0`
    /// and `u0` in the mean frame), mapped to each demo by `maps` (the map
    /// of the mean displacement to the demo's); `targets[i][k]` is
    /// `y_i - g_i` on the grid (so `targets[i][0]` is the demo's start
    /// `z0_i`). `similar` says the maps are frame-independent (`scales[i]`
    /// their `s_i`).
    pub(crate) fn new(
        mean: DemoKernel,
        maps: &[Mapping],
        targets: &[Vec<[f64; 3]>],
        similar: Option<&[f64]>,
    ) -> Self {
        let demos = maps.len();
        let n = mean.steps.len();
        let views = match similar {
            Some(scales) => {
                let mut flat = Vec::with_capacity(n * demos);
                for (map, (target, &s)) in maps.iter().zip(targets.iter().zip(scales)) {
                    flat.extend(target.iter().map(|&t| inverse_similar(map, s, t)));
                }
                Views::Similar {
                    scale: scales.to_vec(),
                    targets: flat,
                }
            }
            None => {
                let factors: Vec<[f64; 3]> = maps.iter().map(diagonal).collect();
                let z0 = mean.z0;
                let offsets: Vec<[f64; 3]> = factors
                    .iter()
                    .zip(targets)
                    .map(|(a, t)| std::array::from_fn(|ax| t[0][ax] - a[ax] * z0[ax]))
                    .collect();
                let any = offsets.iter().flatten().any(|&r| r != 0.0);
                let flat: Vec<[f64; 3]> = targets.iter().flatten().copied().collect();
                Views::Axes {
                    factors,
                    offsets: any.then_some(offsets),
                    targets: flat,
                }
            }
        };
        Self { mean, views, demos }
    }

    /// Each demo's `[d, a_peak, E]` per lane: `d` and `a_peak` from its
    /// regeneration `kernels[i]`, E read off the skill's run while that
    /// integrates (the reading's square roots then overlap the
    /// integration's additions). Each lane's numbers are those of a lone
    /// pair, to the bit.
    pub(crate) fn regenerate_lanes<const L: usize>(
        &self,
        kernels: &[DemoKernel],
        dm: f64,
        km: [f64; L],
    ) -> Vec<[[f64; L]; 3]> {
        let run = self.run(dm, km);
        let n = self.mean.steps.len();
        let dt = 1.0 / (n - 1) as f64;
        let regenerate = |i: usize| -> [[f64; L]; 3] {
            let kernel = &kernels[i];
            let range = i * n..(i + 1) * n;
            // E is `sum_k w_k |e_i(k)| dt`, times `s_i` for
            // frame-independent maps.
            match &self.views {
                Views::Similar { scale, targets } => {
                    let mut reader = Similar {
                        z: &run.z,
                        targets: &targets[range],
                        sum: [0.0; L],
                    };
                    let (d, a) = integrate_reading::<L, true, _>(kernel, dm, km, &mut reader);
                    [d, a, reader.sum.map(|e| e * dt).map(|e| e * scale[i])]
                }
                Views::Axes {
                    factors,
                    offsets: None,
                    targets,
                } => {
                    let mut reader = Axes::<L, false> {
                        z: &run.z,
                        h: &run.h,
                        factors: factors[i],
                        offsets: [0.0; 3],
                        targets: &targets[range],
                        sum: [0.0; L],
                    };
                    let (d, a) = integrate_reading::<L, true, _>(kernel, dm, km, &mut reader);
                    [d, a, reader.sum.map(|e| e * dt)]
                }
                Views::Axes {
                    factors,
                    offsets: Some(offsets),
                    targets,
                } => {
                    let mut reader = Axes::<L, true> {
                        z: &run.z,
                        h: &run.h,
                        factors: factors[i],
                        offsets: offsets[i],
                        targets: &targets[range],
                        sum: [0.0; L],
                    };
                    let (d, a) = integrate_reading::<L, true, _>(kernel, dm, km, &mut reader);
                    [d, a, reader.sum.map(|e| e * dt)]
                }
            }
        };
        debug_assert_eq!(kernels.len(), self.demos, "one regeneration per demo");
        (0..self.demos).map(regenerate).collect()
    }

    /// The skill's run in the mean frame at `(dm, km[l])`, at every grid
    /// point.
    fn run<const L: usize>(&self, dm: f64, km: [f64; L]) -> MeanRun<L> {
        let n = self.mean.steps.len();
        let mut record = Record {
            zs: Vec::with_capacity(n),
        };
        // The position kernel itself (its d, against targets of 0, unused).
        integrate_reading::<L, false, _>(&self.mean, dm, km, &mut record);
        let h = match self.views {
            Views::Axes {
                offsets: Some(_), ..
            } => crate::kernels::dispatch::run(Homogeneous { n, dm, km }),
            _ => Vec::new(),
        };
        MeanRun { z: record.zs, h }
    }
}

/// `T = P^{-1} target` for a frame-independent map `P = s R`.
fn inverse_similar(map: &Mapping, s: f64, target: [f64; 3]) -> [f64; 3] {
    match map {
        Mapping::Diagonal(d) => std::array::from_fn(|ax| target[ax] / d[ax]),
        // P^T = s R^T, so P^{-1} = P^T / s^2.
        Mapping::Matrix(m) => {
            let s2 = s * s;
            std::array::from_fn(|c| {
                (m[0][c] * target[0] + m[1][c] * target[1] + m[2][c] * target[2]) / s2
            })
        }
    }
}

/// The factors of a per-axis map (every map but the frame-independent
/// skill's is diagonal).
fn diagonal(map: &Mapping) -> [f64; 3] {
    match map {
        Mapping::Diagonal(d) => *d,
        Mapping::Matrix(m) => std::array::from_fn(|ax| m[ax][ax]),
    }
}

/// The skill's run in the mean frame at `L` gain pairs: `z` at every grid
/// point, and `h` (empty unless a demo's start needs it).
struct MeanRun<const L: usize> {
    z: Vec<[[f64; L]; 3]>,
    h: Vec<[f64; L]>,
}

/// [`Views::Similar`]'s reader of one demo.
struct Similar<'a, const L: usize> {
    z: &'a [[[f64; L]; 3]],
    /// The demo's `T_i` per grid point.
    targets: &'a [[f64; 3]],
    sum: [f64; L],
}

impl<const L: usize> StepRead<L> for Similar<'_, L> {
    #[inline(always)]
    fn step(&mut self, k: usize, w: f64, _regenerated: &[[f64; L]; 3]) {
        let (z, t) = (&self.z[k], self.targets[k]);
        for l in 0..L {
            let e0 = z[0][l] - t[0];
            let e1 = z[1][l] - t[1];
            let e2 = z[2][l] - t[2];
            self.sum[l] += w * (e0 * e0 + e1 * e1 + e2 * e2).sqrt();
        }
    }
}

/// [`Views::Axes`]'s reader of one demo, with `h r_i` when `H`.
struct Axes<'a, const L: usize, const H: bool> {
    z: &'a [[[f64; L]; 3]],
    h: &'a [[f64; L]],
    factors: [f64; 3],
    offsets: [f64; 3],
    /// The demo's `y_i - g_i` per grid point.
    targets: &'a [[f64; 3]],
    sum: [f64; L],
}

impl<const L: usize, const H: bool> StepRead<L> for Axes<'_, L, H> {
    #[inline(always)]
    fn step(&mut self, k: usize, w: f64, _regenerated: &[[f64; L]; 3]) {
        let (z, t) = (&self.z[k], self.targets[k]);
        let (a, r) = (self.factors, self.offsets);
        for l in 0..L {
            let e: [f64; 3] = std::array::from_fn(|ax| {
                let y = a[ax] * z[ax][l];
                let y = if H { y + self.h[k][l] * r[ax] } else { y };
                y - t[ax]
            });
            self.sum[l] += w * (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]).sqrt();
        }
    }
}

/// Keeps an integration's `z` at every grid point.
struct Record<const L: usize> {
    zs: Vec<[[f64; L]; 3]>,
}

impl<const L: usize> StepRead<L> for Record<L> {
    #[inline(always)]
    fn step(&mut self, _k: usize, _w: f64, z: &[[f64; L]; 3]) {
        self.zs.push(*z);
    }
}

/// The unforced run from 1 at rest, `h`, at every grid point, as a call
/// the dispatch compiles per instruction set.
struct Homogeneous<const L: usize> {
    n: usize,
    dm: f64,
    km: [f64; L],
}

impl<const L: usize> crate::kernels::dispatch::Kernel for Homogeneous<L> {
    type Output = Vec<[f64; L]>;

    #[inline(always)]
    fn call(self) -> Vec<[f64; L]> {
        let Self { n, dm, km } = self;
        let dt = 1.0 / (n - 1) as f64;
        let ddt = dm * dt;
        let kdt2 = km.map(|k| k * dt * dt);
        let (mut h, mut uh) = ([1.0; L], [0.0; L]);
        let mut hs = Vec::with_capacity(n);
        for _ in 0..n {
            hs.push(h);
            for l in 0..L {
                let du = -(kdt2[l] * h[l]) - ddt * uh[l];
                uh[l] += du;
                h[l] += uh[l];
            }
        }
        hs
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fit::mapping::Scaling;
    use crate::geom::Vec3;

    const N: usize = 201;

    /// A smooth made-up curve per axis, `amp` in size.
    fn curve(seed: f64, amp: f64) -> Vec<[f64; 3]> {
        (0..N)
            .map(|k| {
                let t = k as f64 / (N - 1) as f64;
                std::array::from_fn(|ax| amp * (seed + 1.7 * ax as f64 + 3.1 * t).sin())
            })
            .collect()
    }

    /// The skill run towards each demo as E was computed before this
    /// kernel, one integration per demo (the forcing term `P_i G`, start
    /// `z0_i`, `u0_i = P_i u0`): as a regeneration, its `d` is that E.
    fn direct(
        parts: &[[[f64; 3]; 3]],
        u0: [f64; 3],
        maps: &[Mapping],
        targets: &[Vec<[f64; 3]>],
    ) -> Vec<DemoKernel> {
        let apply = |m: &Mapping, v: [f64; 3]| -> [f64; 3] { m.apply(Vec3::from(v)).into() };
        maps.iter()
            .zip(targets)
            .map(|(m, target)| {
                let steps = parts
                    .iter()
                    .zip(target)
                    .map(|(p, t)| {
                        let g = p.map(|c| apply(m, c));
                        std::array::from_fn(|ax| [g[0][ax], g[1][ax], g[2][ax], t[ax]])
                    })
                    .collect();
                DemoKernel::from_parts(steps, target[0], apply(m, u0))
            })
            .collect()
    }

    /// The skill's run in the mean frame read by each demo gives the E of
    /// a run per demo, for frame-independent maps (rotations), per-axis
    /// factors with an axis whose mean displacement is 0 (the start then
    /// needs the homogeneous run) and no map.
    #[test]
    fn one_mean_run_gives_every_demos_e() {
        let dt2 = 1.0 / ((N - 1) * (N - 1)) as f64;
        let own: Vec<Vec3> = [[0.3, 0.1, -0.2], [-0.3, 0.25, 0.1], [0.1, 0.2, 0.05]]
            .map(Vec3::from)
            .to_vec();
        let p: [Vec<[f64; 3]>; 3] = [curve(0.5, 20.0), curve(1.5, 1.0), curve(2.5, 3.0)];
        let parts: Vec<[[f64; 3]; 3]> = (0..N)
            .map(|k| std::array::from_fn(|c| p[c][k].map(|v| v * dt2)))
            .collect();
        let u0 = [0.01, -0.02, 0.005];
        let (dm, km) = (12.0, [25.0, 160.0, 400.0, 1200.0]);
        for mode in ["frame", "per-axis, x mean 0", "none"] {
            let mut own = own.clone();
            if mode != "frame" {
                // x: +0.3, -0.3 and 0: a mean of exactly 0.
                own[2][0] = 0.0;
            }
            let mean_d = Vec3::from_fn(|a, _| own.iter().map(|d| d[a]).sum::<f64>() / 3.0);
            // Each demo starts at minus its displacement from its goal.
            let targets: Vec<Vec<[f64; 3]>> = own
                .iter()
                .enumerate()
                .map(|(i, d)| {
                    let mut t = curve(i as f64, 0.2);
                    t[0] = d.map(|v| -v).into();
                    t
                })
                .collect();
            let maps: Vec<Mapping> = own
                .iter()
                .map(|&d| match mode {
                    "frame" => Mapping::between(mean_d, d, Scaling::Frame).expect("map"),
                    "none" => Mapping::IDENTITY,
                    _ => Mapping::between(mean_d, d, Scaling::Paper).expect("map"),
                })
                .collect();
            let scales: Vec<f64> = own
                .iter()
                .map(|&d| crate::fit::mapping::norm(d) / crate::fit::mapping::norm(mean_d))
                .collect();
            let steps = parts
                .iter()
                .map(|p| std::array::from_fn(|ax| [p[0][ax], p[1][ax], p[2][ax], 0.0]))
                .collect();
            let z0 = mean_d.map(|v| -v).into();
            let mean = DemoKernel::from_parts(steps, z0, u0);
            let similar = (mode == "frame").then_some(scales.as_slice());
            let kernel = SkillKernel::new(mean, &maps, &targets, similar);
            if mode != "frame" {
                assert!(
                    matches!(
                        &kernel.views,
                        Views::Axes {
                            offsets: Some(_),
                            ..
                        }
                    ),
                    "{mode}: the starts need the homogeneous run"
                );
            }
            let regenerations = direct(&parts, u0, &maps, &targets);
            let ours = kernel.regenerate_lanes(&regenerations, dm, km);
            for (i, [want, _, e]) in ours.iter().enumerate() {
                for l in 0..4 {
                    let rel = (e[l] - want[l]).abs() / want[l];
                    assert!(
                        rel < 1e-12,
                        "{mode}, demo {i}, lane {l}: {} vs {}",
                        e[l],
                        want[l]
                    );
                }
            }
            // A lone pair gives the bits of its lane in a batch.
            let lone = kernel.regenerate_lanes(&regenerations, dm, [km[2]]);
            for (a, b) in lone.iter().zip(&ours) {
                assert_eq!(a.map(|q| q[0]), b.map(|q| q[2]));
            }
        }
    }
}
