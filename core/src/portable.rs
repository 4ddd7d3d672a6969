//! The transcendental functions of every computation whose numbers the
//! browser must give to the bit as the native build does, from the `libm`
//! crate (a port of musl's): the same code in both, where the platform's
//! functions differ (glibc natively, compiler-builtins' port in
//! WebAssembly), now and then in the last bit. With these and only
//! `+ - * / sqrt`, which IEEE 754 fixes, a computation gives the same
//! numbers natively and in the browser. The GUI's drawing (colour scales,
//! ticks, the 3D grid) keeps the platform's functions: it changes no
//! number a user reads or exports.
//!
//! A last bit matters. The orientation's error angle `2 acos(|q . q_raw|)`
//! of a small error reads `1 - |q . q_raw|`, so a rounding of the dot
//! product becomes about 1e-9 of the angle: the quaternions a `sin` of a
//! different last bit prepared gave Table I's `d_rot` 5e-10 apart in the
//! browser (`web/tests/browser.mjs` compares them). And an RL run is
//! chaotic ([`crate::rl`]).
//!
//! May use: nothing.

/// `e^x`.
#[inline]
pub fn exp(x: f64) -> f64 {
    libm::exp(x)
}

/// The natural logarithm.
#[inline]
pub fn ln(x: f64) -> f64 {
    libm::log(x)
}

/// The base-10 logarithm.
#[inline]
pub fn log10(x: f64) -> f64 {
    libm::log10(x)
}

/// `x^y`.
#[inline]
pub fn pow(x: f64, y: f64) -> f64 {
    libm::pow(x, y)
}

/// `sin(x)`.
#[inline]
pub fn sin(x: f64) -> f64 {
    libm::sin(x)
}

/// `cos(x)`.
#[inline]
pub fn cos(x: f64) -> f64 {
    libm::cos(x)
}

/// `(sin(x), cos(x))`.
#[inline]
pub fn sin_cos(x: f64) -> (f64, f64) {
    libm::sincos(x)
}

/// `atan2(y, x)`.
#[inline]
pub fn atan2(y: f64, x: f64) -> f64 {
    libm::atan2(y, x)
}

/// `acos(x)`.
#[inline]
pub fn acos(x: f64) -> f64 {
    libm::acos(x)
}

/// `tanh(x)`.
#[inline]
pub fn tanh(x: f64) -> f64 {
    libm::tanh(x)
}
