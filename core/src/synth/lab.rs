//! A lab take as tracking labs record it: a tracker's poses
//! (`geometry_msgs/msg/PoseStamped` on `/tracker/pose`, 250 Hz) beside a
//! camera (`sensor_msgs/msg/Image`, rgb8, 30 Hz) in one MCAP file, every
//! message in time order, so the poses are a small part of chunks that are
//! mostly images. The hand reaches from a home to a goal and back, with a
//! rest at each end, again and again. The images are a moving gradient
//! with noise in their six low bits, about as compressible as a camera's.
//! Deterministic from a seed; fast enough to write gigabytes.

use std::collections::BTreeMap;
use std::io::{Seek, Write};

use crate::rng::Rng;

/// What to write.
#[derive(Clone, Debug, PartialEq)]
pub struct LabTake {
    /// Length of the take, seconds.
    pub seconds: f64,
    /// Tracker rate, Hz.
    pub pose_hz: f64,
    /// Camera rate, Hz.
    pub camera_hz: f64,
    /// Camera image width and height, pixels (rgb8).
    pub image: (u32, u32),
    /// Chunk compression: `None`, or zstd.
    pub zstd: bool,
    /// Chunk size, bytes.
    pub chunk_size: u64,
    /// The seed.
    pub seed: u64,
}

impl Default for LabTake {
    fn default() -> Self {
        Self {
            seconds: 72.0,
            pose_hz: 250.0,
            camera_hz: 30.0,
            image: (640, 480),
            zstd: true,
            chunk_size: 4 << 20,
            seed: 1,
        }
    }
}

/// The pose topic of a lab take.
pub const POSE_TOPIC: &str = "/tracker/pose";
/// The camera topic of a lab take.
pub const CAMERA_TOPIC: &str = "/camera/image_raw";

const START_NS: u64 = 1_765_000_000_000_000_000;

/// Writes the take; its MCAP as the writer leaves it.
pub fn write_lab_take<W: Write + Seek>(out: W, take: &LabTake) -> mcap::McapResult<W> {
    let mut w = mcap::WriteOptions::new()
        .compression(take.zstd.then_some(mcap::Compression::Zstd))
        .chunk_size(Some(take.chunk_size))
        .library(concat!("dmpscope/", env!("CARGO_PKG_VERSION")))
        .create(out)?;
    let pose_schema = w.add_schema(
        "geometry_msgs/msg/PoseStamped",
        "ros2msg",
        crate::load::decode::ros2::POSE_STAMPED_SCHEMA.as_bytes(),
    )?;
    let image_schema = w.add_schema("sensor_msgs/msg/Image", "ros2msg", IMAGE_SCHEMA.as_bytes())?;
    let pose = w.add_channel(pose_schema, POSE_TOPIC, "cdr", &BTreeMap::new())?;
    let camera = w.add_channel(image_schema, CAMERA_TOPIC, "cdr", &BTreeMap::new())?;
    let hand = Hand::new(take.seed);
    let mut frame = Frame::new(take.image, take.seed);
    let pose_dt = 1e9 / take.pose_hz;
    let camera_dt = 1e9 / take.camera_hz;
    let end = (take.seconds * 1e9) as u64;
    let (mut next_pose, mut next_image) = (0.0f64, 0.0f64);
    let (mut pose_seq, mut image_seq) = (0u32, 0u32);
    loop {
        let (t, is_pose) = if next_pose <= next_image {
            (next_pose as u64, true)
        } else {
            (next_image as u64, false)
        };
        if t >= end {
            break;
        }
        let stamp = START_NS + t;
        let (channel_id, sequence, data) = if is_pose {
            next_pose += pose_dt;
            pose_seq += 1;
            (
                pose,
                pose_seq,
                pose_message(stamp, hand.at(t as f64 * 1e-9)),
            )
        } else {
            next_image += camera_dt;
            image_seq += 1;
            (camera, image_seq, frame.next(stamp))
        };
        let header = mcap::records::MessageHeader {
            channel_id,
            sequence,
            log_time: stamp,
            publish_time: stamp,
        };
        w.write_to_known_channel(&header, &data)?;
    }
    w.finish()?;
    Ok(w.into_inner())
}

/// The hand: reaches from home to a goal and back, resting at each end.
struct Hand {
    home: [f64; 3],
    goals: Vec<[f64; 3]>,
}

/// A reach's and a return's duration, and each rest's, seconds.
const MOVE_S: f64 = 1.2;
const REST_S: f64 = 0.8;

