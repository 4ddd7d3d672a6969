//! Figures of gain sets compared (issue 45), drawn with plotters so that
//! they work headless: the selected demo's three position components
//! against time (one panel per axis, the demo solid black, each set's
//! regeneration in its colour) and each set's distance from the demo,
//! beside the 3D paths of every demo shown (the demo grey, each set in its
//! colour), with a legend. SVG everywhere (the CLI, the app, the browser),
//! PNG natively.

use dmpscope_core::Model;
use dmpscope_core::report::compare::GainSet;
use plotters::coord::Shift;
use plotters::prelude::*;

/// The sets' colours, in pin order: Okabe and Ito's colour-blind-safe
/// palette (without its yellow, faint on white).
pub const SET_COLOURS: [[u8; 3]; 6] = [
    [230, 159, 0],
    [86, 180, 233],
    [0, 158, 115],
    [0, 114, 178],
    [213, 94, 0],
    [204, 121, 167],
];

/// The figure's size, pixels.
pub const SIZE: (u32, u32) = (1400, 900);

/// One demo in a figure: its times, its recorded path and each set's
/// regeneration (absolute metres, on the unit-time grid).
#[derive(Clone, Debug)]
pub struct FigureDemo {
    /// Its name.
    pub name: String,
    /// Real time of each point, seconds.
    pub t: Vec<f64>,
    /// The recorded path.
    pub recorded: Vec<[f64; 3]>,
    /// Each set's regeneration, in the sets' order.
    pub regenerated: Vec<Vec<[f64; 3]>>,
}

/// What a figure shows.
#[derive(Clone, Debug)]
pub struct Figure {
    /// Its title.
    pub title: String,
    /// Each set's name and colour.
    pub sets: Vec<(String, [u8; 3])>,
    /// The demos drawn in 3D (every one, or the selected one).
    pub demos: Vec<FigureDemo>,
    /// The one whose components are plotted against time (an index into
    /// `demos`).
    pub selected: usize,
}

impl Figure {
    /// The regenerations of `demos` (model indices; every demo when empty)
    /// at every set (with its colour), with demo `selected` (an index into
    /// the model) against time.
    pub fn of_model(
        model: &Model,
        sets: &[(GainSet, [u8; 3])],
        demos: &[usize],
        selected: usize,
    ) -> Self {
        let all: Vec<usize> = (0..model.demos().len()).collect();
        let demos = if demos.is_empty() { &all[..] } else { demos };
        let figure_demos: Vec<FigureDemo> = demos
            .iter()
            .map(|&i| {
                let d = &model.demos()[i];
                let n = d.y_raw.len();
                let abs =
                    |p: &dmpscope_core::geom::Vec3| [p.x + d.p0.x, p.y + d.p0.y, p.z + d.p0.z];
                FigureDemo {
                    name: d.name.clone(),
                    t: (0..n)
                        .map(|k| d.duration_s * k as f64 / (n - 1).max(1) as f64)
                        .collect(),
                    recorded: d.y_raw.iter().map(abs).collect(),
                    regenerated: sets
                        .iter()
                        .map(|(s, _)| model.rollout(i, s.dm, s.km).y.iter().map(abs).collect())
                        .collect(),
                }
            })
            .collect();
        let title = match demos {
            [one] => format!("{} regenerated", model.demos()[*one].name),
            _ => format!("{} demos regenerated", demos.len()),
        };
        Self {
            title,
            sets: sets.iter().map(|(s, c)| (s.name.clone(), *c)).collect(),
            selected: demos.iter().position(|&i| i == selected).unwrap_or(0),
            demos: figure_demos,
        }
    }

    /// The sets in [`SET_COLOURS`], in order.
    pub fn coloured(sets: &[GainSet]) -> Vec<(GainSet, [u8; 3])> {
        sets.iter()
            .cloned()
            .zip(SET_COLOURS.iter().copied().cycle())
            .collect()
    }
}

