//! The orientation DMP's integration (method.md section 12) over `L` gain
//! pairs that share D/M, for landscapes of `d_rot`, and the one step every
//! orientation rollout takes: the orientation's counterpart of the
//! position kernel in `position_kernel.rs`. Every lane does the arithmetic of a lone
//! pair, so a landscape point, [`crate::landscape::model::Model::evaluate`] and
//! [`crate::kernels::orientation_run::rollout_forcing`] agree to the bit.
//!
//! The state is the rotation still to go, `r = q_g * conj(q)`, not `q`:
//! `2 log(q_g * conj(q))` is then `2 log(r)`, the update
//! `q <- exp(w dt / 2) * q` is `r <- r * conj(exp(w dt / 2))`, and the
//! error's `|q . q_raw|` is `|r . (q_g * conj(q_raw))|`, a dot product with
//! a target prepared once. `r` is brought back to unit norm every 16
//! steps (one Newton step of `1 / |r|`); between them `|r| - 1` stays of
//! rounding size.
//!
//! The transcendental functions are polynomials where their arguments
//! allow, so the lanes vectorise (each evaluated as its even and odd
//! halves in `x^2`, two chains of half the length: 476 -> 460 ms for the
//! planted8 d_rot landscape against one Horner chain): with `x = 1 - c`
//! for a unit quaternion's scalar part `c` in [0, 1], `2 atan2(|v|, c) /
//! |v| = LOG(x)` and `2 acos(c) = sqrt(x) ANGLE(x)`, Chebyshev interpolants
//! on [0, 1] (relative errors 1.6e-12 for `LOG`, which drives the rollout:
//! at degree 12, 5.7e-11, `alpha_peak` at K/M 900 left the golden 1e-9;
//! 3.9e-10 for `ANGLE`, which only weighs the error angle). Where every
//! lane's `x` is at most 0.3 (a rotation of up to 91 degrees, the usual
//! step) shorter interpolants on [0, 0.3] take their place (degree 8
//! instead of 14 for `LOG`, 1.7e-13; 6 instead of 9 for `ANGLE`, 5.1e-12:
//! the planted8 d_rot landscape 412 -> 373 ms); a lane past 0.3 takes the
//! long one, lane by lane, so a lane's numbers never depend on its
//! neighbours.
//! `exp(u)` is its Taylor series in `|u|^2`, short while `|u|^2 <= 1e-4`
//! and longer while `|u|^2 <= 2.5e-3` (truncation below 3e-16). Where an
//! argument leaves that range (a rotation to go of more than 180 degrees,
//! `|w| dt / 2` over 0.05 rad, an angular step over 0.1 rad) the lane takes
//! `atan2`, `sin` and `cos` of `crate::portable` (the `libm` crate). Plain
//! multiplications and additions, no fused multiply-add, and the same
//! `libm` natively and in the browser: the browser's build gives the same
//! bits.

use crate::fit::lwr::Projections;
use crate::fit::orientation::OrientationRollout;
use crate::prepare::orientation::PreparedOrientation;
use wide::f64x4;

use crate::kernels::orientation_poly::{
    ANGLE, ANGLE_SHORT, COS, COS_SHORT, LOG, LOG_SHORT, SHORT_X, SINC, SINC_SHORT, horner,
    horner_split,
};
use crate::kernels::orientation_poly::{Lane, each};
use crate::rotation;
use crate::rotation::QuatXyzw;

/// The largest `|u|^2` for which `exp(u)` takes its short Taylor series
/// ([`SINC_SHORT`], [`COS_SHORT`]: truncation below 3e-16 relative), that
/// is `|w| <= 20` rad per unit time at 1001 grid points.
const EXP_SHORT_MAX: f64 = 1e-4;

