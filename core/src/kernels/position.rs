//! The position DMP's integration (method.md section 4) over lanes of gain
//! pairs that share D/M, in the scaled variables `z = y - g` and
//! `u = v dt`: what every landscape point, [`crate::landscape::model::Model::evaluate`] and
//! the skill error E integrate. The kernel is written over `L` lanes as
//! plain arrays, which LLVM vectorises (an explicit `wide::f64x4` version,
//! as the orientation kernel has, measured 3-10 % slower here: this kernel
//! is bound by its additions, multiplications and one square root per step,
//! not by registers); every lane does the arithmetic of a lone pair in the
//! same order, so one pair gives the same bits alone or in a batch,
//! natively or in the browser (no fused multiply-add).

/// One demo laid out for the integration kernel, in scaled variables
/// `z = y - g` and `u = v dt`, so that a step is
/// `u += (F0 + D F1 + K F2) dt^2 - K dt^2 z - D dt u; z += u`.
#[derive(Clone, Debug)]
pub(crate) struct DemoKernel {
    /// Per grid point and axis: `[F0 dt^2, F1 dt^2, F2 dt^2, y_raw - g]`.
    pub(crate) steps: Vec<[[f64; 4]; 3]>,
    /// `y_raw(0) - g`.
    pub(crate) z0: [f64; 3],
    /// `y'(0) dt`.
    pub(crate) u0: [f64; 3],
}

impl DemoKernel {
    /// A kernel from its parts: per grid point and axis
    /// `[F0 dt^2, F1 dt^2, F2 dt^2, y_raw - g]`, `z0 = y_raw(0) - g` and
    /// `u0 = y'(0) dt`.
    pub(crate) fn from_parts(steps: Vec<[[f64; 4]; 3]>, z0: [f64; 3], u0: [f64; 3]) -> Self {
        Self { steps, z0, u0 }
    }

    /// The kernel of a prepared demo and its projections.
    pub(crate) fn new(
        demo: &crate::prepare::demo::PreparedDemo,
        proj: &crate::fit::lwr::Projections,
    ) -> Self {
        let n = demo.len();
        let dt = 1.0 / (n - 1) as f64;
        let dt2 = dt * dt;
        let g = demo.goal;
        let steps = proj
            .f
            .iter()
            .zip(&demo.y_raw)
            .map(|(fk, yr)| {
                std::array::from_fn(|ax| {
                    [
                        fk[ax][0] * dt2,
                        fk[ax][1] * dt2,
                        fk[ax][2] * dt2,
                        yr[ax] - g[ax],
                    ]
                })
            })
            .collect();
        Self {
            steps,
            z0: std::array::from_fn(|ax| demo.y_raw[0][ax] - g[ax]),
            u0: std::array::from_fn(|ax| demo.yd[0][ax] * dt),
        }
    }
}

/// Something computed at each grid point alongside an integration (the
/// skill error's reading of the skill's run, [`crate::skill_kernel`]).
pub(crate) trait StepRead<const L: usize> {
    /// Called at grid point `k` (weight `w` of the trapezoid rule), with
    /// the integration's `z = y - g` there.
    fn step(&mut self, k: usize, w: f64, z: &[[f64; L]; 3]);
}

impl<const L: usize> StepRead<L> for () {
    #[inline(always)]
    fn step(&mut self, _k: usize, _w: f64, _z: &[[f64; L]; 3]) {}
}

/// Integrates a kernel at `(dm, km[l])` for each lane (method.md section
/// 4, in the kernel's scaled variables) and returns `d` (or `e`) and, when
/// `PEAK`, `a_peak` per lane.
pub(crate) fn integrate<const L: usize, const PEAK: bool>(
    kernel: &DemoKernel,
    dm: f64,
    km: [f64; L],
) -> ([f64; L], [f64; L]) {
    integrate_reading::<L, PEAK, ()>(kernel, dm, km, &mut ())
}

/// [`integrate`], with `read` stepped at every grid point.
pub(crate) fn integrate_reading<const L: usize, const PEAK: bool, R: StepRead<L>>(
    kernel: &DemoKernel,
    dm: f64,
    km: [f64; L],
    read: &mut R,
) -> ([f64; L], [f64; L]) {
    crate::kernels::dispatch::run(Lanes::<L, PEAK, R> {
        kernel,
        dm,
        km,
        read,
    })
}

/// [`integrate_reading`]'s arguments, as a call the dispatch compiles per
/// instruction set.
struct Lanes<'a, const L: usize, const PEAK: bool, R> {
    kernel: &'a DemoKernel,
    dm: f64,
    km: [f64; L],
    read: &'a mut R,
}

impl<const L: usize, const PEAK: bool, R: StepRead<L>> crate::kernels::dispatch::Kernel
    for Lanes<'_, L, PEAK, R>
{
    type Output = ([f64; L], [f64; L]);

    #[inline(always)]
    fn call(self) -> Self::Output {
        integrate_lanes::<L, PEAK, R>(self.kernel, self.dm, self.km, self.read)
    }
}

/// [`integrate`] on the instruction set it is inlined into.
#[inline(always)]
fn integrate_lanes<const L: usize, const PEAK: bool, R: StepRead<L>>(
    kernel: &DemoKernel,
    dm: f64,
    km: [f64; L],
    read: &mut R,
) -> ([f64; L], [f64; L]) {
    let n = kernel.steps.len();
    let dt = 1.0 / (n - 1) as f64;
    let dt2 = dt * dt;
    let ddt = dm * dt;
    let kdt2 = km.map(|k| k * dt2);
    let mut z: [[f64; L]; 3] = std::array::from_fn(|ax| [kernel.z0[ax]; L]);
    let mut u: [[f64; L]; 3] = std::array::from_fn(|ax| [kernel.u0[ax]; L]);
    let mut err_sum = [0.0; L];
    let mut du2_max = [0.0f64; L];
    for (k, step) in kernel.steps.iter().enumerate() {
        let w = if k == 0 || k + 1 == n { 0.5 } else { 1.0 };
        read.step(k, w, &z);
        let mut e2 = [0.0; L];
        let mut du2 = [0.0; L];
        for ax in 0..3 {
            let [f0, f1, f2, target] = step[ax];
            let fd = f0 + dm * f1;
            for l in 0..L {
                let e = z[ax][l] - target;
                e2[l] += e * e;
                // a dt^2 = f dt^2 - K dt^2 (y - g) - D dt (v dt)
                let du = fd + km[l] * f2 - kdt2[l] * z[ax][l] - ddt * u[ax][l];
                if PEAK {
                    du2[l] += du * du;
                }
                u[ax][l] += du;
                z[ax][l] += u[ax][l];
            }
        }
        for l in 0..L {
            err_sum[l] += w * e2[l].sqrt();
            if PEAK {
                du2_max[l] = crate::kernels::dispatch::larger(du2_max[l], du2[l]);
            }
        }
    }
    (err_sum.map(|e| e * dt), du2_max.map(|m| m.sqrt() / dt2))
}
