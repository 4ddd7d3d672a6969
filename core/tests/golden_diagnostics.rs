//! The diagnostics (method.md section 9) against the independent reference
//! `tests/golden/diagnostics.py` (`expected_diagnostics.json`, made by
//! `make_diagnostics.py` on the demos and 16 x 16 grid of `expected.json`).
//!
//! Quantities that are exact functions of given gains or of the grid (shares
//! and k_ratio at fixed gains, balanced_k, depth) agree to 1e-9. Refined
//! optima agree in their value (J or S) to 1e-9; their location only to what
//! a minimum defines (J is flat to rounding over ~1e-7 in log space there,
//! and two correct Nelder-Mead runs stop at different points of it): 1e-5.

mod golden_data;

use std::sync::Arc;

use dmpscope_core::extract;
use dmpscope_core::extract::diagnostics::Diagnostics;
use dmpscope_core::extract::diagnostics::balance::depth;
use dmpscope_core::extract::diagnostics::resample::percentiles;
use dmpscope_core::extract::diagnostics::{DiagSettings, DiagnosticsJob};
use dmpscope_core::landscape::grid::{Axis, AxisScale, FillOrder, Grid, LandscapeJob};
use dmpscope_core::report::table::TableRow;
use dmpscope_core::{Extraction, Landscape, Model};
use golden_data::{close, f, fs, golden, model};
use serde_json::Value;

const EXACT: f64 = 1e-9;
const LOCATION: f64 = 1e-5;

fn grid() -> Grid {
    let axis = Axis {
        lo: 0.1,
        hi: 1000.0,
        n: 16,
        scale: AxisScale::Log,
    };
    Grid { dm: axis, km: axis }
}

/// The landscape on the reference's grid and its extraction, whose optimum
/// matches the reference's.
fn landscape_and_extraction(g: &Value, model: &Arc<Model>) -> (Landscape, Extraction) {
    let mut job = LandscapeJob::new(model.clone(), grid(), FillOrder::Raster).expect("job");
    while !job.step(usize::MAX) {}
    let land = job.into_landscape();
    let x = extract(model, &land, 20.0).expect("extraction");
    close(x.j, f(&g["optimum"]["j"]), EXACT, "J*");
    close(x.eval.dm, f(&g["optimum"]["dm"]), LOCATION, "D/M*");
    close(x.eval.km, f(&g["optimum"]["km"]), LOCATION, "K/M*");
    (land, x)
}

/// The diagnostics run on the reference's own bootstrap resamples.
fn diagnostics_on_the_reference_resamples(
    g: &Value,
    model: &Arc<Model>,
    land: &Landscape,
    x: &Extraction,
) -> DiagnosticsJob {
    let resamples: Vec<Vec<usize>> = g["resamples"]
        .as_array()
        .expect("resamples")
        .iter()
        .map(|r| fs(r).into_iter().map(|v| v as usize).collect())
        .collect();
    let settings = DiagSettings {
        grid_points: 16,
        bootstrap: resamples.len(),
        seed: 0,
    };
    let mut diag = DiagnosticsJob::with_resamples(model.clone(), land, x, settings, resamples);
    diag.run(&|_| {});
    diag
}

/// Depth, flatness, balanced k, k_ratio and the shares at the optimum.
fn check_depth_balance_and_shares(g: &Value, d: &Diagnostics) {
    close(d.depth.expect("depth"), f(&g["depth"]), EXACT, "depth");
    assert_eq!(d.flat, f(&g["depth"]) < 0.02);
    close(
        d.balanced_k.expect("balanced k"),
        f(&g["balanced_k"]),
        EXACT,
        "balanced_k",
    );
    close(
        d.k_ratio.expect("k_ratio"),
        f(&g["k_ratio_at_optimum"]),
        1e-6,
        "k_ratio at J*",
    );
    for (i, share) in fs(&g["s_share_at_optimum"]).iter().enumerate() {
        close(
            d.demos[i].s_share.expect("share"),
            *share,
            1e-6,
            "share at J*",
        );
    }
}

