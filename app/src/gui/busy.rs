//! The app's "busy" indicator: egui's spinner, turning at most
//! [`BUSY_FRAME`] apart. egui's own asks for a frame every frame; in the
//! browser under a software rasteriser a frame holds the page's thread for
//! 150-250 ms, so a spinner drawn back to back starves what it waits for:
//! every `Blob` read and every slice of a job waits a frame
//! (`web/tests/hostile_probe.mjs`: a hostile file's two reads took 0.7-1.0
//! s with it, with the page's thread free between frames a few ms).

use std::time::Duration;

use eframe::egui;

/// The longest time between two frames of the spinner: natively every
/// frame, in the browser once a second.
pub const BUSY_FRAME: Duration = if cfg!(target_arch = "wasm32") {
    Duration::from_secs(1)
} else {
    Duration::ZERO
};

/// A spinner the size of a line of text that asks for its next frame
/// [`BUSY_FRAME`] from now (news the app waits for asks for one sooner).
pub fn spinner(ui: &mut egui::Ui) -> egui::Response {
    let size = ui.style().spacing.interact_size.y;
    let (rect, response) = ui.allocate_exact_size(egui::vec2(size, size), egui::Sense::hover());
    if ui.is_rect_visible(rect) {
        let radius = rect.height() / 2.0 - 2.0;
        let time = ui.input(|i| i.time);
        let start_angle = time * std::f64::consts::TAU;
        let end_angle = start_angle + 240f64.to_radians() * time.sin();
        let points: Vec<egui::Pos2> = (0..=30)
            .map(|i| {
                let angle = egui::lerp(start_angle..=end_angle, f64::from(i) / 30.0);
                let (sin, cos) = angle.sin_cos();
                rect.center() + radius * egui::vec2(cos as f32, sin as f32)
            })
            .collect();
        let stroke = egui::Stroke::new(3.0, ui.visuals().strong_text_color());
        ui.painter().add(egui::Shape::line(points, stroke));
        ui.ctx().request_repaint_after(BUSY_FRAME);
    }
    response
}
