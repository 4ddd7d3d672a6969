//! Tests that would catch a wrong method (shared/method.md), not just run it:
//! LWR and
//! regeneration on cases whose answer is known exactly, the invariances of
//! `S`, `J` recombination, bit-identical landscape fill paths, extraction on a
//! landscape with a known interior optimum, and the paper presets.

mod common;

use common::{close, max_abs};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use dmpscope_core::fit::basis::Basis;
use dmpscope_core::fit::lwr::{fit_weights, forcing_from_weights};
use dmpscope_core::fit::settings::DmpSettings;
use dmpscope_core::landscape::grid;
use dmpscope_core::landscape::grid::{Axis, AxisScale, FillOrder, Grid};
use dmpscope_core::report::presets::preset;
use dmpscope_core::synth::vive;
use dmpscope_core::{
    Error, Landscape, LandscapeJob, Model, PAPER_PRESETS, PrepSettings, PreparedDemo, RawDemo,
    extract, prepare,
};

// ---------------------------------------------------------------- helpers

fn reach_raw(seed: u64, count: usize) -> Vec<RawDemo> {
    vive::reach_raw_demos(seed, count, 1_700_000_000_000_000_000)
}

fn model_of(raws: &[RawDemo]) -> Model {
    let prepared = raws
        .iter()
        .map(|r| prepare(r, &PrepSettings::default()).expect("prepare"))
        .collect();
    Model::new(prepared, DmpSettings::default()).expect("model")
}

fn log_grid(dm: (f64, f64, usize), km: (f64, f64, usize)) -> Grid {
    let axis = |(lo, hi, n)| Axis {
        lo,
        hi,
        n,
        scale: AxisScale::Log,
    };
    Grid {
        dm: axis(dm),
        km: axis(km),
    }
}

