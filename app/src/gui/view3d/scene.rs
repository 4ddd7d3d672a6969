//! What the 3D view draws, as screen-space line segments: a ground grid and
//! axes, each demo (solid) and its regeneration at the operating point
//! (dashed, lighter, same hue), start and goal markers, and the time cursor.
//! Coordinates are relative to a fixed scene origin so f32 keeps
//! sub-millimetre precision far from the tracker's origin.

use dmpscope_core::geom;
use dmpscope_core::rotation::QuatXyzw;
use dmpscope_core::{PreparedDemo, Rollout};
use glam::Vec3;

use super::camera::Bounds;
use crate::gui::thinning::thinned;

/// One segment as the GPU reads it (see `lines.wgsl`).
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(C)]
pub struct Segment {
    /// First end, scene coordinates.
    pub p0: [f32; 3],
    /// Second end.
    pub p1: [f32; 3],
    /// sRGB colour with straight alpha.
    pub colour: [f32; 4],
    /// Width in pixels, dash period (0: solid), arc length at p0 and at p1.
    pub style: [f32; 4],
}

/// Points drawn per path at most (paths are on a 1001-point grid; a few
/// hundred points are smooth at any size the view has).
const MAX_PATH_POINTS: usize = 250;

/// Points drawn per pinned set's path at most: six sets over every demo
/// are hundreds of paths, and half the points of a demo's own path keep
/// them smooth at the view's size (`tests/frame_time.sh` with six pins).
pub(super) const PIN_PATH_POINTS: usize = 125;

/// Line widths in physical pixels.
const WIDTH: f32 = 2.0;
const WIDTH_SELECTED: f32 = 3.5;

/// The dark rims of the markers and handles.
pub(super) const DARK: [f32; 4] = [0.08, 0.08, 0.1, 1.0];

/// The demo paths and their regenerations, in world coordinates (metres).
pub struct SceneInput<'a> {
    /// The prepared demos.
    pub demos: &'a [PreparedDemo],
    /// Their regenerations at the operating point (same order), if shown.
    pub regen: &'a [Rollout],
    /// Which demos are shown.
    pub visible: &'a [bool],
    /// The demo the plots show (drawn wider, carries the time cursor).
    pub selected: usize,
    /// The time cursor in unit time, 0..=1.
    pub t: f64,
    /// sRGB colour per demo.
    pub colours: &'a [[u8; 3]],
    /// Pixels per point (widths scale with it).
    pub pixels_per_point: f32,
    /// A path an RL agent learned: (demo index, positions in demo
    /// coordinates), drawn gold on top.
    pub learned: Option<(usize, &'a [geom::Vec3])>,
    /// A run at a new target, drawn white with its start and goal handles.
    pub generalised: Option<SceneTarget<'a>>,
    /// Per demo, its orientation on the unit-time grid (the raw target,
    /// method.md section 12), `None` without one.
    pub demo_turns: &'a [Option<&'a [QuatXyzw]>],
    /// Per demo, its regenerated orientation (same grid), if shown.
    pub regen_turns: &'a [Option<&'a [QuatXyzw]>],
    /// Draw orientation triads along the paths.
    pub triads: bool,
    /// Pinned gain sets: each shown demo regenerated at each, and each
    /// one's run at the new target.
    pub pins: &'a [ScenePin<'a>],
}

/// A pinned gain set in the scene.
#[derive(Clone, Copy)]
pub struct ScenePin<'a> {
    /// Its colour (sRGB).
    pub colour: [u8; 3],
    /// Its regeneration of every demo (relative to each demo's start).
    pub regen: &'a [Rollout],
    /// Its run at the new target (absolute), if any.
    pub target: Option<&'a [geom::Vec3]>,
}

/// The scene's segments, and how many paths each pin drew.
pub struct Built {
    /// The segments in painter's order.
    pub segments: Vec<Segment>,
    /// Per pin, the paths drawn (its regenerations and its target run).
    pub pin_paths: Vec<usize>,
}

/// A generalised run in the scene (absolute positions).
pub struct SceneTarget<'a> {
    /// The path on the unit-time grid.
    pub path: &'a [geom::Vec3],
    /// A skill's ±1 SD per axis (empty for a demo).
    pub band: &'a [geom::Vec3],
    /// The start handle.
    pub start: geom::Vec3,
    /// The goal handle.
    pub goal: geom::Vec3,
    /// The handle being dragged: 0 start, 1 goal.
    pub active: Option<usize>,
    /// Its orientation on the grid, where the run has one.
    pub turns: Option<&'a [QuatXyzw]>,
    /// Its time cursor, unit time.
    pub t: f64,
}

/// The scene's frame: the origin subtracted from world points and the box
/// the camera fits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// World point at the scene origin.
    pub origin: geom::Vec3,
    /// The demos' box in scene coordinates.
    pub bounds: Bounds,
    /// The mean displacement from start to goal.
    pub motion: Vec3,
}

