//! A heat map of one landscape quantity over (D/M, K/M): a texture (one
//! texel per grid point, viridis, linear or log colour), axes, a colour bar,
//! labelled markers, iso-zeta lines, a cloud of points (the bootstrap
//! optima), points masked out (beyond an a_peak limit), a hover read-out of
//! sum d, S, J and a_peak, and the operating point, which a click or drag
//! moves.

use dmpscope_core::landscape::grid::{Axis, AxisScale, Grid};
use dmpscope_core::landscape::quantity;
use dmpscope_core::landscape::quantity::PointValues;
use eframe::egui::{
    self, Align2, Color32, ColorImage, FontId, Pos2, Rect, Sense, Stroke, TextureHandle,
    TextureOptions, Vec2,
};

/// A labelled point on the map.
pub struct Marker {
    /// The label.
    pub label: String,
    /// D/M.
    pub dm: f64,
    /// K/M.
    pub km: f64,
    /// Its colour.
    pub colour: Color32,
}

/// The damping ratios drawn as iso-zeta lines (`K/M = (D/M / 2 zeta)^2`).
pub const ISO_ZETA: [f64; 3] = [0.5, 1.0, 2.0];

/// The texture of one map, rebuilt only when its key changes.
#[derive(Default)]
pub struct Cache {
    key: Option<(u64, u64, bool, u64)>,
    texture: Option<TextureHandle>,
    range: (f64, f64),
}

/// What a map shows.
pub struct MapInput<'a> {
    /// The title above it.
    pub title: &'a str,
    /// Values `[i_dm][i_km]` row-major (NaN: not computed).
    pub values: &'a [f64],
    /// Identifies `values` (snapshot version, k bits) for the cache.
    pub key: (u64, u64),
    /// The grid.
    pub grid: Grid,
    /// Colour on a log scale.
    pub log_colour: bool,
    /// Read-out of J and every quantity of the table at a grid point.
    pub readout: &'a dyn Fn(usize, usize) -> (f64, PointValues),
    /// Points to mask (grey): `(a_peak per point, limit)`, those above it.
    pub mask: Option<(&'a [f64], f64)>,
    /// Draw the iso-zeta lines.
    pub iso_zeta: bool,
    /// Small dots to draw (the bootstrap optima), `(D/M, K/M)`.
    pub cloud: &'a [(f64, f64)],
    /// The acceptable region (method.md section 11), per grid point: its
    /// outline is drawn.
    pub region: Option<&'a [bool]>,
    /// Said across the map (e.g. that nothing is computed yet).
    pub note: Option<&'a str>,
    /// Label the markers (one map of several: the others keep the circles,
    /// in the same colours).
    pub labels: bool,
}

/// The colour of the acceptable region's outline.
pub const REGION_COLOUR: Color32 = Color32::from_rgb(120, 255, 140);

/// The colour of masked points.
const MASKED: Color32 = Color32::from_rgb(90, 70, 70);

/// The least map side with iso-zeta labels.
const LABELLED_SIDE: f32 = 150.0;

/// Where a marker's label may go, in order: right above, right below,
/// left above, left below its circle.
const LABEL_SIDES: [(f32, f32); 4] = [(1.0, -1.0), (1.0, 1.0), (-1.0, -1.0), (-1.0, 1.0)];

const AXIS_MARGIN: f32 = 44.0;
const BAR_WIDTH: f32 = 14.0;
const BAR_MARGIN: f32 = 58.0;

/// The fraction along an axis of a value, at texel centres (0..1).
fn fraction(axis: &Axis, v: f64) -> f64 {
    let (lo, hi) = (axis.to_coord(axis.lo), axis.to_coord(axis.hi));
    let f = (axis.to_coord(v) - lo) / (hi - lo);
    (f * (axis.n - 1) as f64 + 0.5) / axis.n as f64
}

/// The value at a fraction along an axis (inverse of [`fraction`]), clamped.
fn value_at(axis: &Axis, f: f64) -> f64 {
    let (lo, hi) = (axis.to_coord(axis.lo), axis.to_coord(axis.hi));
    let t = ((f * axis.n as f64 - 0.5) / (axis.n - 1) as f64).clamp(0.0, 1.0);
    axis.from_coord(lo + t * (hi - lo)).clamp(axis.lo, axis.hi)
}

/// Steps of the colour table: viridis at 1024 points is within one level
/// of 8 bits of the continuous map, at a table lookup per pixel (the
/// continuous map costs 24 ns a pixel natively, about 0.8 ms a 128 x 128
/// map in the browser, where a new landscape preview remakes three maps in
/// one frame).
const COLOUR_STEPS: usize = 1024;

