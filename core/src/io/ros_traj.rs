//! ROS 2 trajectories of a generalised path, in CDR: `nav_msgs/msg/Path`
//! (what Foxglove's 3D panel draws) and
//! `trajectory_msgs/msg/MultiDOFJointTrajectory` (positions, velocities,
//! accelerations and `time_from_start`: what a ROS 2 node replays). One
//! message each per path, stamped at the path's start. The decoders are the
//! inverses, for tests and for tools that read exports back.

use super::cdr::{CdrReader, CdrWriter};

/// MCAP schema name of the path message.
pub const PATH_NAME: &str = "nav_msgs/msg/Path";
/// MCAP schema name of the trajectory message.
pub const MULTI_DOF_NAME: &str = "trajectory_msgs/msg/MultiDOFJointTrajectory";

const SEP: &str =
    "================================================================================\n";

/// The `ros2msg` schema text of `nav_msgs/msg/Path`.
pub fn path_schema() -> String {
    [
        "std_msgs/Header header\ngeometry_msgs/PoseStamped[] poses\n",
        SEP,
        "MSG: std_msgs/Header\nbuiltin_interfaces/Time stamp\nstring frame_id\n",
        SEP,
        "MSG: builtin_interfaces/Time\nint32 sec\nuint32 nanosec\n",
        SEP,
        "MSG: geometry_msgs/PoseStamped\nstd_msgs/Header header\nPose pose\n",
        SEP,
        "MSG: geometry_msgs/Pose\nPoint position\nQuaternion orientation\n",
        SEP,
        "MSG: geometry_msgs/Point\nfloat64 x\nfloat64 y\nfloat64 z\n",
        SEP,
        "MSG: geometry_msgs/Quaternion\nfloat64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n",
    ]
    .concat()
}

/// The `ros2msg` schema text of `trajectory_msgs/msg/MultiDOFJointTrajectory`.
pub fn multi_dof_schema() -> String {
    [
        "std_msgs/Header header\nstring[] joint_names\nMultiDOFJointTrajectoryPoint[] points\n",
        SEP,
        "MSG: std_msgs/Header\nbuiltin_interfaces/Time stamp\nstring frame_id\n",
        SEP,
        "MSG: builtin_interfaces/Time\nint32 sec\nuint32 nanosec\n",
        SEP,
        "MSG: trajectory_msgs/MultiDOFJointTrajectoryPoint\n\
         geometry_msgs/Transform[] transforms\n\
         geometry_msgs/Twist[] velocities\n\
         geometry_msgs/Twist[] accelerations\n\
         builtin_interfaces/Duration time_from_start\n",
        SEP,
        "MSG: geometry_msgs/Transform\nVector3 translation\nQuaternion rotation\n",
        SEP,
        "MSG: geometry_msgs/Vector3\nfloat64 x\nfloat64 y\nfloat64 z\n",
        SEP,
        "MSG: geometry_msgs/Quaternion\nfloat64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n",
        SEP,
        "MSG: geometry_msgs/Twist\nVector3 linear\nVector3 angular\n",
        SEP,
        "MSG: builtin_interfaces/Duration\nint32 sec\nuint32 nanosec\n",
    ]
    .concat()
}

/// A path in real time: what both messages carry.
#[derive(Clone, Debug, PartialEq)]
pub struct TimedPath {
    /// Frame of the positions.
    pub frame_id: String,
    /// The joint (end effector) name in the trajectory message.
    pub joint: String,
    /// Stamp of the first point, nanoseconds.
    pub stamp_ns: i64,
    /// Seconds from the start of each point.
    pub t: Vec<f64>,
    /// Positions, metres.
    pub y: Vec<[f64; 3]>,
    /// Velocities, m/s.
    pub v: Vec<[f64; 3]>,
    /// Accelerations, m/s^2.
    pub a: Vec<[f64; 3]>,
}

/// Seconds and nanoseconds of a stamp, saturated together to what an
/// `int32` of seconds holds.
fn split_ns(ns: i64) -> (i32, u32) {
    let sec = ns.div_euclid(1_000_000_000);
    let nanosec = ns.rem_euclid(1_000_000_000) as u32;
    match i32::try_from(sec) {
        Ok(sec) => (sec, nanosec),
        Err(_) if sec > 0 => (i32::MAX, 999_999_999),
        Err(_) => (i32::MIN, 0),
    }
}

fn seconds_ns(t: f64) -> i64 {
    (t * 1e9).round() as i64
}

fn header(w: &mut CdrWriter, stamp_ns: i64, frame_id: &str) {
    let (sec, nanosec) = split_ns(stamp_ns);
    w.i32(sec);
    w.u32(nanosec);
    w.string(frame_id);
}

fn vector(w: &mut CdrWriter, v: [f64; 3]) {
    for c in v {
        w.f64(c);
    }
}

fn identity_quaternion(w: &mut CdrWriter) {
    vector(w, [0.0; 3]);
    w.f64(1.0);
}

