//! Reading demonstrations from recordings.
//!
//! [`mcap_file`] walks an MCAP file with mcap's sans-IO reader (so the same
//! code reads a file, a byte slice from a browser upload or a stream) and hands
//! every message to the decoder its schema names. A decoder is one small
//! function from message bytes to a [`PoseSample`]; [`decoder_for`] is the
//! registry. [`write`] is the reverse path, used by the sample generator and
//! by the tests to make files.

pub mod cdr;
pub mod mcap_file;
pub mod ros2;
pub mod write;

pub use mcap_file::{Loaded, load_bytes, load_path, load_reader};

/// What a decoder extracts from one message.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PoseSample {
    /// The message's own stamp in nanoseconds, `None` when it has none.
    pub stamp_ns: Option<i64>,
    /// The position in metres.
    pub position: [f64; 3],
}

/// A decoder: message bytes to one pose sample, or a reason it failed.
pub type Decoder = fn(&[u8]) -> Result<PoseSample, String>;

/// The decoder for a channel, from its message encoding and its schema's
/// encoding and name (MCAP registry names); `None` when dmpscope does not read it.
pub fn decoder_for(
    message_encoding: &str,
    schema_encoding: &str,
    schema_name: &str,
) -> Option<Decoder> {
    match (message_encoding, schema_encoding, schema_name) {
        ("cdr", "ros2msg", "geometry_msgs/msg/PoseStamped") => Some(ros2::decode_pose_stamped),
        _ => None,
    }
}
