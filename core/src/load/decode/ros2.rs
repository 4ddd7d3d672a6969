//! ROS 2 message layouts (CDR): each decoder reads only the fields dmpscope
//! needs, in wire order, and checks that the rest of the message is there.
//!
//! Read: `geometry_msgs/msg/PoseStamped`, `PoseWithCovarianceStamped`,
//! `PointStamped` (one pose per message), `TransformStamped` (one pose keyed
//! by its child frame) and `tf2_msgs/msg/TFMessage` (one pose per transform).
//! The `encode_*` functions are the inverses, for fixtures and tests.

use std::borrow::Cow;

use crate::load::decode::cdr::{CdrReader, CdrWriter};
use crate::load::decode::{MessageDecoder, PoseSample, SinglePose};

/// The `ros2msg` definitions every stamped message depends on (header, time).
macro_rules! header_defs {
    () => {
        "================================================================================
MSG: std_msgs/Header
builtin_interfaces/Time stamp
string frame_id
================================================================================
MSG: builtin_interfaces/Time
int32 sec
uint32 nanosec
"
    };
}

/// The `ros2msg` definitions of `geometry_msgs/Point` and `Quaternion`.
macro_rules! point_quaternion_defs {
    () => {
        "================================================================================
MSG: geometry_msgs/Point
float64 x
float64 y
float64 z
================================================================================
MSG: geometry_msgs/Quaternion
float64 x 0
float64 y 0
float64 z 0
float64 w 1
"
    };
}

/// The `ros2msg` definitions of `geometry_msgs/Transform` and its parts.
macro_rules! transform_defs {
    () => {
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
float64 x 0
float64 y 0
float64 z 0
float64 w 1
"
    };
}

/// The `ros2msg` schema text of `geometry_msgs/msg/PoseStamped`.
pub const POSE_STAMPED_SCHEMA: &str = concat!(
    "std_msgs/Header header
geometry_msgs/Pose pose
",
    header_defs!(),
    "================================================================================
MSG: geometry_msgs/Pose
Point position
Quaternion orientation
",
    point_quaternion_defs!()
);

/// The `ros2msg` schema text of `geometry_msgs/msg/PoseWithCovarianceStamped`.
pub const POSE_WITH_COVARIANCE_STAMPED_SCHEMA: &str = concat!(
    "std_msgs/Header header
geometry_msgs/PoseWithCovariance pose
",
    header_defs!(),
    "================================================================================
MSG: geometry_msgs/PoseWithCovariance
Pose pose
float64[36] covariance
================================================================================
MSG: geometry_msgs/Pose
Point position
Quaternion orientation
",
    point_quaternion_defs!()
);

/// The `ros2msg` schema text of `geometry_msgs/msg/PointStamped`.
pub const POINT_STAMPED_SCHEMA: &str = concat!(
    "std_msgs/Header header
geometry_msgs/Point point
",
    header_defs!(),
    "================================================================================
MSG: geometry_msgs/Point
float64 x
float64 y
float64 z
"
);

/// The `ros2msg` schema text of `geometry_msgs/msg/TransformStamped`.
pub const TRANSFORM_STAMPED_SCHEMA: &str = concat!(
    "std_msgs/Header header
string child_frame_id
geometry_msgs/Transform transform
",
    header_defs!(),
    transform_defs!()
);

/// The `ros2msg` schema text of `tf2_msgs/msg/TFMessage`.
pub const TF_MESSAGE_SCHEMA: &str = concat!(
    "geometry_msgs/TransformStamped[] transforms
================================================================================
MSG: geometry_msgs/TransformStamped
std_msgs/Header header
string child_frame_id
Transform transform
",
    header_defs!(),
    transform_defs!()
);

/// `builtin_interfaces/Time` to nanoseconds; `None` for the zero stamp,
/// which ROS uses for "no stamp".
pub(crate) fn stamp_ns(sec: i32, nanosec: u32) -> Option<i64> {
    if sec == 0 && nanosec == 0 {
        None
    } else {
        Some(i64::from(sec) * 1_000_000_000 + i64::from(nanosec))
    }
}