/// Steps between two renormalisations of the rotation to go: the `exp`
/// (truncation below 3e-16) and the product keep `|r|` within a rounding
/// of one per step, so
/// `|r| - 1` stays near 1e-15 (the method renormalises only the prepared
/// `q`; the quaternions stay unit to 1e-12, tested).
const RENORMALISE_EVERY: usize = 16;

/// The largest `|u|^2` for which `exp(u)` takes its Taylor series.
const EXP_SERIES_MAX: f64 = 2.5e-3;

// A lane past the short series' range is tested for the libm fallback.
const _: () = assert!(EXP_SERIES_MAX > EXP_SHORT_MAX);

/// One demo's orientation laid out for the kernel.
#[derive(Clone, Debug)]
pub(crate) struct RotKernel {
    /// Per grid point: `[F0, F1, F2]` per axis of the forcing term.
    pub(crate) forcing: Vec<[[f64; 3]; 3]>,
    /// Per grid point: `q_g * conj(q_raw)`, the error's target seen from
    /// the goal.
    pub(crate) target: Vec<QuatXyzw>,
    /// Where the rollout starts.
    pub(crate) start: Start,
    /// The start orientation and the goal the kernel was made from (the
    /// path `orientation_point` records).
    pub(crate) ends: (QuatXyzw, QuatXyzw),
}

/// Where an orientation rollout starts: the rotation to go and the
/// angular velocity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Start {
    /// `q_g * conj(q_0)`, unit norm.
    pub(crate) r0: QuatXyzw,
    /// `w(0)`, unit time.
    pub(crate) w0: [f64; 3],
}

impl Start {
    /// From a start orientation, an initial angular velocity and a goal.
    pub(crate) fn new(start: QuatXyzw, w0: [f64; 3], goal: QuatXyzw) -> Self {
        Self {
            r0: rotation::normalised(rotation::mul(goal, rotation::conj(start))),
            w0,
        }
    }
}

impl RotKernel {
    /// The kernel of a prepared orientation and its projections.
    pub(crate) fn new(prepared: &PreparedOrientation, proj: &Projections) -> Self {
        let goal = prepared.goal;
        Self {
            forcing: proj.f.clone(),
            target: prepared
                .q_raw
                .iter()
                .map(|&t| rotation::mul(goal, rotation::conj(t)))
                .collect(),
            start: Start::new(prepared.q[0], prepared.w[0], goal),
            ends: (prepared.q[0], goal),
        }
    }
}

/// Vectors of four `f64` a landscape integrates together: enough
/// independent work to hide the latency of the polynomials' chains, few
/// enough that the state stays in registers. A lone pair (an operating
/// point, a path) takes one vector; a lane's numbers do not depend on it.
const V_LANDSCAPE: usize = 4;

/// One axis of a step's forcing term per lane: `F0 + D F1` and `F2`, the
/// step's term being `F0 + D F1 + K F2`.
pub(crate) struct Forcing<const V: usize> {
    /// `F0 + D F1`.
    pub(crate) fd: Lane<V>,
    /// `F2`.
    pub(crate) f2: Lane<V>,
}

/// The state of `4 V` orientation rollouts that share D/M.
pub(crate) struct Lanes<const V: usize> {
    /// The rotation to go per component.
    r: [Lane<V>; 4],
    /// The angular velocity per axis.
    w: [Lane<V>; 3],
    /// Steps taken (the renormalisation's schedule).
    steps: usize,
}

impl Lanes<1> {
    /// Four lanes, each at its own start.
    pub(crate) fn from_starts(starts: [Start; 4]) -> Self {
        Self {
            r: std::array::from_fn(|c| [f64x4::new(starts.map(|s| s.r0[c]))]),
            w: std::array::from_fn(|c| [f64x4::new(starts.map(|s| s.w0[c]))]),
            steps: 0,
        }
    }
}

impl<const V: usize> Lanes<V> {
    /// Every lane at `start`.
    pub(crate) fn new(start: Start) -> Self {
        Self {
            r: start.r0.map(|c| [f64x4::splat(c); V]),
            w: start.w0.map(|c| [f64x4::splat(c); V]),
            steps: 0,
        }
    }

