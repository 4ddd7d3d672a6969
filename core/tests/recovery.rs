//! The method on demos that share one forcing term at planted gains
//! (`core::planted`): the S minimum comes back at the planted gains, J's
//! optimum is interior and determined; on the bundled reach sample (whose
//! demos hesitate and correct) the optimum is flagged. Stiffer planted
//! gains come back biased by the preprocessing: measured and bounded here.

mod common;

use std::sync::Arc;

use dmpscope_core::extract::diagnostics::{DiagSettings, Diagnostics, DiagnosticsJob};
use dmpscope_core::fit::settings::DmpSettings;
use dmpscope_core::landscape::grid::{FillOrder, Grid, LandscapeJob};
use dmpscope_core::synth::planted_forcing::PlantedSpec;
use dmpscope_core::{Extraction, Model, PrepSettings, RawDemo, Unusable, build_model, extract};

/// The model, its extraction and the cheap diagnostics (no resampling).
fn diagnose(demos: &[RawDemo]) -> (Arc<Model>, Extraction, Diagnostics) {
    diagnose_with(demos, DmpSettings::default())
}

/// [`diagnose`] with other DMP settings (the axis SD floor).
fn diagnose_with(demos: &[RawDemo], dmp: DmpSettings) -> (Arc<Model>, Extraction, Diagnostics) {
    let built = build_model(demos, &PrepSettings::default(), dmp, Unusable::Fail).expect("model");
    let model = Arc::new(built.model);
    let mut job =
        LandscapeJob::new(model.clone(), Grid::default(), FillOrder::Raster).expect("job");
    while !job.step_par(usize::MAX) {}
    let land = job.into_landscape();
    let x = extract(&model, &land, 20.0).expect("extraction");
    let settings = DiagSettings {
        bootstrap: 0,
        ..DiagSettings::default()
    };
    let diag = DiagnosticsJob::new(model.clone(), &land, &x, settings);
    (model, x, diag.diagnostics().clone())
}

fn planted(dm: f64, km: f64, noise_m: f64) -> Vec<RawDemo> {
    let spec = PlantedSpec {
        scale_forcing: None,
        dm,
        km,
        noise_m,
        demos: 8,
        seed: 42,
    };
    common::planted_raw(&spec)
}

#[test]
fn planted_paper_gains_come_back_from_the_s_minimum_and_j_is_determined() {
    let (_, x, d) = diagnose(&planted(10.73, 20.71, 0.0));
    let m = d.s_minimum.expect("S minimum");
    let (edm, ekm) = (m.dm / 10.73 - 1.0, m.km / 20.71 - 1.0);
    eprintln!(
        "planted 10.73 / 20.71, no noise: S minimum {:.4} / {:.4} ({:+.2} % / {:+.2} %), \
         J optimum {:.4} / {:.4}, depth {:.3}",
        m.dm,
        m.km,
        100.0 * edm,
        100.0 * ekm,
        x.eval.dm,
        x.eval.km,
        d.depth.unwrap_or(f64::NAN)
    );
    assert!(
        edm.abs() < 0.05 && ekm.abs() < 0.05,
        "within 5 %: {edm} {ekm}"
    );
    assert!(!x.on_edge(), "J's optimum is interior");
    assert!(!d.flat, "and determined: depth {:?}", d.depth);
    assert!(
        d.inconsistent().is_empty(),
        "no demo stands out: {:?}",
        d.demos
    );
}

#[test]
fn the_bundled_reach_sample_is_flagged() {
    let (_, x, d) = diagnose(&common::sample_demos());
    assert!(x.on_edge(), "the sample's optimum is on the K/M edge");
    assert!(d.flat, "and flat: depth {:?}", d.depth);
}

