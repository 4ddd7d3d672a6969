//! Unit-quaternion arithmetic for the orientation DMP (method.md section
//! 12), on plain `[x, y, z, w]` arrays: the Hamilton product, the
//! conjugate, `log` and `exp` as the method writes them, slerp and the
//! angle between two orientations. Written out (not nalgebra's) so that
//! every formula is the method's and the kernels stay on arrays.
//!
//! May use: portable.

/// A quaternion `[x, y, z, w]`.
pub type QuatXyzw = [f64; 4];

/// The identity rotation.
pub const IDENTITY: QuatXyzw = [0.0, 0.0, 0.0, 1.0];

/// The Hamilton product `a * b`.
pub fn mul(a: QuatXyzw, b: QuatXyzw) -> QuatXyzw {
    let [ax, ay, az, aw] = a;
    let [bx, by, bz, bw] = b;
    [
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
        aw * bw - ax * bx - ay * by - az * bz,
    ]
}

/// The conjugate `(-v, w)`.
pub fn conj(q: QuatXyzw) -> QuatXyzw {
    [-q[0], -q[1], -q[2], q[3]]
}

/// The four-component dot product.
pub fn dot(a: QuatXyzw, b: QuatXyzw) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3]
}

/// The quaternion scaled to unit norm (the identity for a zero one).
pub fn normalised(q: QuatXyzw) -> QuatXyzw {
    let n = dot(q, q).sqrt();
    if n > 0.0 && n.is_finite() {
        q.map(|c| c / n)
    } else {
        IDENTITY
    }
}

/// `log(q) = atan2(|v|, w) v / |v|` (0 when `v = 0`).
pub fn log(q: QuatXyzw) -> [f64; 3] {
    let v = [q[0], q[1], q[2]];
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if n == 0.0 {
        return [0.0; 3];
    }
    let s = crate::portable::atan2(n, q[3]) / n;
    v.map(|c| c * s)
}

/// `exp(u) = (sin|u| u / |u|, cos|u|)`.
pub fn exp(u: [f64; 3]) -> QuatXyzw {
    let n = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt();
    if n == 0.0 {
        return IDENTITY;
    }
    let (sin, cos) = crate::portable::sin_cos(n);
    let s = sin / n;
    [u[0] * s, u[1] * s, u[2] * s, cos]
}

/// The rotation vector `2 log(a * conj(b))` taking `b` to `a` (radians
/// times the axis).
pub fn rotation_vector(a: QuatXyzw, b: QuatXyzw) -> [f64; 3] {
    log(mul(a, conj(b))).map(|c| 2.0 * c)
}

/// The angle between two orientations, `2 acos(min(1, |a . b|))`, radians
/// (NaN for a NaN quaternion).
pub fn angle(a: QuatXyzw, b: QuatXyzw) -> f64 {
    let d = dot(a, b).abs();
    if d.is_nan() {
        return f64::NAN;
    }
    2.0 * crate::portable::acos(d.min(1.0))
}

/// Spherical linear interpolation from `a` (t = 0) to `b` (t = 1) along
/// the shorter arc of the two (for `a . b < 0` the arc to `-b`).
pub fn slerp(a: QuatXyzw, b: QuatXyzw, t: f64) -> QuatXyzw {
    let mut d = dot(a, b);
    let b = if d < 0.0 {
        d = -d;
        b.map(|c| -c)
    } else {
        b
    };
    if d > 1.0 - 1e-12 {
        // Nearly equal: the chord is the arc to rounding.
        return normalised(std::array::from_fn(|i| a[i] + t * (b[i] - a[i])));
    }
    let theta = crate::portable::acos(d.min(1.0));
    let sin = crate::portable::sin(theta);
    let (wa, wb) = (
        crate::portable::sin((1.0 - t) * theta) / sin,
        crate::portable::sin(t * theta) / sin,
    );
    std::array::from_fn(|i| wa * a[i] + wb * b[i])
}

/// Flips signs in order so that consecutive quaternions have a
/// non-negative dot product (the same rotations, no 360-degree jumps).
pub fn sign_continuous(qs: &mut [QuatXyzw]) {
    for k in 1..qs.len() {
        if dot(qs[k], qs[k - 1]) < 0.0 {
            qs[k] = qs[k].map(|c| -c);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_and_exp_invert_and_the_product_composes_rotations() {
        let u = [0.3, -0.2, 0.5];
        let q = exp(u);
        let back = log(q);
        for i in 0..3 {
            assert!((back[i] - u[i]).abs() < 1e-15);
        }
        // Two quarter turns about z make a half turn.
        let quarter = exp([0.0, 0.0, std::f64::consts::FRAC_PI_4]);
        let half = mul(quarter, quarter);
        assert!((angle(half, [0.0, 0.0, 1.0, 0.0])).abs() < 1e-7);
        assert!((angle(quarter, IDENTITY) - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        // The rotation vector from b to a rotates b onto a.
        let a = exp([0.1, 0.2, -0.3]);
        let b = exp([-0.4, 0.0, 0.2]);
        let r = rotation_vector(a, b);
        let moved = mul(exp(r.map(|c| 0.5 * c)), b);
        assert!(angle(moved, a) < 1e-7);
        // Slerp halfway is the midpoint; a flipped sign changes nothing.
        let mid = slerp(IDENTITY, half, 0.5);
        assert!(angle(mid, quarter) < 1e-7);
        let flipped = slerp(IDENTITY, half.map(|c| -c), 0.5);
        assert!(angle(flipped, quarter) < 1e-7);
        let mut qs = [quarter, quarter.map(|c| -c), half];
        sign_continuous(&mut qs);
        assert!(dot(qs[0], qs[1]) > 0.0 && dot(qs[1], qs[2]) > 0.0);
    }
}
