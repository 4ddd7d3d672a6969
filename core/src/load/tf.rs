//! A TF buffer (method.md section 13): the transforms of `/tf` and
//! `/tf_static` (and Foxglove `FrameTransform`s) as a tree of frames, each frame's transform to its parent
//! over time, so a frame's position can be expressed in any other frame of
//! the tree at any stamp, as ROS's `tf2` buffer does: static transforms hold
//! at every time, dynamic ones are interpolated between their two nearest
//! stamps (linear in translation, spherical in rotation) and held at their
//! ends outside the recorded span (`tf2` refuses to extrapolate; the loader
//! counts those stamps and says so).

use std::collections::BTreeMap;

use crate::rotation::{QuatXyzw, conj, mul};

const IDENTITY: QuatXyzw = [0.0, 0.0, 0.0, 1.0];

/// A frame's transform to its parent: `x_parent = rotation * x + translation`.
#[derive(Clone, Debug, PartialEq)]
struct Edge {
    parent: String,
    is_static: bool,
    /// `(stamp_ns, translation, rotation)`, sorted by stamp once finished.
    samples: Vec<(i64, [f64; 3], QuatXyzw)>,
}

/// The transforms seen, by child frame.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TfBuffer {
    edges: BTreeMap<String, Edge>,
    sorted: bool,
}

/// A frame name without ROS 1's leading slash.
pub fn frame_name(name: &str) -> &str {
    name.strip_prefix('/').unwrap_or(name)
}

impl TfBuffer {
    /// Adds one transform of `child` to `parent` at `stamp_ns`. A static
    /// transform replaces the frame's earlier ones; a child that changes
    /// parent keeps its latest parent.
    pub fn add(
        &mut self,
        parent: &str,
        child: &str,
        stamp_ns: i64,
        translation: [f64; 3],
        rotation: QuatXyzw,
        is_static: bool,
    ) {
        let (parent, child) = (frame_name(parent), frame_name(child));
        let rotation = normalised(rotation);
        let edge = self.edges.entry(child.to_owned()).or_insert_with(|| Edge {
            parent: parent.to_owned(),
            is_static,
            samples: Vec::new(),
        });
        if edge.parent != parent || is_static || edge.is_static {
            edge.parent = parent.to_owned();
            edge.samples.clear();
            edge.is_static = is_static;
        }
        edge.samples.push((stamp_ns, translation, rotation));
        self.sorted = false;
    }

    /// Whether the buffer holds any transform.
    pub fn is_empty(&self) -> bool {
        self.edges.is_empty()
    }

    fn sort(&mut self) {
        if !self.sorted {
            for e in self.edges.values_mut() {
                e.samples.sort_by_key(|s| s.0);
            }
            self.sorted = true;
        }
    }

    /// The origin of `frame` in `target` at `stamp_ns`, and whether a
    /// dynamic transform had to be held past its recorded span.
    pub fn origin_in(
        &mut self,
        target: &str,
        frame: &str,
        stamp_ns: i64,
    ) -> Result<([f64; 3], bool), String> {
        self.pose_in(target, frame, stamp_ns)
            .map(|(origin, _, held)| (origin, held))
    }

    /// The pose of `frame` in `target` at `stamp_ns` (its origin and its
    /// rotation `[x, y, z, w]`), and whether a dynamic transform had to be
    /// held past its recorded span.
    pub fn pose_in(
        &mut self,
        target: &str,
        frame: &str,
        stamp_ns: i64,
    ) -> Result<([f64; 3], QuatXyzw, bool), String> {
        self.sort();
        let (target, frame) = (frame_name(target), frame_name(frame));
        let (root_a, q_frame, origin, held_a) = self.to_root(frame, stamp_ns)?;
        let (root_b, q, t, held_b) = self.to_root(target, stamp_ns)?;
        if root_a != root_b {
            return Err(format!(
                "no transform chain joins {frame} (under {root_a}) and {target} (under {root_b})"
            ));
        }
        let d = [origin[0] - t[0], origin[1] - t[1], origin[2] - t[2]];
        let rotation = mul(conj(q), q_frame);
        Ok((rotate(conj(q), d), rotation, held_a || held_b))
    }

    /// `frame`'s transform to the root of its tree.
    fn to_root(
        &self,
        frame: &str,
        stamp_ns: i64,
    ) -> Result<(String, QuatXyzw, [f64; 3], bool), String> {
        let (mut q, mut t) = (IDENTITY, [0.0; 3]);
        let mut current = frame.to_owned();
        let mut held = false;
        for _ in 0..=self.edges.len() {
            let Some(edge) = self.edges.get(&current) else {
                return Ok((current, q, t, held));
            };
            let (te, qe, h) = edge.at(stamp_ns);
            held |= h;
            q = mul(qe, q);
            let r = rotate(qe, t);
            t = [r[0] + te[0], r[1] + te[1], r[2] + te[2]];
            current.clone_from(&edge.parent);
        }
        Err(format!("the TF tree has a loop through {frame}"))
    }
}

