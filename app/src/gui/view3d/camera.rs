//! The orbit camera of the 3D view: it looks at a target from a yaw, pitch
//! and distance, with Z up (the loaders turn Y-up recordings Z-up).
//! Left drag orbits, right or middle drag pans, the wheel zooms, a
//! double-click fits the scene again.

use glam::{Mat4, Vec2, Vec3};

/// Vertical field of view, radians.
const FOV_Y: f32 = 0.7;
/// Pitch is kept off the poles so "up" stays defined.
const MAX_PITCH: f32 = 1.55;

/// An axis-aligned box around what the view shows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    /// The lowest corner.
    pub min: Vec3,
    /// The highest corner.
    pub max: Vec3,
}

impl Bounds {
    /// The box around `points`; `None` when there are none (or none finite).
    pub fn around(points: impl IntoIterator<Item = Vec3>) -> Option<Self> {
        let mut out: Option<Self> = None;
        for p in points.into_iter().filter(|p| p.is_finite()) {
            out = Some(match out {
                None => Self { min: p, max: p },
                Some(b) => Self {
                    min: b.min.min(p),
                    max: b.max.max(p),
                },
            });
        }
        out
    }

    /// The centre.
    pub fn centre(&self) -> Vec3 {
        0.5 * (self.min + self.max)
    }

    /// Half the diagonal (at least 1 mm, so a point still has a size).
    pub fn radius(&self) -> f32 {
        (0.5 * (self.max - self.min).length()).max(1e-3)
    }
}

/// An orbit camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrbitCamera {
    /// The point looked at.
    pub target: Vec3,
    /// Rotation about Z, radians.
    pub yaw: f32,
    /// Elevation above the XY plane, radians.
    pub pitch: f32,
    /// Distance from the target.
    pub distance: f32,
}

impl OrbitCamera {
    /// A camera showing all of `bounds`, looking across `motion` (the
    /// main direction of the demos, so they are seen from the side) from
    /// slightly above.
    pub fn fit(bounds: &Bounds, motion: Vec3) -> Self {
        let yaw = if motion.truncate().length() > 1e-6 {
            motion.y.atan2(motion.x) - std::f32::consts::FRAC_PI_2
        } else {
            -2.2
        };
        Self {
            target: bounds.centre(),
            yaw,
            pitch: 0.45,
            distance: bounds.radius() / (0.5 * FOV_Y).tan() * 0.95,
        }
    }

    /// Where the eye is.
    pub fn eye(&self) -> Vec3 {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        self.target + self.distance * Vec3::new(cp * cy, cp * sy, sp)
    }

    /// World to clip space for a viewport of `aspect` = width / height, with
    /// depth in [0, 1] as wgpu wants.
    pub fn view_proj(&self, aspect: f32) -> Mat4 {
        let near = (self.distance * 0.01).max(1e-4);
        let far = self.distance * 100.0 + 1.0;
        // Right-handed, depth in [0, 1], Y up: glam's "directx" convention is wgpu's.
        let proj = glam::camera::rh::proj::directx::perspective(FOV_Y, aspect.max(1e-3), near, far);
        let view = glam::camera::rh::view::look_at_mat4(self.eye(), self.target, Vec3::Z);
        proj * view
    }

    /// The ray through normalised device coordinates `ndc` (x right, y up,
    /// -1..1): its origin on the near plane and its direction (unit).
    pub fn ray(&self, aspect: f32, ndc: Vec2) -> (Vec3, Vec3) {
        let inv = self.view_proj(aspect).inverse();
        let near = inv.project_point3(Vec3::new(ndc.x, ndc.y, 0.0));
        let far = inv.project_point3(Vec3::new(ndc.x, ndc.y, 1.0));
        (near, (far - near).normalize_or_zero())
    }

    /// Where the ray through `ndc` meets the horizontal plane at height
    /// `z`, if it does in front of the camera and not too far away
    /// (`within` of `near_to`): a grazing ray gives `None`, not a point at
    /// infinity.
    pub fn hit_level(
        &self,
        aspect: f32,
        ndc: Vec2,
        z: f32,
        near_to: Vec3,
        within: f32,
    ) -> Option<Vec3> {
        let (o, d) = self.ray(aspect, ndc);
        if d.z.abs() < 1e-4 {
            return None;
        }
        let t = (z - o.z) / d.z;
        let hit = o + t * d;
        (t > 0.0 && (hit - near_to).length() <= within).then_some(hit)
    }

