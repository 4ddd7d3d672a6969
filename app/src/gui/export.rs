//! What the app exports: a heat map as a PNG (grid resolution, scaled up
//! with square pixels, K/M up), the gains as JSON, Table I as CSV or
//! Markdown (`table.rs`).

use dmpscope_core::landscape::Grid;
use dmpscope_core::{Extraction, TableRow};
use eframe::egui::ColorImage;

use super::heatmap::colour_image;

/// The PNG of a map of `values` on `grid`, each grid point a square of
/// pixels so the image is at least 512 pixels wide.
pub fn heatmap_png(values: &[f64], grid: &Grid, log_colour: bool) -> Result<Vec<u8>, String> {
    let (image, _) = colour_image(values, grid, log_colour);
    png_of(&image, (512 / image.width().max(1)).max(1))
}

/// Encodes `image` as an 8-bit RGBA PNG, each pixel `scale` x `scale`.
pub fn png_of(image: &ColorImage, scale: usize) -> Result<Vec<u8>, String> {
    let [w, h] = image.size;
    let (sw, sh) = (w * scale, h * scale);
    let mut rgba = Vec::with_capacity(sw * sh * 4);
    for y in 0..sh {
        for x in 0..sw {
            rgba.extend_from_slice(&image.pixels[(y / scale) * w + x / scale].to_array());
        }
    }
    let too_big = |_| format!("a {sw} x {sh} image is too large for PNG");
    let (pw, ph) = (
        u32::try_from(sw).map_err(too_big)?,
        u32::try_from(sh).map_err(too_big)?,
    );
    let mut out = Vec::new();
    let mut encoder = png::Encoder::new(&mut out, pw, ph);
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().map_err(|e| e.to_string())?;
    writer.write_image_data(&rgba).map_err(|e| e.to_string())?;
    writer.finish().map_err(|e| e.to_string())?;
    Ok(out)
}

/// The gains as JSON: k, the extraction (when known, with its edge flags),
/// and every row of Table I with its per-demo d_mean and a_peak.
pub fn gains_json(
    k: f64,
    extraction: Option<&Extraction>,
    rows: &[TableRow],
    demos: &[String],
) -> String {
    let row = |r: &TableRow| {
        serde_json::json!({
            "name": r.name,
            "dm": r.dm,
            "km": r.km,
            "zeta": r.zeta,
            "s": r.s,
            "d_sum": r.d_sum,
            "j": r.j,
            "d_mean_m": r.d_mean,
            "a_peak": r.a_peak,
        })
    };
    let extracted = extraction.map(|x| {
        serde_json::json!({
            "m": 1.0,
            "dm": x.eval.dm,
            "km": x.eval.km,
            "zeta": x.eval.zeta,
            "j": x.j,
            "on_edge": x.on_edge(),
            "edge": x.edges.describe(),
        })
    });
    let value = serde_json::json!({
        "k": k,
        "extracted": extracted,
        "demos": demos,
        "rows": rows.iter().map(row).collect::<Vec<_>>(),
    });
    serde_json::to_string_pretty(&value).unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use dmpscope_core::landscape::{Axis, AxisScale};

    #[test]
    fn a_heat_map_png_decodes_to_the_map_scaled_up() {
        let axis = |n| Axis {
            lo: 1.0,
            hi: 10.0,
            n,
            scale: AxisScale::Log,
        };
        let grid = Grid {
            dm: axis(4),
            km: axis(2),
        };
        let values = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, f64::NAN];
        let bytes = heatmap_png(&values, &grid, false).expect("png");
        let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
        let mut reader = decoder.read_info().expect("header");
        let mut buf = vec![0; reader.output_buffer_size().expect("size")];
        let info = reader.next_frame(&mut buf).expect("frame");
        assert_eq!((info.width, info.height), (512, 256));
        let px = |x: usize, y: usize| &buf[(y * 512 + x) * 4..(y * 512 + x) * 4 + 4];
        // Lowest value (dm 0, km 0) bottom left: viridis' dark purple.
        let low = colorous::VIRIDIS.eval_continuous(0.0);
        assert_eq!(px(0, 255), &[low.r, low.g, low.b, 255]);
        // Highest finite (dm 3, km 0) bottom right: viridis' yellow.
        let high = colorous::VIRIDIS.eval_continuous(1.0);
        assert_eq!(px(511, 255), &[high.r, high.g, high.b, 255]);
        // NaN (dm 3, km 1) top right: dark grey.
        assert_eq!(px(511, 0), &[40, 40, 40, 255]);
    }

    #[test]
    fn gains_json_names_every_row() {
        let row = TableRow {
            name: "Hrstc1".into(),
            dm: 25.0,
            km: 156.25,
            zeta: 1.0,
            s: 0.3,
            d_sum: 0.01,
            j: 0.5,
            d_mean: vec![0.001],
            a_peak: vec![4.0],
        };
        let text = gains_json(20.0, None, &[row], &["demo".into()]);
        let v: serde_json::Value = serde_json::from_str(&text).expect("json");
        assert_eq!(v["k"], 20.0);
        assert!(v["extracted"].is_null());
        assert_eq!(v["rows"][0]["name"], "Hrstc1");
        assert_eq!(v["rows"][0]["km"], 156.25);
    }
}
