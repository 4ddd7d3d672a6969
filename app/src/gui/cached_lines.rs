//! Plot lines tessellated once and drawn again from a cache: an
//! `egui_plot` item for series that do not change from frame to frame (a
//! pinned gain set's regeneration, the demo itself) while something else
//! in the plot does (the operating point dragged on a map). egui_plot's
//! `Line` maps and tessellates every point every frame; this item keeps
//! its mesh in egui's memory, keyed by the plot's frame and bounds, the
//! points' values and the highlight, and hands the same mesh back while
//! they are the same (`tests/frame_time.sh` with six pins: the issue 45
//! note has the figures). [`SnappedBounds`] keeps the bounds still while a
//! changing series moves a little, so the cache is not missed every frame.

use std::ops::RangeInclusive;
use std::sync::Arc;

use eframe::egui::{self, Color32, Mesh, Shape, Ui, epaint};
use egui_plot::{PlotBounds, PlotGeometry, PlotItem, PlotItemBase, PlotPoint, PlotTransform};

/// Polylines of one colour and width under one name (one legend entry),
/// in plot coordinates, drawn from a cached mesh.
pub struct CachedLines {
    base: PlotItemBase,
    colour: Color32,
    width: f32,
    lines: Vec<Vec<PlotPoint>>,
    bounds: PlotBounds,
    key: u64,
    cache_id: egui::Id,
}

/// What a cached mesh was made for: the content's hash, the plot's frame
/// and bounds, and the highlight.
#[derive(Clone, Copy, PartialEq)]
struct Made {
    key: u64,
    frame: egui::Rect,
    bounds: [f64; 4],
    highlight: bool,
}

impl CachedLines {
    /// `lines` (plot coordinates) named `name` in `colour`, `width` points
    /// wide; `cache_id` must be unique to this item in its plot (a plot's
    /// id with the item's name, say).
    pub fn new(
        name: impl Into<String>,
        colour: Color32,
        width: f32,
        lines: Vec<Vec<[f64; 2]>>,
        cache_id: egui::Id,
    ) -> Self {
        let mut bounds = PlotBounds::NOTHING;
        let mut key = Hash64::default();
        for line in &lines {
            key.word(line.len() as u64);
            for &[x, y] in line {
                if x.is_finite() && y.is_finite() {
                    bounds.extend_with(&PlotPoint::new(x, y));
                }
                key.word(x.to_bits());
                key.word(y.to_bits());
            }
        }
        key.word(u64::from(width.to_bits()));
        key.word(u64::from(u32::from_le_bytes(colour.to_array())));
        let lines = lines
            .into_iter()
            .map(|l| l.into_iter().map(|[x, y]| PlotPoint::new(x, y)).collect())
            .collect();
        Self {
            base: PlotItemBase::new(name.into()),
            colour,
            width,
            lines,
            bounds,
            key: key.0,
            cache_id,
        }
    }

    /// The mesh for `transform`: the cached one when it was made for the
    /// same content, frame, bounds and highlight, else a new one (kept).
    fn mesh(&self, ui: &Ui, transform: &PlotTransform) -> Arc<Mesh> {
        let b = transform.bounds();
        let made = Made {
            key: self.key,
            frame: *transform.frame(),
            bounds: [b.min()[0], b.min()[1], b.max()[0], b.max()[1]],
            highlight: self.highlighted(),
        };
        let cached = ui
            .ctx()
            .data(|d| d.get_temp::<(CacheTag, Arc<Mesh>)>(self.cache_id));
        if let Some((CacheTag(tag), mesh)) = cached
            && tag == made
        {
            return mesh;
        }
        let mesh = Arc::new(self.tessellate(ui, transform, made.highlight));
        ui.ctx().data_mut(|d| {
            d.insert_temp(self.cache_id, (CacheTag(made), Arc::clone(&mesh)));
        });
        mesh
    }

    fn tessellate(&self, ui: &Ui, transform: &PlotTransform, highlight: bool) -> Mesh {
        let ctx = ui.ctx();
        let options = ctx.tessellation_options(|o| *o);
        let texture_size = ctx.fonts(|f| f.font_image_size());
        let mut tessellator =
            epaint::Tessellator::new(ctx.pixels_per_point(), options, texture_size, Vec::new());
        tessellator.set_clip_rect(*transform.frame());
        let width = if highlight {
            self.width * 2.0
        } else {
            self.width
        };
        let mut mesh = Mesh::default();
        for line in &self.lines {
            let points: Vec<egui::Pos2> = line
                .iter()
                .filter(|p| p.x.is_finite() && p.y.is_finite())
                .map(|p| transform.position_from_point(p))
                .collect();
            if points.len() >= 2 {
                let path = epaint::PathShape::line(points, egui::Stroke::new(width, self.colour));
                tessellator.tessellate_path(&path, &mut mesh);
            }
        }
        mesh
    }
}