    /// Lane `l`'s rotation to go.
    pub(crate) fn r(&self, l: usize) -> QuatXyzw {
        self.r.map(|c| c[l / 4].as_array()[l % 4])
    }

    /// Lane `l`'s angular velocity.
    pub(crate) fn w(&self, l: usize) -> [f64; 3] {
        self.w.map(|c| c[l / 4].as_array()[l % 4])
    }

    /// The angle `2 acos(min(1, |q . q_raw|))` per lane, `target` being
    /// `q_g * conj(q_raw)`.
    #[inline(always)]
    pub(crate) fn angle(&self, target: QuatXyzw) -> Lane<V> {
        self.angle_of(target.map(|c| [f64x4::splat(c); V]))
    }

    /// [`Lanes::angle`] with a target per lane (its components).
    #[inline(always)]
    pub(crate) fn angle_of(&self, t: [Lane<V>; 4]) -> Lane<V> {
        let r = &self.r;
        let c = each::<V>(|v| {
            (r[0][v] * t[0][v] + r[1][v] * t[1][v] + r[2][v] * t[2][v] + r[3][v] * t[3][v]).abs()
        });
        // min(1, c) as 1 - c >= 0; a NaN state (a diverged run) stays NaN
        // (its compare is false).
        let x = each::<V>(|v| {
            let x = ONE - c[v];
            x.simd_lt(f64x4::ZERO).bitselect(f64x4::ZERO, x)
        });
        let (p, _) = short_or_long(&ANGLE_SHORT, &ANGLE, x);
        each(|v| x[v].sqrt() * p[v])
    }

    /// One step with the forcing parts `parts` (`[F0, F1, F2]` per axis)
    /// at `(dm, km)`: returns the angular acceleration per axis and lane
    /// and advances `w` and `r` by `dt`.
    #[inline(always)]
    pub(crate) fn step(
        &mut self,
        parts: &[[f64; 3]; 3],
        dm: f64,
        km: &Lane<V>,
        dt: f64,
    ) -> [Lane<V>; 3] {
        let forcing = parts.map(|[f0, f1, f2]| Forcing {
            fd: [f64x4::splat(f0 + dm * f1); V],
            f2: [f64x4::splat(f2); V],
        });
        self.step_with(&forcing, dm, km, &[f64x4::splat(dt); V])
    }

    /// [`Lanes::step`] with the forcing term and the time step given per
    /// lane (lanes of different demos).
    #[inline(always)]
    pub(crate) fn step_with(
        &mut self,
        forcing: &[Forcing<V>; 3],
        dm: f64,
        km: &Lane<V>,
        dt: &Lane<V>,
    ) -> [Lane<V>; 3] {
        // 2 log(r) = LOG(1 - r_w) vec(r), exact where r_w < 0.
        let (mut factor, long) = short_or_long(&LOG_SHORT, &LOG, each::<V>(|v| ONE - self.r[3][v]));
        // Past 180 degrees (r_w < 0, so 1 - r_w > SHORT_X): the exact
        // factor, vector by vector.
        if long.any() {
            for v in 0..V {
                let rw = self.r[3][v].to_array();
                if rw.iter().any(|&c| c < 0.0) {
                    let mut f = factor[v].to_array();
                    for l in 0..4 {
                        if rw[l] < 0.0 {
                            f[l] = 2.0 * exact_log_factor(self.r(4 * v + l));
                        }
                    }
                    factor[v] = f64x4::new(f);
                }
            }
        }
        let dmv = f64x4::splat(dm);
        let a: [Lane<V>; 3] = std::array::from_fn(|ax| {
            let Forcing { fd, f2 } = &forcing[ax];
            each(|v| {
                let rv = factor[v] * self.r[ax][v];
                -dmv * self.w[ax][v] + km[v] * rv + (fd[v] + km[v] * f2[v])
            })
        });
        for ax in 0..3 {
            for v in 0..V {
                self.w[ax][v] += a[ax][v] * dt[v];
            }
        }
        self.steps += 1;
        self.turn(dt, self.steps.is_multiple_of(RENORMALISE_EVERY));
        a
    }