/// The decoder of a ROS 2 schema, by its MCAP schema name.
pub fn decoder(schema_name: &str) -> Option<Box<dyn MessageDecoder>> {
    match schema_name {
        "geometry_msgs/msg/PoseStamped" => Some(Box::new(SinglePose(decode_pose_stamped))),
        "geometry_msgs/msg/PoseWithCovarianceStamped" => {
            Some(Box::new(SinglePose(decode_pose_with_covariance_stamped)))
        }
        "geometry_msgs/msg/PointStamped" => Some(Box::new(SinglePose(decode_point_stamped))),
        "geometry_msgs/msg/TransformStamped" => Some(Box::new(TransformStampedDecoder)),
        "tf2_msgs/msg/TFMessage" => Some(Box::new(TfMessageDecoder)),
        "nav_msgs/msg/Odometry" => Some(Box::new(SinglePose(decode_odometry))),
        _ => None,
    }
}

// ------------------------------------------------------------ field groups

/// `std_msgs/Header`: the stamp (the frame id is read past).
fn header(r: &mut CdrReader<'_>) -> Result<Option<i64>, String> {
    let sec = r.i32("header.stamp.sec")?;
    let nanosec = r.u32("header.stamp.nanosec")?;
    r.string("header.frame_id")?;
    Ok(stamp_ns(sec, nanosec))
}

/// Three float64 fields, named `names`.
fn vec3(r: &mut CdrReader<'_>, names: [&str; 3]) -> Result<[f64; 3], String> {
    Ok([r.f64(names[0])?, r.f64(names[1])?, r.f64(names[2])?])
}

/// Four float64 fields (a quaternion `[x, y, z, w]`).
fn vec4(r: &mut CdrReader<'_>, names: [&str; 4]) -> Result<[f64; 4], String> {
    Ok([
        r.f64(names[0])?,
        r.f64(names[1])?,
        r.f64(names[2])?,
        r.f64(names[3])?,
    ])
}

/// The fields of `geometry_msgs/Pose`: the position and the orientation.
fn pose(r: &mut CdrReader<'_>) -> Result<([f64; 3], [f64; 4]), String> {
    let p = vec3(r, ["pose.position.x", "pose.position.y", "pose.position.z"])?;
    let q = vec4(
        r,
        [
            "pose.orientation.x",
            "pose.orientation.y",
            "pose.orientation.z",
            "pose.orientation.w",
        ],
    )?;
    Ok((p, q))
}

/// One `geometry_msgs/TransformStamped`, keyed by its child frame (borrowed
/// from the message).
fn transform_stamped<'a>(r: &mut CdrReader<'a>) -> Result<PoseSample<'a>, String> {
    let sec = r.i32("header.stamp.sec")?;
    let nanosec = r.u32("header.stamp.nanosec")?;
    let parent = r.string("header.frame_id")?;
    let child = r.string("child_frame_id")?;
    let position = vec3(
        r,
        [
            "transform.translation.x",
            "transform.translation.y",
            "transform.translation.z",
        ],
    )?;
    let rotation = vec4(
        r,
        [
            "transform.rotation.x",
            "transform.rotation.y",
            "transform.rotation.z",
            "transform.rotation.w",
        ],
    )?;
    Ok(PoseSample {
        key: Some(Cow::Borrowed(child)),
        stamp_ns: stamp_ns(sec, nanosec),
        position,
        parent: Some(Cow::Borrowed(parent)),
        orientation: Some(rotation),
    })
}

// ---------------------------------------------------------------- decoders

/// Decodes `geometry_msgs/msg/PoseStamped`: header (stamp, frame id), then the
/// pose (position and orientation).
pub fn decode_pose_stamped(message: &[u8]) -> Result<PoseSample<'static>, String> {
    let mut r = CdrReader::new(message)?;
    let stamp_ns = header(&mut r)?;
    let (position, orientation) = pose(&mut r)?;
    Ok(PoseSample::single(stamp_ns, position, Some(orientation)))
}

