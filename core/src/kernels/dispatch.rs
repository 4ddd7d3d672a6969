//! Runs a landscape kernel with the best vector instructions the CPU has.
//!
//! The kernels are plain arrays of lanes that LLVM vectorises for whatever
//! instructions the function is compiled with. Natively the build's
//! baseline is x86-64-v3 (AVX2, 16 vector registers); on a CPU with
//! AVX-512 (32 registers, eight `f64` per instruction) the same code,
//! inlined into a function compiled for AVX-512 by `pulp`'s safe dispatch,
//! keeps the lanes' state in registers. Every lane does the same IEEE
//! additions, multiplications and square roots in the same order on either
//! path (Rust never contracts into fused multiply-adds), so the numbers are
//! the same bits (`core/tests/kernel_dispatch.rs`), and the browser, which
//! has no dispatch, agrees with the native build.
//!
//! `DMPSCOPE_SIMD=baseline` in the environment, or [`set_avx512`], turns
//! the AVX-512 path off (to compare, or for a CPU that misreports it).

use std::sync::atomic::{AtomicU8, Ordering};

/// 0: not decided yet; 1: AVX-512 allowed; 2: baseline only.
static ALLOWED: AtomicU8 = AtomicU8::new(0);

/// Allows (the default, unless `DMPSCOPE_SIMD=baseline`) or forbids the
/// AVX-512 path for every kernel from now on, in every thread.
pub fn set_avx512(allowed: bool) {
    ALLOWED.store(if allowed { 1 } else { 2 }, Ordering::Relaxed);
}

/// Whether the AVX-512 path may be taken (the environment decides once).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn allowed() -> bool {
    match ALLOWED.load(Ordering::Relaxed) {
        0 => {
            let yes = std::env::var("DMPSCOPE_SIMD").map_or(true, |v| v != "baseline");
            // A concurrent `set_avx512` wins over the environment.
            let _ = ALLOWED.compare_exchange(
                0,
                if yes { 1 } else { 2 },
                Ordering::Relaxed,
                Ordering::Relaxed,
            );
            ALLOWED.load(Ordering::Relaxed) == 1
        }
        v => v == 1,
    }
}

/// A kernel's call: its arguments and an `#[inline(always)]` body, so
/// that the body is compiled for the instruction set [`run`] picks (a
/// closure would be compiled once, for the baseline).
pub(crate) trait Kernel {
    /// What the kernel returns.
    type Output;
    /// Runs the kernel; must be `#[inline(always)]`, as everything it
    /// calls in its loops.
    fn call(self) -> Self::Output;
}

/// Runs `kernel` compiled for the best instruction set available.
#[inline(always)]
pub(crate) fn run<K: Kernel>(kernel: K) -> K::Output {
    #[cfg(target_arch = "x86_64")]
    {
        if let Some(simd) = avx512() {
            return pulp::Simd::vectorize(simd, Call(kernel));
        }
    }
    baseline(kernel)
}

/// `kernel` compiled for the build's baseline, in a function of its own
/// (inlined beside the AVX-512 copy it was compiled worse: 10-30 % slower).
#[inline(never)]
fn baseline<K: Kernel>(kernel: K) -> K::Output {
    kernel.call()
}

/// The AVX-512 token where the CPU has it and it is allowed.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn avx512() -> Option<pulp::x86::V4> {
    if allowed() {
        pulp::x86::V4::try_new()
    } else {
        None
    }
}

/// A kernel as pulp's vectorised operation (the instruction set's token is
/// not used: the compiler vectorises the kernel's arrays).
#[cfg(target_arch = "x86_64")]
struct Call<K>(K);

#[cfg(target_arch = "x86_64")]
impl<K: Kernel> pulp::WithSimd for Call<K> {
    type Output = K::Output;

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) -> K::Output {
        self.0.call()
    }
}

/// The larger of `kept` and `x`, keeping `kept` where `x` is NaN: what
/// `kept.max(x)` gives for a `kept` that is not NaN, written as a compare
/// and a select. `f64::max` is IEEE `maxNum`, which WebAssembly lacks (its
/// `f64.max` propagates NaN), so on wasm32 LLVM compiles every `max` into
/// a call to `fmax`: one call per lane and step, and a loop around it that
/// is not vectorised. The select is one `f64x2.pmax` there (and one
/// `vmaxpd` natively, against `maxNum`'s three instructions).
#[inline(always)]
pub(crate) fn larger(kept: f64, x: f64) -> f64 {
    if x > kept { x } else { kept }
}

/// The instruction set the kernels run with now (for `bench`).
pub fn instruction_set() -> &'static str {
    #[cfg(target_arch = "x86_64")]
    {
        if avx512().is_some() {
            "AVX-512"
        } else if cfg!(target_feature = "avx2") {
            "AVX2"
        } else {
            "SSE2 (a build without x86-64-v3)"
        }
    }
    #[cfg(target_arch = "wasm32")]
    {
        "WebAssembly SIMD"
    }
    #[cfg(not(any(target_arch = "x86_64", target_arch = "wasm32")))]
    {
        "the build's baseline"
    }
}
