//! The polynomials of the orientation kernel (`kernels/orientation.rs`,
//! method.md section 12): the Chebyshev interpolants for `log` and `acos`,
//! the Taylor series of `exp`, and their evaluation per lane, each
//! coefficient a plain multiplication and addition (no fused
//! multiply-add), so the browser's build gives the same bits.

use wide::f64x4;

/// A value per lane: `V` vectors of four.
pub(crate) type Lane<const V: usize> = [f64x4; V];

/// `f` of each vector of lanes.
#[inline(always)]
pub(crate) fn each<const V: usize>(f: impl Fn(usize) -> f64x4) -> Lane<V> {
    std::array::from_fn(f)
}

/// `2 acos(1 - x) / sqrt(x)`, the error angle over `sqrt(x)`, on [0, 1]:
/// Chebyshev interpolant of degree 9 in monomial form (relative error
/// 3.9e-10; it only weighs the error angle, whose contract is 1e-6:
/// degree 12 gave 1.4e-12 for 6 more operations per step). Where
/// `x <= SHORT_X`, [`ANGLE_SHORT`] gives it.
pub(crate) const ANGLE: [f64; 10] = [
    2.828_427_124_074_19,
    0.235_702_394_493_850_2,
    0.053_028_633_638_371_31,
    0.015_838_438_300_986_43,
    0.005_026_433_606_959_383,
    0.003_200_380_551_135_496_2,
    -0.001_814_969_980_478_054,
    0.003_553_913_856_012_514_5,
    -0.002_160_501_576_145_179_7,
    0.000_790_805_398_719_385_3,
];

/// [`ANGLE`] on [0, [`SHORT_X`]]: Chebyshev interpolant of degree 6
/// (relative error 5.1e-12), the usual step's (an error of up to 91
/// degrees).
pub(crate) const ANGLE_SHORT: [f64; 7] = [
    2.828_427_124_759_226_5,
    0.235_702_256_142_462_65,
    0.053_033_233_931_524_634,
    0.015_779_185_263_589_61,
    0.005_412_222_803_681_203,
    0.001_783_223_116_703_333_9,
    0.001_198_615_635_381_677_7,
];

/// Where the short polynomials [`ANGLE_SHORT`] and [`LOG_SHORT`] hold:
/// `x = 1 - c <= 0.3`, a rotation of up to 91 degrees.
pub(crate) const SHORT_X: f64 = 0.3;

/// `acos(1 - x) / sqrt(x (2 - x))` on [0, 1]: Chebyshev interpolant of
/// degree 14 in monomial form (relative error 1.6e-12); the kernel takes
/// [`LOG`], its double.
const H: [f64; 15] = [
    1.000_000_000_001_252_8,
    0.333_333_332_770_229_14,
    0.133_333_375_148_984_94,
    0.057_141_637_300_469_77,
    0.025_415_364_999_111_064,
    0.011_375_321_663_665_916,
    0.006_322_844_843_329_726,
    -0.001_502_298_021_389_347,
    0.012_347_249_346_905_799,
    -0.021_609_571_116_093_653,
    0.031_309_013_051_909_154,
    -0.030_025_049_047_274_998,
    0.019_484_702_657_264_683,
    -0.007_507_430_365_838_659,
    0.001_377_833_559_918_371_2,
];

/// `2 H`, `2 log(r) / vec(r)` of a rotation `r` with `x = 1 - r_w` in
/// [0, 1]: exactly [`H`]'s coefficients doubled. Where `x <= SHORT_X`,
/// [`LOG_SHORT`] gives it.
pub(crate) const LOG: [f64; 15] = doubled(H);

/// [`LOG`] on [0, [`SHORT_X`]]: Chebyshev interpolant of degree 8
/// (relative error 1.7e-13, below [`H`]'s), the usual step's (a rotation
/// to go of up to 91 degrees).
pub(crate) const LOG_SHORT: [f64; 9] = [
    2.000_000_000_000_326_4,
    0.666_666_666_489_788_6,
    0.266_666_682_337_534_1,
    0.114_285_182_232_789_31,
    0.050_802_650_174_964_13,
    0.023_003_180_967_102_552,
    0.011_119_874_069_248_173,
    0.003_531_066_208_666_623_3,
    0.004_609_437_726_561_291,
];

/// Every coefficient times two (exact in binary).
const fn doubled<const N: usize>(c: [f64; N]) -> [f64; N] {
    let mut out = c;
    let mut k = 0;
    while k < N {
        out[k] = 2.0 * c[k];
        k += 1;
    }
    out
}

