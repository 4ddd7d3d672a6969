//! The core against an independent NumPy/SciPy implementation of method.md
//! (`tests/golden/`, see its README for how the values were made).

mod golden_data;

use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use dmpscope_core::fit::settings::DmpSettings;
use dmpscope_core::landscape::grid::compute;
use dmpscope_core::landscape::grid::{Axis, AxisScale, Grid};
use dmpscope_core::{Model, PrepSettings, extract, prepare};
use golden_data::{close, f, fs, golden, model, raw_demos};
use serde_json::Value;

const REL: f64 = 1e-9;

#[test]
fn preprocessing_matches_reference() {
    let expected = golden("expected.json");
    let m = model();
    for (demo, exp) in m
        .demos()
        .iter()
        .zip(expected["prepared"].as_array().expect("list"))
    {
        assert_eq!(
            demo.n0,
            exp["n0"].as_u64().expect("n0") as usize,
            "{}",
            demo.name
        );
        close(demo.duration_s, f(&exp["T"]), 1e-14, "T");
        close(demo.median_interval_s, f(&exp["h"]), 1e-12, "h");
        for ax in 0..3 {
            close(demo.goal[ax], f(&exp["g"][ax]), REL, "g");
            close(demo.p0[ax], f(&exp["p0"][ax]), 1e-14, "p0");
        }
        let idx: Vec<usize> = exp["idx"]
            .as_array()
            .expect("idx")
            .iter()
            .map(|v| v.as_u64().expect("index") as usize)
            .collect();
        for (field, ours) in [
            ("y_raw", &demo.y_raw),
            ("y", &demo.y),
            ("yd", &demo.yd),
            ("ydd", &demo.ydd),
        ] {
            // Scale by the field's peak: values that pass through zero are
            // compared relative to the signal, not to themselves.
            let peak = ours
                .iter()
                .flat_map(|p| p.iter().map(|v| v.abs()))
                .fold(0.0, f64::max);
            for (slot, &k) in idx.iter().enumerate() {
                for ax in 0..3 {
                    let golden = f(&exp[field][slot][ax]);
                    let diff = (ours[k][ax] - golden).abs();
                    assert!(
                        diff <= REL * peak,
                        "{} {field}[{k}][{ax}]: {} vs {golden}",
                        demo.name,
                        ours[k][ax]
                    );
                }
            }
        }
    }
}

#[test]
fn points_match_reference() {
    let expected = golden("expected.json");
    let m = model();
    for p in expected["points"].as_array().expect("points") {
        let (dm, km) = (f(&p["dm"]), f(&p["km"]));
        let e = m.evaluate(dm, km);
        let at = format!("({dm}, {km})");
        close(e.zeta, f(&p["zeta"]), 1e-14, &format!("zeta {at}"));
        for (i, (d, a)) in e.d.iter().zip(&e.a_peak).enumerate() {
            close(*d, f(&p["d"][i]), REL, &format!("d[{i}] {at}"));
            close(*a, f(&p["a_peak"][i]), REL, &format!("a_peak[{i}] {at}"));
        }
        close(e.s, f(&p["s"]), REL, &format!("S {at}"));
        close(e.j(20.0), f(&p["j"]), REL, &format!("J {at}"));
        let w = m.projections(0).weights_at(0, dm, km);
        let first = fs(&p["weights_demo0_x_first5"]);
        let last = fs(&p["weights_demo0_x_last5"]);
        let wmax = w.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        for (ours, golden) in w
            .iter()
            .take(5)
            .zip(&first)
            .chain(w[w.len() - 5..].iter().zip(&last))
        {
            assert!(
                (ours - golden).abs() <= REL * wmax,
                "weights {at}: {ours} vs {golden}"
            );
        }
        let forcing = m.forcing(0, dm, km);
        let fmax = forcing.iter().fold(0.0f64, |a, v| a.max(v[0].abs()));
        let idx = p["idx"].as_array().expect("idx");
        for (slot, k) in idx.iter().enumerate() {
            let k = k.as_u64().expect("index") as usize;
            let golden = f(&p["f_fit_demo0_x"][slot]);
            assert!(
                (forcing[k][0] - golden).abs() <= REL * fmax,
                "f_fit[{k}] {at}"
            );
        }
    }
}