#[test]
fn stiff_planted_gains_come_back_biased_low_by_the_preprocessing() {
    let (_, _, d) = diagnose(&planted(30.0, 400.0, 0.0));
    let m = d.s_minimum.expect("S minimum");
    let (edm, ekm) = (m.dm / 30.0 - 1.0, m.km / 400.0 - 1.0);
    eprintln!(
        "planted 30 / 400, no noise: S minimum {:.3} / {:.3} ({:+.1} % / {:+.1} %)",
        m.dm,
        m.km,
        100.0 * edm,
        100.0 * ekm
    );
    // Savitzky-Golay's smoothing and the resampling bias the recovery low
    // at stiff gains. An independent study measured about -17 % / -25 % on
    // reaches of about 1.3 s; these planted reaches last 2 to 3 s, so the
    // 21-sample window covers less of each: measured -5.7 % / -5.3 %.
    assert!(
        (-0.10..0.0).contains(&edm) && (-0.10..0.0).contains(&ekm),
        "{edm} {ekm}"
    );
}

#[test]
fn with_the_bundled_planted_samples_noise_the_optimum_stays_interior_and_determined() {
    let (_, x, d) = diagnose(&planted(10.73, 20.71, 1e-4));
    let m = d.s_minimum.expect("S minimum");
    eprintln!(
        "planted 10.73 / 20.71, 0.1 mm noise: S minimum {:.3} / {:.3}, J optimum {:.3} / {:.3}, \
         depth {:.3}",
        m.dm,
        m.km,
        x.eval.dm,
        x.eval.km,
        d.depth.unwrap_or(f64::NAN)
    );
    assert!(!x.on_edge() && !d.flat, "depth {:?}", d.depth);
    // Noise on y'' raises S most where the spring is soft: the S minimum
    // moves to stiffer gains (measured +13 % / +13 %), still near.
    assert!(m.dm / 10.73 < 1.3 && m.km / 20.71 < 1.3, "{m:?}");
}

#[test]
fn an_axis_sd_floor_keeps_a_noisy_axis_from_dominating_s() {
    // planted8: demo_05's z forcing term is mostly noise, which the
    // method's standardisation scales to unit variance like any signal: it
    // takes 27 % of S and is flagged. Flooring each axis's SD at 0.6 of the
    // demo's largest (an option beyond the method) flags nobody and brings
    // J's optimum nearer the planted gains.
    let demos = common::planted8_demos();
    let (_, x0, d0) = diagnose(&demos);
    let floored = DmpSettings {
        axis_sd_floor: 0.6,
        ..DmpSettings::default()
    };
    let (_, x1, d1) = diagnose_with(&demos, floored);
    let error = |x: &Extraction| {
        (
            (x.eval.dm / 10.73 - 1.0).abs(),
            (x.eval.km / 20.71 - 1.0).abs(),
        )
    };
    let (e0, e1) = (error(&x0), error(&x1));
    eprintln!(
        "planted8: floor 0 -> {:.3} / {:.3} (flagged {:?}), floor 0.6 -> {:.3} / {:.3} (flagged {:?})",
        x0.eval.dm,
        x0.eval.km,
        d0.inconsistent(),
        x1.eval.dm,
        x1.eval.km,
        d1.inconsistent()
    );
    assert_eq!(
        d0.inconsistent(),
        vec![4],
        "the method as written flags demo_05"
    );
    assert!(d1.inconsistent().is_empty(), "the floor flags nobody");
    assert!(
        e1.0 < e0.0 && e1.1 < e0.1,
        "nearer the planted gains: {e1:?} vs {e0:?}"
    );
    assert!(!d1.flat);
    // Out of [0, 1] is refused, naming the setting.
    let bad = DmpSettings {
        axis_sd_floor: 1.5,
        ..DmpSettings::default()
    };
    let Err(err) = build_model(&demos, &PrepSettings::default(), bad, Unusable::Fail) else {
        panic!("an axis SD floor of 1.5 is refused");
    };
    assert!(err.to_string().contains("axis SD floor"), "{err}");
}
