//! One orientation rollout (method.md section 12) through the orientation
//! kernel's own step, one lane wide, so a rollout equals the landscape's
//! evaluation to the bit.

use crate::fit::lwr::Projections;
use crate::fit::orientation::{OrientationRollout, OrientationTarget, forcing_at};
use crate::kernels::orientation::{KeepPath, Lanes, Observe as _, Start};

/// Integrates the orientation DMP with the fitted forcing term of `proj`
/// at `(dm, km)` from `target` (method.md section 12).
pub fn rollout(
    proj: &Projections,
    dm: f64,
    km: f64,
    target: OrientationTarget,
) -> OrientationRollout {
    rollout_forcing(&forcing_at(proj, dm, km), dm, km, target)
}

/// Integrates the orientation DMP with a forcing term on the grid (the
/// kernel's steps: [`crate::kernels::orientation`]).
pub fn rollout_forcing(
    forcing: &[[f64; 3]],
    dm: f64,
    km: f64,
    target: OrientationTarget,
) -> OrientationRollout {
    let n = forcing.len();
    let dt = 1.0 / (n.max(2) - 1) as f64;
    let mut lanes = Lanes::<1>::new(Start::new(target.start, target.w0, target.goal));
    let mut keep = KeepPath::new(target.start, target.goal, n);
    for (k, f) in forcing.iter().enumerate() {
        keep.before(k, &lanes);
        // -0.0, not 0.0: `v + D (-0) + K (-0)` is `v` to the bit, a `-0`
        // included, as the kernel's `F0 + D F1 + K F2` with the same sum.
        let parts = f.map(|v| [v, -0.0, -0.0]);
        let a = lanes.step(&parts, dm, &[wide::f64x4::splat(km)], dt);
        keep.after(&a);
    }
    keep.into_path()
}
