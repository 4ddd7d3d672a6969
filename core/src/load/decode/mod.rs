//! Decode: message bytes turned into pose samples. A decoder turns a
//! message of its channel's schema into zero or more [`PoseSample`]s (a TF
//! message holds one per child frame); [`decoder_for`] is the registry, one
//! arm per message encoding: ROS 2 CDR ([`ros2`] over [`cdr`]), ROS 1
//! ([`ros1`]), Foxglove protobuf ([`foxglove_proto`]) and JSON
//! ([`foxglove_json`]), the Foxglove schemas' shared parts in
//! [`foxglove_schemas`].

pub mod cdr;
pub mod foxglove_json;
pub mod foxglove_proto;
pub mod foxglove_schemas;
pub mod ros1;
pub mod ros2;

use std::borrow::Cow;

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
