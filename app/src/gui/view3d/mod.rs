//! The 3D view: demos and their regenerations at the operating point, drawn
//! by a custom wgpu pipeline in an egui-wgpu paint callback ([`gpu`]) from
//! segments built each frame ([`scene`]) and an orbit camera ([`camera`]).
//! Without the wgpu renderer (a test harness without one) it says so.

mod camera;
mod gpu;
mod scene;

use std::sync::Arc;

use dmpscope_core::{Model, Rollout};
use eframe::egui::{self, Align2, Color32, FontId, Sense};
use eframe::egui_wgpu;
use glam::Vec2;

use camera::OrbitCamera;
use scene::Frame;

/// The hue of demo `i` (Tableau 10, repeating), sRGB.
pub fn demo_colour(i: usize) -> [u8; 3] {
    let c = colorous::TABLEAU10[i % colorous::TABLEAU10.len()];
    [c.r, c.g, c.b]
}

/// The 3D view's state: camera, per-demo visibility, whether the
/// regenerations are drawn.
pub struct View3d {
    /// Whether the wgpu pipeline is installed.
    gpu: bool,
    /// The camera; `None` until fitted to a scene.
    camera: Option<OrbitCamera>,
    /// The scene frame the camera was fitted to.
    frame: Option<Frame>,
    /// Per model demo: drawn or not.
    pub visible: Vec<bool>,
    /// Draw the regenerated paths.
    pub show_regen: bool,
}

impl View3d {
    /// A view drawing with the pipeline in `render_state`, if any.
    pub fn new(render_state: Option<&egui_wgpu::RenderState>) -> Self {
        if let Some(rs) = render_state {
            gpu::install(rs);
        }
        Self {
            gpu: render_state.is_some(),
            camera: None,
            frame: None,
            visible: Vec::new(),
            show_regen: true,
        }
    }

    /// Forgets the camera and visibility (a new model).
    pub fn reset(&mut self) {
        self.camera = None;
        self.frame = None;
        self.visible.clear();
    }

    /// The visibility toggles, one coloured button per demo.
    pub fn toggles(&mut self, ui: &mut egui::Ui, n: usize) {
        self.visible.resize(n, true);
        ui.horizontal_wrapped(|ui| {
            ui.label("show");
            for (i, v) in self.visible.iter_mut().enumerate() {
                let [r, g, b] = demo_colour(i);
                let colour = Color32::from_rgb(r, g, b);
                let text = egui::RichText::new(format!("{}", i + 1)).color(if *v {
                    Color32::BLACK
                } else {
                    colour
                });
                let button = egui::Button::new(text)
                    .fill(if *v { colour } else { Color32::TRANSPARENT })
                    .stroke(egui::Stroke::new(1.0, colour));
                if ui
                    .add(button)
                    .on_hover_text(format!("demo {}: show or hide", i + 1))
                    .clicked()
                {
                    *v = !*v;
                }
            }
            ui.checkbox(&mut self.show_regen, "regenerated");
        });
    }

    /// Draws the view in the space left in `ui`, for `model` with the demos'
    /// regenerations `regen` (same order), `selected` demo and time cursor
    /// `t` (unit time) and a `learned` RL path (demo index, positions).
    pub fn show(
        &mut self,
        ui: &mut egui::Ui,
        model: &Model,
        regen: &[Rollout],
        selected: usize,
        t: f64,
        learned: Option<(usize, &[[f64; 3]])>,
    ) {
        let size = ui.available_size().max(egui::vec2(120.0, 120.0));
        let (rect, response) = ui.allocate_exact_size(size, Sense::click_and_drag());
        let painter = ui.painter_at(rect);
        painter.rect_filled(rect, 4.0, Color32::from_rgb(22, 24, 30));
        if !self.gpu {
            painter.text(
                rect.center(),
                Align2::CENTER_CENTER,
                "The 3D view needs the wgpu renderer.",
                FontId::proportional(14.0),
                Color32::GRAY,
            );
            return;
        }
        let Some(frame) = Frame::of(model.demos()) else {
            return;
        };
        if self.frame != Some(frame) || self.camera.is_none() {
            self.frame = Some(frame);
            self.camera = Some(OrbitCamera::fit(&frame.bounds, frame.motion));
        }
        let mut camera = self
            .camera
            .unwrap_or_else(|| OrbitCamera::fit(&frame.bounds, frame.motion));
        // Orbit (left drag), pan (right or middle drag), zoom (wheel),
        // fit again (double-click).
        let delta = Vec2::new(response.drag_delta().x, response.drag_delta().y);
        if response.dragged_by(egui::PointerButton::Primary) {
            camera.orbit(delta);
        } else if response.dragged_by(egui::PointerButton::Secondary)
            || response.dragged_by(egui::PointerButton::Middle)
        {
            camera.pan(delta, rect.height());
        }
        if response.hovered() {
            let scroll = ui.input(|i| i.smooth_scroll_delta.y);
            if scroll != 0.0 {
                camera.zoom(scroll);
            }
        }
        if response.double_clicked() {
            camera = OrbitCamera::fit(&frame.bounds, frame.motion);
        }
        self.camera = Some(camera);

        let ppp = ui.ctx().pixels_per_point();
        let n = model.demos().len();
        self.visible.resize(n, true);
        let colours: Vec<[u8; 3]> = (0..n).map(demo_colour).collect();
        let input = scene::SceneInput {
            demos: model.demos(),
            regen: if self.show_regen { regen } else { &[] },
            visible: &self.visible,
            selected,
            t,
            colours: &colours,
            pixels_per_point: ppp,
            learned,
        };
        let segments = Arc::new(scene::build(&frame, &input));
        let aspect = rect.width() / rect.height().max(1.0);
        let view_proj = camera.view_proj(aspect);
        let uniforms = gpu::Uniforms {
            view_proj: view_proj.to_cols_array_2d(),
            viewport: [rect.width() * ppp, rect.height() * ppp],
            pad: [0.0; 2],
        };
        painter.add(egui_wgpu::Callback::new_paint_callback(
            rect,
            gpu::DrawLines { uniforms, segments },
        ));

        // Axis names and the grid step, as text over the picture.
        let step = frame.grid_step();
        let o = frame.axes_origin();
        let to_screen = |p: glam::Vec3| {
            let c = view_proj * p.extend(1.0);
            (c.w > 1e-6).then(|| {
                let ndc = c.truncate() / c.w;
                rect.center() + egui::vec2(ndc.x, -ndc.y) * (rect.size() * 0.5)
            })
        };
        for (axis, name) in [
            (glam::Vec3::X, "x"),
            (glam::Vec3::Y, "y"),
            (glam::Vec3::Z, "z"),
        ] {
            if let Some(pos) = to_screen(o + axis * step * 1.25) {
                painter.text(
                    pos,
                    Align2::CENTER_CENTER,
                    name,
                    FontId::monospace(12.0),
                    Color32::LIGHT_GRAY,
                );
            }
        }
        let hint = |pos, align, text: String| {
            painter.text(pos, align, text, FontId::proportional(11.0), Color32::GRAY);
        };
        hint(
            rect.left_top() + egui::vec2(6.0, 6.0),
            Align2::LEFT_TOP,
            format!(
                "solid: demo · dashed: DMP · gold: RL{} · grid {:.0} mm",
                if learned.is_some() { "" } else { " (none yet)" },
                step * 1000.0
            ),
        );
        hint(
            rect.left_bottom() + egui::vec2(6.0, -6.0),
            Align2::LEFT_BOTTOM,
            "drag: orbit · right-drag: pan · wheel: zoom · double-click: reset".to_owned(),
        );
    }
}
