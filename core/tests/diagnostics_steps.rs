//! The diagnostics come out the same however they are stepped: all at once
//! on every core (`run`), one extraction at a time (`step`), or a few
//! landscape points at a time (`step_points`, the browser's slices), and
//! the progress they report adds up.

mod golden_data;

use std::sync::Arc;

use dmpscope_core::extract;
use dmpscope_core::extract::diagnostics::{DiagSettings, DiagnosticsJob};
use dmpscope_core::landscape::grid::{Axis, AxisScale, FillOrder, Grid, LandscapeJob};

fn job() -> DiagnosticsJob {
    let model = Arc::new(golden_data::model());
    let axis = |lo: f64, hi: f64| Axis {
        lo,
        hi,
        n: 12,
        scale: AxisScale::Log,
    };
    let grid = Grid {
        dm: axis(1.0, 100.0),
        km: axis(1.0, 1000.0),
    };
    let mut land = LandscapeJob::new(model.clone(), grid, FillOrder::Raster).expect("grid");
    while !land.step(usize::MAX) {}
    let x = extract(&model, land.landscape(), 20.0).expect("extraction");
    let settings = DiagSettings {
        grid_points: 8,
        bootstrap: 6,
        seed: 3,
    };
    DiagnosticsJob::new(model, land.landscape(), &x, settings)
}

#[test]
fn stepping_does_not_change_the_diagnostics() {
    let mut all = job();
    let n = all.diagnostics().demos.len();
    assert_eq!(all.progress(), (0, n + 6));
    all.run(&|_| {});
    assert!(all.is_done());
    assert!(all.diagnostics().bootstrap.is_some());

    let mut one = job();
    while !one.step() {}
    assert_eq!(one.diagnostics(), all.diagnostics());

    let mut sliced = job();
    let mut steps = 0;
    let mut last = 0;
    while !sliced.step_points(7) {
        let (done, total) = sliced.progress();
        assert!(done >= last && total == n + 6, "{done}/{total}");
        last = done;
        steps += 1;
    }
    // 64 points per extraction in slices of 7: many steps, each short.
    assert!(steps > 10 * (n + 6), "{steps} steps");
    assert_eq!(sliced.progress(), (n + 6, n + 6));
    assert_eq!(sliced.diagnostics(), all.diagnostics());
    assert_eq!(sliced.bootstrap_optima(), all.bootstrap_optima());
}

#[test]
fn parts_computed_elsewhere_in_any_order_give_the_same_diagnostics() {
    let mut all = job();
    all.run(&|_| {});

    let model = Arc::new(golden_data::model());
    let mut handed = job();
    let (grid, k) = (handed.part_grid(), handed.k());
    let mut parts = Vec::new();
    while let Some(part) = handed.take_part() {
        parts.push(part);
    }
    let n = parts.len();
    assert!(!handed.is_done(), "not done while parts are out");
    assert_eq!(handed.progress(), (0, n));
    // A worker died with the first part: it is handed out again.
    let lost = parts.remove(0);
    handed.return_part(lost.id);
    let again = handed.take_part().expect("handed out again");
    assert_eq!(again, lost);
    parts.push(again);
    // Answers in reverse order; a second answer for a part is refused.
    parts.reverse();
    for part in &parts {
        let found = extract::diagnostics::resample::optimum_of(&model, &part.indices, grid, k).ok();
        assert!(handed.put_part(part.id, found));
        assert!(!handed.put_part(part.id, found), "an answer given twice");
    }
    assert!(handed.is_done());
    assert_eq!(handed.progress(), (n, n));
    assert_eq!(handed.diagnostics(), all.diagnostics());
    assert_eq!(handed.bootstrap_optima(), all.bootstrap_optima());
}
