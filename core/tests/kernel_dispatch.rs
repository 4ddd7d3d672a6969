//! The landscape kernels give the same bits on the AVX-512 path as on the
//! build's baseline (`core/src/kernel_dispatch.rs`): every quantity of a
//! landscape of the planted sample (positions, E, S and the orientation's
//! `d_rot`) and each demo's `d`, `a_peak`, `e`, `d_rot` and `alpha_peak` at
//! single gain pairs. On a CPU without AVX-512 both runs take the baseline
//! and the test says so, unless `DMPSCOPE_REQUIRE_AVX512=1` (which
//! `.ci/run` sets where `/proc/cpuinfo` lists x86-64-v4's AVX-512
//! features): then it fails,
//! since the dispatch did not find what the CPU has.

mod common;

use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use dmpscope_core::fit::settings::DmpSettings;
use dmpscope_core::kernels::dispatch::{instruction_set, set_avx512};
use dmpscope_core::landscape::grid;
use dmpscope_core::landscape::grid::{Axis, AxisScale, Grid};
use dmpscope_core::{Model, PrepSettings, Quantity, Unusable, build_model};

fn model() -> Model {
    let settings = DmpSettings {
        orientation_map: true,
        ..DmpSettings::default()
    };
    build_model(
        &common::planted8_demos(),
        &PrepSettings::default(),
        settings,
        Unusable::Fail,
    )
    .expect("a model")
    .model
}

/// Every number a landscape and single points give, as bits.
fn fingerprint(model: &Arc<Model>) -> Vec<u64> {
    let axis = Axis {
        lo: 0.5,
        hi: 800.0,
        n: 20,
        scale: AxisScale::Log,
    };
    let grid = Grid { dm: axis, km: axis };
    let cancel = AtomicBool::new(false);
    let land = grid::compute(model.clone(), grid, &cancel, &mut |_, _| {}).expect("a landscape");
    // Every quantity is there to compare: d_rot too, finite at most points.
    let finite = land
        .values(Quantity::DRotSum)
        .iter()
        .filter(|v| v.is_finite())
        .count();
    assert!(
        finite > 20 * 20 / 2,
        "d_rot finite at {finite} of 400 points"
    );
    let mut bits: Vec<u64> = land.values.iter().flatten().map(|v| v.to_bits()).collect();
    for (dm, km) in [(1.0, 3.0), (25.0, 156.25), (40.0, 900.0), (300.0, 2.0)] {
        let p = model.evaluate(dm, km);
        bits.extend(p.d.iter().chain(&p.a_peak).chain(&p.e).map(|v| v.to_bits()));
        for i in 0..model.demos().len() {
            let (d, a) = model.rotation_error(i, dm, km).expect("an orientation");
            bits.extend([d.to_bits(), a.to_bits()]);
        }
    }
    bits
}

#[test]
fn avx512_path_gives_the_baseline_bits() {
    let model = Arc::new(model());
    set_avx512(true);
    let best = instruction_set();
    let fast = fingerprint(&model);
    set_avx512(false);
    if cfg!(target_arch = "x86_64") {
        assert_eq!(instruction_set(), "AVX2");
    }
    let baseline = fingerprint(&model);
    set_avx512(true);
    if best != "AVX-512" {
        assert!(
            std::env::var("DMPSCOPE_REQUIRE_AVX512").as_deref() != Ok("1"),
            "DMPSCOPE_REQUIRE_AVX512=1 but the kernels ran on {best}"
        );
        eprintln!("skipped: this CPU has no AVX-512, both runs took {best}");
    }
    assert_eq!(fast.len(), baseline.len());
    let differing = fast.iter().zip(&baseline).filter(|(a, b)| a != b).count();
    assert_eq!(differing, 0, "{differing} of {} numbers differ", fast.len());
    assert!(fast.len() > 20 * 20 * 5, "every quantity is compared");
}
