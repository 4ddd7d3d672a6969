//! The orientation DMP (method.md section 12) against the independent
//! NumPy reference `tests/golden/orientation.py` on the bundled planted
//! sample (`assets/planted8.mcap`, eight demos with real orientations):
//! the prepared orientation, each demo's `d_rot` and `alpha_peak` and its
//! regenerated orientation at three gain pairs, and the `sum d_rot` map of
//! a 12 x 12 landscape (`tests/golden/make_orientation.py` writes
//! `expected_orientation.json`).
//!
//! Tolerances: the prepared values, `alpha_peak` and the regenerated
//! orientations to 1e-9; `d_rot` to 1e-6 relative, the contract, because
//! `theta = 2 acos(|q . q_raw|)` is ill-conditioned where the two agree
//! (a rounding of `|q|` moves `d_rot` by up to 1e-7 relative).

mod common;
mod golden_data;

use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use dmpscope_core::landscape::grid;
use dmpscope_core::landscape::grid::{Axis, AxisScale, Grid};
use dmpscope_core::rotation;
use dmpscope_core::rotation::QuatXyzw;
use dmpscope_core::{Model, PrepSettings, Quantity, Unusable, build_model};
use golden_data::{close, f, fs, golden};
use serde_json::Value;

/// The relative tolerance of `d_rot` (the 1e-6 contract).
const REL: f64 = 1e-6;
/// The tolerance of the prepared values, `alpha_peak` and paths.
const TIGHT: f64 = 1e-9;

fn model() -> Model {
    let built = build_model(
        &common::planted8_demos(),
        &PrepSettings::default(),
        Default::default(),
        Unusable::Fail,
    )
    .expect("model");
    built.model
}

fn quat(v: &Value) -> QuatXyzw {
    let q = fs(v);
    [q[0], q[1], q[2], q[3]]
}

/// The same orientation up to sign, component by component.
#[track_caller]
fn close_q(ours: QuatXyzw, theirs: QuatXyzw, what: &str) {
    let sign = if rotation::dot(ours, theirs) < 0.0 {
        -1.0
    } else {
        1.0
    };
    for c in 0..4 {
        let d = (ours[c] - sign * theirs[c]).abs();
        assert!(d <= TIGHT, "{what}[{c}]: {} vs {}", ours[c], theirs[c]);
    }
}

/// The grid indices the reference records values at.
fn indices(expected: &Value) -> Vec<usize> {
    fs(&expected["meta"]["idx"])
        .iter()
        .map(|&v| v as usize)
        .collect()
}

/// Our demo index of the reference's demo `name` (a topic).
fn index_of(model: &Model, name: &str) -> usize {
    model
        .demos()
        .iter()
        .position(|d| d.name.ends_with(name))
        .unwrap_or_else(|| panic!("no demo {name}"))
}

#[test]
fn the_prepared_orientation_matches_the_reference() {
    let expected = golden("expected_orientation.json");
    let model = model();
    let idx = indices(&expected);
    for demo in expected["demos"].as_array().expect("demos") {
        let name = demo["name"].as_str().expect("name");
        let i = index_of(&model, name);
        let ours = model.demos()[i].orientation.as_ref().expect("orientation");
        close_q(ours.goal, quat(&demo["goal"]), &format!("{name} goal"));
        for (n, &k) in idx.iter().enumerate() {
            close_q(
                ours.q_raw[k],
                quat(&demo["q_raw"][n]),
                &format!("{name} q_raw[{k}]"),
            );
            close_q(ours.q[k], quat(&demo["q"][n]), &format!("{name} q[{k}]"));
            let (w, wd) = (fs(&demo["w"][n]), fs(&demo["wd"][n]));
            for ax in 0..3 {
                close(ours.w[k][ax], w[ax], TIGHT, &format!("{name} w[{k}][{ax}]"));
                let scale = wd.iter().fold(1.0f64, |m, v| m.max(v.abs()));
                assert!(
                    (ours.wd[k][ax] - wd[ax]).abs() <= TIGHT * scale,
                    "{name} wd[{k}][{ax}]: {} vs {}",
                    ours.wd[k][ax],
                    wd[ax]
                );
            }
        }
    }
}

#[test]
fn each_demos_orientation_error_and_path_match_the_reference() {
    let expected = golden("expected_orientation.json");
    let model = model();
    let idx = indices(&expected);
    for point in expected["points"].as_array().expect("points") {
        let (dm, km) = (f(&point["dm"]), f(&point["km"]));
        let eval = model.evaluate(dm, km);
        let mut sum = 0.0;
        for demo in point["demos"].as_array().expect("demos") {
            let name = demo["name"].as_str().expect("name");
            let i = index_of(&model, name);
            let what = format!("{name} at {dm} / {km}");
            close(
                eval.d_rot[i],
                f(&demo["d_rot"]),
                REL,
                &format!("{what}: d_rot"),
            );
            close(
                eval.alpha_peak[i],
                f(&demo["alpha_peak"]),
                TIGHT,
                &format!("{what}: alpha_peak"),
            );
            sum += f(&demo["d_rot"]);
            let path = model.orientation_rollout(i, dm, km).expect("rollout");
            for (n, &k) in idx.iter().enumerate() {
                close_q(path.q[k], quat(&demo["q"][n]), &format!("{what}: q[{k}]"));
            }
        }
        close(eval.d_rot_sum, sum.to_degrees(), REL, "sum d_rot [deg]");
    }
}

#[test]
fn the_d_rot_map_matches_the_reference() {
    let expected = golden("expected_orientation.json");
    let grid_json = &expected["grid"];
    let (dm, km) = (fs(&grid_json["dm"]), fs(&grid_json["km"]));
    let axis = |n: usize| Axis {
        lo: 0.1,
        hi: 1000.0,
        n,
        scale: AxisScale::Log,
    };
    let grid = Grid {
        dm: axis(dm.len()),
        km: axis(km.len()),
    };
    let land = grid::compute(
        Arc::new(model()),
        grid,
        &AtomicBool::new(false),
        &mut |_, _| {},
    )
    .expect("landscape");
    for (ours, theirs) in land.dm.iter().zip(&dm).chain(land.km.iter().zip(&km)) {
        close(*ours, *theirs, 1e-12, "grid axis");
    }
    let rows = grid_json["d_rot_sum"].as_array().expect("rows");
    let ours = land.values(Quantity::DRotSum);
    for (i, row) in rows.iter().enumerate() {
        for (j, v) in fs(row).iter().enumerate() {
            close(
                ours[land.index(i, j)],
                v.to_degrees(),
                REL,
                &format!("sum d_rot at ({i}, {j})"),
            );
        }
    }
}