/// `nav_msgs/msg/Path`: each pose stamped at its time, identity orientation.
pub fn encode_path(path: &TimedPath) -> Vec<u8> {
    let mut w = CdrWriter::new();
    header(&mut w, path.stamp_ns, &path.frame_id);
    w.u32(path.y.len() as u32);
    for (t, y) in path.t.iter().zip(&path.y) {
        header(&mut w, path.stamp_ns + seconds_ns(*t), &path.frame_id);
        vector(&mut w, *y);
        identity_quaternion(&mut w);
    }
    w.finish()
}

/// `trajectory_msgs/msg/MultiDOFJointTrajectory`: one joint, a point per
/// sample with its translation, linear velocity and acceleration (angular
/// parts zero) and `time_from_start`.
pub fn encode_multi_dof(path: &TimedPath) -> Vec<u8> {
    let mut w = CdrWriter::new();
    header(&mut w, path.stamp_ns, &path.frame_id);
    w.u32(1);
    w.string(&path.joint);
    w.u32(path.y.len() as u32);
    for k in 0..path.y.len() {
        w.u32(1);
        vector(&mut w, path.y[k]);
        identity_quaternion(&mut w);
        w.u32(1);
        vector(&mut w, path.v[k]);
        vector(&mut w, [0.0; 3]);
        w.u32(1);
        vector(&mut w, path.a[k]);
        vector(&mut w, [0.0; 3]);
        let (sec, nanosec) = split_ns(seconds_ns(path.t[k]));
        w.i32(sec);
        w.u32(nanosec);
    }
    w.finish()
}

fn read_header(r: &mut CdrReader<'_>) -> Result<(i64, String), String> {
    let sec = r.i32("header.stamp.sec")?;
    let nanosec = r.u32("header.stamp.nanosec")?;
    let frame = r.string("header.frame_id")?.to_owned();
    Ok((i64::from(sec) * 1_000_000_000 + i64::from(nanosec), frame))
}

fn read_vector(r: &mut CdrReader<'_>, what: &str) -> Result<[f64; 3], String> {
    Ok([r.f64(what)?, r.f64(what)?, r.f64(what)?])
}

/// Reads a length that must fit in what is left of the message.
fn read_len(r: &mut CdrReader<'_>, what: &str, left: usize) -> Result<usize, String> {
    let n = r.u32(what)? as usize;
    if n > left {
        return Err(format!("{what}: {n} entries cannot fit in the message"));
    }
    Ok(n)
}

/// A decoded `nav_msgs/msg/Path`: its stamp, frame and
/// `(stamp_ns, position)` per pose.
pub type DecodedPath = (i64, String, Vec<(i64, [f64; 3])>);

/// Decodes [`encode_path`].
pub fn decode_path(message: &[u8]) -> Result<DecodedPath, String> {
    let mut r = CdrReader::new(message)?;
    let (stamp, frame) = read_header(&mut r)?;
    let n = read_len(&mut r, "poses", message.len())?;
    let mut poses = Vec::with_capacity(n);
    for _ in 0..n {
        let (s, _) = read_header(&mut r)?;
        let p = read_vector(&mut r, "pose.position")?;
        let _q = [r.f64("q")?, r.f64("q")?, r.f64("q")?, r.f64("q")?];
        poses.push((s, p));
    }
    Ok((stamp, frame, poses))
}

/// Decodes [`encode_multi_dof`] into a [`TimedPath`] (one joint).
pub fn decode_multi_dof(message: &[u8]) -> Result<TimedPath, String> {
    let mut r = CdrReader::new(message)?;
    let (stamp_ns, frame_id) = read_header(&mut r)?;
    let joints = read_len(&mut r, "joint_names", message.len())?;
    let mut names = Vec::with_capacity(joints);
    for _ in 0..joints {
        names.push(r.string("joint_names")?.to_owned());
    }
    if joints != 1 {
        return Err(format!("expected one joint, found {joints}"));
    }
    let n = read_len(&mut r, "points", message.len())?;
    let mut out = TimedPath {
        frame_id,
        joint: names.remove(0),
        stamp_ns,
        t: Vec::with_capacity(n),
        y: Vec::with_capacity(n),
        v: Vec::with_capacity(n),
        a: Vec::with_capacity(n),
    };
    for _ in 0..n {
        let one = |what: &str, r: &mut CdrReader<'_>| -> Result<(), String> {
            let count = r.u32(what)?;
            if count != 1 {
                return Err(format!("{what}: expected one entry, found {count}"));
            }
            Ok(())
        };
        one("transforms", &mut r)?;
        out.y.push(read_vector(&mut r, "translation")?);
        let _q = [r.f64("q")?, r.f64("q")?, r.f64("q")?, r.f64("q")?];
        one("velocities", &mut r)?;
        out.v.push(read_vector(&mut r, "velocity.linear")?);
        read_vector(&mut r, "velocity.angular")?;
        one("accelerations", &mut r)?;
        out.a.push(read_vector(&mut r, "acceleration.linear")?);
        read_vector(&mut r, "acceleration.angular")?;
        let sec = r.i32("time_from_start.sec")?;
        let nanosec = r.u32("time_from_start.nanosec")?;
        out.t
            .push((i64::from(sec) * 1_000_000_000 + i64::from(nanosec)) as f64 * 1e-9);
    }
    Ok(out)
}
