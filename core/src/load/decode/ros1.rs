//! ROS 1 message layouts (MCAP message encoding `ros1`, schema encoding
//! `ros1msg`): little-endian, no alignment, no encapsulation header; strings
//! are a u32 length (no NUL) and the bytes, `time` is u32 seconds and u32
//! nanoseconds, `std_msgs/Header` is u32 seq, time stamp, string frame_id.
//!
//! Read: `geometry_msgs/PoseStamped`, `PoseWithCovarianceStamped`,
//! `PointStamped`, `TransformStamped` and `nav_msgs/Odometry` (one pose per
//! message), and `tf2_msgs/TFMessage` (also the identical `tf/tfMessage`;
//! one pose per transform, keyed by child frame). The `encode_*` functions are the
//! inverses, for fixtures and tests.

use std::borrow::Cow;

use crate::load::decode::ros2::StampedTransform;
use crate::load::decode::{MessageDecoder, PoseSample, SinglePose};

/// The `ros1msg` definitions of `std_msgs/Header`.
macro_rules! header_def {
    () => {
        "================================================================================
MSG: std_msgs/Header
uint32 seq
time stamp
string frame_id
"
    };
}

/// The `ros1msg` schema text of `geometry_msgs/PoseStamped`.
pub const POSE_STAMPED_SCHEMA: &str = concat!(
    "Header header
Pose pose
",
    header_def!(),
    "================================================================================
MSG: geometry_msgs/Pose
Point position
Quaternion orientation
================================================================================
MSG: geometry_msgs/Point
float64 x
float64 y
float64 z
================================================================================
MSG: geometry_msgs/Quaternion
float64 x
float64 y
float64 z
float64 w
"
);

/// The `ros1msg` schema text of `tf2_msgs/TFMessage`.
pub const TF_MESSAGE_SCHEMA: &str = concat!(
    "geometry_msgs/TransformStamped[] transforms
================================================================================
MSG: geometry_msgs/TransformStamped
Header header
string child_frame_id
Transform transform
",
    header_def!(),
    "================================================================================
MSG: geometry_msgs/Transform
Vector3 translation
Quaternion rotation
================================================================================
MSG: geometry_msgs/Vector3
float64 x
float64 y
float64 z
================================================================================
MSG: geometry_msgs/Quaternion
float64 x
float64 y
float64 z
float64 w
"
);

/// The decoder of a ROS 1 schema, by its MCAP schema name.
pub fn decoder(schema_name: &str) -> Option<Box<dyn MessageDecoder>> {
    match schema_name {
        "geometry_msgs/PoseStamped" => Some(Box::new(SinglePose(decode_pose_stamped))),
        "geometry_msgs/PoseWithCovarianceStamped" => {
            Some(Box::new(SinglePose(decode_pose_with_covariance_stamped)))
        }
        "geometry_msgs/PointStamped" => Some(Box::new(SinglePose(decode_point_stamped))),
        "geometry_msgs/TransformStamped" => Some(Box::new(TransformStampedDecoder)),
        "nav_msgs/Odometry" => Some(Box::new(SinglePose(decode_odometry))),
        "tf2_msgs/TFMessage" | "tf/tfMessage" => Some(Box::new(TfMessageDecoder)),
        _ => None,
    }
}

/// Reads primitives from one ROS 1 message, unaligned and little-endian.
struct Ros1Cursor<'a> {
    data: &'a [u8],
    pos: usize,
}

impl<'a> Ros1Cursor<'a> {
    fn new(data: &'a [u8]) -> Self {
        Self { data, pos: 0 }
    }

    fn take<const N: usize>(&mut self, what: &str) -> Result<[u8; N], String> {
        let bytes = self
            .data
            .get(self.pos..self.pos.saturating_add(N))
            .ok_or_else(|| format!("message ends before {what} (offset {})", self.pos))?;
        self.pos += N;
        let mut out = [0; N];
        out.copy_from_slice(bytes);
        Ok(out)
    }

    fn u32(&mut self, what: &str) -> Result<u32, String> {
        self.take::<4>(what).map(u32::from_le_bytes)
    }

    fn f64(&mut self, what: &str) -> Result<f64, String> {
        self.take::<8>(what).map(f64::from_le_bytes)
    }

