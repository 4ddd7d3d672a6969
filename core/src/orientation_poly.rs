//! The polynomials of the orientation kernel (`orientation_kernel.rs`,
//! method.md section 12): the Chebyshev interpolants for `log` and `acos`,
//! the Taylor series of `exp`, and their evaluation per lane, each
//! coefficient a plain multiplication and addition (no fused
//! multiply-add), so the browser's build gives the same bits.

use wide::f64x4;

use crate::orientation_kernel::{Lane, each};

/// `acos(1 - x) / sqrt(2 x)` on [0, 1]: Chebyshev interpolant of degree
/// 9 in monomial form (relative error 3.9e-10; it only weighs the error
/// angle, whose contract is 1e-6: degree 12 gave 1.4e-12 for 6 more
/// operations per step).
pub(crate) const P: [f64; 10] = [
    0.999_999_999_762_410_8,
    0.083_333_380_744_394_71,
    0.018_748_453_218_823_91,
    0.005_599_733_581_045_396,
    0.001_777_112_581_952_619_5,
    0.001_131_505_507_113_143,
    -0.000_641_688_886_021_077_3,
    0.001_256_498_308_949_558_4,
    -0.000_763_852_629_054_951_1,
    0.000_279_591_916_451_759_03,
];

/// `acos(1 - x) / sqrt(x (2 - x))` on [0, 1]: Chebyshev interpolant of
/// degree 14 in monomial form (relative error 1.6e-12).
pub(crate) const H: [f64; 15] = [
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
