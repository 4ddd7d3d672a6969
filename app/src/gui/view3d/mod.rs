//! The 3D view: demos and their regenerations at the operating point, drawn
//! by a custom wgpu pipeline in an egui-wgpu paint callback ([`gpu`]) from
//! segments built each frame ([`scene`]) and an orbit camera ([`camera`]).
//! Without the wgpu renderer (a test harness without one) it says so.

mod camera;
mod compose;
mod gpu;
mod overlays;
mod scene;

use dmpscope_core::geom;
use std::sync::Arc;

use dmpscope_core::fit::orientation::OrientationRollout;
use dmpscope_core::{Model, Rollout};
use eframe::egui::{self, Align2, Color32, FontId, Sense};
use eframe::egui_wgpu;
use glam::Vec2;

use camera::OrbitCamera;
pub use scene::ScenePin;
use scene::{Frame, SceneTarget};

/// A run at a new target drawn over the demos, its start and goal draggable.
pub struct TargetOverlay<'a> {
    /// Absolute positions on the unit-time grid.
    pub path: &'a [geom::Vec3],
    /// A skill's ±1 SD per axis (empty for a demo).
    pub band: &'a [geom::Vec3],
    /// The start, absolute.
    pub start: geom::Vec3,
    /// The goal, absolute.
    pub goal: geom::Vec3,
    /// Its orientation on the grid, where the run has one.
    pub turns: Option<&'a [[f64; 4]]>,
    /// Its time cursor, unit time.
    pub t: f64,
}

/// What the view draws over the demos and their regenerations at the
/// operating point: the learned path, the run at a new target and the
/// pinned gain sets.
#[derive(Clone, Copy, Default)]
pub struct Layers<'a> {
    /// A path an RL agent learned: (demo index, positions in demo
    /// coordinates).
    pub learned: Option<(usize, &'a [geom::Vec3])>,
    /// The run at a new target, with its handles.
    pub overlay: Option<&'a TargetOverlay<'a>>,
    /// The pinned gain sets, with their names for the legend.
    pub pins: &'a [(String, ScenePin<'a>)],
}

/// A handle of the overlay.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Handle {
    /// The start.
    Start,
    /// The goal.
    Goal,
}

/// A handle dragged this frame: moved, or (the goal with Ctrl) turned.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum HandleMove {
    /// A handle moved to a new place.
    Moved {
        /// Which.
        handle: Handle,
        /// Where to, absolute metres.
        to: geom::Vec3,
    },
    /// The goal orientation turned by this rotation vector (radians about
    /// its axis, in the scene's frame): a drag across the screen turns it
    /// about the vertical, up and down about the screen's horizontal.
    Turned([f64; 3]),
}

/// Radians of turn per point of a Ctrl-drag on the goal.
const TURN_PER_POINT: f32 = 0.01;

/// How close (points) a press must be to a handle to grab it.
const GRAB_RADIUS: f32 = 14.0;

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
    /// The browser probe turned the drawing off (`testing` builds).
    #[cfg(feature = "testing")]
    probe_off: bool,
    /// The camera; `None` until fitted to a scene.
    camera: Option<OrbitCamera>,
    /// The scene frame the camera was fitted to.
    frame: Option<Frame>,
    /// Per model demo: drawn or not.
    pub visible: Vec<bool>,
    /// Draw the regenerated paths.
    pub show_regen: bool,
    /// Draw orientation triads along the paths (demos with orientation).
    pub show_triads: bool,
    /// The overlay's handle being dragged.
    dragging: Option<Handle>,
    /// Where the overlay's start and goal were drawn last frame (screen
    /// points), for tests and tools.
    handles_on_screen: Option<[egui::Pos2; 2]>,
    /// Per pinned set, the paths drawn last frame (tests and tools).
    pub pin_paths: Vec<usize>,
}

