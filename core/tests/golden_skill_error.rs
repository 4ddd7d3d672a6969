//! The skill error E, its depth and the acceptable region (method.md
//! section 11) against the independent NumPy reference
//! (`tests/golden/skill_error.py`, `expected_skill_error.json`): on the
//! reference's synthetic demos and on both bundled samples, in every skill
//! mode, to 1e-6 relative.

mod golden_data;

use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use dmpscope_core::extract::allowed::{Allowed, PickSettings, e_depth};
use dmpscope_core::fit::settings::DmpSettings;
use dmpscope_core::landscape::grid;
use dmpscope_core::landscape::grid::{Axis, AxisScale, Grid};
use dmpscope_core::{Model, PrepSettings, Quantity, RawDemo, SkillMode, extract, prepare};
use golden_data::{close, f, fs, golden, raw_demos};
use serde_json::Value;

const REL: f64 = 1e-6;

/// The raw demos of a set of `input_samples.json`.
fn sample_demos(set: &str) -> Vec<RawDemo> {
    let input = golden("input_samples.json");
    input["sets"][set]
        .as_array()
        .expect("set")
        .iter()
        .map(|d| golden_data::raw_demo(d, &format!("{set}.mcap")))
        .collect()
}

fn model(raw: &[RawDemo], mode: SkillMode) -> Arc<Model> {
    let prepared = raw
        .iter()
        .map(|r| prepare(r, &PrepSettings::default()).expect("prepare"))
        .collect();
    let settings = DmpSettings {
        skill_mode: mode,
        ..DmpSettings::default()
    };
    Arc::new(Model::new(prepared, settings).expect("model"))
}

fn check_set(name: &str, raw: &[RawDemo], exp: &Value) {
    let n = exp["grid"]["n"].as_u64().expect("n") as usize;
    let axis = Axis {
        lo: f(&exp["grid"]["lo"]),
        hi: f(&exp["grid"]["hi"]),
        n,
        scale: AxisScale::Log,
    };
    let grid = Grid { dm: axis, km: axis };
    for mode in SkillMode::ALL {
        let m = model(raw, mode);
        let e = &exp["modes"][mode.name()];
        let land = grid::compute(
            Arc::clone(&m),
            grid,
            &AtomicBool::new(false),
            &mut |_, _| {},
        )
        .expect("landscape");
        let ours = land.values(Quantity::ESum);
        let mut worst = 0.0f64;
        for i in 0..n {
            for j in 0..n {
                let at = format!("{name} {} E[{i}][{j}]", mode.name());
                let want = f(&e["e_sum"][i][j]);
                close(ours[land.index(i, j)], want, REL, &at);
                worst = worst.max((ours[land.index(i, j)] - want).abs() / want.abs());
            }
        }
        eprintln!("{name} {}: E grid within {worst:.1e} relative", mode.name());
        let depth = e_depth(&land).expect("depth");
        let want = f(&e["e_depth"]);
        assert!(
            (depth - want).abs() <= REL * want.max(1e-3),
            "{name} {} E depth {depth} vs {want}",
            mode.name()
        );
        for p in e["points"].as_array().expect("points") {
            let eval = m.evaluate(f(&p["dm"]), f(&p["km"]));
            for (k, (ours, want)) in eval.e.iter().zip(fs(&p["e"])).enumerate() {
                close(*ours, want, REL, &format!("{name} {} e[{k}]", mode.name()));
            }
        }
        // The acceptable region does not depend on the mode.
        let x = extract(&m, &land, 20.0).expect("extract");
        close(x.j, f(&exp["optimum"]["j"]), 1e-9, &format!("{name} J*"));
        let allowed = Allowed::new(&m, &land, &x, PickSettings::default());
        let acc = &exp["acceptable"];
        let region = &allowed.acceptable;
        assert!(
            (region.fraction - f(&acc["fraction"])).abs() < 1e-12,
            "{name} fraction {} vs {}",
            region.fraction,
            acc["fraction"]
        );
        for (key, ours) in [("dm", region.dm), ("km", region.km), ("zeta", region.zeta)] {
            match (ours, acc[key].as_array()) {
                (Some(r), Some(w)) => {
                    close(r[0], f(&w[0]), REL, &format!("{name} {key} lo"));
                    close(r[1], f(&w[1]), REL, &format!("{name} {key} hi"));
                }
                (None, None) => {}
                (o, w) => panic!("{name} {key}: ours {o:?}, reference {w:?}"),
            }
        }
    }
}

#[test]
fn skill_error_and_region_match_the_reference_on_the_synthetic_demos() {
    let expected = golden("expected_skill_error.json");
    check_set("input", &raw_demos(), &expected["sets"]["input"]);
}

#[test]
fn skill_error_and_region_match_the_reference_on_the_bundled_samples() {
    let expected = golden("expected_skill_error.json");
    for set in ["reach10", "planted8"] {
        check_set(set, &sample_demos(set), &expected["sets"][set]);
    }
}

#[test]
fn with_one_demo_e_equals_d_to_the_bit() {
    for mode in SkillMode::ALL {
        let m = model(&raw_demos()[..1], mode);
        for (dm, km) in [(10.73, 20.71), (25.0, 156.25), (0.3, 900.0)] {
            let e = m.evaluate(dm, km);
            assert_eq!(e.e, e.d, "{}", mode.name());
            assert_eq!(e.e_sum, e.d_sum, "{}", mode.name());
        }
    }
}