/// The S minimum: its value exactly, its location to what a minimum defines.
fn check_the_s_minimum(g: &Value, d: &Diagnostics) {
    let s_min = d.s_minimum.expect("S minimum");
    close(s_min.s, f(&g["s_minimum"]["s"]), EXACT, "S minimum: S");
    close(
        s_min.dm,
        f(&g["s_minimum"]["dm"]),
        LOCATION,
        "S minimum: D/M",
    );
    close(
        s_min.km,
        f(&g["s_minimum"]["km"]),
        LOCATION,
        "S minimum: K/M",
    );
}

/// Shares and k_ratio at the reference's gains, and depth at its J*.
fn check_the_exact_functions(g: &Value, model: &Arc<Model>, land: &Landscape) {
    // Shares and k_ratio as exact functions of the gains.
    for p in g["points"].as_array().expect("points") {
        let (dm, km) = (f(&p["dm"]), f(&p["km"]));
        let shares = model.similarity().shares(dm, km).expect("shares");
        for (a, b) in shares.iter().zip(fs(&p["s_share"])) {
            close(*a, b, EXACT, &format!("share at ({dm}, {km})"));
        }
        let row = TableRow::from_eval("p", &model.evaluate(dm, km), 20.0);
        close(20.0 * row.d_sum / row.s, f(&p["k_ratio"]), EXACT, "k_ratio");
    }
    // Depth as a function of J* (the reference's own J*).
    close(
        depth(land, 20.0, f(&g["optimum"]["j"])).expect("depth"),
        f(&g["depth"]),
        EXACT,
        "depth at the reference's J*",
    );
}

/// Each leave-one-out optimum.
fn check_leave_one_out(g: &Value, d: &Diagnostics) {
    for (i, loo) in g["loo"].as_array().expect("loo").iter().enumerate() {
        let mine = d.demos[i].loo.expect("leave-one-out optimum");
        close(mine.j, f(&loo["j"]), EXACT, "LOO J");
        close(mine.dm, f(&loo["dm"]), LOCATION, "LOO D/M");
        close(mine.km, f(&loo["km"]), LOCATION, "LOO K/M");
        assert_eq!(Some(mine.on_edge), loo["on_edge"].as_bool(), "LOO edge {i}");
    }
}

/// Each bootstrap optimum, their percentiles and edge fraction, and the
/// percentiles of the reference's own optima computed here.
fn check_the_bootstrap(g: &Value, diag: &DiagnosticsJob) {
    let d = diag.diagnostics();
    let optima = diag.bootstrap_optima();
    let expected = g["bootstrap"]["optima"].as_array().expect("optima");
    assert_eq!(optima.len(), expected.len());
    for (mine, theirs) in optima.iter().zip(expected) {
        close(mine.j, f(&theirs["j"]), EXACT, "bootstrap J");
        close(mine.dm, f(&theirs["dm"]), LOCATION, "bootstrap D/M");
        assert_eq!(Some(mine.on_edge), theirs["on_edge"].as_bool());
    }
    let b = d.bootstrap.expect("bootstrap");
    for (a, e) in b.dm.iter().zip(fs(&g["bootstrap"]["dm"])) {
        close(*a, e, LOCATION, "bootstrap D/M percentile");
    }
    for (a, e) in b.km.iter().zip(fs(&g["bootstrap"]["km"])) {
        close(*a, e, LOCATION, "bootstrap K/M percentile");
    }
    assert_eq!(b.on_edge_fraction, f(&g["bootstrap"]["on_edge_fraction"]));
    // The percentiles of the reference's own optima, computed here.
    let theirs_dm: Vec<f64> = expected.iter().map(|o| f(&o["dm"])).collect();
    for (a, e) in percentiles(&theirs_dm, [5.0, 50.0, 95.0])
        .iter()
        .zip(fs(&g["bootstrap"]["dm"]))
    {
        close(*a, e, EXACT, "percentiles as NumPy's");
    }
}

#[test]
fn the_diagnostics_match_the_reference() {
    let g = golden("expected_diagnostics.json");
    let model = Arc::new(model());
    let (land, x) = landscape_and_extraction(&g, &model);
    let diag = diagnostics_on_the_reference_resamples(&g, &model, &land, &x);
    let d = diag.diagnostics();
    check_depth_balance_and_shares(&g, d);
    check_the_s_minimum(&g, d);
    check_the_exact_functions(&g, &model, &land);
    check_leave_one_out(&g, d);
    check_the_bootstrap(&g, &diag);
}
