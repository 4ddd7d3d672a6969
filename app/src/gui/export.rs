//! What the app exports besides the core's report (gains, extraction and
//! Table I as JSON, CSV or Markdown): a heat map as a PNG (grid resolution,
//! scaled up with square pixels, K/M up).

use dmpscope_core::landscape::grid::Grid;
use eframe::egui::ColorImage;

use super::heatmap::colour_image;

/// The PNG of a map of `values` on `grid`, each grid point a square of
/// pixels so the image is at least 512 pixels wide.
pub fn heatmap_png(values: &[f64], grid: &Grid, log_colour: bool) -> Result<Vec<u8>, String> {
    let (image, _) = colour_image(values, grid, log_colour, None);
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

#[cfg(test)]
mod tests {
    use super::*;
    use dmpscope_core::landscape::grid::{Axis, AxisScale};

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
}
