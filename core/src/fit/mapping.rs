//! How a DMP's forcing term follows a moved start and goal (method.md
//! section 10, `docs/export.md`): the [`Scaling`] modes and the 3 x 3
//! [`Mapping`] each gives from one displacement `g - y0` to another.
//!
//! The rotation is written out (Rodrigues, a pi turn near opposite
//! directions) rather than taken from a geometry crate because
//! `docs/export.md` specifies it formula by formula, so that any runner
//! reproduces the same map to rounding.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::geom::Vec3;

/// How the forcing term follows a moved goal (method.md section 10).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Scaling {
    /// The paper's per-axis factor `(g'_a - y0'_a) / (g_a - y0_a)`, left at
    /// 1 where `|g_a - y0_a| < 1e-9`.
    #[default]
    Paper,
    /// Frame-independent (Koutras and Doulgeri, 2020): the smallest rotation
    /// taking `g - y0` onto the direction of `g' - y0'`, times the ratio of
    /// their lengths.
    Frame,
}

impl Scaling {
    /// The name used on the command line and in exports.
    pub fn name(self) -> &'static str {
        match self {
            Self::Paper => "paper",
            Self::Frame => "frame",
        }
    }
}

/// A linear map of forcing terms and velocities from one displacement to
/// another. A diagonal is kept apart so that a factor of exactly 1 changes
/// no bit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Mapping {
    /// Per-axis factors.
    Diagonal([f64; 3]),
    /// A full matrix, row-major.
    Matrix([[f64; 3]; 3]),
}

impl Mapping {
    /// The identity.
    pub const IDENTITY: Self = Self::Diagonal([1.0; 3]);

    /// Applies the map to a vector.
    pub fn apply(&self, v: Vec3) -> Vec3 {
        match self {
            Self::Diagonal(d) => Vec3::from_fn(|a, _| d[a] * v[a]),
            Self::Matrix(m) => {
                Vec3::from_fn(|a, _| m[a][0] * v[0] + m[a][1] * v[1] + m[a][2] * v[2])
            }
        }
    }

    /// The map as a row-major matrix.
    pub fn matrix(&self) -> [[f64; 3]; 3] {
        match self {
            Self::Diagonal(d) => {
                std::array::from_fn(|r| std::array::from_fn(|c| if r == c { d[r] } else { 0.0 }))
            }
            Self::Matrix(m) => *m,
        }
    }

    /// The map taking displacement `from` (`g - y0`) to `to` (`g' - y0'`)
    /// under `scaling`. Frame-independent scaling needs `from` non-zero.
    pub fn between(from: Vec3, to: Vec3, scaling: Scaling) -> Result<Self> {
        let (from, to): ([f64; 3], [f64; 3]) = (from.into(), to.into());
        if from == to {
            return Ok(Self::IDENTITY);
        }
        match scaling {
            Scaling::Paper => Ok(Self::Diagonal(std::array::from_fn(|a| {
                if from[a].abs() < 1e-9 {
                    1.0
                } else {
                    to[a] / from[a]
                }
            }))),
            Scaling::Frame => {
                let (lf, lt) = (norm(from), norm(to));
                if lf < 1e-9 {
                    return Err(Error::InvalidSetting(
                        "frame-independent scaling needs a motion whose goal differs from its \
                         start; this one ends where it starts (use per-axis scaling)"
                            .into(),
                    ));
                }
                let s = lt / lf;
                let r = smallest_rotation(from.map(|v| v / lf), to.map(|v| v / lt.max(1e-300)));
                Ok(match r {
                    None => Self::Diagonal([s; 3]),
                    Some(r) => Self::Matrix(r.map(|row| row.map(|v| s * v))),
                })
            }
        }
    }
}

