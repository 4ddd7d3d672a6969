//! ROS 2 trajectories of a generalised path, in CDR: `nav_msgs/msg/Path`
//! (what Foxglove's 3D panel draws) and
//! `trajectory_msgs/msg/MultiDOFJointTrajectory` (positions, velocities,
//! accelerations and `time_from_start`: what a ROS 2 node replays). One
//! message each per path, stamped at the path's start. The decoders are the
//! inverses, for tests and for tools that read exports back.

use crate::load::decode::cdr::{CdrReader, CdrWriter};

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
    /// The orientation along the path (method.md section 12), where the
    /// DMP has one; else the messages carry the identity and no turn.
    pub orientation: Option<TimedOrientation>,
}

/// The orientation along a [`TimedPath`], one entry per point.
#[derive(Clone, Debug, PartialEq)]
pub struct TimedOrientation {
    /// Unit quaternions `[x, y, z, w]`.
    pub q: Vec<[f64; 4]>,
    /// Angular velocities, rad/s (space frame).
    pub w: Vec<[f64; 3]>,
    /// Angular accelerations, rad/s^2.
    pub alpha: Vec<[f64; 3]>,
}

impl TimedPath {
    /// Point `k`'s orientation, angular velocity and acceleration: the
    /// identity and zeros without an orientation.
    fn turn_at(&self, k: usize) -> ([f64; 4], [f64; 3], [f64; 3]) {
        match &self.orientation {
            Some(o) => (
                o.q.get(k).copied().unwrap_or(IDENTITY),
                o.w.get(k).copied().unwrap_or([0.0; 3]),
                o.alpha.get(k).copied().unwrap_or([0.0; 3]),
            ),
            None => (IDENTITY, [0.0; 3], [0.0; 3]),
        }
    }
}

const IDENTITY: [f64; 4] = [0.0, 0.0, 0.0, 1.0];

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

fn quaternion(w: &mut CdrWriter, q: [f64; 4]) {
    for c in q {
        w.f64(c);
    }
}

/// `nav_msgs/msg/Path`: each pose stamped at its time, with its
/// orientation (the identity where the path has none).
pub fn encode_path(path: &TimedPath) -> Vec<u8> {
    let mut w = CdrWriter::new();
    header(&mut w, path.stamp_ns, &path.frame_id);
    w.u32(path.y.len() as u32);
    for (k, (t, y)) in path.t.iter().zip(&path.y).enumerate() {
        header(&mut w, path.stamp_ns + seconds_ns(*t), &path.frame_id);
        vector(&mut w, *y);
        quaternion(&mut w, path.turn_at(k).0);
    }
    w.finish()
}

/// `trajectory_msgs/msg/MultiDOFJointTrajectory`: one joint, a point per
/// sample with its translation and rotation, linear and angular velocity
/// and acceleration (angular parts zero where the path has no orientation)
/// and `time_from_start`.
pub fn encode_multi_dof(path: &TimedPath) -> Vec<u8> {
    let mut w = CdrWriter::new();
    header(&mut w, path.stamp_ns, &path.frame_id);
    w.u32(1);
    w.string(&path.joint);
    w.u32(path.y.len() as u32);
    for k in 0..path.y.len() {
        let (q, omega, alpha) = path.turn_at(k);
        w.u32(1);
        vector(&mut w, path.y[k]);
        quaternion(&mut w, q);
        w.u32(1);
        vector(&mut w, path.v[k]);
        vector(&mut w, omega);
        w.u32(1);
        vector(&mut w, path.a[k]);
        vector(&mut w, alpha);
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
/// `(stamp_ns, position, orientation)` per pose.
pub type DecodedPath = (i64, String, Vec<(i64, [f64; 3], [f64; 4])>);

/// Decodes [`encode_path`].
pub fn decode_path(message: &[u8]) -> Result<DecodedPath, String> {
    let mut r = CdrReader::new(message)?;
    let (stamp, frame) = read_header(&mut r)?;
    let n = read_len(&mut r, "poses", message.len())?;
    let mut poses = Vec::with_capacity(n);
    for _ in 0..n {
        let (s, _) = read_header(&mut r)?;
        let p = read_vector(&mut r, "pose.position")?;
        let q = [r.f64("q")?, r.f64("q")?, r.f64("q")?, r.f64("q")?];
        poses.push((s, p, q));
    }
    Ok((stamp, frame, poses))
}

/// Decodes [`encode_multi_dof`] into a [`TimedPath`] (one joint; no
/// orientation where every rotation is the identity without a turn).
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
        orientation: None,
    };
    let mut turn = TimedOrientation {
        q: Vec::with_capacity(n),
        w: Vec::with_capacity(n),
        alpha: Vec::with_capacity(n),
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
        turn.q
            .push([r.f64("q")?, r.f64("q")?, r.f64("q")?, r.f64("q")?]);
        one("velocities", &mut r)?;
        out.v.push(read_vector(&mut r, "velocity.linear")?);
        turn.w.push(read_vector(&mut r, "velocity.angular")?);
        one("accelerations", &mut r)?;
        out.a.push(read_vector(&mut r, "acceleration.linear")?);
        turn.alpha
            .push(read_vector(&mut r, "acceleration.angular")?);
        let sec = r.i32("time_from_start.sec")?;
        let nanosec = r.u32("time_from_start.nanosec")?;
        out.t
            .push((i64::from(sec) * 1_000_000_000 + i64::from(nanosec)) as f64 * 1e-9);
    }
    // The identity without a turn is what a path without orientation
    // writes: read back as none.
    let still = turn.q.iter().all(|q| *q == IDENTITY)
        && turn.w.iter().chain(&turn.alpha).all(|v| *v == [0.0; 3]);
    out.orientation = (!still).then_some(turn);
    Ok(out)
}