    /// A string: a u32 length (no NUL counted or written), then the bytes.
    fn string(&mut self, what: &str) -> Result<&'a str, String> {
        let len = self.u32(what)? as usize;
        let bytes = self
            .data
            .get(self.pos..self.pos.saturating_add(len))
            .ok_or_else(|| format!("{what}: string length {len} runs past the message"))?;
        self.pos += len;
        std::str::from_utf8(bytes).map_err(|e| format!("{what}: not UTF-8: {e}"))
    }

    /// `std_msgs/Header`: seq, stamp (the result; `None` when zero), frame id.
    fn header(&mut self) -> Result<Option<i64>, String> {
        self.u32("header.seq")?;
        let secs = self.u32("header.stamp.secs")?;
        let nsecs = self.u32("header.stamp.nsecs")?;
        self.string("header.frame_id")?;
        Ok(if secs == 0 && nsecs == 0 {
            None
        } else {
            Some(i64::from(secs) * 1_000_000_000 + i64::from(nsecs))
        })
    }

    fn vec3(&mut self, names: [&str; 3]) -> Result<[f64; 3], String> {
        Ok([
            self.f64(names[0])?,
            self.f64(names[1])?,
            self.f64(names[2])?,
        ])
    }

    /// `geometry_msgs/Pose`: the position and the orientation.
    fn pose(&mut self) -> Result<([f64; 3], [f64; 4]), String> {
        let p = self.vec3(["pose.position.x", "pose.position.y", "pose.position.z"])?;
        let q = self.vec4([
            "pose.orientation.x",
            "pose.orientation.y",
            "pose.orientation.z",
            "pose.orientation.w",
        ])?;
        Ok((p, q))
    }

    /// `n` float64 fields read past.
    fn skip_f64s(&mut self, n: usize, what: &str) -> Result<(), String> {
        for _ in 0..n {
            self.f64(what)?;
        }
        Ok(())
    }

    /// Four float64 fields (a quaternion `[x, y, z, w]`).
    fn vec4(&mut self, names: [&str; 4]) -> Result<[f64; 4], String> {
        Ok([
            self.f64(names[0])?,
            self.f64(names[1])?,
            self.f64(names[2])?,
            self.f64(names[3])?,
        ])
    }

    /// One `geometry_msgs/TransformStamped`, keyed by its child frame.
    fn transform_stamped(&mut self) -> Result<PoseSample<'a>, String> {
        self.u32("header.seq")?;
        let secs = self.u32("header.stamp.secs")?;
        let nsecs = self.u32("header.stamp.nsecs")?;
        let parent = self.string("header.frame_id")?;
        let stamp_ns =
            (secs != 0 || nsecs != 0).then(|| i64::from(secs) * 1_000_000_000 + i64::from(nsecs));
        let child = self.string("child_frame_id")?;
        let position = self.vec3([
            "transform.translation.x",
            "transform.translation.y",
            "transform.translation.z",
        ])?;
        let rotation = self.vec4([
            "transform.rotation.x",
            "transform.rotation.y",
            "transform.rotation.z",
            "transform.rotation.w",
        ])?;
        Ok(PoseSample {
            key: Some(Cow::Borrowed(child)),
            stamp_ns,
            position,
            parent: Some(Cow::Borrowed(parent)),
            orientation: Some(rotation),
        })
    }
}

/// Decodes ROS 1 `geometry_msgs/PoseStamped`: header, then the pose
/// (position and orientation).
pub fn decode_pose_stamped(message: &[u8]) -> Result<PoseSample<'static>, String> {
    let mut r = Ros1Cursor::new(message);
    let stamp_ns = r.header()?;
    let (position, orientation) = r.pose()?;
    Ok(PoseSample::single(stamp_ns, position, Some(orientation)))
}

/// Decodes ROS 1 `geometry_msgs/PoseWithCovarianceStamped`: header, the
/// pose, then the 36 covariance entries (read past, but they must be there).
pub fn decode_pose_with_covariance_stamped(message: &[u8]) -> Result<PoseSample<'static>, String> {
    let mut r = Ros1Cursor::new(message);
    let stamp_ns = r.header()?;
    let (position, orientation) = r.pose()?;
    r.skip_f64s(36, "pose.covariance")?;
    Ok(PoseSample::single(stamp_ns, position, Some(orientation)))
}

/// Decodes ROS 1 `geometry_msgs/PointStamped`: header, then the point (no
/// orientation).
pub fn decode_point_stamped(message: &[u8]) -> Result<PoseSample<'static>, String> {
    let mut r = Ros1Cursor::new(message);
    let stamp_ns = r.header()?;
    let position = r.vec3(["point.x", "point.y", "point.z"])?;
    Ok(PoseSample::single(stamp_ns, position, None))
}

/// Decodes ROS 1 `nav_msgs/Odometry`: header, child frame id, the pose
/// with covariance (the sample), then the twist with covariance (read past).
pub fn decode_odometry(message: &[u8]) -> Result<PoseSample<'static>, String> {
    let mut r = Ros1Cursor::new(message);
    let stamp_ns = r.header()?;
    r.string("child_frame_id")?;
    let (position, orientation) = r.pose()?;
    r.skip_f64s(36, "pose.covariance")?;
    r.skip_f64s(6 + 36, "twist")?;
    Ok(PoseSample::single(stamp_ns, position, Some(orientation)))
}