/// The cache's tag (a newtype so that egui's type map holds nothing else
/// under it).
#[derive(Clone, Copy)]
struct CacheTag(Made);

impl PlotItem for CachedLines {
    fn shapes(&self, ui: &Ui, transform: &PlotTransform, shapes: &mut Vec<Shape>) {
        let mesh = self.mesh(ui, transform);
        if !mesh.is_empty() {
            shapes.push(Shape::Mesh(mesh));
        }
    }

    fn initialize(&mut self, _x_range: RangeInclusive<f64>) {}

    fn color(&self) -> Color32 {
        self.colour
    }

    /// One line's points can be hovered (egui_plot's label of the nearest
    /// point); several lines under one name cannot.
    fn geometry(&self) -> PlotGeometry<'_> {
        match self.lines.as_slice() {
            [line] => PlotGeometry::Points(line),
            _ => PlotGeometry::None,
        }
    }

    fn bounds(&self) -> PlotBounds {
        self.bounds
    }

    fn base(&self) -> &PlotItemBase {
        &self.base
    }

    fn base_mut(&mut self) -> &mut PlotItemBase {
        &mut self.base
    }
}

/// A plot item whose bounds are widened to whole steps of `step` on the y
/// axis: a series that changes a little every frame (the regeneration at
/// a dragged operating point) then leaves the plot's automatic bounds
/// where they were, and with them the other items' cached meshes.
pub struct SnappedBounds<T> {
    inner: T,
    step: f64,
}

impl<T> SnappedBounds<T> {
    /// `inner` with its y bounds snapped outward to multiples of `step`
    /// (left as they are where `step` is not positive and finite).
    pub fn new(inner: T, step: f64) -> Self {
        Self { inner, step }
    }
}

impl<T: PlotItem> PlotItem for SnappedBounds<T> {
    fn shapes(&self, ui: &Ui, transform: &PlotTransform, shapes: &mut Vec<Shape>) {
        self.inner.shapes(ui, transform, shapes);
    }

    fn initialize(&mut self, x_range: RangeInclusive<f64>) {
        self.inner.initialize(x_range);
    }

    fn color(&self) -> Color32 {
        self.inner.color()
    }

    fn geometry(&self) -> PlotGeometry<'_> {
        self.inner.geometry()
    }

    fn bounds(&self) -> PlotBounds {
        let b = self.inner.bounds();
        if !self.step.is_finite() || self.step <= 0.0 || !b.is_valid_y() {
            return b;
        }
        let (lo, hi) = (b.min()[1], b.max()[1]);
        let lo = (lo / self.step).floor() * self.step;
        let hi = (hi / self.step).ceil() * self.step;
        PlotBounds::from_min_max([b.min()[0], lo], [b.max()[0], hi])
    }

    fn base(&self) -> &PlotItemBase {
        self.inner.base()
    }

    fn base_mut(&mut self) -> &mut PlotItemBase {
        self.inner.base_mut()
    }
}

/// A small multiplicative hash of 64-bit words (the content key of a
/// cached mesh; a few microseconds for a regeneration's thousands of
/// values, where SipHash took about ten times as long).
#[derive(Default)]
struct Hash64(u64);

impl Hash64 {
    fn word(&mut self, w: u64) {
        self.0 = (self.0.rotate_left(5) ^ w).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn snapped_bounds_widen_to_whole_steps_and_keep_x() {
        let line = egui_plot::Line::new("l", vec![[0.0, 0.12], [2.0, 0.93]]);
        let b = SnappedBounds::new(line, 0.25).bounds();
        assert_eq!(b.min(), [0.0, 0.0]);
        assert_eq!(b.max(), [2.0, 1.0]);
        let line = egui_plot::Line::new("l", vec![[0.0, 0.12], [2.0, 0.93]]);
        let b = SnappedBounds::new(line, f64::NAN).bounds();
        assert_eq!(b.max(), [2.0, 0.93]);
    }

    #[test]
    fn the_content_key_changes_with_any_value() {
        let id = egui::Id::unique("cached lines test");
        let a = CachedLines::new(
            "a",
            Color32::RED,
            1.0,
            vec![vec![[0.0, 1.0], [1.0, 2.0]]],
            id,
        );
        let b = CachedLines::new(
            "a",
            Color32::RED,
            1.0,
            vec![vec![[0.0, 1.0], [1.0, 2.0]]],
            id,
        );
        let c = CachedLines::new(
            "a",
            Color32::RED,
            1.0,
            vec![vec![[0.0, 1.0], [1.0, 2.5]]],
            id,
        );
        let d = CachedLines::new(
            "a",
            Color32::BLUE,
            1.0,
            vec![vec![[0.0, 1.0], [1.0, 2.0]]],
            id,
        );
        assert_eq!(a.key, b.key);
        assert_ne!(a.key, c.key);
        assert_ne!(a.key, d.key);
        assert_eq!(a.bounds().max(), [1.0, 2.0]);
    }
}
