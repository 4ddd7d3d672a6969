//! Reading demonstrations from recordings.
//!
//! [`mcap_file`] walks an MCAP file with mcap's sans-IO reader (so the same
//! code reads a file, a byte slice from a browser upload or a stream) and hands
//! every message to the decoder its channel's schema names. A decoder turns
//! message bytes into zero or more [`PoseSample`]s (a TF message holds one per
//! child frame); [`decoder_for`] is the registry, one arm per encoding.
//! [`write`] is the reverse path, used by the sample generator and the tests.

pub mod cdr;
pub mod chunks;
pub(crate) mod collect;
pub mod csv;
pub mod dmp_doc;
pub mod export;
pub mod formats;
pub mod foxglove_json;
pub mod foxglove_proto;
pub mod foxglove_schemas;
pub mod mcap_file;
mod orientation_check;
pub mod ros1;
pub mod ros2;
pub mod ros_traj;
pub mod rosbag1;
pub mod rosbag2;
pub mod source;
pub mod write;

use std::borrow::Cow;

pub use mcap_file::{
    LoadOptions, Loaded, UpAxis, load_bytes, load_bytes_with, load_path, load_path_with,
    load_reader,
};
pub use source::{SourceData, SourceDemos, load_source, load_streams};

/// One pose a decoder found in a message.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PoseSample<'a> {
    /// Which of several poses in one message this is (a TF child frame, an
    /// index into a pose array); `None` for single-pose messages. Each key of
    /// a topic becomes its own demo.
    pub key: Option<Cow<'a, str>>,
    /// The message's own stamp in nanoseconds, `None` when it has none (or
    /// the zero stamp, which ROS uses for "no stamp").
    pub stamp_ns: Option<i64>,
    /// The position in metres, in the recording's own axes.
    pub position: [f64; 3],
    /// For a transform (ROS TF, Foxglove `FrameTransform`), its parent
    /// frame, which the TF buffer of `--fixed-frame` needs; `None` for
    /// poses.
    pub parent: Option<Cow<'a, str>>,
    /// The orientation `[x, y, z, w]` as stored (a pose's orientation, a
    /// transform's rotation), not yet checked or normalised; `None` when
    /// the schema has none (a point). The TF buffer takes a missing or
    /// all-zero rotation as the identity.
    pub orientation: Option<[f64; 4]>,
}

impl PoseSample<'_> {
    /// A single pose (no key, no parent): what most pose messages give.
    pub fn single(
        stamp_ns: Option<i64>,
        position: [f64; 3],
        orientation: Option<[f64; 4]>,
    ) -> PoseSample<'static> {
        PoseSample {
            key: None,
            stamp_ns,
            position,
            parent: None,
            orientation,
        }
    }
}

/// Decodes the messages of one channel.
pub trait MessageDecoder: Send {
    /// Decodes one message, handing every pose in it to `out`; an `Err` is
    /// the reason the bytes are not a valid message of the schema.
    fn decode(&mut self, data: &[u8], out: &mut dyn FnMut(PoseSample<'_>)) -> Result<(), String>;
}

/// A decoder that is a plain function giving one pose per message.
pub struct SinglePose(pub fn(&[u8]) -> Result<PoseSample<'static>, String>);

impl MessageDecoder for SinglePose {
    fn decode(&mut self, data: &[u8], out: &mut dyn FnMut(PoseSample<'_>)) -> Result<(), String> {
        out((self.0)(data)?);
        Ok(())
    }
}

/// What the registry needs to know about a channel.
#[derive(Clone, Copy, Debug)]
pub struct ChannelSchema<'a> {
    /// The channel's message encoding (`cdr`, `ros1`, `protobuf`, `json`).
    pub message_encoding: &'a str,
    /// The schema's name, e.g. `geometry_msgs/msg/PoseStamped`.
    pub schema_name: &'a str,
    /// The schema's encoding (`ros2msg`, `ros1msg`, `protobuf`, `jsonschema`).
    pub schema_encoding: &'a str,
    /// The schema's bytes (a FileDescriptorSet for protobuf).
    pub schema_data: &'a [u8],
}

/// The decoder for a channel, `None` when dmpscope does not read its schema,
/// `Some(Err)` when it should but the schema itself is unusable.
pub fn decoder_for(channel: &ChannelSchema<'_>) -> Option<Result<Box<dyn MessageDecoder>, String>> {
    match channel.message_encoding {
        "cdr" => ros2::decoder(channel.schema_name).map(Ok),
        "ros1" => ros1::decoder(channel.schema_name).map(Ok),
        "protobuf" => foxglove_proto::decoder(channel),
        "json" => foxglove_json::decoder(channel),
        _ => None,
    }
}