/// Decodes `geometry_msgs/msg/PoseWithCovarianceStamped`: header, the pose,
/// then the 36 covariance entries (read past, but they must be there).
pub fn decode_pose_with_covariance_stamped(message: &[u8]) -> Result<PoseSample<'static>, String> {
    let mut r = CdrReader::new(message)?;
    let stamp_ns = header(&mut r)?;
    let (position, orientation) = pose(&mut r)?;
    for _ in 0..36 {
        r.f64("pose.covariance")?;
    }
    Ok(PoseSample::single(stamp_ns, position, Some(orientation)))
}

/// Decodes `nav_msgs/msg/Odometry`: header, the child frame id, the pose
/// with its 36 covariance entries, then the twist with its own (read past,
/// but they must be there).
pub fn decode_odometry(message: &[u8]) -> Result<PoseSample<'static>, String> {
    let mut r = CdrReader::new(message)?;
    let stamp_ns = header(&mut r)?;
    r.string("child_frame_id")?;
    let (position, orientation) = pose(&mut r)?;
    for _ in 0..36 {
        r.f64("pose.covariance")?;
    }
    for _ in 0..(6 + 36) {
        r.f64("twist")?;
    }
    Ok(PoseSample::single(stamp_ns, position, Some(orientation)))
}

/// Decodes `geometry_msgs/msg/PointStamped`: header, then the point.
pub fn decode_point_stamped(message: &[u8]) -> Result<PoseSample<'static>, String> {
    let mut r = CdrReader::new(message)?;
    let stamp_ns = header(&mut r)?;
    let position = vec3(&mut r, ["point.x", "point.y", "point.z"])?;
    Ok(PoseSample::single(stamp_ns, position, None))
}

/// Decodes `geometry_msgs/msg/TransformStamped`: header, child frame id (the
/// sample's key), then the translation and the rotation.
pub fn decode_transform_stamped(message: &[u8]) -> Result<PoseSample<'_>, String> {
    let mut r = CdrReader::new(message)?;
    transform_stamped(&mut r)
}

/// Decodes `tf2_msgs/msg/TFMessage`: a u32 count, then that many
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
    let mut r = CdrReader::new(message)?;
    let count = r.u32("transforms (sequence length)")?;
    for i in 0..count {
        out(transform_stamped(&mut r).map_err(|e| format!("transforms[{i}]: {e}"))?);
    }
    Ok(())
}

/// The decoder of `geometry_msgs/msg/TransformStamped` (one pose per message,
/// keyed by child frame).
#[derive(Clone, Copy, Debug, Default)]
pub struct TransformStampedDecoder;