    /// World units per screen point at `p`, in a view `height` points tall.
    pub fn units_per_point(&self, p: Vec3, height: f32) -> f32 {
        2.0 * (p - self.eye()).length() * (0.5 * FOV_Y).tan() / height.max(1.0)
    }

    /// Orbits by a drag of `delta` points.
    pub fn orbit(&mut self, delta: Vec2) {
        self.yaw -= delta.x * 0.01;
        self.pitch = (self.pitch + delta.y * 0.01).clamp(-MAX_PITCH, MAX_PITCH);
    }

    /// Pans by a drag of `delta` points in a view `height` points tall, so
    /// the target follows the pointer.
    pub fn pan(&mut self, delta: Vec2, height: f32) {
        let (right, up) = self.right_up();
        let per_point = 2.0 * self.distance * (0.5 * FOV_Y).tan() / height.max(1.0);
        self.target += (-delta.x * right + delta.y * up) * per_point;
    }

    /// The screen's right and up directions in the scene.
    pub fn right_up(&self) -> (Vec3, Vec3) {
        let forward = (self.target - self.eye()).normalize_or_zero();
        let right = forward.cross(Vec3::Z).normalize_or_zero();
        (right, right.cross(forward))
    }

    /// Zooms by a wheel movement of `scroll` points (positive: closer).
    pub fn zoom(&mut self, scroll: f32) {
        self.distance = (self.distance * (-scroll * 0.002).exp()).clamp(1e-3, 1e4);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec4;

    fn bounds() -> Bounds {
        Bounds::around([Vec3::new(0.0, 0.0, 0.0), Vec3::new(0.4, 0.2, 0.1)]).expect("points")
    }

    #[test]
    fn the_fitted_scene_projects_inside_the_view_with_wgpu_depth() {
        let b = bounds();
        let m = OrbitCamera::fit(&b, Vec3::X).view_proj(1.5);
        for x in [b.min.x, b.max.x] {
            for y in [b.min.y, b.max.y] {
                for z in [b.min.z, b.max.z] {
                    let c = m * Vec4::new(x, y, z, 1.0);
                    let ndc = c / c.w;
                    assert!(c.w > 0.0);
                    assert!(ndc.x.abs() < 1.0 && ndc.y.abs() < 1.0, "{ndc:?}");
                    assert!((0.0..=1.0).contains(&ndc.z), "{ndc:?}");
                }
            }
        }
    }

    #[test]
    fn the_target_is_at_the_centre_and_controls_move_the_camera() {
        let b = bounds();
        let mut cam = OrbitCamera::fit(&b, Vec3::new(1.0, 1.0, 0.2));
        let c = cam.view_proj(1.0) * cam.target.extend(1.0);
        assert!((c.x / c.w).abs() < 1e-5 && (c.y / c.w).abs() < 1e-5);
        let before = cam;
        cam.orbit(Vec2::new(10.0, 500.0));
        assert!(cam.pitch <= MAX_PITCH && cam.yaw != before.yaw);
        cam.zoom(100.0);
        assert!(cam.distance < before.distance);
        let target = cam.target;
        cam.pan(Vec2::new(20.0, 0.0), 400.0);
        assert!((cam.target - target).length() > 0.0);
        assert_eq!(cam.target.z, target.z, "a horizontal pan stays level");
    }

    #[test]
    fn a_pointer_ray_meets_the_level_of_a_point_at_that_point() {
        let b = bounds();
        let cam = OrbitCamera::fit(&b, Vec3::X);
        let aspect = 1.6;
        let p = Vec3::new(0.3, 0.15, 0.05);
        let c = cam.view_proj(aspect) * p.extend(1.0);
        let ndc = Vec2::new(c.x / c.w, c.y / c.w);
        let hit = cam.hit_level(aspect, ndc, p.z, p, 1.0).expect("hit");
        assert!((hit - p).length() < 1e-4, "{hit:?} vs {p:?}");
        // A ray looking up from below the plane's far side misses.
        assert!(
            cam.hit_level(aspect, Vec2::new(0.0, 1.0), 10.0, p, 1.0)
                .is_none()
        );
        assert!(cam.units_per_point(p, 400.0) > 0.0);
    }

    #[test]
    fn no_points_no_bounds() {
        assert!(Bounds::around([]).is_none());
        assert!(Bounds::around([Vec3::NAN]).is_none());
    }
}