/// Viridis at `t` in 0..1 (clamped).
fn colour(t: f64) -> Color32 {
    static TABLE: std::sync::OnceLock<Vec<Color32>> = std::sync::OnceLock::new();
    let table = TABLE.get_or_init(|| {
        (0..COLOUR_STEPS)
            .map(|i| {
                let c = colorous::VIRIDIS.eval_continuous(i as f64 / (COLOUR_STEPS - 1) as f64);
                Color32::from_rgb(c.r, c.g, c.b)
            })
            .collect()
    });
    // NaN clamps to NaN and casts to 0.
    let i = (t.clamp(0.0, 1.0) * (COLOUR_STEPS - 1) as f64).round() as usize;
    table[i.min(COLOUR_STEPS - 1)]
}

fn transform(v: f64, log: bool) -> f64 {
    if log {
        if v > 0.0 { v.ln() } else { f64::NAN }
    } else {
        v
    }
}

/// The map as an image (one pixel per grid point, D/M to the right, K/M
/// up, viridis, NaN dark grey, masked points reddish grey) and the colour
/// range `(lo, hi)` of the points not masked (of ln v on a log colour
/// scale).
pub fn colour_image(
    values: &[f64],
    grid: &Grid,
    log_colour: bool,
    mask: Option<(&[f64], f64)>,
) -> (ColorImage, (f64, f64)) {
    let (n_dm, n_km) = (grid.dm.n, grid.km.n);
    let masked = |idx: usize| mask.is_some_and(|(a, limit)| a.get(idx).is_some_and(|&a| a > limit));
    let t: Vec<f64> = values.iter().map(|&v| transform(v, log_colour)).collect();
    let (lo, hi) = t
        .iter()
        .enumerate()
        .filter(|(i, v)| v.is_finite() && !masked(*i))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), (_, &v)| {
            (a.min(v), b.max(v))
        });
    let span = if hi > lo { hi - lo } else { 1.0 };
    let mut pixels = vec![Color32::from_gray(40); n_dm * n_km];
    for i in 0..n_dm {
        for j in 0..n_km {
            let idx = i * n_km + j;
            let v = t.get(idx).copied().unwrap_or(f64::NAN);
            // x = D/M index, y = K/M index from the top (high K/M up).
            let pixel = &mut pixels[(n_km - 1 - j) * n_dm + i];
            if masked(idx) {
                *pixel = MASKED;
            } else if v.is_finite() {
                *pixel = colour((v - lo) / span);
            }
        }
    }
    (ColorImage::new([n_dm, n_km], pixels), (lo, hi))
}

fn build(ctx: &egui::Context, input: &MapInput<'_>) -> (TextureHandle, (f64, f64)) {
    #[cfg(feature = "testing")]
    let start = web_time::Instant::now();
    let (image, range) = colour_image(input.values, &input.grid, input.log_colour, input.mask);
    let texture = ctx.load_texture(input.title, image, TextureOptions::NEAREST);
    #[cfg(feature = "testing")]
    BUILD_MS.with(|ms| ms.borrow_mut().push(start.elapsed().as_secs_f64() * 1e3));
    (texture, range)
}