    /// `r <- r * conj(exp(w dt / 2))`, then, when `renormalise`, back to
    /// unit norm.
    #[inline(always)]
    fn turn(&mut self, dt: &Lane<V>, renormalise: bool) {
        let half = dt.map(|dt| f64x4::splat(0.5) * dt);
        let u = self.w.map(|w| each::<V>(|v| w[v] * half[v]));
        let s = each::<V>(|v| u[0][v] * u[0][v] + u[1][v] * u[1][v] + u[2][v] * u[2][v]);
        // sin|u| / |u| and cos|u| by their series in s = |u|^2: short where
        // s is small (the usual step), longer where it is not, lane by lane.
        let mut sinc = horner(&SINC_SHORT, s);
        let mut cos = horner(&COS_SHORT, s);
        let short_max = f64x4::splat(EXP_SHORT_MAX);
        // One test for all the vectors in the usual step (every lane short;
        // EXP_SERIES_MAX is above EXP_SHORT_MAX), then vector by vector.
        let long = (1..V).fold(s[0].simd_gt(short_max), |m, v| m | s[v].simd_gt(short_max));
        if long.any() {
            for v in 0..V {
                let longer = s[v].simd_gt(short_max);
                if longer.any() {
                    sinc[v] = longer.bitselect(horner(&SINC, [s[v]])[0], sinc[v]);
                    cos[v] = longer.bitselect(horner(&COS, [s[v]])[0], cos[v]);
                }
            }
            for v in 0..V {
                let sa = s[v].to_array();
                if sa.iter().any(|&s| s > EXP_SERIES_MAX) {
                    let (mut sn, mut cs) = (sinc[v].to_array(), cos[v].to_array());
                    for l in 0..4 {
                        if sa[l] > EXP_SERIES_MAX {
                            let n = sa[l].sqrt();
                            sn[l] = crate::portable::sin(n) / n;
                            cs[l] = crate::portable::cos(n);
                        }
                    }
                    sinc[v] = f64x4::new(sn);
                    cos[v] = f64x4::new(cs);
                }
            }
        }
        // e = (sinc u, cos); r * conj(e) with conj(e) = (-sinc u, cos).
        let (one_half, half_one) = (f64x4::splat(1.5), f64x4::splat(0.5));
        for v in 0..V {
            let [rx, ry, rz, rw] = [self.r[0][v], self.r[1][v], self.r[2][v], self.r[3][v]];
            let (ex, ey, ez, ew) = (
                -sinc[v] * u[0][v],
                -sinc[v] * u[1][v],
                -sinc[v] * u[2][v],
                cos[v],
            );
            let nx = rw * ex + rx * ew + ry * ez - rz * ey;
            let ny = rw * ey - rx * ez + ry * ew + rz * ex;
            let nz = rw * ez + rx * ey - ry * ex + rz * ew;
            let nw = rw * ew - rx * ex - ry * ey - rz * ez;
            let [nx, ny, nz, nw] = if renormalise {
                // One Newton step of 1 / |n| from 1: |n| - 1 is of rounding
                // size.
                let g = one_half - half_one * (nx * nx + ny * ny + nz * nz + nw * nw);
                [nx * g, ny * g, nz * g, nw * g]
            } else {
                [nx, ny, nz, nw]
            };
            self.r[0][v] = nx;
            self.r[1][v] = ny;
            self.r[2][v] = nz;
            self.r[3][v] = nw;
        }
    }
}