impl MessageDecoder for TransformStampedDecoder {
    fn decode(&mut self, data: &[u8], out: &mut dyn FnMut(PoseSample<'_>)) -> Result<(), String> {
        out(decode_transform_stamped(data)?);
        Ok(())
    }
}

/// The decoder of `tf2_msgs/msg/TFMessage` (one pose per transform).
#[derive(Clone, Copy, Debug, Default)]
pub struct TfMessageDecoder;

impl MessageDecoder for TfMessageDecoder {
    fn decode(&mut self, data: &[u8], out: &mut dyn FnMut(PoseSample<'_>)) -> Result<(), String> {
        decode_tf_message(data, out)
    }
}

// ---------------------------------------------------------------- encoders

/// One transform to encode as a `TransformStamped` (ROS 2 or ROS 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StampedTransform<'a> {
    /// The header stamp in nanoseconds.
    pub stamp_ns: i64,
    /// The parent frame (`header.frame_id`).
    pub frame_id: &'a str,
    /// The child frame, the key the decoders give.
    pub child_frame_id: &'a str,
    /// The translation in metres.
    pub translation: [f64; 3],
    /// The rotation `[x, y, z, w]`.
    pub rotation: [f64; 4],
}

/// Writes `std_msgs/Header`.
fn write_header(w: &mut CdrWriter, stamp_ns: i64, frame_id: &str) {
    w.i32(stamp_ns.div_euclid(1_000_000_000) as i32);
    w.u32(stamp_ns.rem_euclid(1_000_000_000) as u32);
    w.string(frame_id);
}

/// Writes a position and an orientation `[x, y, z, w]`.
fn write_pose(w: &mut CdrWriter, position: [f64; 3], orientation: [f64; 4]) {
    for v in position.into_iter().chain(orientation) {
        w.f64(v);
    }
}

/// Writes one `TransformStamped`.
fn write_transform(w: &mut CdrWriter, t: &StampedTransform<'_>) {
    write_header(w, t.stamp_ns, t.frame_id);
    w.string(t.child_frame_id);
    for v in t.translation.into_iter().chain(t.rotation) {
        w.f64(v);
    }
}

/// Encodes `geometry_msgs/msg/PoseStamped` with an identity orientation.
pub fn encode_pose_stamped(stamp_ns: i64, frame_id: &str, position: [f64; 3]) -> Vec<u8> {
    encode_oriented_pose_stamped(stamp_ns, frame_id, position, [0.0, 0.0, 0.0, 1.0])
}

/// Encodes `geometry_msgs/msg/PoseStamped` with an orientation `[x, y, z, w]`.
pub fn encode_oriented_pose_stamped(
    stamp_ns: i64,
    frame_id: &str,
    position: [f64; 3],
    orientation: [f64; 4],
) -> Vec<u8> {
    let mut w = CdrWriter::new();
    write_header(&mut w, stamp_ns, frame_id);
    write_pose(&mut w, position, orientation);
    w.finish()
}

/// Encodes `geometry_msgs/msg/PoseWithCovarianceStamped` with an identity
/// orientation and a diagonal covariance of 1e-6.
pub fn encode_pose_with_covariance_stamped(
    stamp_ns: i64,
    frame_id: &str,
    position: [f64; 3],
) -> Vec<u8> {
    let mut w = CdrWriter::new();
    write_header(&mut w, stamp_ns, frame_id);
    write_pose(&mut w, position, [0.0, 0.0, 0.0, 1.0]);
    for i in 0..36 {
        w.f64(if i % 7 == 0 { 1e-6 } else { 0.0 });
    }
    w.finish()
}

/// Encodes `nav_msgs/msg/Odometry` (child frame `base_link`, zero twist
/// and covariances).
pub fn encode_odometry(
    stamp_ns: i64,
    frame_id: &str,
    position: [f64; 3],
    orientation: [f64; 4],
) -> Vec<u8> {
    let mut w = CdrWriter::new();
    write_header(&mut w, stamp_ns, frame_id);
    w.string("base_link");
    write_pose(&mut w, position, orientation);
    for _ in 0..(36 + 6 + 36) {
        w.f64(0.0);
    }
    w.finish()
}

/// Encodes `geometry_msgs/msg/PointStamped`.
pub fn encode_point_stamped(stamp_ns: i64, frame_id: &str, position: [f64; 3]) -> Vec<u8> {
    let mut w = CdrWriter::new();
    write_header(&mut w, stamp_ns, frame_id);
    for v in position {
        w.f64(v);
    }
    w.finish()
}

/// Encodes `geometry_msgs/msg/TransformStamped` with an identity rotation.
pub fn encode_transform_stamped(t: &StampedTransform<'_>) -> Vec<u8> {
    let mut w = CdrWriter::new();
    write_transform(&mut w, t);
    w.finish()
}

/// Encodes `tf2_msgs/msg/TFMessage` holding `transforms` in order.
pub fn encode_tf_message(transforms: &[StampedTransform<'_>]) -> Vec<u8> {
    let mut w = CdrWriter::new();
    w.u32(transforms.len() as u32);
    for t in transforms {
        write_transform(&mut w, t);
    }
    w.finish()
}