impl Frame {
    /// The frame around all demos; `None` without finite points.
    pub fn of(demos: &[PreparedDemo]) -> Option<Self> {
        let world = || demos.iter().flat_map(|d| d.y_raw.iter().map(|p| d.p0 + p));
        let first = world().find(|p| p.iter().all(|c| c.is_finite()))?;
        let local = |p: geom::Vec3| to_vec(p, first);
        let b = Bounds::around(world().map(local))?;
        let c = b.centre();
        let origin = geom::Vec3::new(
            first[0] + f64::from(c.x),
            first[1] + f64::from(c.y),
            first[2] + f64::from(c.z),
        );
        let bounds = Bounds {
            min: b.min - c,
            max: b.max - c,
        };
        let sum = demos
            .iter()
            .map(|d| to_vec(d.goal, geom::Vec3::zeros()))
            .filter(|v| v.is_finite())
            .fold(Vec3::ZERO, |a, b| a + b);
        let motion = sum / demos.len().max(1) as f32;
        Some(Self {
            origin,
            bounds,
            motion,
        })
    }

    /// A world point in scene coordinates.
    pub fn local(&self, p: geom::Vec3) -> Vec3 {
        to_vec(p, self.origin)
    }

    /// The ground grid's spacing: a 1-2-5 step giving about eight cells
    /// across the demos.
    pub fn grid_step(&self) -> f32 {
        let span = (self.bounds.max - self.bounds.min).max_element().max(1e-3);
        let raw = f64::from(span) / 8.0;
        let decade = 10f64.powf(raw.log10().floor());
        let step = [1.0, 2.0, 5.0, 10.0]
            .into_iter()
            .map(|m| m * decade)
            .find(|s| *s >= raw * (1.0 - 1e-6))
            .unwrap_or(10.0 * decade);
        step as f32
    }

    /// The corner of the grid where the axes start.
    pub fn axes_origin(&self) -> Vec3 {
        let s = self.grid_step();
        Vec3::new(
            (self.bounds.min.x / s).floor() * s,
            (self.bounds.min.y / s).floor() * s,
            self.bounds.min.z,
        )
    }
}

pub(super) fn to_vec(p: geom::Vec3, origin: geom::Vec3) -> Vec3 {
    Vec3::new(
        (p[0] - origin[0]) as f32,
        (p[1] - origin[1]) as f32,
        (p[2] - origin[2]) as f32,
    )
}

pub(super) fn rgba(c: [u8; 3], alpha: f32) -> [f32; 4] {
    [
        f32::from(c[0]) / 255.0,
        f32::from(c[1]) / 255.0,
        f32::from(c[2]) / 255.0,
        alpha,
    ]
}

pub(super) fn lighter(c: [u8; 3], amount: f32) -> [u8; 3] {
    c.map(|v| (f32::from(v) + (255.0 - f32::from(v)) * amount).round() as u8)
}

/// Builds segments in painter's order.
#[derive(Default)]
pub struct SegmentList {
    /// The segments.
    pub segments: Vec<Segment>,
}

impl SegmentList {
    pub(super) fn line(&mut self, a: Vec3, b: Vec3, colour: [f32; 4], width: f32) {
        self.segments.push(Segment {
            p0: a.into(),
            p1: b.into(),
            colour,
            style: [width, 0.0, 0.0, 0.0],
        });
    }

    pub(super) fn dot(&mut self, p: Vec3, colour: [f32; 4], diameter: f32) {
        self.line(p, p, colour, diameter);
    }

    /// A polyline through `points` (decimated), dashed when `dash > 0`.
    pub(super) fn path(&mut self, points: &[Vec3], colour: [f32; 4], width: f32, dash: f32) {
        let picked = thinned(points, MAX_PATH_POINTS);
        let mut s = 0.0;
        for w in picked.windows(2) {
            let len = (w[1] - w[0]).length();
            self.segments.push(Segment {
                p0: w[0].into(),
                p1: w[1].into(),
                colour,
                style: [width, dash, s, s + len],
            });
            s += len;
        }
    }
}

/// The triad's axes: x red, y green, z blue.
const TRIAD: [[f32; 3]; 3] = [[0.95, 0.3, 0.25], [0.3, 0.85, 0.35], [0.3, 0.55, 1.0]];

impl SegmentList {
    /// The body axes of orientation `q` at `p`, `length` long.
    pub(super) fn triad(&mut self, p: Vec3, q: QuatXyzw, length: f32, width: f32, alpha: f32) {
        let q = glam::Quat::from_xyzw(q[0] as f32, q[1] as f32, q[2] as f32, q[3] as f32);
        if !q.is_finite() || q.length_squared() < 1e-6 {
            return;
        }
        let q = q.normalize();
        for (axis, c) in [Vec3::X, Vec3::Y, Vec3::Z].into_iter().zip(TRIAD) {
            self.line(p, p + q * axis * length, [c[0], c[1], c[2], alpha], width);
        }
    }