/// The polynomial `short` of `x` per lane where `x <= SHORT_X` (every
/// lane in the usual step: one test for all the vectors), `long` where it
/// is not, lane by lane; and whether any lane took `long`. A lane's value
/// depends only on its own `x`, whatever its neighbours.
#[inline(always)]
fn short_or_long<const S: usize, const N: usize, const V: usize>(
    short: &[f64; S],
    long: &[f64; N],
    x: Lane<V>,
) -> (Lane<V>, f64x4) {
    let mut p = horner_split(short, x);
    let limit = f64x4::splat(SHORT_X);
    let beyond = (1..V).fold(x[0].simd_gt(limit), |m, v| m | x[v].simd_gt(limit));
    if beyond.any() {
        for v in 0..V {
            let past = x[v].simd_gt(limit);
            if past.any() {
                p[v] = past.bitselect(horner_split(long, [x[v]])[0], p[v]);
            }
        }
    }
    (p, beyond)
}

const ONE: f64x4 = f64x4::splat(1.0);

/// `atan2(|v|, w) / |v|` of a unit quaternion `(v, w)`, 0 where `v = 0`
/// (method.md section 12's `log`, without its vector).
fn exact_log_factor(r: QuatXyzw) -> f64 {
    let n = (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
    if n == 0.0 {
        0.0
    } else {
        crate::portable::atan2(n, r[3]) / n
    }
}

/// Integrates `kernel` at `(dm, km[l])` for each lane: `d_rot` (radians)
/// and, when `PEAK`, `alpha_peak` per lane. The lanes go through time in
/// chunks of four-wide vectors (a lone pair fills one with copies of
/// itself); each lane's numbers are the same whatever chunk it is in.
pub(crate) fn integrate<const L: usize, const PEAK: bool>(
    kernel: &RotKernel,
    dm: f64,
    km: [f64; L],
) -> ([f64; L], [f64; L]) {
    crate::kernels::dispatch::run(Call::<L, PEAK> { kernel, dm, km })
}

/// [`integrate`]'s arguments, as a call the dispatch compiles per
/// instruction set.
struct Call<'a, const L: usize, const PEAK: bool> {
    kernel: &'a RotKernel,
    dm: f64,
    km: [f64; L],
}

impl<const L: usize, const PEAK: bool> crate::kernels::dispatch::Kernel for Call<'_, L, PEAK> {
    type Output = ([f64; L], [f64; L]);

    #[inline(always)]
    fn call(self) -> Self::Output {
        if L >= 4 * V_LANDSCAPE {
            integrate_in::<L, PEAK, V_LANDSCAPE>(self.kernel, self.dm, self.km)
        } else {
            integrate_in::<L, PEAK, 1>(self.kernel, self.dm, self.km)
        }
    }
}

/// [`integrate`] in chunks of `4 V` lanes.
#[inline(always)]
fn integrate_in<const L: usize, const PEAK: bool, const V: usize>(
    kernel: &RotKernel,
    dm: f64,
    km: [f64; L],
) -> ([f64; L], [f64; L]) {
    let mut d = [0.0; L];
    let mut peak = [0.0; L];
    for start in (0..L).step_by(4 * V) {
        let at = |l: usize| km[(start + l).min(L - 1)];
        let chunk = each::<V>(|v| f64x4::new(std::array::from_fn(|c| at(4 * v + c))));
        let (dc, pc) = integrate_chunk::<PEAK, V, _>(kernel, dm, &chunk, &mut NoPath);
        let count = (4 * V).min(L - start);
        d[start..start + count].copy_from_slice(&dc[..count]);
        peak[start..start + count].copy_from_slice(&pc[..count]);
    }
    (d, peak)
}