/// The figure as SVG text.
pub fn svg(figure: &Figure) -> anyhow::Result<String> {
    fonts()?;
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, SIZE).into_drawing_area();
        draw(&root, figure).map_err(|e| anyhow::anyhow!("drawing the figure: {e}"))?;
    }
    Ok(out)
}

/// The figure as a PNG image.
#[cfg(not(target_arch = "wasm32"))]
pub fn png(figure: &Figure) -> anyhow::Result<Vec<u8>> {
    fonts()?;
    let (w, h) = SIZE;
    let mut rgb = vec![0u8; (w * h * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, SIZE).into_drawing_area();
        draw(&root, figure).map_err(|e| anyhow::anyhow!("drawing the figure: {e}"))?;
    }
    let mut out = Vec::new();
    let mut encoder = png::Encoder::new(&mut out, w, h);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header()?;
    writer.write_image_data(&rgb)?;
    writer.finish()?;
    Ok(out)
}

/// Registers the embedded font plotters measures and draws text with
/// (natively; a browser measures with its own).
fn fonts() -> anyhow::Result<()> {
    #[cfg(not(target_arch = "wasm32"))]
    {
        static REGISTERED: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
        let ok = *REGISTERED.get_or_init(|| {
            plotters::style::register_font(
                "sans-serif",
                FontStyle::Normal,
                epaint_default_fonts::UBUNTU_LIGHT,
            )
            .is_ok()
        });
        anyhow::ensure!(ok, "the figure's font did not load");
    }
    Ok(())
}

type DrawResult<DB> = Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

fn colour(c: [u8; 3]) -> RGBColor {
    RGBColor(c[0], c[1], c[2])
}

/// The whole figure: the title, the time panels on the left, 3D on the
/// right.
fn draw<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, figure: &Figure) -> DrawResult<DB> {
    root.fill(&WHITE)?;
    let body = root.titled(&figure.title, ("sans-serif", 24))?;
    let (left, right) = body.split_horizontally(SIZE.0 * 11 / 20);
    if let Some(demo) = figure.demos.get(figure.selected) {
        let rows = left.split_evenly((4, 1));
        for (axis, area) in rows.iter().take(3).enumerate() {
            time_panel(area, figure, demo, axis)?;
        }
        if let Some(area) = rows.get(3) {
            error_panel(area, figure, demo)?;
        }
    }
    space_panel(&right, figure)?;
    root.present()
}

/// The range of `values` with a margin of 5 % (a unit range around a
/// constant).
fn range(values: impl Iterator<Item = f64>) -> std::ops::Range<f64> {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
            (l.min(v), h.max(v))
        });
    if !lo.is_finite() {
        return 0.0..1.0;
    }
    let pad = ((hi - lo) * 0.05).max(1e-3);
    lo - pad..hi + pad
}

/// One axis of the selected demo against time: the demo, then each set.
fn time_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    figure: &Figure,
    demo: &FigureDemo,
    axis: usize,
) -> DrawResult<DB> {
    let name = ["x", "y", "z"][axis];
    let values = demo
        .recorded
        .iter()
        .chain(demo.regenerated.iter().flatten())
        .map(|p| p[axis]);
    let t_end = demo.t.last().copied().unwrap_or(1.0).max(1e-3);
    let mut chart = ChartBuilder::on(area)
        .margin(8)
        .x_label_area_size(30)
        .y_label_area_size(60)
        .caption(format!("{name}: {}", demo.name), ("sans-serif", 15))
        .build_cartesian_2d(0.0..t_end, range(values))?;
    chart
        .configure_mesh()
        .x_desc("t [s]")
        .y_desc(format!("{name} [m]"))
        .label_style(("sans-serif", 12))
        .axis_desc_style(("sans-serif", 13))
        .light_line_style(BLACK.mix(0.05))
        .draw()?;
    let points = |path: &[[f64; 3]]| -> Vec<(f64, f64)> {
        demo.t
            .iter()
            .zip(path)
            .map(|(&t, p)| (t, p[axis]))
            .collect()
    };
    chart
        .draw_series(LineSeries::new(
            points(&demo.recorded),
            BLACK.stroke_width(2),
        ))?
        .label("demo")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(2)));
    for ((set, c), path) in figure.sets.iter().zip(&demo.regenerated) {
        let c = colour(*c);
        chart
            .draw_series(LineSeries::new(points(path), c.stroke_width(2)))?
            .label(set.clone())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2)));
    }
    if axis == 0 {
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::LowerRight)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK.mix(0.3))
            .label_font(("sans-serif", 12))
            .draw()?;
    }
    Ok(())
}