impl View3d {
    /// Turns the drawing off or on again for the browser probe, which
    /// measures what the view costs a frame.
    #[cfg(feature = "testing")]
    pub fn set_drawing(&mut self, on: bool) {
        self.probe_off = !on;
    }

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
            show_triads: true,
            dragging: None,
            handles_on_screen: None,
            pin_paths: Vec::new(),
            #[cfg(feature = "testing")]
            probe_off: false,
        }
    }

    /// Where the start and goal handles of the run at a new target were
    /// drawn last frame, screen points.
    pub fn handles_on_screen(&self) -> Option<[egui::Pos2; 2]> {
        self.handles_on_screen
    }

    /// Forgets the camera and visibility (a new model).
    pub fn reset(&mut self) {
        self.camera = None;
        self.frame = None;
        self.visible.clear();
    }

    /// The visibility toggles, one coloured button per demo, the
    /// regenerations and (with `oriented` demos) the orientation triads.
    pub fn toggles(&mut self, ui: &mut egui::Ui, n: usize, oriented: bool) {
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
            if oriented {
                ui.checkbox(&mut self.show_triads, "orientation")
                    .on_hover_text(
                        "triads along the demos and the DMP (x red, y green, z blue), the start \
                         and goal orientations, and the pose at the time cursor",
                    );
            }
        });
    }

    /// Draws the view in the space left in `ui`, for `model` with the demos'
    /// regenerations `regen` (same order), `selected` demo and time cursor
    /// `t` (unit time), a `learned` RL path (demo index, positions) and a
    /// run at a new target. Returns where a dragged handle of that run went.
    #[allow(clippy::too_many_arguments)]
    pub fn show(
        &mut self,
        ui: &mut egui::Ui,
        model: &Model,
        regen: (&[Rollout], &[Option<OrientationRollout>]),
        selected: usize,
        t: f64,
        layers: Layers<'_>,
    ) -> Option<HandleMove> {
        let Layers {
            learned,
            overlay,
            pins,
        } = layers;
        let (regen, turns) = regen;
        let size = ui.available_size().max(egui::vec2(120.0, 120.0));
        let (rect, response) = ui.allocate_exact_size(size, Sense::click_and_drag());
        let painter = ui.painter_at(rect);
        painter.rect_filled(rect, 4.0, Color32::from_rgb(22, 24, 30));
        #[cfg(feature = "testing")]
        if self.probe_off {
            return None;
        }
        let frame = Frame::of(model.demos())?;
        let (camera, moved) = self.steer_camera(ui, &response, rect, &frame, overlay);
        let drawn = Drawn {
            model,
            regen,
            turns,
            selected,
            t,
            learned,
            overlay,
            pins,
        };
        let ppp = ui.ctx().pixels_per_point();
        let view_proj = self.scene_ui(&painter, rect, ppp, &frame, &camera, &drawn);
        if !self.gpu {
            // The scene is built (tests read what it holds) but not drawn.
            painter.text(
                rect.center(),
                Align2::CENTER_CENTER,
                "The 3D view needs the wgpu renderer.",
                FontId::proportional(14.0),
                Color32::GRAY,
            );
            return moved;
        }
        view3d_labels_ui(&painter, rect, &frame, view_proj, &drawn);
        pins_legend_ui(&painter, rect, pins);
        moved
    }

    /// Fits the camera to `frame`, then lets the pointer move a handle or the camera.
    fn steer_camera(
        &mut self,
        ui: &egui::Ui,
        response: &egui::Response,
        rect: egui::Rect,
        frame: &Frame,
        overlay: Option<&TargetOverlay<'_>>,
    ) -> (OrbitCamera, Option<HandleMove>) {
        if self.frame != Some(*frame) || self.camera.is_none() {
            self.frame = Some(*frame);
            self.camera = Some(OrbitCamera::fit(&frame.bounds, frame.motion));
        }
        let mut camera = self
            .camera
            .unwrap_or_else(|| OrbitCamera::fit(&frame.bounds, frame.motion));
        let delta = Vec2::new(response.drag_delta().x, response.drag_delta().y);
        let moved = match overlay {
            Some(ov) => self.drag_handle(ui, response, rect, &camera, frame, ov),
            None => {
                self.dragging = None;
                None
            }
        };
        // Orbit (left drag), pan (right or middle drag), zoom (wheel),
        // fit again (double-click).
        if self.dragging.is_some() {
            // The drag moves a handle, not the camera.
        } else if response.dragged_by(egui::PointerButton::Primary) {
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
        (camera, moved)
    }

    /// The scene's segments in a paint callback; returns the view-projection.
    fn scene_ui(
        &mut self,
        painter: &egui::Painter,
        rect: egui::Rect,
        ppp: f32,
        frame: &Frame,
        camera: &OrbitCamera,
        drawn: &Drawn<'_>,
    ) -> glam::Mat4 {
        let aspect = rect.width() / rect.height().max(1.0);
        let n = drawn.model.demos().len();
        self.visible.resize(n, true);
        let colours: Vec<[u8; 3]> = (0..n).map(demo_colour).collect();
        let demo_turns: Vec<Option<&[[f64; 4]]>> = drawn
            .model
            .demos()
            .iter()
            .map(|d| d.orientation.as_ref().map(|o| o.q_raw.as_slice()))
            .collect();
        let regen_turns: Vec<Option<&[[f64; 4]]>> = if self.show_regen {
            drawn
                .turns
                .iter()
                .map(|t| t.as_ref().map(|t| t.q.as_slice()))
                .collect()
        } else {
            Vec::new()
        };
        let scene_pins: Vec<ScenePin<'_>> = drawn.pins.iter().map(|(_, p)| *p).collect();
        let input = scene::SceneInput {
            demos: drawn.model.demos(),
            regen: if self.show_regen { drawn.regen } else { &[] },
            visible: &self.visible,
            selected: drawn.selected,
            t: drawn.t,
            colours: &colours,
            pixels_per_point: ppp,
            learned: drawn.learned,
            generalised: drawn.overlay.map(|ov| SceneTarget {
                path: ov.path,
                band: ov.band,
                start: ov.start,
                goal: ov.goal,
                active: self.dragging.map(|h| match h {
                    Handle::Start => 0,
                    Handle::Goal => 1,
                }),
                turns: ov.turns,
                t: ov.t,
            }),
            demo_turns: &demo_turns,
            regen_turns: &regen_turns,
            triads: self.show_triads,
            pins: &scene_pins,
        };
        let built = compose::build(frame, &input);
        self.pin_paths = built.pin_paths;
        let segments = Arc::new(built.segments);
        let view_proj = camera.view_proj(aspect);
        let to_screen = |p: glam::Vec3| project(view_proj, rect, p);
        self.handles_on_screen = drawn.overlay.and_then(|ov| {
            let screen = |p: geom::Vec3| to_screen(frame.local(p));
            Some([screen(ov.start)?, screen(ov.goal)?])
        });
        let uniforms = gpu::Uniforms {
            view_proj: view_proj.to_cols_array_2d(),
            viewport: [rect.width() * ppp, rect.height() * ppp],
            pad: [0.0; 2],
        };
        if self.gpu {
            painter.add(egui_wgpu::Callback::new_paint_callback(
                rect,
                gpu::DrawLines { uniforms, segments },
            ));
        }
        view_proj
    }

    /// Grabs a handle of `ov` when a drag starts on it, and moves it while
    /// the drag lasts: on the horizontal plane through it, or up and down
    /// with Shift; with Ctrl (Cmd) the goal of a run with orientation turns
    /// instead (method.md section 12).
    fn drag_handle(
        &mut self,
        ui: &egui::Ui,
        response: &egui::Response,
        rect: egui::Rect,
        camera: &OrbitCamera,
        frame: &Frame,
        ov: &TargetOverlay<'_>,
    ) -> Option<HandleMove> {
        let aspect = rect.width() / rect.height().max(1.0);
        let view_proj = camera.view_proj(aspect);
        let to_screen = |p: glam::Vec3| project(view_proj, rect, p);
        if response.drag_started_by(egui::PointerButton::Primary)
            && let Some(press) = ui.input(|i| i.pointer.press_origin())
        {
            let distance = |p: geom::Vec3| {
                to_screen(frame.local(p)).map_or(f32::INFINITY, |s| s.distance(press))
            };
            let (ds, dg) = (distance(ov.start), distance(ov.goal));
            self.dragging = if dg <= GRAB_RADIUS && dg <= ds {
                Some(Handle::Goal)
            } else if ds <= GRAB_RADIUS {
                Some(Handle::Start)
            } else {
                None
            };
        }
        let handle = self.dragging?;
        if !response.dragged_by(egui::PointerButton::Primary) {
            self.dragging = None;
            return None;
        }
        if handle == Handle::Goal && ov.turns.is_some() && ui.input(|i| i.modifiers.command) {
            let d = response.drag_delta() * TURN_PER_POINT;
            let (right, _) = camera.right_up();
            let v = glam::Vec3::Z * d.x + right * d.y;
            return (v.length() > 0.0)
                .then(|| HandleMove::Turned([f64::from(v.x), f64::from(v.y), f64::from(v.z)]));
        }
        let current = match handle {
            Handle::Start => ov.start,
            Handle::Goal => ov.goal,
        };
        let p = frame.local(current);
        let new_local = if ui.input(|i| i.modifiers.shift) {
            let dz = -response.drag_delta().y * camera.units_per_point(p, rect.height());
            Some(p + glam::Vec3::Z * dz)
        } else {
            let pointer = response.interact_pointer_pos()?;
            let rel = (pointer - rect.center()) / (rect.size() * 0.5);
            let reach = 10.0 * frame.bounds.radius();
            camera.hit_level(aspect, Vec2::new(rel.x, -rel.y), p.z, p, reach)
        }?;
        let to = geom::Vec3::from_fn(|a, _| frame.origin[a] + f64::from(new_local[a]));
        Some(HandleMove::Moved { handle, to })
    }
}