#[cfg(feature = "testing")]
thread_local! {
    /// The time of each map's image and texture made (the browser tests'
    /// probes read it).
    pub static BUILD_MS: std::cell::RefCell<Vec<f64>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// Tick values of an axis: decades on a log axis, five steps on a linear one.
fn ticks(axis: &Axis) -> Vec<f64> {
    match axis.scale {
        AxisScale::Log => {
            let (a, b) = (
                axis.lo.log10().ceil() as i32,
                axis.hi.log10().floor() as i32,
            );
            (a..=b).map(|e| 10f64.powi(e)).collect()
        }
        AxisScale::Linear => (0..=4)
            .map(|i| axis.lo + (axis.hi - axis.lo) * i as f64 / 4.0)
            .collect(),
    }
}

fn tick_label(v: f64) -> String {
    if v >= 1.0 {
        format!("{v:.0}")
    } else {
        format!("{v}")
    }
}

/// The side of a map that fits in `size` with its axes, title and colour bar.
pub fn side_for(size: Vec2) -> f32 {
    (size.x - AXIS_MARGIN - BAR_MARGIN).min(size.y - 50.0)
}

/// Shows the map (`side` pixels square); returns true when the user moved
/// the operating point.
pub fn show(
    ui: &mut egui::Ui,
    cache: &mut Cache,
    input: &MapInput<'_>,
    markers: &[Marker],
    op: &mut (f64, f64),
    side: f32,
) -> bool {
    refresh_cache(ui.ctx(), cache, input);
    ui.label(egui::RichText::new(input.title).strong());
    let side = side.max(80.0);
    let (outer, _) = ui.allocate_exact_size(
        Vec2::new(side + AXIS_MARGIN + BAR_MARGIN, side + 30.0),
        Sense::hover(),
    );
    let map = Rect::from_min_size(outer.min + Vec2::new(AXIS_MARGIN, 4.0), Vec2::splat(side));
    let response = ui.interact(
        map,
        ui.scope_id().with(input.title),
        Sense::click_and_drag(),
    );
    // What a screen reader (and the GUI tests) hear of the map.
    response.widget_info(|| {
        let label = match input.note {
            Some(note) => format!("{} map: {note}", input.title),
            None => format!("{} map", input.title),
        };
        egui::WidgetInfo::labeled(egui::accesskit::Role::Image, true, label)
    });
    let area = MapArea {
        painter: ui.painter_at(outer),
        outer,
        map,
        grid: input.grid,
        text: ui.visuals().text_color(),
        font: FontId::proportional(11.0),
    };
    if let Some(texture) = &cache.texture {
        area.painter.image(
            texture.id(),
            map,
            Rect::from_min_max(Pos2::ZERO, Pos2::new(1.0, 1.0)),
            Color32::WHITE,
        );
    }
    if let Some(note) = input.note {
        area.painter.text(
            map.center(),
            Align2::CENTER_CENTER,
            note,
            area.font.clone(),
            area.text,
        );
    }
    heatmap_axes_ui(&area);
    heatmap_colour_bar_ui(&area, side, cache.range, input.log_colour);
    if input.iso_zeta {
        iso_zeta(
            &area.painter,
            &area.grid,
            &|dm: f64, km: f64| area.to_screen(dm, km),
            map,
            &area.font,
        );
    }
    if let Some(region) = input.region {
        region_outline(&area, region);
    }
    heatmap_points_ui(&area, input.cloud, markers, *op, input.labels);
    heatmap_readout_ui(&area, &response, input);
    if (response.dragged() || response.clicked())
        && let Some(pos) = response.interact_pointer_pos()
    {
        *op = area.at(pos);
        return true;
    }
    false
}

/// Rebuilds the cached texture when the map's values, colour scale or mask changed.
fn refresh_cache(ctx: &egui::Context, cache: &mut Cache, input: &MapInput<'_>) {
    let mask_key = input.mask.map_or(0, |(_, limit)| limit.to_bits());
    let key = (input.key.0, input.key.1, input.log_colour, mask_key);
    if cache.key != Some(key) || cache.texture.is_none() {
        let (texture, range) = build(ctx, input);
        cache.texture = Some(texture);
        cache.range = range;
        cache.key = Some(key);
    }
}

/// Where a map is drawn: its painter, the space with its axes, the map
/// square, its grid and the text's colour and font.
struct MapArea {
    painter: egui::Painter,
    outer: Rect,
    map: Rect,
    grid: Grid,
    text: Color32,
    font: FontId,
}

impl MapArea {
    /// The screen position of `(D/M, K/M)`.
    fn to_screen(&self, dm: f64, km: f64) -> Pos2 {
        Pos2::new(
            self.map.left() + fraction(&self.grid.dm, dm) as f32 * self.map.width(),
            self.map.bottom() - fraction(&self.grid.km, km) as f32 * self.map.height(),
        )
    }

    /// The `(D/M, K/M)` at a screen position, clamped to the axes.
    fn at(&self, pos: Pos2) -> (f64, f64) {
        let fx = f64::from((pos.x - self.map.left()) / self.map.width());
        let fy = f64::from((self.map.bottom() - pos.y) / self.map.height());
        (value_at(&self.grid.dm, fx), value_at(&self.grid.km, fy))
    }
}

/// The ticks and names of the D/M and K/M axes.
fn heatmap_axes_ui(area: &MapArea) {
    let (painter, grid, map) = (&area.painter, &area.grid, area.map);
    let (text, font) = (area.text, &area.font);
    for v in ticks(&grid.dm) {
        let p = area.to_screen(v, grid.km.lo);
        painter.text(
            Pos2::new(p.x, map.bottom() + 3.0),
            Align2::CENTER_TOP,
            tick_label(v),
            font.clone(),
            text,
        );
    }
    for v in ticks(&grid.km) {
        let p = area.to_screen(grid.dm.lo, v);
        painter.text(
            Pos2::new(map.left() - 4.0, p.y),
            Align2::RIGHT_CENTER,
            tick_label(v),
            font.clone(),
            text,
        );
    }
    painter.text(
        Pos2::new(map.center().x, map.bottom() + 16.0),
        Align2::CENTER_TOP,
        "D/M",
        font.clone(),
        text,
    );
    painter.text(
        Pos2::new(area.outer.left() + 2.0, map.top()),
        Align2::LEFT_TOP,
        "K/M",
        font.clone(),
        text,
    );
}

/// The colour bar right of the map (`side` high), labelled with the colour range `(lo, hi)`.
fn heatmap_colour_bar_ui(area: &MapArea, side: f32, (lo, hi): (f64, f64), log_colour: bool) {
    let (painter, map) = (&area.painter, area.map);
    let bar = Rect::from_min_size(
        Pos2::new(map.right() + 8.0, map.top()),
        Vec2::new(BAR_WIDTH, side),
    );
    let steps = 48;
    for s in 0..steps {
        let t0 = s as f32 / steps as f32;
        let r = Rect::from_min_max(
            Pos2::new(
                bar.left(),
                bar.bottom() - (t0 + 1.0 / steps as f32) * bar.height(),
            ),
            Pos2::new(bar.right(), bar.bottom() - t0 * bar.height()),
        );
        painter.rect_filled(r, 0.0, colour(f64::from(t0)));
    }
    let shown = |v: f64| if log_colour { v.exp() } else { v };
    if lo.is_finite() {
        painter.text(
            bar.right_top() + Vec2::new(3.0, 0.0),
            Align2::LEFT_TOP,
            format!("{:.3}", shown(hi)),
            area.font.clone(),
            area.text,
        );
        painter.text(
            bar.right_bottom() + Vec2::new(3.0, 0.0),
            Align2::LEFT_BOTTOM,
            format!("{:.3}", shown(lo)),
            area.font.clone(),
            area.text,
        );
    }
}

/// The outline of a region of grid points: the texel edges between a
/// point in it and one out of it (or the map's border).
fn region_outline(area: &MapArea, region: &[bool]) {
    let (n_dm, n_km) = (area.grid.dm.n, area.grid.km.n);
    if region.len() != n_dm * n_km {
        return;
    }
    let (w, h) = (
        area.map.width() / n_dm as f32,
        area.map.height() / n_km as f32,
    );
    let inside = |i: isize, j: isize| {
        i >= 0
            && j >= 0
            && (i as usize) < n_dm
            && (j as usize) < n_km
            && region[i as usize * n_km + j as usize]
    };
    let stroke = Stroke::new(1.5, REGION_COLOUR);
    for i in 0..n_dm as isize {
        for j in 0..n_km as isize {
            if !inside(i, j) {
                continue;
            }
            let x0 = area.map.left() + i as f32 * w;
            let y0 = area.map.bottom() - (j + 1) as f32 * h;
            let (x1, y1) = (x0 + w, y0 + h);
            let edges = [
                (inside(i - 1, j), [Pos2::new(x0, y0), Pos2::new(x0, y1)]),
                (inside(i + 1, j), [Pos2::new(x1, y0), Pos2::new(x1, y1)]),
                (inside(i, j - 1), [Pos2::new(x0, y1), Pos2::new(x1, y1)]),
                (inside(i, j + 1), [Pos2::new(x0, y0), Pos2::new(x1, y0)]),
            ];
            for (neighbour, line) in edges {
                if !neighbour {
                    area.painter.line_segment(line, stroke);
                }
            }
        }
    }
}

/// The cloud of points, the labelled markers and the operating point `op`.
fn heatmap_points_ui(
    area: &MapArea,
    cloud: &[(f64, f64)],
    markers: &[Marker],
    op: (f64, f64),
    labels: bool,
) {
    let painter = &area.painter;
    for &(dm, km) in cloud {
        painter.circle_filled(
            area.to_screen(dm, km),
            2.0,
            Color32::from_rgb(255, 200, 120),
        );
    }
    for m in markers {
        painter.circle_stroke(area.to_screen(m.dm, m.km), 4.0, Stroke::new(1.5, m.colour));
    }
    // Each label where it covers no other (none where no side is free).
    if labels {
        let mut placed: Vec<Rect> = Vec::new();
        for m in markers {
            let p = area.to_screen(m.dm, m.km);
            let galley = painter.layout_no_wrap(m.label.clone(), area.font.clone(), m.colour);
            let size = galley.size();
            let free = LABEL_SIDES.iter().find_map(|&(dx, dy)| {
                let corner = p + Vec2::new(dx * 5.0, dy * 5.0);
                let min = corner
                    - Vec2::new(
                        if dx < 0.0 { size.x } else { 0.0 },
                        if dy < 0.0 { size.y } else { 0.0 },
                    );
                let rect = Rect::from_min_size(min, size);
                (area.map.contains_rect(rect) && placed.iter().all(|r| !r.intersects(rect)))
                    .then_some(rect)
            });
            if let Some(rect) = free {
                placed.push(rect);
                painter.galley(rect.min, galley, m.colour);
            }
        }
    }
    let p = area.to_screen(op.0, op.1);
    painter.circle_filled(p, 5.0, Color32::WHITE);
    painter.circle_stroke(p, 5.0, Stroke::new(1.5, Color32::BLACK));
}

/// The read-out of J and every quantity of the table (those computed there)
/// under the pointer, and whether the point is in the acceptable region.
fn heatmap_readout_ui(area: &MapArea, response: &egui::Response, input: &MapInput<'_>) {
    if let Some(pos) = response.hover_pos() {
        let (dm, km) = area.at(pos);
        let (i, j) = (nearest(&area.grid.dm, dm), nearest(&area.grid.km, km));
        let (jv, values) = (input.readout)(i, j);
        let zeta = dmpscope_core::landscape::model::zeta(dm, km);
        let inside = match input.region {
            Some(r) if r.get(i * area.grid.km.n + j) == Some(&true) => "\nin the acceptable region",
            _ => "",
        };
        let mut text = format!("D/M {dm:.3}  K/M {km:.3}  zeta {zeta:.3}\nJ {jv:.5}");
        for q in quantity::ALL {
            let (v, about) = (values[q.index()], q.about());
            if !v.is_nan() {
                text.push_str(&format!("\n{} {v:.5} {}", about.label, about.unit));
            }
        }
        text.push_str(inside);
        response.clone().on_hover_text_at_pointer(text);
    }
}

/// The iso-zeta lines `K/M = (D/M / (2 zeta))^2` across the map, each
/// labelled where it leaves it.
fn iso_zeta(
    painter: &egui::Painter,
    grid: &Grid,
    to_screen: &dyn Fn(f64, f64) -> Pos2,
    map: Rect,
    font: &FontId,
) {
    const SAMPLES: usize = 64;
    let colour = Color32::from_rgba_unmultiplied(255, 255, 255, 110);
    let (lo, hi) = (grid.dm.to_coord(grid.dm.lo), grid.dm.to_coord(grid.dm.hi));
    for (n, zeta) in ISO_ZETA.into_iter().enumerate() {
        let mut line: Vec<Pos2> = Vec::new();
        for s in 0..=SAMPLES {
            let dm = grid
                .dm
                .from_coord(lo + (hi - lo) * s as f64 / SAMPLES as f64);
            let km = (dm / (2.0 * zeta)).powi(2);
            if km >= grid.km.lo && km <= grid.km.hi {
                line.push(to_screen(dm, km));
            }
        }
        if line.len() < 2 {
            continue;
        }
        let last = line[line.len() - 1];
        // Solid and faint: dashes cost a shape each, 2.4 ms a frame for the
        // three maps (tests/frame_time.sh).
        painter.add(egui::Shape::line(line, Stroke::new(1.0, colour)));
        // Labels only where there is room for them (the big map).
        if map.width() < LABELLED_SIDE {
            continue;
        }
        // Staggered so that lines leaving close together stay readable.
        let at = Pos2::new(
            last.x.min(map.right() - 2.0),
            last.y.max(map.top() + 2.0) + 11.0 * n as f32,
        );
        painter.text(
            at,
            Align2::RIGHT_TOP,
            format!("ζ={zeta}"),
            font.clone(),
            colour,
        );
    }
}

/// The grid index nearest a value.
pub fn nearest(axis: &Axis, v: f64) -> usize {
    let f = fraction(axis, v) * axis.n as f64;
    (f.floor().max(0.0) as usize).min(axis.n - 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The table's colour is within one level of 8 bits of the continuous
    /// map, everywhere between its steps and at the ends.
    #[test]
    fn the_colour_table_follows_viridis() {
        for i in 0..=10_000 {
            let t = f64::from(i) / 10_000.0;
            let exact = colorous::VIRIDIS.eval_continuous(t);
            let got = colour(t);
            for (a, b) in [(exact.r, got.r()), (exact.g, got.g()), (exact.b, got.b())] {
                assert!(a.abs_diff(b) <= 1, "t = {t}: {exact:?} against {got:?}");
            }
        }
        assert_eq!(colour(-1.0), colour(0.0));
        assert_eq!(colour(2.0), colour(1.0));
    }
}
