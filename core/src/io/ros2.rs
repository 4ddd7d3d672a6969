//! ROS 2 message layouts (CDR): each decoder reads only the fields dmpscope
//! needs, in wire order.

use super::cdr::{CdrReader, CdrWriter};
use super::{MessageDecoder, PoseSample, SinglePose};

/// The `ros2msg` schema text of `geometry_msgs/msg/PoseStamped`.
pub const POSE_STAMPED_SCHEMA: &str = "std_msgs/Header header
geometry_msgs/Pose pose
================================================================================
MSG: std_msgs/Header
builtin_interfaces/Time stamp
string frame_id
================================================================================
MSG: builtin_interfaces/Time
int32 sec
uint32 nanosec
================================================================================
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
float64 x 0
float64 y 0
float64 z 0
float64 w 1
";

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
        _ => None,
    }
}

/// Decodes `geometry_msgs/msg/PoseStamped`: header (stamp, frame id), then the
/// position of the pose (the orientation is not needed).
pub fn decode_pose_stamped(message: &[u8]) -> Result<PoseSample<'static>, String> {
    let mut r = CdrReader::new(message)?;
    let sec = r.i32("header.stamp.sec")?;
    let nanosec = r.u32("header.stamp.nanosec")?;
    r.string("header.frame_id")?;
    let x = r.f64("pose.position.x")?;
    let y = r.f64("pose.position.y")?;
    let z = r.f64("pose.position.z")?;
    for field in [
        "pose.orientation.x",
        "pose.orientation.y",
        "pose.orientation.z",
        "pose.orientation.w",
    ] {
        r.f64(field)?;
    }
    Ok(PoseSample {
        key: None,
        stamp_ns: stamp_ns(sec, nanosec),
        position: [x, y, z],
    })
}

/// Encodes `geometry_msgs/msg/PoseStamped` with an identity orientation.
pub fn encode_pose_stamped(stamp_ns: i64, frame_id: &str, position: [f64; 3]) -> Vec<u8> {
    let mut w = CdrWriter::new();
    w.i32(stamp_ns.div_euclid(1_000_000_000) as i32);
    w.u32(stamp_ns.rem_euclid(1_000_000_000) as u32);
    w.string(frame_id);
    for v in position {
        w.f64(v);
    }
    for v in [0.0, 0.0, 0.0, 1.0] {
        w.f64(v);
    }
    w.finish()
}