/// What [`View3d::show`] draws besides the scene's frame: the model, the
/// regenerations, the selection, the learned path and the overlay.
struct Drawn<'a> {
    model: &'a Model,
    regen: &'a [Rollout],
    turns: &'a [Option<OrientationRollout>],
    selected: usize,
    t: f64,
    learned: Option<(usize, &'a [geom::Vec3])>,
    overlay: Option<&'a TargetOverlay<'a>>,
    pins: &'a [(String, ScenePin<'a>)],
}

/// The pinned sets' names in their colours, top right.
fn pins_legend_ui(painter: &egui::Painter, rect: egui::Rect, pins: &[(String, ScenePin<'_>)]) {
    for (k, (name, pin)) in pins.iter().enumerate() {
        let [r, g, b] = pin.colour;
        let y = rect.top() + 8.0 + 15.0 * k as f32;
        let right = rect.right() - 8.0;
        painter.line_segment(
            [
                egui::pos2(right - 18.0, y + 6.0),
                egui::pos2(right, y + 6.0),
            ],
            egui::Stroke::new(2.0, Color32::from_rgb(r, g, b)),
        );
        painter.text(
            egui::pos2(right - 24.0, y),
            Align2::RIGHT_TOP,
            name,
            FontId::proportional(11.0),
            Color32::from_rgb(r, g, b),
        );
    }
}

/// The axis names and the hints over the picture.
fn view3d_labels_ui(
    painter: &egui::Painter,
    rect: egui::Rect,
    frame: &Frame,
    view_proj: glam::Mat4,
    drawn: &Drawn<'_>,
) {
    let to_screen = |p: glam::Vec3| project(view_proj, rect, p);
    // Axis names and the grid step, as text over the picture.
    let step = frame.grid_step();
    let o = frame.axes_origin();
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
            "solid: demo · dashed: DMP · gold: RL{}{} · grid {:.0} mm",
            if drawn.learned.is_some() {
                ""
            } else {
                " (none yet)"
            },
            if drawn.overlay.is_some() {
                " · white: new target (drag start/goal, Shift: up, Ctrl: turn the goal)"
            } else {
                ""
            },
            step * 1000.0
        ),
    );
    hint(
        rect.left_bottom() + egui::vec2(6.0, -6.0),
        Align2::LEFT_BOTTOM,
        "drag: orbit · right-drag: pan · wheel: zoom · double-click: reset".to_owned(),
    );
}

/// Where scene point `p` lands in `rect` under `view_proj` (screen points);
/// `None` behind the camera.
fn project(view_proj: glam::Mat4, rect: egui::Rect, p: glam::Vec3) -> Option<egui::Pos2> {
    let c = view_proj * p.extend(1.0);
    (c.w > 1e-6).then(|| {
        let ndc = c.truncate() / c.w;
        rect.center() + egui::vec2(ndc.x, -ndc.y) * (rect.size() * 0.5)
    })
}