fn norm(v: impl Into<[f64; 3]>) -> f64 {
    let v: [f64; 3] = v.into();
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// Whether `v` lies in the axis' range, up to a relative `slack`.
fn inside(v: f64, a: &Axis, slack: f64) -> bool {
    v >= a.lo * (1.0 - slack) && v <= a.hi * (1.0 + slack)
}

fn compute(m: &Arc<Model>, grid: Grid) -> Landscape {
    grid::compute(m.clone(), grid, &AtomicBool::new(false), &mut |_, _| {}).expect("landscape")
}

const D0: f64 = 6.0;
const K0: f64 = 20.0;

/// Section 4's recurrence at `(D0, K0)` with forcing `x * c` per axis from
/// `y = 0`, `y' = v0`: `[y, y', y'']` at every grid point.
fn simulate(x: &[f64], g: [f64; 3], v0: [f64; 3], c: [f64; 3]) -> [Vec<[f64; 3]>; 3] {
    let dt = 1.0 / (x.len() - 1) as f64;
    let (mut y, mut v) = ([0.0; 3], v0);
    let mut out: [Vec<[f64; 3]>; 3] = Default::default();
    for &xk in x {
        let a = [0, 1, 2].map(|ax| -D0 * v[ax] - K0 * (y[ax] - g[ax]) + xk * c[ax]);
        out[0].push(y);
        out[1].push(v);
        out[2].push(a);
        for ax in 0..3 {
            v[ax] += a[ax] * dt;
            y[ax] += v[ax] * dt;
        }
    }
    out
}

/// A demo that is itself a DMP at `(D0, K0)` with forcing `x * c`, `c` chosen
/// (the end point is affine in it) so that the path ends at `g`.
fn dmp_demo(g: [f64; 3], v0: [f64; 3]) -> (PreparedDemo, [f64; 3]) {
    let x = Basis::new(&DmpSettings::default(), 1001).expect("basis").x;
    let end = |c| simulate(&x, g, v0, c)[0][1000];
    let (e0, e1) = (end([0.0; 3]), end([1.0; 3]));
    let c = [0, 1, 2].map(|ax| (g[ax] - e0[ax]) / (e1[ax] - e0[ax]));
    let [y, yd, ydd] = simulate(&x, g, v0, c);
    let (name, goal, y_raw) = (format!("dmp {g:?}"), y[1000], y.clone());
    let (duration_s, median_interval_s, n0, p0) = (1.0, 1e-3, 1001, [0.0; 3]);
    let vecs = |v: Vec<[f64; 3]>| v.into_iter().map(Into::into).collect();
    let demo = PreparedDemo {
        name,
        n_samples: 1001,
        duration_s,
        median_interval_s,
        n0,
        p0: p0.into(),
        goal: goal.into(),
        y_raw: vecs(y_raw),
        y: vecs(y),
        yd: vecs(yd),
        ydd: vecs(ydd),
        orientation: None,
        acc_noise: None,
        suggested_sg_seconds: None,
    };
    (demo, c)
}

/// Three DMP demos at `(D0, K0)` that differ in goal and initial velocity;
/// their forcing constants share a sign per axis, so `S(D0, K0) = 0` and `J`
/// has its exact minimum 0 there.
fn dmp_model() -> Model {
    let (a, c0) = dmp_demo([0.30, 0.20, -0.10], [0.1, -0.2, 0.05]);
    let (b, c1) = dmp_demo([0.25, 0.35, -0.20], [-0.3, 0.1, 0.2]);
    let (c, c2) = dmp_demo([0.40, 0.10, -0.15], [0.0; 3]);
    let signs = [c0, c1, c2].map(|c| c.map(f64::signum));
    assert!(
        signs.iter().all(|s| *s == signs[0]),
        "precondition: c signs {signs:?}"
    );
    Model::new(vec![a, b, c], DmpSettings::default()).expect("model")
}

// ------------------------------------------------------------------- LWR

#[test]
fn basis_and_lwr_weights_follow_the_contract() {
    let settings = DmpSettings::default();
    assert_eq!(settings.basis_functions, 100);
    let alpha = 100f64.ln();
    close(settings.alpha_x, alpha, 1e-15, "alpha_x");
    let basis = Basis::new(&settings, 1001).expect("basis");
    let c: Vec<f64> = (0..100).map(|i| (-alpha * i as f64 / 99.0).exp()).collect();
    for i in 0..100 {
        close(basis.centres[i], c[i], 1e-15 * c[i], format_args!("c[{i}]"));
        let h = 1.0 / (c[i.min(98) + 1] - c[i.min(98)]).powi(2);
        close(basis.widths[i], h, 1e-12 * h, format_args!("h[{i}]"));
    }
    for k in [0, 1, 500, 999, 1000] {
        let x = (-alpha * k as f64 / 1000.0).exp();
        close(basis.x[k], x, 1e-15, format_args!("x[{k}]"));
        for i in [0, 37, 99] {
            let psi = (-basis.widths[i] * (x - c[i]).powi(2)).exp();
            close(basis.row(k)[i], psi, 1e-12, format_args!("psi[{k}][{i}]"));
        }
    }
    close(basis.x[1000], 0.01, 1e-15, "x(1)");
    // LWR weights, summed here independently.
    let target: Vec<f64> = (0..1001)
        .map(|k| (k as f64 * 0.013).cos() * 3.0 - 1.0)
        .collect();
    let w = fit_weights(&basis, &target);
    for i in 0..basis.len() {
        let (mut num, mut den) = (0.0, 0.0);
        for k in 0..1001 {
            let (x, psi) = (basis.x[k], basis.row(k)[i]);
            num += x * psi * target[k];
            den += x * x * psi;
        }
        let expected = if den < 1e-300 { 0.0 } else { num / den };
        let tol = 1e-12 * expected.abs().max(1.0);
        close(w[i], expected, tol, format_args!("w[{i}]"));
    }
}

#[test]
fn lwr_is_exact_for_a_representable_target() {
    let basis = Basis::new(&DmpSettings::default(), 1001).expect("basis");
    for c in [1.0, -37.5, 2.5e3] {
        // f = x * c, built by the forcing term from constant weights.
        let target = forcing_from_weights(&basis, &vec![c; basis.len()]);
        let tol = 1e-12 * c.abs();
        for (k, f) in target.iter().enumerate() {
            close(*f, basis.x[k] * c, tol, format_args!("target[{k}]"));
        }
        let w = fit_weights(&basis, &target);
        for (i, wi) in w.iter().enumerate() {
            close(*wi, c, tol, format_args!("w[{i}]"));
        }
        let fit = forcing_from_weights(&basis, &w);
        let tol = 1e-9 * max_abs(target.iter().copied());
        for k in 0..1001 {
            close(fit[k], target[k], tol, format_args!("f[{k}]"));
        }
    }
}

#[test]
fn lwr_does_not_reproduce_a_non_representable_target() {
    // Alternating weights: a forcing term the basis can express, but LWR (a
    // local average, not a projection) does not recover: the test above can fail.
    let basis = Basis::new(&DmpSettings::default(), 1001).expect("basis");
    let w: Vec<f64> = (0..basis.len()).map(|i| [1.0, -1.0][i % 2]).collect();
    let target = forcing_from_weights(&basis, &w);
    let fit = forcing_from_weights(&basis, &fit_weights(&basis, &target));
    let err = max_abs(fit.iter().zip(&target).map(|(a, b)| a - b));
    assert!(err > 1e-3 * max_abs(target.iter().copied()), "error {err}");
}

// ----------------------------------------------------------- regeneration

#[test]
fn regeneration_with_the_exact_forcing_term_reproduces_the_demo() {
    let m = dmp_model();
    let x = &m.basis().x;
    let e = m.evaluate(D0, K0);
    for (i, demo) in m.demos().iter().enumerate() {
        // f_target at (D0, K0) is x * c, which LWR fits exactly.
        let f = m.forcing(i, D0, K0);
        for k in 0..demo.len() {
            for ax in 0..3 {
                let (y, g) = (demo.y[k][ax], demo.goal[ax]);
                let target = demo.ydd[k][ax] + D0 * demo.yd[k][ax] + K0 * (y - g);
                let c = (demo.ydd[0][ax] + D0 * demo.yd[0][ax] - K0 * g) / x[0];
                let tol = 1e-9 * c.abs();
                close(target, x[k] * c, tol, format_args!("x c [{k}][{ax}]"));
                close(f[k][ax], target, tol, format_args!("fit[{k}][{ax}]"));
            }
        }
        let r = m.rollout(i, D0, K0);
        let scale = max_abs(demo.y.iter().flatten().copied());
        let dev =
            r.y.iter()
                .zip(&demo.y_raw)
                .map(|(a, b)| norm([0, 1, 2].map(|ax| a[ax] - b[ax])));
        close(max_abs(dev), 0.0, 1e-9 * scale, "rollout");
        close(e.d[i], 0.0, 1e-10, format_args!("d[{i}]"));
        close(m.path_error(i, &r.y), e.d[i], 1e-12, "path_error");
        // a_peak is the largest acceleration norm of the regenerated path.
        let a_peak = demo.ydd.iter().map(|a| norm(*a)).fold(0.0, f64::max);
        close(e.a_peak[i], a_peak, 1e-9 * a_peak, "a_peak");
    }
    close(e.s, 0.0, 1e-9, "S");
    // Other gains do not reproduce it: d measures something.
    for (dm, km) in [(2.0 * D0, K0), (D0, 0.5 * K0), (1.0, 300.0)] {
        let e = m.evaluate(dm, km);
        assert!(e.d.iter().chain([&e.s]).all(|&v| v > 1e-5), "{e:?}");
    }
}

#[test]
fn d_a_peak_s_and_the_fit_match_an_independent_evaluation() {
    let m = model_of(&reach_raw(5, 3));
    let n = m.demos()[0].len();
    let dt = 1.0 / (n - 1) as f64;
    let trap = |k: usize| if k == 0 || k + 1 == n { 0.5 } else { 1.0 };
    for (dm, km) in [(10.73, 20.71), (0.3, 500.0), (100.0, 2.0)] {
        let e = m.evaluate(dm, km);
        let mut sig2 = vec![0.0; n];
        for ax in 0..3 {
            let mut stand = Vec::new();
            for (i, d) in m.demos().iter().enumerate() {
                // Section 3: f_target and its LWR fit, from the prepared demo.
                let f: Vec<f64> = (0..n)
                    .map(|k| d.ydd[k][ax] + dm * d.yd[k][ax] + km * (d.y[k][ax] - d.goal[ax]))
                    .collect();
                let fit = forcing_from_weights(m.basis(), &fit_weights(m.basis(), &f));
                let tol = 1e-10 * max_abs(fit.iter().copied());
                for (k, fk) in m.forcing(i, dm, km).iter().enumerate() {
                    close(fk[ax], fit[k], tol, format_args!("fit[{i}][{k}][{ax}]"));
                }
                // Section 5: standardise with the population SD.
                let mean = f.iter().sum::<f64>() / n as f64;
                let sd = (f.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n as f64).sqrt();
                let inv = if sd < 1e-12 { 0.0 } else { 1.0 / sd };
                stand.push(f.iter().map(|v| (v - mean) * inv).collect::<Vec<_>>());
            }
            // The sample SD across demos at each grid point.
            let nd = stand.len() as f64;
            for k in 0..n {
                let mean = stand.iter().map(|s| s[k]).sum::<f64>() / nd;
                sig2[k] += stand.iter().map(|s| (s[k] - mean).powi(2)).sum::<f64>() / (nd - 1.0);
            }
        }
        let s: f64 = (0..n).map(|k| trap(k) * sig2[k].sqrt()).sum::<f64>() * dt;
        close(e.s, s, 1e-10 * s, format_args!("S({dm}, {km})"));
        // Section 4: semi-implicit Euler, trapezoid d, peak acceleration.
        for (i, demo) in m.demos().iter().enumerate() {
            let (f, g) = (m.forcing(i, dm, km), demo.goal);
            let (mut y, mut v) = (demo.y_raw[0], demo.yd[0]);
            let (mut d, mut a_peak) = (0.0, 0.0f64);
            for k in 0..n {
                let a: [f64; 3] =
                    std::array::from_fn(|ax| -dm * v[ax] - km * (y[ax] - g[ax]) + f[k][ax]);
                d += trap(k) * norm(std::array::from_fn(|ax| y[ax] - demo.y_raw[k][ax])) * dt;
                a_peak = a_peak.max(norm(a));
                for ax in 0..3 {
                    v[ax] += a[ax] * dt;
                    y[ax] += v[ax] * dt;
                }
            }
            close(e.d[i], d, 1e-12 * d, format_args!("d[{i}]({dm}, {km})"));
            close(
                e.a_peak[i],
                a_peak,
                1e-12 * a_peak,
                format_args!("a_peak[{i}]"),
            );
        }
        assert_eq!(e.d_sum, e.d.iter().sum::<f64>());
    }
}

// ------------------------------------------------------------- similarity

/// `base` with positions `scale * p + shift` and stamps `t0 + stretch * (t - t_first)`.
fn transformed(
    base: &RawDemo,
    (scale, shift, t0, stretch): ([f64; 3], [f64; 3], i64, i64),
) -> RawDemo {
    let first = base.stamps_ns[0];
    let stamps_ns = base
        .stamps_ns
        .iter()
        .map(|s| t0 + (s - first) * stretch)
        .collect();
    let moved = |p: &dmpscope_core::geom::Vec3| {
        dmpscope_core::geom::Vec3::from_fn(|ax, _| scale[ax] * p[ax] + shift[ax])
    };
    let positions = base.positions.iter().map(moved).collect();
    RawDemo {
        stamps_ns,
        positions,
        ..base.clone()
    }
}

#[test]
fn similarity_vanishes_for_scaled_shifted_retimed_copies() {
    let base = reach_raw(7, 1).remove(0);
    let copies: Vec<RawDemo> = [
        ([1.0; 3], [0.0; 3], 0, 1),
        ([2.0, 0.5, 3.0], [0.0; 3], 0, 1),
        ([1.0; 3], [1.0, -2.0, 0.3], 5_000_000_000, 1),
        ([1.0; 3], [0.0; 3], 123_456_789, 3),
        ([0.7, 1.9, 0.25], [-0.4, 0.1, 2.0], 9_000_000_000, 2),
    ]
    .into_iter()
    .map(|t| transformed(&base, t))
    .collect();
    let m = model_of(&copies);
    assert!(m.demos().iter().all(|d| d.n0 == m.demos()[0].n0), "same n0");
    let gains = [
        (0.1, 0.1),
        (10.73, 20.71),
        (100.0, 20.0),
        (3.0, 900.0),
        (1000.0, 1000.0),
    ];
    for (dm, km) in gains {
        close(
            m.evaluate(dm, km).s,
            0.0,
            1e-9,
            format_args!("S({dm}, {km})"),
        );
    }
    let different = model_of(&reach_raw(7, 4));
    let one = model_of(&reach_raw(7, 1));
    for (dm, km) in gains {
        let s = different.evaluate(dm, km).s;
        assert!(s > 1e-3, "S({dm}, {km}) = {s} for different demos");
        assert_eq!(one.evaluate(dm, km).s, 0.0, "one demo");
    }
}

// -------------------------------------------------------------- landscape

#[test]
fn recombined_j_equals_direct_evaluation_bit_for_bit() {
    let m = Arc::new(model_of(&reach_raw(3, 3)));
    let land = compute(&m, log_grid((0.5, 500.0, 8), (0.2, 800.0, 8)));
    assert!(land.is_complete());
    let ks = [0.0, 1.0, 20.0, 1e3];
    let js: Vec<Vec<f64>> = ks.iter().map(|&k| land.j(k)).collect();
    for (i, &dm) in land.dm.iter().enumerate() {
        for (jj, &km) in land.km.iter().enumerate() {
            let idx = land.index(i, jj);
            let e = m.evaluate(dm, km);
            let ours = (land.d_sum()[idx].to_bits(), land.s()[idx].to_bits());
            assert_eq!(ours, (e.d_sum.to_bits(), e.s.to_bits()), "[{i}][{jj}]");
            for (kk, &k) in ks.iter().enumerate() {
                assert_eq!(js[kk][idx], e.j(k), "J(k = {k}) at [{i}][{jj}]");
            }
        }
    }
}

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

#[test]
fn landscape_fill_paths_are_bit_identical() {
    let m = Arc::new(model_of(&reach_raw(11, 3)));
    let grid = log_grid((0.1, 1000.0, 12), (0.1, 1000.0, 12));
    let job = |order| LandscapeJob::new(m.clone(), grid, order).expect("job");
    let no_cancel = AtomicBool::new(false);

    let mut raster = job(FillOrder::Raster);
    while !raster.step(7) {}
    let mut c2f = job(FillOrder::CoarseToFine);
    while !c2f.step(5) {}
    let mut parallel = job(FillOrder::CoarseToFine);
    parallel.run(&no_cancel, &mut |_, _| {}).expect("run");
    let mut mixed = job(FillOrder::Raster);
    mixed.step(3);
    mixed.step(9);
    mixed.run(&no_cancel, &mut |_, _| {}).expect("run");

    let reference = raster.into_landscape();
    assert!(reference.is_complete());
    assert!(
        reference
            .d_sum()
            .iter()
            .chain(reference.s())
            .all(|v| v.is_finite())
    );
    for (name, other) in [("coarse-to-fine", c2f), ("run", parallel), ("mixed", mixed)] {
        let l = other.into_landscape();
        assert!(l.is_complete(), "{name}");
        assert_eq!(bits(l.d_sum()), bits(reference.d_sum()), "sum d, {name}");
        assert_eq!(bits(l.s()), bits(reference.s()), "S, {name}");
    }
}

#[test]
fn landscape_cancellation_and_partial_previews() {
    let m = Arc::new(model_of(&reach_raw(11, 3)));
    // Set before the start: nothing is computed.
    let grid = log_grid((0.1, 1000.0, 12), (0.1, 1000.0, 12));
    let mut job = LandscapeJob::new(m.clone(), grid, FillOrder::CoarseToFine).expect("job");
    let r = job.run(&AtomicBool::new(true), &mut |_, _| {});
    assert!(matches!(r, Err(Error::Cancelled)), "{r:?}");
    assert_eq!(job.progress().0, 0);

    // Partial fills in slices: every preview point has a value.
    for order in [FillOrder::CoarseToFine, FillOrder::Raster] {
        let mut job = LandscapeJob::new(m.clone(), grid, order).expect("job");
        job.step(7);
        let l = job.landscape();
        assert!(!l.is_complete() && l.d_sum().iter().any(|v| v.is_nan()));
        for values in [l.d_sum(), l.s()] {
            assert!(l.preview(values).iter().all(|v| !v.is_nan()), "{order:?}");
        }
    }

    // Cancelled mid-run (after the first 1024-point tile): the points done
    // stay and equal a full run's.
    let big = log_grid((0.1, 1000.0, 40), (0.1, 1000.0, 40));
    let cancel = AtomicBool::new(false);
    let mut job = LandscapeJob::new(m.clone(), big, FillOrder::CoarseToFine).expect("job");
    let r = job.run(&cancel, &mut |_, _| cancel.store(true, Ordering::Relaxed));
    assert!(matches!(r, Err(Error::Cancelled)), "{r:?}");
    let (done, total) = job.progress();
    assert!(done > 0 && done < total, "{done} of {total}");
    let partial = job.landscape();
    assert_eq!(partial.filled, done);
    for values in [partial.d_sum(), partial.s()] {
        assert!(partial.preview(values).iter().all(|v| !v.is_nan()));
    }
    let full = compute(&m, big);
    for (idx, (d, s)) in partial.d_sum().iter().zip(partial.s()).enumerate() {
        if !d.is_nan() {
            assert_eq!(bits(&[*d, *s]), bits(&[full.d_sum()[idx], full.s()[idx]]));
        }
    }
}

// ------------------------------------------------------------- extraction

#[test]
fn extraction_finds_a_known_interior_optimum() {
    // J = 0 exactly at (D0, K0) and > 0 elsewhere; the grid does not contain
    // that point. (With k = 1 the grid minimum is a different local minimum
    // at the K/M = 2 edge, which is what the method then refines.)
    let m = Arc::new(dmp_model());
    let land = compute(&m, log_grid((1.0, 60.0, 12), (2.0, 200.0, 12)));
    for k in [20.0, 1e3] {
        let x = extract(&m, &land, k).expect("extract");
        let (i, j, grid_j) = land.argmin(k).expect("argmin");
        assert_eq!(((i, j), grid_j), (x.grid_min, x.grid_min_j));
        assert!(x.converged, "k = {k}: not converged");
        assert!(!x.on_edge(), "k = {k}: edges {:?}", x.edges);
        assert!(x.j <= x.grid_min_j, "k = {k}: {x:?}");
        close(x.j, 0.0, 1e-6, format_args!("J, k = {k}"));
        close(x.eval.dm, D0, 1e-5 * D0, format_args!("D/M, k = {k}"));
        close(x.eval.km, K0, 1e-5 * K0, format_args!("K/M, k = {k}"));
        assert_eq!(x.eval.zeta, x.eval.dm / (2.0 * x.eval.km.sqrt()));
    }
}

#[test]
fn extraction_flags_a_box_that_cuts_off_the_minimum() {
    let m = Arc::new(dmp_model());
    // Boxes that cut (D0, K0) = (6, 20) off on each side.
    let boxes = [
        ((1.0, 60.0), (0.1, 1.0), "K/M at its maximum"),
        ((1.0, 60.0), (50.0, 500.0), "K/M at its minimum"),
        ((1.0, 5.0), (2.0, 200.0), "D/M at its maximum"),
        ((10.0, 100.0), (2.0, 200.0), "D/M at its minimum"),
    ];
    for ((d0, d1), (k0, k1), words) in boxes {
        let grid = log_grid((d0, d1, 8), (k0, k1, 8));
        let land = compute(&m, grid);
        // (For the first box and k = 1e3 the optimum is a corner.)
        for k in [20.0, 1e3].into_iter().take(if k1 < K0 { 1 } else { 2 }) {
            let x = extract(&m, &land, k).expect("extract");
            assert!(x.on_edge(), "{words}, k = {k}: not on the edge");
            assert_eq!(x.edges.describe(), words, "k = {k}: {:?}", x.edges);
            let (e, slack) = (&x.eval, 0.0);
            assert!(
                inside(e.dm, &grid.dm, slack) && inside(e.km, &grid.km, slack),
                "{e:?}"
            );
            assert!(x.j <= x.grid_min_j * (1.0 + slack), "{words}: {x:?}");
        }
    }
}

#[test]
fn extraction_stays_inside_the_box_and_never_above_the_grid_minimum() {
    let m = Arc::new(dmp_model());
    for ((d0, d1), (k0, k1)) in [((1.0, 4.0), (5.0, 80.0)), ((0.5, 3.0), (10.0, 40.0))] {
        let grid = log_grid((d0, d1, 8), (k0, k1, 8));
        let x = extract(&m, &compute(&m, grid), 20.0).expect("extract");
        let e = &x.eval;
        assert!(
            inside(e.dm, &grid.dm, 0.0),
            "D/M = {} outside {:?}",
            e.dm,
            grid.dm
        );
        assert!(
            inside(e.km, &grid.km, 0.0),
            "K/M = {} outside {:?}",
            e.km,
            grid.km
        );
        assert!(
            x.j <= x.grid_min_j,
            "J = {} > grid minimum {}",
            x.j,
            x.grid_min_j
        );
    }
}

// ----------------------------------------------------------------- presets

#[test]
fn paper_presets_have_the_table_names_gains_and_zeta() {
    let table = [
        ("Ours", 10.73, 20.71, "1.18"),
        ("Hrstc1", 25.0, 156.25, "1.00"),
        ("Hrstc2", 10.0, 200.0, "0.35"),
        ("Hrstc3", 100.0, 20.0, "11.18"),
        ("Hrstc4", 4.0, 4.0, "1.00"),
    ];
    assert_eq!(PAPER_PRESETS.len(), table.len());
    let m = model_of(&reach_raw(3, 2));
    for (p, (name, dm, km, zeta)) in PAPER_PRESETS.iter().zip(table) {
        assert_eq!((p.name, p.dm, p.km), (name, dm, km));
        let z = dmpscope_core::landscape::model::zeta(p.dm, p.km);
        assert_eq!(z, dm / (2.0 * km.sqrt()));
        assert_eq!(format!("{z:.2}"), zeta, "{name}");
        assert_eq!(m.evaluate(p.dm, p.km).zeta, z);
        assert_eq!(preset(&name.to_lowercase()), Some(*p));
    }
}
