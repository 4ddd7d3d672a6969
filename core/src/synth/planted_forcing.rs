//! What the planted demos share (method.md sections 3 and 12): their spec
//! and the one forcing term, fitted at the planted gains to a nominal
//! minimum-jerk reach, towards any reach; see [`crate::synth::planted`].

use crate::fit::basis::Basis;
use crate::fit::lwr::fit_weights;
use crate::fit::settings::DmpSettings;

/// Substeps of the fine integration per step of the unit-time grid.
pub(crate) const SUBSTEPS: usize = 10;

/// Points of the unit-time grid the nominal forcing term is fitted on.
pub(crate) const GRID: usize = crate::DEFAULT_GRID_POINTS;

/// What to generate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlantedSpec {
    /// The planted D/M.
    pub dm: f64,
    /// The planted K/M.
    pub km: f64,
    /// Standard deviation of the position noise per axis, metres.
    pub noise_m: f64,
    /// Number of demonstrations.
    pub demos: usize,
    /// The seed.
    pub seed: u64,
    /// How the shared forcing term follows each demo's goal: `None` keeps
    /// it absolute (the same in every demo, as a DMP without spatial
    /// scaling); `Some(scaling)` maps it from the nominal reach to the
    /// demo's as section 10's scaling does (`Frame`: turned and scaled
    /// with the goal).
    pub scale_forcing: Option<crate::fit::mapping::Scaling>,
}

/// Minimum-jerk profile on [0, 1] and its first two derivatives.
fn min_jerk(u: f64) -> [f64; 3] {
    let (u2, u3) = (u * u, u * u * u);
    [
        u3 * (10.0 - 15.0 * u + 6.0 * u2),
        30.0 * u2 - 60.0 * u3 + 30.0 * u2 * u2,
        60.0 * u - 180.0 * u2 + 120.0 * u3,
    ]
}

/// The nominal reach (metres, relative to its start).
pub(crate) const NOMINAL: [f64; 3] = [0.25, 0.28, 0.14];

/// The forcing term `f(x) = x sum psi_i w_i / sum psi_i` at any phase.
pub(crate) struct Forcing {
    pub(crate) centres: Vec<f64>,
    pub(crate) widths: Vec<f64>,
    pub(crate) weights: [Vec<f64>; 3],
}

/// The forcing term fitted to the nominal reach at `(dm, km)`.
pub(crate) fn nominal_forcing(dm: f64, km: f64) -> Forcing {
    forcing_towards(dm, km, NOMINAL)
}

/// The forcing term fitted at `(dm, km)` to a minimum-jerk motion of
/// `reach` from rest to rest (per axis; for the orientation, `reach` is
/// the rotation vector, and `2 log(q_g * conj(q))` is `reach (1 - p)`).
pub(crate) fn forcing_towards(dm: f64, km: f64, reach: [f64; 3]) -> Forcing {
    let settings = DmpSettings::default();
    // The paper's basis cannot fail on the default settings and grid; an
    // empty basis (no weights) would give a zero forcing term.
    let basis = Basis::new(&settings, GRID).ok();
    let weights = std::array::from_fn(|ax| {
        let target: Vec<f64> = (0..GRID)
            .map(|k| {
                let [p, v, a] = min_jerk(k as f64 / (GRID - 1) as f64);
                let g = reach[ax];
                a * g + dm * v * g + km * (p * g - g)
            })
            .collect();
        basis
            .as_ref()
            .map_or_else(Vec::new, |b| fit_weights(b, &target))
    });
    let (centres, widths) = basis.map_or((Vec::new(), Vec::new()), |b| (b.centres, b.widths));
    Forcing {
        centres,
        widths,
        weights,
    }
}

/// Rotates `v` about the z axis by `angle` radians.
pub(crate) fn turn(v: [f64; 3], angle: f64) -> [f64; 3] {
    let (s, c) = angle.sin_cos();
    [c * v[0] - s * v[1], s * v[0] + c * v[1], v[2]]
}
