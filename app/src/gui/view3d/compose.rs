//! The scene put together: the ground and axes, the demos and their
//! regenerations, the overlays and the time cursor, in drawing order.

use glam::Vec3;

use super::overlays;
use super::scene::{Built, DARK, Frame, SceneInput, SegmentList, at_time, lighter, nearest, rgba};

/// All segments of the scene in `frame`.
pub fn build(frame: &Frame, input: &SceneInput<'_>) -> Built {
    let mut out = SegmentList::default();
    ground_and_axes(&mut out, frame, input.pixels_per_point);

    // Demos, then regenerations on top, then markers.
    let demo_paths: Vec<Vec<Vec3>> = input
        .demos
        .iter()
        .map(|d| d.y_raw.iter().map(|p| frame.local(d.p0 + p)).collect())
        .collect();
    let regen_paths: Vec<Vec<Vec3>> = input
        .demos
        .iter()
        .zip(input.regen)
        .map(|(d, r)| r.y.iter().map(|p| frame.local(d.p0 + p)).collect())
        .collect();
    demo_paths_and_markers(&mut out, frame, input, &demo_paths, &regen_paths);
    if input.triads {
        overlays::demo_triads(&mut out, frame, input, &demo_paths, &regen_paths);
    }
    let pin_paths = overlays::pinned(&mut out, frame, input);

    // A run at a new target: white, its band faint, its handles on top.
    if let Some(g) = &input.generalised {
        overlays::generalised_run(&mut out, frame, g, input);
    }

    // The time cursor on the selected demo and its regeneration.
    let sel = input.selected;
    if input.shown(sel) {
        let ppp = input.pixels_per_point;
        let c = rgba(input.colour_of(sel), 1.0);
        for path in [demo_paths.get(sel), regen_paths.get(sel)]
            .into_iter()
            .flatten()
        {
            if let Some(p) = at_time(path, input.t) {
                out.dot(p, [1.0, 1.0, 1.0, 1.0], 12.0 * ppp);
                out.dot(p, c, 8.0 * ppp);
            }
        }
        // The pose at the cursor: a triad on the demo and its regeneration.
        let cursor_turns = [
            (demo_paths.get(sel), input.demo_turns.get(sel)),
            (regen_paths.get(sel), input.regen_turns.get(sel)),
        ];
        for (path, turns) in cursor_turns.into_iter().filter(|_| input.triads) {
            if let (Some(path), Some(Some(turns))) = (path, turns)
                && let (Some(p), Some(q)) = (at_time(path, input.t), nearest(turns, input.t))
            {
                out.triad(p, q, 0.45 * frame.grid_step(), 3.0 * ppp, 1.0);
            }
        }
    }
    Built {
        segments: out.segments,
        pin_paths,
    }
}

/// The ground grid and the axes, `ppp` pixels per point.
fn ground_and_axes(out: &mut SegmentList, frame: &Frame, ppp: f32) {
    let step = frame.grid_step();
    let o = frame.axes_origin();
    let b = frame.bounds;
    let nx = ((b.max.x - o.x) / step).ceil().max(1.0) as usize;
    let ny = ((b.max.y - o.y) / step).ceil().max(1.0) as usize;
    let grey = [0.55, 0.55, 0.6, 0.35];
    for i in 0..=nx {
        let x = o.x + i as f32 * step;
        out.line(
            Vec3::new(x, o.y, o.z),
            Vec3::new(x, o.y + ny as f32 * step, o.z),
            grey,
            ppp,
        );
    }
    for j in 0..=ny {
        let y = o.y + j as f32 * step;
        out.line(
            Vec3::new(o.x, y, o.z),
            Vec3::new(o.x + nx as f32 * step, y, o.z),
            grey,
            ppp,
        );
    }
    for (axis, colour) in [
        (Vec3::X, [0.9, 0.35, 0.3, 1.0]),
        (Vec3::Y, [0.35, 0.8, 0.4, 1.0]),
        (Vec3::Z, [0.35, 0.55, 0.95, 1.0]),
    ] {
        out.line(o, o + axis * step, colour, 2.5 * ppp);
    }
}

/// The demos, their regenerations (dashed), the learned path and the start and goal markers.
fn demo_paths_and_markers(
    out: &mut SegmentList,
    frame: &Frame,
    input: &SceneInput<'_>,
    demo_paths: &[Vec<Vec3>],
    regen_paths: &[Vec<Vec3>],
) {
    let ppp = input.pixels_per_point;
    let dash = frame.bounds.radius() / 30.0;
    for (i, path) in demo_paths
        .iter()
        .enumerate()
        .filter(|(i, _)| input.shown(*i))
    {
        out.path(path, rgba(input.colour_of(i), 1.0), input.width_of(i), 0.0);
    }
    for (i, path) in regen_paths
        .iter()
        .enumerate()
        .filter(|(i, _)| input.shown(*i))
    {
        let c = lighter(input.colour_of(i), 0.45);
        out.path(path, rgba(c, 0.95), input.width_of(i), dash);
    }
    if let Some((i, path)) = input.learned
        && let Some(d) = input.demos.get(i)
    {
        let points: Vec<Vec3> = path.iter().map(|p| frame.local(d.p0 + p)).collect();
        out.path(&points, [1.0, 0.84, 0.3, 1.0], 3.0 * ppp, 0.0);
    }
    for (i, d) in input
        .demos
        .iter()
        .enumerate()
        .filter(|(i, _)| input.shown(*i))
    {
        let c = rgba(input.colour_of(i), 1.0);
        let start = frame.local(d.p0);
        let goal = frame.local(d.p0 + d.goal);
        // Start: a filled disc; goal: a ring.
        out.dot(start, DARK, 10.0 * ppp);
        out.dot(start, c, 7.0 * ppp);
        out.dot(goal, c, 11.0 * ppp);
        out.dot(goal, DARK, 5.0 * ppp);
    }
}