/// The decoder of ROS 1 `geometry_msgs/TransformStamped` (one pose, keyed
/// by its child frame).
#[derive(Clone, Copy, Debug, Default)]
pub struct TransformStampedDecoder;

impl MessageDecoder for TransformStampedDecoder {
    fn decode(&mut self, data: &[u8], out: &mut dyn FnMut(PoseSample<'_>)) -> Result<(), String> {
        out(Ros1Cursor::new(data).transform_stamped()?);
        Ok(())
    }
}

/// Decodes ROS 1 `tf2_msgs/TFMessage`: a u32 count, then that many
/// `TransformStamped`, each handed to `out` with its own stamp and keyed by
/// its child frame. The whole message is checked before the first transform
/// is handed out, so a bad message gives no samples.
pub fn decode_tf_message(
    message: &[u8],
    out: &mut dyn FnMut(PoseSample<'_>),
) -> Result<(), String> {
    each_transform(message, &mut |_| {})?;
    each_transform(message, out)
}

/// Walks the transforms of a `TFMessage`.
fn each_transform(message: &[u8], out: &mut dyn FnMut(PoseSample<'_>)) -> Result<(), String> {
    let mut r = Ros1Cursor::new(message);
    let count = r.u32("transforms (array length)")?;
    for i in 0..count {
        out(r
            .transform_stamped()
            .map_err(|e| format!("transforms[{i}]: {e}"))?);
    }
    Ok(())
}

/// The decoder of ROS 1 `tf2_msgs/TFMessage` (one pose per transform).
#[derive(Clone, Copy, Debug, Default)]
pub struct TfMessageDecoder;

impl MessageDecoder for TfMessageDecoder {
    fn decode(&mut self, data: &[u8], out: &mut dyn FnMut(PoseSample<'_>)) -> Result<(), String> {
        decode_tf_message(data, out)
    }
}

// ---------------------------------------------------------------- encoders

/// Writes `std_msgs/Header` with seq 0; stamps outside `0..2^32` s are
/// clamped to that range.
fn write_header(buf: &mut Vec<u8>, stamp_ns: i64, frame_id: &str) {
    let secs = u32::try_from(stamp_ns.div_euclid(1_000_000_000).max(0)).unwrap_or(u32::MAX);
    let nsecs = stamp_ns.rem_euclid(1_000_000_000) as u32;
    buf.extend_from_slice(&0u32.to_le_bytes());
    buf.extend_from_slice(&secs.to_le_bytes());
    buf.extend_from_slice(&nsecs.to_le_bytes());
    write_string(buf, frame_id);
}

/// Writes a string: u32 length without NUL, then the bytes.
fn write_string(buf: &mut Vec<u8>, s: &str) {
    buf.extend_from_slice(&(s.len() as u32).to_le_bytes());
    buf.extend_from_slice(s.as_bytes());
}

/// Writes a position and an orientation `[x, y, z, w]`.
fn write_pose(buf: &mut Vec<u8>, position: [f64; 3], orientation: [f64; 4]) {
    for v in position.into_iter().chain(orientation) {
        buf.extend_from_slice(&v.to_le_bytes());
    }
}

/// Encodes ROS 1 `geometry_msgs/PoseStamped` with seq 0 and an identity
/// orientation.
pub fn encode_pose_stamped(stamp_ns: i64, frame_id: &str, position: [f64; 3]) -> Vec<u8> {
    encode_oriented_pose_stamped(stamp_ns, frame_id, position, [0.0, 0.0, 0.0, 1.0])
}

/// Encodes ROS 1 `geometry_msgs/PoseStamped` with seq 0 and an orientation
/// `[x, y, z, w]`.
pub fn encode_oriented_pose_stamped(
    stamp_ns: i64,
    frame_id: &str,
    position: [f64; 3],
    orientation: [f64; 4],
) -> Vec<u8> {
    let mut buf = Vec::with_capacity(72 + frame_id.len());
    write_header(&mut buf, stamp_ns, frame_id);
    write_pose(&mut buf, position, orientation);
    buf
}

/// Encodes ROS 1 `tf2_msgs/TFMessage` holding `transforms` in order (seq 0,
/// identity rotations).
pub fn encode_tf_message(transforms: &[StampedTransform<'_>]) -> Vec<u8> {
    let mut buf = Vec::new();
    buf.extend_from_slice(&(transforms.len() as u32).to_le_bytes());
    for t in transforms {
        write_header(&mut buf, t.stamp_ns, t.frame_id);
        write_string(&mut buf, t.child_frame_id);
        for v in t.translation.into_iter().chain(t.rotation) {
            buf.extend_from_slice(&v.to_le_bytes());
        }
    }
    buf
}