#[test]
fn landscape_and_optimum_match_reference() {
    let expected = golden("expected.json");
    let ls = &expected["landscape"];
    let axis = |v: &Value| {
        let values = fs(v);
        Axis {
            lo: values[0],
            hi: values[values.len() - 1],
            n: values.len(),
            scale: AxisScale::Log,
        }
    };
    let grid = Grid {
        dm: axis(&ls["dm_axis"]),
        km: axis(&ls["km_axis"]),
    };
    let m = Arc::new(model());
    let land =
        compute(m.clone(), grid, &AtomicBool::new(false), &mut |_, _| {}).expect("landscape");
    for (ours, golden) in land.dm.iter().zip(fs(&ls["dm_axis"])) {
        close(*ours, golden, 1e-14, "dm axis");
    }
    let j = land.j(20.0);
    for i in 0..grid.dm.n {
        for jj in 0..grid.km.n {
            let idx = land.index(i, jj);
            let at = format!("[{i}][{jj}]");
            close(
                land.d_sum()[idx],
                f(&ls["d_sum"][i][jj]),
                REL,
                &format!("d_sum {at}"),
            );
            close(land.s()[idx], f(&ls["s"][i][jj]), REL, &format!("S {at}"));
            close(j[idx], f(&ls["j"][i][jj]), REL, &format!("J {at}"));
        }
    }
    let gm = &ls["grid_min"];
    let (i, jj, _) = land.argmin(20.0).expect("argmin");
    assert_eq!(
        (i as u64, jj as u64),
        (
            gm["i_dm"].as_u64().expect("i"),
            gm["i_km"].as_u64().expect("j")
        )
    );

    let opt = &expected["optimum"];
    let x = extract(&m, &land, 20.0).expect("extract");
    // J is flat at the minimum: compare J tightly, the location to 1e-5.
    close(x.j, f(&opt["j"]), 1e-9, "J at optimum");
    close(x.eval.dm, f(&opt["dm"]), 1e-5, "D/M at optimum");
    close(x.eval.km, f(&opt["km"]), 1e-5, "K/M at optimum");
    assert_eq!(x.on_edge(), opt["on_edge"].as_bool().expect("bool"));
    assert!(x.converged);
}

#[test]
fn single_demo_has_zero_similarity() {
    let expected = golden("expected.json");
    let single = &expected["single_demo"];
    let raw = &raw_demos()[0];
    let prepared = prepare(raw, &PrepSettings::default()).expect("prepare");
    let m = Model::new(vec![prepared], DmpSettings::default()).expect("model");
    let e = m.evaluate(f(&single["dm"]), f(&single["km"]));
    assert_eq!(e.s, 0.0);
    assert_eq!(f(&single["s"]), 0.0);
    let d = single["d"]
        .as_array()
        .map_or_else(|| f(&single["d"]), |a| f(&a[0]));
    close(e.d[0], d, REL, "single demo d");
}

/// `standardised` sums sigma_f and each demo's share of S in one pass; the
/// numbers are the definitions' (method.md section 9) to the bit.
#[test]
fn the_one_pass_sigma_and_shares_are_the_definitions() {
    let m = model();
    for (dm, km) in [(25.0, 156.25), (3.0, 700.0), (60.0, 2.5)] {
        let st = m.similarity().standardised(dm, km);
        let (nd, n) = (st.f.len(), st.sigma.len());
        assert!(nd >= 2 && n >= 2);
        let mut q = vec![0.0; nd];
        for k in 0..n {
            let w = if k == 0 || k + 1 == n { 0.5 } else { 1.0 };
            let var: f64 = (0..3)
                .map(|axis| {
                    let mean = st.f.iter().map(|d| d[k][axis]).sum::<f64>() / nd as f64;
                    for (qi, d) in q.iter_mut().zip(&st.f) {
                        *qi += w * (d[k][axis] - mean) * (d[k][axis] - mean);
                    }
                    st.f.iter()
                        .map(|d| (d[k][axis] - mean) * (d[k][axis] - mean))
                        .sum::<f64>()
                        / (nd - 1) as f64
                })
                .sum();
            assert_eq!(st.sigma[k].to_bits(), var.sqrt().to_bits(), "sigma at {k}");
        }
        let dt = 1.0 / (n - 1) as f64;
        let total: f64 = q.iter().map(|v| v * dt).sum();
        let shares: Vec<f64> = q.iter().map(|v| v * dt / total).collect();
        assert_eq!(st.shares(), Some(shares), "shares at ({dm}, {km})");
    }
}
