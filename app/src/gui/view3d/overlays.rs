//! The scene's overlays on the demos: orientation triads along the paths,
//! the pinned gain sets' regenerations and target runs (issue 45), and the
//! run at a new target with its handles.

use dmpscope_core::geom;
use glam::Vec3;

use super::scene::{
    DARK, Frame, PIN_PATH_POINTS, SceneInput, SceneTarget, SegmentList, at_time, lighter, rgba,
};

/// Triads along every shown demo (solid) and its regeneration (lighter),
/// one every 0.8 grid steps of path, and larger ones at the start and goal
/// orientations.
pub(super) fn demo_triads(
    out: &mut SegmentList,
    frame: &Frame,
    input: &SceneInput<'_>,
    demo_paths: &[Vec<Vec3>],
    regen_paths: &[Vec<Vec3>],
) {
    let ppp = input.pixels_per_point;
    let step = frame.grid_step();
    for (i, path) in demo_paths
        .iter()
        .enumerate()
        .filter(|(i, _)| input.shown(*i))
    {
        let Some(Some(turns)) = input.demo_turns.get(i) else {
            continue;
        };
        out.triads_along(path, turns, 0.8 * step, 0.22 * step, 1.5 * ppp, 0.9);
        if let (Some(p0), Some(q0)) = (path.first(), turns.first()) {
            out.triad(*p0, *q0, 0.4 * step, 2.5 * ppp, 1.0);
        }
        if let (Some(pg), Some(qg)) = (path.last(), turns.last()) {
            out.triad(*pg, *qg, 0.4 * step, 2.5 * ppp, 1.0);
        }
    }
    for (i, path) in regen_paths
        .iter()
        .enumerate()
        .filter(|(i, _)| input.shown(*i))
    {
        if let Some(Some(turns)) = input.regen_turns.get(i) {
            out.triads_along(path, turns, 0.8 * step, 0.22 * step, 1.0 * ppp, 0.5);
        }
    }
}

/// Each pinned set's regeneration of every shown demo, solid in its
/// colour, its run at the new target wider, and its cursor on the selected
/// demo; returns the paths each pin drew.
pub(super) fn pinned(out: &mut SegmentList, frame: &Frame, input: &SceneInput<'_>) -> Vec<usize> {
    let ppp = input.pixels_per_point;
    let sel = input.selected;
    input
        .pins
        .iter()
        .map(|pin| {
            let mut drawn = 0;
            let c = rgba(pin.colour, 0.95);
            for (i, (d, r)) in input.demos.iter().zip(pin.regen).enumerate() {
                if !input.shown(i) {
                    continue;
                }
                let local = |p: &geom::Vec3| frame.local(d.p0 + p);
                let path: Vec<Vec3> = crate::gui::thinning::thinned(&r.y, PIN_PATH_POINTS)
                    .iter()
                    .map(local)
                    .collect();
                out.path(&path, c, 1.6 * ppp, 0.0);
                drawn += 1;
                if i == sel
                    && let Some(p) = cursor(&r.y, input.t, local)
                {
                    out.dot(p, DARK, 9.0 * ppp);
                    out.dot(p, rgba(lighter(pin.colour, 0.2), 1.0), 6.0 * ppp);
                }
            }
            if let Some(run) = pin.target {
                let path: Vec<Vec3> = run.iter().map(|p| frame.local(*p)).collect();
                out.path(&path, c, 2.5 * ppp, 0.0);
                drawn += 1;
                if let Some(g) = &input.generalised
                    && let Some(p) = at_time(&path, g.t)
                {
                    out.dot(p, DARK, 10.0 * ppp);
                    out.dot(p, c, 7.0 * ppp);
                }
            }
            drawn
        })
        .collect()
}

/// The point at unit time `t` on `points` (a unit-time grid), mapped by
/// `local`: only the two neighbours are mapped, not the whole path.
fn cursor(points: &[geom::Vec3], t: f64, local: impl Fn(&geom::Vec3) -> Vec3) -> Option<Vec3> {
    let last = points.len().checked_sub(1)?;
    let x = t.clamp(0.0, 1.0) * last as f64;
    let i = (x.floor() as usize).min(last);
    let pair = [local(&points[i]), local(&points[(i + 1).min(last)])];
    at_time(&pair, x - i as f64)
}

/// A run at a new target `g`: its path, its band, its handles and its time cursor.
pub(super) fn generalised_run(
    out: &mut SegmentList,
    frame: &Frame,
    g: &SceneTarget<'_>,
    input: &SceneInput<'_>,
) {
    let ppp = input.pixels_per_point;
    let dash = frame.bounds.radius() / 30.0;
    let local = |p: &geom::Vec3| frame.local(*p);
    let path: Vec<Vec3> = g.path.iter().map(local).collect();
    if g.band.len() == g.path.len() {
        for sign in [-1.0, 1.0] {
            let edge: Vec<Vec3> = g
                .path
                .iter()
                .zip(g.band)
                .map(|(p, b)| local(&geom::Vec3::from_fn(|a, _| p[a] + sign * b[a])))
                .collect();
            out.path(&edge, [1.0, 1.0, 1.0, 0.35], 1.0 * ppp, dash);
        }
    }
    out.path(&path, [0.97, 0.97, 0.97, 1.0], 3.0 * ppp, 0.0);
    if let Some(turns) = g.turns {
        let step = frame.grid_step();
        if input.triads {
            out.triads_along(&path, turns, 0.5 * step, 0.22 * step, 1.5 * ppp, 0.9);
        }
        // The orientation the run ends at, beside its ring, always.
        if let (Some(pg), Some(qg)) = (path.last(), turns.last()) {
            out.triad(*pg, *qg, 0.5 * step, 3.0 * ppp, 1.0);
        }
        if let Some(q0) = turns.first() {
            out.triad(frame.local(g.start), *q0, 0.5 * step, 3.0 * ppp, 1.0);
        }
    }
    let handle = |i: usize| {
        if g.active == Some(i) {
            [1.0, 0.85, 0.3, 1.0]
        } else {
            [0.97, 0.97, 0.97, 1.0]
        }
    };
    let (start, goal) = (frame.local(g.start), frame.local(g.goal));
    out.dot(start, DARK, 13.0 * ppp);
    out.dot(start, handle(0), 10.0 * ppp);
    out.dot(goal, handle(1), 16.0 * ppp);
    out.dot(goal, DARK, 8.0 * ppp);
    if let Some(p) = at_time(&path, g.t) {
        out.dot(p, [0.1, 0.1, 0.1, 1.0], 12.0 * ppp);
        out.dot(p, [0.97, 0.97, 0.97, 1.0], 8.0 * ppp);
    }
}
