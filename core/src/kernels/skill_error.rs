//! The skill error E (method.md section 11): how well the one skill of all
//! demos (section 10), generalised back to each demo's own start and goal,
//! reproduces that demo.
//!
//! The skill's forcing term is `mean_j Q_j f_j` and each demo's fitted
//! `f_j = F0_j + D/M F1_j + K/M F2_j` is linear in the gains, as are the
//! maps `Q_j` (from `d_j` to `d_bar`) and `P_i` (from `d_bar` back to
//! `d_i`), which do not depend on them. So the skill's forcing term in the
//! mean frame is `G0 + D/M G1 + K/M G2` with `G_c = mean_j Q_j F_c,j`,
//! built once per model, and its run towards demo i is `P_i` times its run
//! in the mean frame (plus the start `P_i` does not give; see
//! [`crate::skill_kernel`]): a gain pair costs one more integration,
//! whatever the number of demos.

use crate::fit::lwr::Projections;
use crate::fit::mapping::Mapping;
use crate::fit::settings::SkillMode;
use crate::geom::Vec3;
use crate::kernels::position::DemoKernel;
use crate::kernels::skill::SkillKernel;
use crate::prepare::demo::PreparedDemo;

/// The smallest mean displacement a frame skill accepts, metres.
pub const MIN_FRAME_DISPLACEMENT: f64 = 1e-9;

/// The kernel of the skill run towards each demo, or why there is none
/// (a frame skill without a direction).
pub(crate) fn kernels(
    demos: &[PreparedDemo],
    projections: &[Projections],
    mode: SkillMode,
) -> Result<SkillKernel, String> {
    let own: Vec<Vec3> = demos.iter().map(|d| d.goal - d.y_raw[0]).collect();
    let nf = demos.len() as f64;
    let mut mean_d = Vec3::zeros();
    for d in &own {
        for a in 0..3 {
            mean_d[a] += d[a];
        }
    }
    let mean_d = mean_d.map(|v| v / nf);
    // One demo: the skill is the demo, E = d to the bit, whatever the mode.
    let single = demos.len() == 1;
    let map = |from: Vec3, to: Vec3, who: &str| -> Result<Mapping, String> {
        match mode.scaling() {
            _ if single => Ok(Mapping::IDENTITY),
            None => Ok(Mapping::IDENTITY),
            Some(scaling) => Mapping::between(from, to, scaling).map_err(|e| format!("{who}: {e}")),
        }
    };
    if !single
        && mode == SkillMode::Frame
        && crate::fit::mapping::norm(mean_d) < MIN_FRAME_DISPLACEMENT
    {
        return Err(format!(
            "the demos' mean displacement (goal - start) is below {MIN_FRAME_DISPLACEMENT} m: \
             on average they end where they start (opposite directions cancel, or every demo \
             returns to its start), so a frame-independent skill has no direction; choose the \
             per-axis skill mode (--skill-mode per-axis; in the app, Settings, E: skill mode)"
        ));
    }
    let to_skill: Vec<Mapping> = demos
        .iter()
        .zip(&own)
        .map(|(d, &di)| map(di, mean_d, &d.name))
        .collect::<Result<_, _>>()?;
    let (parts, v0) = mean_parts(demos, projections, &to_skill);
    let n = parts.len();
    let dt = 1.0 / (n.max(2) - 1) as f64;
    let back: Vec<Mapping> = demos
        .iter()
        .zip(&own)
        .map(|(demo, &di)| map(mean_d, di, &demo.name))
        .collect::<Result<_, _>>()?;
    // Frame-independent maps are s R: each demo's error is s |z - T|.
    let similar: Option<Vec<f64>> =
        (mode == SkillMode::Frame).then(|| frame_scales(&back, &own, mean_d));
    let targets: Vec<Vec<[f64; 3]>> = demos
        .iter()
        .map(|d| {
            d.y_raw
                .iter()
                .map(|yr| std::array::from_fn(|ax| yr[ax] - d.goal[ax]))
                .collect()
        })
        .collect();
    let steps = parts
        .iter()
        .map(|p| std::array::from_fn(|ax| [p[0][ax], p[1][ax], p[2][ax], 0.0]))
        .collect();
    let mean = DemoKernel::from_parts(
        steps,
        std::array::from_fn(|ax| -mean_d[ax]),
        std::array::from_fn(|ax| v0[ax] * dt),
    );
    Ok(SkillKernel::new(mean, &back, &targets, similar.as_deref()))
}

/// The skill's three gain-linear parts of the forcing term per step (times
/// dt^2), the mean of the demos' mapped into the mean frame, and its mean
/// mapped initial velocity.
fn mean_parts(
    demos: &[PreparedDemo],
    projections: &[Projections],
    to_skill: &[Mapping],
) -> (Vec<[Vec3; 3]>, Vec3) {
    let nf = demos.len() as f64;
    let n = demos.first().map_or(0, PreparedDemo::len);
    let dt = 1.0 / (n.max(2) - 1) as f64;
    let dt2 = dt * dt;
    let mut parts = vec![[Vec3::zeros(); 3]; n];
    let mut v0 = Vec3::zeros();
    for ((proj, q), demo) in projections.iter().zip(to_skill).zip(demos) {
        for (acc, fk) in parts.iter_mut().zip(&proj.f) {
            for (c, acc_c) in acc.iter_mut().enumerate() {
                let mapped = q.apply(Vec3::from_fn(|ax, _| fk[ax][c] * dt2));
                *acc_c += mapped;
            }
        }
        v0 += q.apply(demo.yd[0]);
    }
    for acc in &mut parts {
        for c in acc.iter_mut() {
            *c = c.map(|v| v / nf);
        }
    }
    (parts, v0.map(|v| v / nf))
}

/// The scale `s` of each frame-independent map back to a demo (`s R`).
fn frame_scales(back: &[Mapping], own: &[Vec3], mean_d: Vec3) -> Vec<f64> {
    back.iter()
        .zip(own)
        .map(|(m, &di)| match m {
            Mapping::Diagonal(d) => d[0],
            Mapping::Matrix(_) => crate::fit::mapping::norm(di) / crate::fit::mapping::norm(mean_d),
        })
        .collect()
}