/// Each set's distance from the recorded path against time, millimetres:
/// where the regenerations, alike at the scale of the motion, differ.
fn error_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    figure: &Figure,
    demo: &FigureDemo,
) -> DrawResult<DB> {
    let errors: Vec<Vec<(f64, f64)>> = demo
        .regenerated
        .iter()
        .map(|path| {
            demo.t
                .iter()
                .zip(path.iter().zip(&demo.recorded))
                .map(|(&t, (p, q))| {
                    let d2: f64 = (0..3).map(|a| (p[a] - q[a]).powi(2)).sum();
                    (t, 1000.0 * d2.sqrt())
                })
                .collect()
        })
        .collect();
    let top = errors
        .iter()
        .flatten()
        .map(|e| e.1)
        .filter(|v| v.is_finite())
        .fold(0.0f64, f64::max)
        .max(1e-3);
    let t_end = demo.t.last().copied().unwrap_or(1.0).max(1e-3);
    let mut chart = ChartBuilder::on(area)
        .margin(8)
        .x_label_area_size(30)
        .y_label_area_size(60)
        .caption("distance from the demo", ("sans-serif", 15))
        .build_cartesian_2d(0.0..t_end, 0.0..top * 1.05)?;
    chart
        .configure_mesh()
        .x_desc("t [s]")
        .y_desc("|regen - demo| [mm]")
        .label_style(("sans-serif", 12))
        .axis_desc_style(("sans-serif", 13))
        .light_line_style(BLACK.mix(0.05))
        .draw()?;
    for ((_, c), e) in figure.sets.iter().zip(errors) {
        chart.draw_series(LineSeries::new(e, colour(*c).stroke_width(2)))?;
    }
    Ok(())
}

/// Every demo shown in 3D (z up): recorded grey, each set in its colour.
fn space_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    figure: &Figure,
) -> DrawResult<DB> {
    let every = || {
        figure
            .demos
            .iter()
            .flat_map(|d| d.recorded.iter().chain(d.regenerated.iter().flatten()))
    };
    // plotters' y is up: (x, z, y) of the recording.
    let (xr, yr, zr) = (
        range(every().map(|p| p[0])),
        range(every().map(|p| p[2])),
        range(every().map(|p| p[1])),
    );
    let mut chart = ChartBuilder::on(area)
        .margin(20)
        .caption("3D paths (z up) [m]", ("sans-serif", 15))
        .build_cartesian_3d(xr, yr, zr)?;
    chart.with_projection(|mut p| {
        p.yaw = 0.6;
        p.pitch = 0.35;
        p.scale = 0.85;
        p.into_matrix()
    });
    chart
        .configure_axes()
        .light_grid_style(BLACK.mix(0.08))
        .max_light_lines(3)
        .label_style(("sans-serif", 11))
        .draw()?;
    let grey = RGBColor(110, 110, 110);
    for d in &figure.demos {
        let recorded = d.recorded.iter().map(|p| (p[0], p[2], p[1]));
        chart.draw_series(LineSeries::new(recorded, grey.stroke_width(2)))?;
        for ((_, c), path) in figure.sets.iter().zip(&d.regenerated) {
            let path = path.iter().map(|p| (p[0], p[2], p[1]));
            chart.draw_series(LineSeries::new(path, colour(*c).stroke_width(1)))?;
        }
    }
    Ok(())
}