    /// Triads along `path` (one orientation per point of the same grid),
    /// one every `spacing` of arc length.
    pub(super) fn triads_along(
        &mut self,
        path: &[Vec3],
        turns: &[QuatXyzw],
        spacing: f32,
        length: f32,
        width: f32,
        alpha: f32,
    ) {
        let mut since = spacing;
        for (k, (p, q)) in path.iter().zip(turns).enumerate() {
            if k > 0 {
                since += (*p - path[k - 1]).length();
            }
            if since >= spacing {
                self.triad(*p, *q, length, width, alpha);
                since = 0.0;
            }
        }
    }
}

/// Interpolates a path on the unit-time grid at `t` in 0..=1.
pub(super) fn at_time(points: &[Vec3], t: f64) -> Option<Vec3> {
    let last = points.len().checked_sub(1)?;
    let x = t.clamp(0.0, 1.0) * last as f64;
    let i = (x.floor() as usize).min(last);
    let j = (i + 1).min(last);
    let f = (x - i as f64) as f32;
    Some(points[i].lerp(points[j], f))
}

/// The orientation nearest unit time `t` on a grid.
pub(super) fn nearest(turns: &[QuatXyzw], t: f64) -> Option<QuatXyzw> {
    let last = turns.len().checked_sub(1)?;
    let k = (t.clamp(0.0, 1.0) * last as f64).round() as usize;
    turns.get(k.min(last)).copied()
}

impl SceneInput<'_> {
    /// Whether demo `i` is shown.
    pub(super) fn shown(&self, i: usize) -> bool {
        self.visible.get(i).copied().unwrap_or(true)
    }

    /// The colour of demo `i`.
    pub(super) fn colour_of(&self, i: usize) -> [u8; 3] {
        self.colours
            .get(i % self.colours.len().max(1))
            .copied()
            .unwrap_or([200, 200, 200])
    }

    /// The width of demo `i`'s paths in physical pixels (wider when selected).
    pub(super) fn width_of(&self, i: usize) -> f32 {
        (if i == self.selected {
            WIDTH_SELECTED
        } else {
            WIDTH
        }) * self.pixels_per_point
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_steps_are_1_2_5() {
        let frame = |span: f32| Frame {
            origin: geom::Vec3::zeros(),
            bounds: Bounds {
                min: Vec3::ZERO,
                max: Vec3::new(span, span / 2.0, 0.1),
            },
            motion: Vec3::X,
        };
        assert!((frame(0.4).grid_step() - 0.05).abs() < 1e-6);
        assert!((frame(0.8).grid_step() - 0.1).abs() < 1e-6);
        assert!((frame(1.2).grid_step() - 0.2).abs() < 1e-6);
    }

    #[test]
    fn paths_are_decimated_keep_their_ends_and_carry_arc_length() {
        let points: Vec<Vec3> = (0..1001)
            .map(|k| Vec3::new(k as f32 * 1e-3, 0.0, 0.0))
            .collect();
        let mut list = SegmentList::default();
        list.path(&points, [1.0; 4], 2.0, 0.01);
        let segs = &list.segments;
        assert!(segs.len() <= MAX_PATH_POINTS);
        assert_eq!(segs[0].p0, [0.0, 0.0, 0.0]);
        let last = segs.last().expect("segments");
        assert!((last.p1[0] - 1.0).abs() < 1e-6);
        assert!(
            (last.style[3] - 1.0).abs() < 1e-4,
            "arc length {}",
            last.style[3]
        );
        for w in segs.windows(2) {
            assert_eq!(w[0].p1, w[1].p0, "a continuous polyline");
            assert_eq!(w[0].style[3], w[1].style[2]);
        }
    }

    #[test]
    fn a_quaternion_and_its_negative_draw_the_same_triads() {
        // Sign flips between or within demos (method.md section 12) change
        // no segment of the picture.
        let path: Vec<Vec3> = (0..200)
            .map(|k| Vec3::new(k as f32 * 1e-3, 0.0, 0.0))
            .collect();
        let turns: Vec<QuatXyzw> = (0..200)
            .map(|k| {
                let a = 0.004 * k as f64;
                [0.3 * a.sin(), 0.2 * a.sin(), a.sin(), a.cos()]
            })
            .collect();
        let flipped: Vec<QuatXyzw> = turns
            .iter()
            .enumerate()
            .map(|(k, q)| if k % 3 == 0 { q.map(|c| -c) } else { *q })
            .collect();
        let draw = |turns: &[QuatXyzw]| {
            let mut list = SegmentList::default();
            list.triads_along(&path, turns, 0.02, 0.01, 1.0, 1.0);
            list.segments
        };
        let (a, b) = (draw(&turns), draw(&flipped));
        assert!(a.len() > 10);
        assert_eq!(a, b);
    }

    #[test]
    fn the_cursor_interpolates_in_unit_time() {
        let points = [Vec3::ZERO, Vec3::X, Vec3::new(2.0, 0.0, 0.0)];
        assert_eq!(at_time(&points, 0.25), Some(Vec3::new(0.5, 0.0, 0.0)));
        assert_eq!(at_time(&points, 1.5), Some(Vec3::new(2.0, 0.0, 0.0)));
        assert_eq!(at_time(&[], 0.5), None);
    }
}