/// [`integrate`] for one chunk of `4 V` lanes: `d_rot` and `alpha_peak`
/// per lane.
#[inline(always)]
fn integrate_chunk<const PEAK: bool, const V: usize, O: Observe<V>>(
    kernel: &RotKernel,
    dm: f64,
    km: &Lane<V>,
    observer: &mut O,
) -> (Vec<f64>, Vec<f64>) {
    let n = kernel.forcing.len();
    let dt = 1.0 / (n.max(2) - 1) as f64;
    let mut lanes = Lanes::<V>::new(kernel.start);
    let mut err_sum = [f64x4::ZERO; V];
    let mut a2_max = vec![0.0f64; 4 * V];
    let half = f64x4::splat(0.5);
    for (k, (parts, target)) in kernel.forcing.iter().zip(&kernel.target).enumerate() {
        let theta = lanes.angle(*target);
        let ends = k == 0 || k + 1 == n;
        for v in 0..V {
            err_sum[v] += if ends { half * theta[v] } else { theta[v] };
        }
        observer.before(k, &lanes);
        let a = lanes.step(parts, dm, km, dt);
        observer.after(&a);
        if PEAK {
            for v in 0..V {
                let a2 = (a[0][v] * a[0][v] + a[1][v] * a[1][v] + a[2][v] * a[2][v]).to_array();
                for l in 0..4 {
                    let m = &mut a2_max[4 * v + l];
                    // The largest, and NaN once any step is NaN.
                    *m = if a2[l].is_nan() || m.is_nan() {
                        f64::NAN
                    } else {
                        crate::kernels::dispatch::larger(*m, a2[l])
                    };
                }
            }
        }
    }
    let dt = f64x4::splat(dt);
    let d = err_sum.iter().flat_map(|e| (*e * dt).to_array()).collect();
    (d, a2_max.into_iter().map(f64::sqrt).collect())
}

/// What [`integrate_chunk`] (and [`crate::kernels::orientation_run::rollout_forcing`])
/// shows an observer around each step.
pub(crate) trait Observe<const V: usize> {
    /// The state before step `k`.
    fn before(&mut self, k: usize, lanes: &Lanes<V>);
    /// The angular acceleration the step took.
    fn after(&mut self, a: &[Lane<V>; 3]);
}

/// The landscape's observer: nothing kept.
struct NoPath;

impl<const V: usize> Observe<V> for NoPath {
    #[inline(always)]
    fn before(&mut self, _k: usize, _lanes: &Lanes<V>) {}

    #[inline(always)]
    fn after(&mut self, _a: &[Lane<V>; 3]) {}
}

/// Keeps one lane's path (lane 0 unless [`KeepPath::in_lane`]): the
/// orientation before each step (the start itself first), its angular
/// velocity and the step's angular acceleration; what every orientation
/// rollout returns.
pub(crate) struct KeepPath {
    start: QuatXyzw,
    goal: QuatXyzw,
    lane: usize,
    path: OrientationRollout,
}

impl KeepPath {
    /// An empty path of a run from `start` to `goal` of `n` steps.
    pub(crate) fn new(start: QuatXyzw, goal: QuatXyzw, n: usize) -> Self {
        Self {
            start,
            goal,
            lane: 0,
            path: OrientationRollout {
                q: Vec::with_capacity(n),
                w: Vec::with_capacity(n),
                a: Vec::with_capacity(n),
            },
        }
    }

    /// The same, keeping lane `lane` of the four.
    pub(crate) fn in_lane(self, lane: usize) -> Self {
        Self { lane, ..self }
    }

    /// The path kept.
    pub(crate) fn into_path(self) -> OrientationRollout {
        self.path
    }
}

impl Observe<1> for KeepPath {
    fn before(&mut self, k: usize, lanes: &Lanes<1>) {
        // q = conj(r) * q_g; the first is the start itself.
        self.path.q.push(if k == 0 {
            self.start
        } else {
            rotation::mul(rotation::conj(lanes.r(self.lane)), self.goal)
        });
        self.path.w.push(lanes.w(self.lane));
    }

    fn after(&mut self, a: &[Lane<1>; 3]) {
        self.path.a.push(a.map(|v| v[0].as_array()[self.lane]));
    }
}