impl Edge {
    fn at(&self, stamp_ns: i64) -> ([f64; 3], QuatXyzw, bool) {
        let s = &self.samples;
        let (Some(first), Some(last)) = (s.first(), s.last()) else {
            return ([0.0; 3], IDENTITY, false);
        };
        if self.is_static {
            return (last.1, last.2, false);
        }
        if stamp_ns <= first.0 {
            return (first.1, first.2, stamp_ns < first.0);
        }
        if stamp_ns >= last.0 {
            return (last.1, last.2, stamp_ns > last.0);
        }
        let i = s.partition_point(|x| x.0 <= stamp_ns);
        let (a, b) = (&s[i - 1], &s[i]);
        if a.0 == stamp_ns {
            return (a.1, a.2, false);
        }
        let u = (stamp_ns - a.0) as f64 / (b.0 - a.0) as f64;
        let t = std::array::from_fn(|k| a.1[k] + u * (b.1[k] - a.1[k]));
        (t, slerp(a.2, b.2, u), false)
    }
}

fn normalised(q: QuatXyzw) -> QuatXyzw {
    let n = q.iter().map(|v| v * v).sum::<f64>().sqrt();
    if n > 0.0 && n.is_finite() {
        q.map(|v| v / n)
    } else {
        IDENTITY
    }
}

/// Rotates `v` by the unit quaternion `q`.
pub fn rotate(q: QuatXyzw, v: [f64; 3]) -> [f64; 3] {
    let p = mul(mul(q, [v[0], v[1], v[2], 0.0]), conj(q));
    [p[0], p[1], p[2]]
}

/// Spherical interpolation from `a` (u = 0) to `b` (u = 1), the short way.
fn slerp(a: QuatXyzw, mut b: QuatXyzw, u: f64) -> QuatXyzw {
    let mut dot: f64 = (0..4).map(|k| a[k] * b[k]).sum();
    if dot < 0.0 {
        b = b.map(|v| -v);
        dot = -dot;
    }
    if dot > 0.9995 {
        return normalised(std::array::from_fn(|k| a[k] + u * (b[k] - a[k])));
    }
    let theta = crate::portable::acos(dot.clamp(-1.0, 1.0));
    let (sa, sb) = (
        crate::portable::sin((1.0 - u) * theta),
        crate::portable::sin(u * theta),
    );
    let s = crate::portable::sin(theta);
    std::array::from_fn(|k| (sa * a[k] + sb * b[k]) / s)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn yaw(angle: f64) -> QuatXyzw {
        [0.0, 0.0, (angle / 2.0).sin(), (angle / 2.0).cos()]
    }

    fn close(a: [f64; 3], b: [f64; 3]) -> bool {
        (0..3).all(|k| (a[k] - b[k]).abs() < 1e-12)
    }

    #[test]
    fn a_chain_composes_through_a_static_rotated_base() {
        let mut tf = TfBuffer::default();
        // world -> base: 1 m along x, turned 90 degrees about z (static).
        tf.add(
            "world",
            "base",
            0,
            [1.0, 0.0, 0.0],
            yaw(std::f64::consts::FRAC_PI_2),
            true,
        );
        // base -> tracker: moves from (0.1, 0, 0) at t=0 to (0.3, 0, 0) at t=10.
        tf.add("base", "tracker", 0, [0.1, 0.0, 0.0], IDENTITY, false);
        tf.add("/base", "tracker", 10, [0.3, 0.0, 0.0], IDENTITY, false);
        let (p, held) = tf.origin_in("world", "tracker", 5).expect("chain");
        assert!(close(p, [1.0, 0.2, 0.0]), "{p:?}");
        assert!(!held);
        // The tracker's rotation in world is the base's turn.
        let (_, q, _) = tf.pose_in("world", "tracker", 5).expect("chain");
        let e = yaw(std::f64::consts::FRAC_PI_2);
        assert!((0..4).all(|k| (q[k] - e[k]).abs() < 1e-12), "{q:?}");
        // And world's rotation in the tracker is its inverse.
        let (_, q, _) = tf.pose_in("tracker", "world", 5).expect("chain");
        assert!(
            (q[2] + e[2]).abs() < 1e-12 && (q[3] - e[3]).abs() < 1e-12,
            "{q:?}"
        );
        // In base the tracker is its own translation; world's origin in
        // tracker is the inverse.
        let (p, _) = tf.origin_in("base", "tracker", 10).expect("chain");
        assert!(close(p, [0.3, 0.0, 0.0]));
        let (p, _) = tf.origin_in("tracker", "world", 0).expect("chain");
        assert!(close(p, [-0.1, 1.0, 0.0]), "{p:?}");
        // Past the end the last transform holds, and that is said.
        let (p, held) = tf.origin_in("world", "tracker", 20).expect("chain");
        assert!(close(p, [1.0, 0.3, 0.0]) && held);
        // A frame of another tree is an error naming both roots.
        tf.add("map", "other", 0, [0.0; 3], IDENTITY, false);
        let err = tf.origin_in("world", "other", 0).expect_err("two trees");
        assert!(
            err.contains("under map") && err.contains("under world"),
            "{err}"
        );
    }

    #[test]
    fn slerp_halves_a_turn() {
        let q = slerp(yaw(0.0), yaw(1.0), 0.5);
        let e = yaw(0.5);
        assert!((0..4).all(|k| (q[k] - e[k]).abs() < 1e-12));
    }
}
