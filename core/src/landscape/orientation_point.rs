//! The operating point's orientation: every demo's `d_rot`, `alpha_peak`
//! and regenerated path at one gain pair, four demos at a time, one demo
//! per lane of the kernel's four-wide vectors (method.md section 12).
//!
//! A lone gain pair fills one vector with copies of itself (the kernel's
//! `integrate` at one lane), so three of its four lanes are wasted work;
//! here each lane runs its own demo with its own forcing term, target and
//! start. A model's demos share one grid ([`crate::landscape::model::Model::new`] checks), so
//! the lanes take the same steps; kernels of different lengths would each
//! run alone. Every lane does the arithmetic of a lone run, so the numbers
//! are [`crate::landscape::model::Model::evaluate`]'s and
//! [`crate::landscape::model::Model::orientation_rollout`]'s to the bit (tested in
//! `core/tests/orientation_dmp.rs`).

use std::array::from_fn;

use wide::f64x4;

use crate::fit::orientation::OrientationRollout;
use crate::kernels::orientation::{Forcing, KeepPath, Lanes, Observe as _, RotKernel};

/// Each demo's `(d_rot, alpha_peak)` and regenerated orientation at
/// `(dm, km)`, in the model's order: from its kernel where it has one, else
/// `(NaN, NaN)` and `path(i)` (no orientation, or no orientation error).
pub(crate) fn evaluate(
    kernels: &[Option<RotKernel>],
    dm: f64,
    km: f64,
    path: impl Fn(usize) -> Option<OrientationRollout>,
) -> (Vec<(f64, f64)>, Vec<Option<OrientationRollout>>) {
    let present: Vec<&RotKernel> = kernels.iter().flatten().collect();
    let mut done = integrate_demos(&present, dm, km).into_iter();
    kernels
        .iter()
        .enumerate()
        .map(
            |(i, kernel)| match kernel.as_ref().and_then(|_| done.next()) {
                Some((error, turns)) => (error, Some(turns)),
                None => ((f64::NAN, f64::NAN), path(i)),
            },
        )
        .unzip()
}

/// `(d_rot, alpha_peak)` and the regenerated path of each kernel at
/// `(dm, km)`, in order.
fn integrate_demos(
    kernels: &[&RotKernel],
    dm: f64,
    km: f64,
) -> Vec<((f64, f64), OrientationRollout)> {
    let len = |k: &RotKernel| (k.forcing.len(), k.target.len());
    let one_grid = kernels.windows(2).all(|w| len(w[0]) == len(w[1]));
    kernels
        .chunks(if one_grid { 4 } else { 1 })
        .flat_map(|group| four(group, dm, km))
        .collect()
}

/// Up to four kernels of one length, one per lane (the last repeated in
/// the lanes left).
fn four(group: &[&RotKernel], dm: f64, km: f64) -> Vec<((f64, f64), OrientationRollout)> {
    let Some(&last) = group.last() else {
        return Vec::new();
    };
    let kernel = |l: usize| group.get(l).copied().unwrap_or(last);
    // As the kernel's own loop: the time step from the forcing term's
    // length, the steps as far as both lists go.
    let n = last.forcing.len();
    let steps = n.min(last.target.len());
    let dt = 1.0 / (n.max(2) - 1) as f64;
    let (dt_lanes, km_lanes) = ([f64x4::splat(dt)], [f64x4::splat(km)]);
    let mut lanes = Lanes::from_starts(from_fn(|l| kernel(l).start));
    let mut keep: Vec<KeepPath> = group
        .iter()
        .enumerate()
        .map(|(l, k)| KeepPath::new(k.ends.0, k.ends.1, n).in_lane(l))
        .collect();
    let mut err_sum = f64x4::ZERO;
    let mut a2_max = [0.0f64; 4];
    for k in 0..steps {
        let target = from_fn(|c| [f64x4::new(from_fn(|l| kernel(l).target[k][c]))]);
        let theta = lanes.angle_of(target)[0];
        err_sum += if k == 0 || k + 1 == n {
            f64x4::splat(0.5) * theta
        } else {
            theta
        };
        for keep in &mut keep {
            keep.before(k, &lanes);
        }
        let forcing: [Forcing<1>; 3] = from_fn(|ax| Forcing {
            fd: [f64x4::new(from_fn(|l| {
                let [f0, f1, _] = kernel(l).forcing[k][ax];
                f0 + dm * f1
            }))],
            f2: [f64x4::new(from_fn(|l| kernel(l).forcing[k][ax][2]))],
        });
        let a = lanes.step_with(&forcing, dm, &km_lanes, &dt_lanes);
        for keep in &mut keep {
            keep.after(&a);
        }
        let a2 = (a[0][0] * a[0][0] + a[1][0] * a[1][0] + a[2][0] * a[2][0]).to_array();
        for (m, a2) in a2_max.iter_mut().zip(a2) {
            // The largest, and NaN once any step is NaN.
            *m = if a2.is_nan() || m.is_nan() {
                f64::NAN
            } else {
                m.max(a2)
            };
        }
    }
    let d = (err_sum * f64x4::splat(dt)).to_array();
    keep.into_iter()
        .enumerate()
        .map(|(l, keep)| ((d[l], a2_max[l].sqrt()), keep.into_path()))
        .collect()
}