/// `c[0] + c[1] x + ...` per lane (Horner).
#[inline(always)]
pub(crate) fn horner<const N: usize, const V: usize>(c: &[f64; N], x: Lane<V>) -> Lane<V> {
    let mut p = [f64x4::splat(c[N - 1]); V];
    for k in (0..N - 1).rev() {
        let ck = f64x4::splat(c[k]);
        for v in 0..V {
            p[v] = p[v] * x[v] + ck;
        }
    }
    p
}

/// `c[0] + c[1] x + ...` per lane as `E(x^2) + x O(x^2)`, the even and
/// odd coefficients each by Horner: two chains of half the length, which
/// the lanes' vectors overlap.
#[inline(always)]
pub(crate) fn horner_split<const N: usize, const V: usize>(c: &[f64; N], x: Lane<V>) -> Lane<V> {
    let x2 = each::<V>(|v| x[v] * x[v]);
    let last_even = (N - 1) & !1;
    let last_odd = if N.is_multiple_of(2) { N - 1 } else { N - 2 };
    let mut even = [f64x4::splat(c[last_even]); V];
    let mut odd = [f64x4::splat(c[last_odd]); V];
    for k in (0..last_even).step_by(2).rev() {
        let ck = f64x4::splat(c[k]);
        for v in 0..V {
            even[v] = even[v] * x2[v] + ck;
        }
    }
    let mut k = last_odd;
    while k >= 3 {
        k -= 2;
        let ck = f64x4::splat(c[k]);
        for v in 0..V {
            odd[v] = odd[v] * x2[v] + ck;
        }
    }
    each(|v| even[v] + x[v] * odd[v])
}

/// `sin(sqrt(s)) / sqrt(s)` to `s^2`, for `s <= EXP_SHORT_MAX`.
pub(crate) const SINC_SHORT: [f64; 3] = [1.0, -1.0 / 6.0, 1.0 / 120.0];

/// `cos(sqrt(s))` to `s^3`, for `s <= EXP_SHORT_MAX`.
pub(crate) const COS_SHORT: [f64; 4] = [1.0, -0.5, 1.0 / 24.0, -1.0 / 720.0];

/// `sin(sqrt(s)) / sqrt(s)`: its Taylor series in `s` to `s^4`.
pub(crate) const SINC: [f64; 5] = [1.0, -1.0 / 6.0, 1.0 / 120.0, -1.0 / 5040.0, 1.0 / 362_880.0];

/// `cos(sqrt(s))`: its Taylor series in `s` to `s^5`.
pub(crate) const COS: [f64; 6] = [
    1.0,
    -0.5,
    1.0 / 24.0,
    -1.0 / 720.0,
    1.0 / 40320.0,
    -1.0 / 3_628_800.0,
];

#[cfg(test)]
mod tests {
    use super::*;

    /// One polynomial at `x`, through the kernel's own evaluation.
    fn eval<const N: usize>(c: &[f64; N], x: f64) -> f64 {
        horner_split(c, [f64x4::splat(x)])[0].as_array()[0]
    }

    /// The largest relative error of `c` against `f` on `n` points of
    /// `(0, hi]`.
    fn worst<const N: usize>(c: &[f64; N], f: impl Fn(f64) -> f64, hi: f64) -> f64 {
        (1..=2000)
            .map(|i| {
                let x = hi * i as f64 / 2000.0;
                (eval(c, x) / f(x) - 1.0).abs()
            })
            .fold(0.0, f64::max)
    }

    /// `2 log(r) / vec(r)` at `x = 1 - r_w`: `2 acos(r_w) / |vec r|`, with
    /// `acos(1 - x) = 2 asin(sqrt(x / 2))` for accuracy near 0.
    fn log_factor(x: f64) -> f64 {
        4.0 * (x / 2.0).sqrt().asin() / (x * (2.0 - x)).sqrt()
    }

    /// `2 acos(1 - x) / sqrt(x)`.
    fn angle(x: f64) -> f64 {
        4.0 * (x / 2.0).sqrt().asin() / x.sqrt()
    }

    #[test]
    fn the_interpolants_hold_their_stated_errors() {
        assert!(worst(&LOG, log_factor, 1.0) < 2e-12);
        assert!(worst(&LOG_SHORT, log_factor, SHORT_X) < 3e-13);
        assert!(worst(&ANGLE, angle, 1.0) < 4e-10);
        assert!(worst(&ANGLE_SHORT, angle, SHORT_X) < 6e-12);
        // The short ones are no use past their range.
        assert!(worst(&LOG_SHORT, log_factor, 1.0) > 1e-9);
        // At 0: 2 and 2 sqrt(2).
        assert!((eval(&LOG_SHORT, 0.0) - 2.0).abs() < 1e-12);
        assert!((eval(&ANGLE_SHORT, 0.0) / 8f64.sqrt() - 1.0).abs() < 6e-12);
    }
}
