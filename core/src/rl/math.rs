//! The transcendental functions of RL, from the `libm` crate (a port of
//! musl's) instead of the platform's: a training run is chaotic, so a last
//! bit of difference between glibc's `tanh` and the browser build's grows
//! into another learning curve. With these (and only `+ - * / sqrt`,
//! which IEEE 754 fixes, elsewhere) a seed gives the same numbers natively
//! and in WebAssembly.

use crate::synth::Rng;

/// `tanh(x)`.
pub fn tanh(x: f64) -> f64 {
    libm::tanh(x)
}

/// `e^x`.
pub fn exp(x: f64) -> f64 {
    libm::exp(x)
}

/// The natural logarithm.
pub fn ln(x: f64) -> f64 {
    libm::log(x)
}

/// `x^y`.
pub fn pow(x: f64, y: f64) -> f64 {
    libm::pow(x, y)
}

/// A standard normal draw (Box-Muller on two of `rng`'s uniforms, as
/// [`Rng::normal`] but with the portable functions).
pub fn normal(rng: &mut Rng) -> f64 {
    let u1 = 1.0 - rng.uniform();
    let u2 = rng.uniform();
    (-2.0 * ln(u1)).sqrt() * libm::cos(std::f64::consts::TAU * u2)
}
