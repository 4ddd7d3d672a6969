//! The small geometric types every per-axis computation goes through: a
//! position or velocity ([`Vec3`]) and an orientation ([`Quat`]), both
//! nalgebra's (measured: a 1001-step rollout on `Vector3<f64>` costs the
//! same as on `[f64; 3]`, ~10 us, with the same bits).
//!
//! May use: nothing.

/// A position, velocity or acceleration in metres (per second, per second
/// squared), z up.
pub type Vec3 = nalgebra::Vector3<f64>;

/// An orientation: a unit quaternion (nalgebra stores `[x, y, z, w]`, as
/// ROS and Foxglove do).
pub type Quat = nalgebra::UnitQuaternion<f64>;

/// The least norm a stored quaternion may have to count as an orientation
/// (an all-zero quaternion, protobuf's unset value, does not).
pub const MIN_QUAT_NORM: f64 = 1e-6;

/// A stored `[x, y, z, w]` as a unit quaternion: normalised, `None` when a
/// part is not finite or its norm is below [`MIN_QUAT_NORM`].
pub fn quat_from_xyzw(q: [f64; 4]) -> Option<Quat> {
    if !q.iter().all(|v| v.is_finite()) {
        return None;
    }
    let [x, y, z, w] = q;
    Quat::try_new(nalgebra::Quaternion::new(w, x, y, z), MIN_QUAT_NORM)
}

/// A unit quaternion as `[x, y, z, w]`.
pub fn xyzw(q: &Quat) -> [f64; 4] {
    let c = q.coords;
    [c.x, c.y, c.z, c.w]
}

/// Vectors as plain `[x, y, z]` arrays (what file formats and plots hold).
pub fn arrays(v: &[Vec3]) -> Vec<[f64; 3]> {
    v.iter().map(|p| (*p).into()).collect()
}

/// The rotation that takes a y-up frame's axes to dmpscope's z-up ones
/// (the same map as the positions': `(x, y, z) -> (-z, -x, y)`).
pub fn y_up_to_z_up() -> Quat {
    let m = nalgebra::Matrix3::new(0.0, 0.0, -1.0, -1.0, 0.0, 0.0, 0.0, 1.0, 0.0);
    Quat::from_matrix(&m)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stored_quaternions_become_unit_or_none() {
        let q = quat_from_xyzw([0.0, 0.0, 2.0, 0.0]).expect("a rotation");
        assert_eq!(xyzw(&q), [0.0, 0.0, 1.0, 0.0]);
        assert!(quat_from_xyzw([0.0; 4]).is_none());
        assert!(quat_from_xyzw([f64::NAN, 0.0, 0.0, 1.0]).is_none());
    }

    #[test]
    fn the_y_up_rotation_maps_axes_as_positions_are_mapped() {
        let r = y_up_to_z_up();
        for (p, e) in [
            ([1.0, 0.0, 0.0], [0.0, -1.0, 0.0]),
            ([0.0, 1.0, 0.0], [0.0, 0.0, 1.0]),
            ([0.0, 0.0, 1.0], [-1.0, 0.0, 0.0]),
        ] {
            let v = r * Vec3::from(p);
            assert!((v - Vec3::from(e)).norm() < 1e-12, "{p:?} -> {v:?}");
        }
    }
}