/// The Euclidean length, summed in axis order (the bits the golden
/// numbers were made with).
pub(crate) fn norm(v: impl Into<[f64; 3]>) -> f64 {
    let v: [f64; 3] = v.into();
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The smallest rotation taking unit vector `a` to unit vector `b`
/// (Rodrigues), `None` when they are parallel (the identity). Vectors
/// within 1e-6 of opposite turn by exactly pi about an axis perpendicular
/// to `a`: near there the smallest rotation's axis depends on the last bits
/// of the inputs, so two implementations would not agree.
fn smallest_rotation(a: [f64; 3], b: [f64; 3]) -> Option<[[f64; 3]; 3]> {
    let c = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let axis = cross(a, b);
    let sin = norm(axis);
    if sin < PARALLEL_SIN && c > 0.0 {
        return None;
    }
    let (k, s, v) = if sin < OPPOSITE_SIN && c <= 0.0 {
        // Opposite: any axis perpendicular to `a`; take the cross product
        // with the (first) coordinate axis least aligned with it.
        let least = (0..3)
            .min_by(|&i, &j| a[i].abs().total_cmp(&a[j].abs()))
            .unwrap_or(0);
        let mut e = [0.0; 3];
        e[least] = 1.0;
        let p = cross(a, e);
        let lp = norm(p);
        (p.map(|v| v / lp), 0.0, 2.0)
    } else {
        let angle = crate::portable::atan2(sin, c);
        (
            axis.map(|v| v / sin),
            crate::portable::sin(angle),
            1.0 - crate::portable::cos(angle),
        )
    };
    Some([
        [
            1.0 - v * (k[1] * k[1] + k[2] * k[2]),
            v * k[0] * k[1] - s * k[2],
            v * k[0] * k[2] + s * k[1],
        ],
        [
            v * k[0] * k[1] + s * k[2],
            1.0 - v * (k[0] * k[0] + k[2] * k[2]),
            v * k[1] * k[2] - s * k[0],
        ],
        [
            v * k[0] * k[2] - s * k[1],
            v * k[1] * k[2] + s * k[0],
            1.0 - v * (k[0] * k[0] + k[1] * k[1]),
        ],
    ])
}

/// Below this `|a x b|` with `a . b > 0`, the directions are the same.
const PARALLEL_SIN: f64 = 1e-15;
/// Below this `|a x b|` with `a . b <= 0`, the directions are opposite.
const OPPOSITE_SIN: f64 = 1e-6;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_smallest_rotation_takes_a_to_b() {
        let a = [1.0, 0.0, 0.0];
        for b in [
            [0.0, 1.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.6, 0.0, 0.8],
            [-0.36, 0.48, 0.8],
        ] {
            let r = smallest_rotation(a, b).expect("not parallel");
            let got = Mapping::Matrix(r).apply(a.into());
            for c in 0..3 {
                assert!((got[c] - b[c]).abs() < 1e-15, "{got:?} vs {b:?}");
            }
            // Orthonormal.
            for i in 0..3 {
                for j in 0..3 {
                    let dot: f64 = (0..3).map(|k| r[i][k] * r[j][k]).sum();
                    let want = if i == j { 1.0 } else { 0.0 };
                    assert!((dot - want).abs() < 1e-15);
                }
            }
        }
        assert!(smallest_rotation(a, a).is_none());
        // Within 1e-6 rad of opposite: exactly the pi turn, whatever the
        // last bits.
        let near = [-1.0, 1e-8, 0.0];
        let len = norm(near);
        let r = smallest_rotation(a, near.map(|v| v / len)).expect("opposite");
        let exact = smallest_rotation(a, [-1.0, 0.0, 0.0]).expect("opposite");
        assert_eq!(r, exact);
        assert_eq!(
            Mapping::Matrix(r).apply(a.into()),
            Vec3::new(-1.0, 0.0, 0.0)
        );
    }

    #[test]
    fn per_axis_factors_leave_a_still_axis_alone() {
        let m = Mapping::between(
            Vec3::new(0.2, 0.0, 1e-12),
            Vec3::new(0.4, 0.3, 0.1),
            Scaling::Paper,
        )
        .expect("paper");
        assert_eq!(m, Mapping::Diagonal([2.0, 1.0, 1.0]));
        assert!(Mapping::between(Vec3::zeros(), Vec3::new(0.1, 0.0, 0.0), Scaling::Frame).is_err());
    }
}
