//! The transcendental functions of RL, the portable ones of
//! [`crate::portable`] (the `libm` crate) instead of the platform's: a
//! training run is chaotic, so a last bit of difference between glibc's
//! `tanh` and the browser build's grows into another learning curve. With
//! these (and only `+ - * / sqrt`, which IEEE 754 fixes, elsewhere) a seed
//! gives the same numbers natively and in WebAssembly.

pub use crate::portable::{exp, ln, pow, tanh};

use crate::rng::Rng;

/// A standard normal draw (Box-Muller on two of `rng`'s uniforms, as
/// [`Rng::normal`] but with the portable functions).
pub fn normal(rng: &mut Rng) -> f64 {
    let u1 = 1.0 - rng.uniform();
    let u2 = rng.uniform();
    (-2.0 * ln(u1)).sqrt() * crate::portable::cos(std::f64::consts::TAU * u2)
}