impl Hand {
    fn new(seed: u64) -> Self {
        let mut rng = Rng::new(seed);
        let goals = (0..64)
            .map(|_| {
                [
                    0.35 + rng.range(-0.1, 0.1),
                    rng.range(-0.25, 0.25),
                    0.2 + rng.range(-0.1, 0.1),
                ]
            })
            .collect();
        Self {
            home: [0.0, 0.0, 0.1],
            goals,
        }
    }

    /// The position at `t` seconds.
    fn at(&self, t: f64) -> [f64; 3] {
        let cycle = 2.0 * (MOVE_S + REST_S);
        let k = (t / cycle) as usize;
        let u = t - k as f64 * cycle;
        let goal = self.goals[k % self.goals.len()];
        let lerp = |a: [f64; 3], b: [f64; 3], s: f64| {
            let s = s * s * s * (10.0 - 15.0 * s + 6.0 * s * s);
            std::array::from_fn(|i| a[i] + (b[i] - a[i]) * s)
        };
        if u < REST_S {
            self.home
        } else if u < REST_S + MOVE_S {
            lerp(self.home, goal, (u - REST_S) / MOVE_S)
        } else if u < 2.0 * REST_S + MOVE_S {
            goal
        } else {
            lerp(goal, self.home, (u - 2.0 * REST_S - MOVE_S) / MOVE_S)
        }
    }
}

/// CDR of a PoseStamped in frame `world` with the identity orientation.
fn pose_message(stamp: u64, p: [f64; 3]) -> Vec<u8> {
    let mut m = Vec::with_capacity(80);
    m.extend_from_slice(&[0, 1, 0, 0]);
    header(&mut m, stamp, "world");
    while m.len() % 8 != 4 {
        m.push(0);
    }
    for v in p.iter().chain(&[0.0, 0.0, 0.0, 1.0]) {
        m.extend_from_slice(&v.to_le_bytes());
    }
    m
}

/// A ROS 2 header: stamp and frame id (4-aligned, after the 4-byte
/// encapsulation).
fn header(m: &mut Vec<u8>, stamp: u64, frame: &str) {
    m.extend_from_slice(&((stamp / 1_000_000_000) as i32).to_le_bytes());
    m.extend_from_slice(&((stamp % 1_000_000_000) as u32).to_le_bytes());
    m.extend_from_slice(&(frame.len() as u32 + 1).to_le_bytes());
    m.extend_from_slice(frame.as_bytes());
    m.push(0);
}

/// The camera: a gradient that moves, with noise in its low bits.
struct Frame {
    width: u32,
    height: u32,
    index: u64,
    noise: u64,
}

impl Frame {
    fn new((width, height): (u32, u32), seed: u64) -> Self {
        Self {
            width,
            height,
            index: 0,
            noise: seed | 1,
        }
    }

    /// The next image as a CDR `sensor_msgs/msg/Image`.
    fn next(&mut self, stamp: u64) -> Vec<u8> {
        let step = self.width as usize * 3;
        let size = step * self.height as usize;
        let mut m = Vec::with_capacity(size + 64);
        m.extend_from_slice(&[0, 1, 0, 0]);
        header(&mut m, stamp, "camera");
        while m.len() % 4 != 0 {
            m.push(0);
        }
        m.extend_from_slice(&self.height.to_le_bytes());
        m.extend_from_slice(&self.width.to_le_bytes());
        m.extend_from_slice(&5u32.to_le_bytes());
        m.extend_from_slice(b"rgb8\0");
        m.push(0); // is_bigendian
        while m.len() % 4 != 0 {
            m.push(0);
        }
        m.extend_from_slice(&(step as u32).to_le_bytes());
        m.extend_from_slice(&(size as u32).to_le_bytes());
        let shift = self.index;
        for row in 0..self.height as u64 {
            let base = (row + shift) & 0xF0;
            for _ in 0..step / 8 {
                // xorshift: four bits of noise per byte over the gradient.
                self.noise ^= self.noise << 13;
                self.noise ^= self.noise >> 7;
                self.noise ^= self.noise << 17;
                let bytes =
                    (self.noise & 0x3F3F_3F3F_3F3F_3F3F) | ((base & 0xC0) * 0x0101_0101_0101_0101);
                m.extend_from_slice(&bytes.to_le_bytes());
            }
            m.resize(m.len() + step % 8, base as u8);
        }
        self.index += 1;
        m
    }
}

/// The message definition of `sensor_msgs/msg/Image` (what a recorder
/// writes as the schema).
const IMAGE_SCHEMA: &str = "std_msgs/Header header\nuint32 height\nuint32 width\nstring encoding\nuint8 is_bigendian\nuint32 step\nuint8[] data\n================================================================================\nMSG: std_msgs/Header\nbuiltin_interfaces/Time stamp\nstring frame_id\n";
