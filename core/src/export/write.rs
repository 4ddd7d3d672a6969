//! Writing demonstrations as MCAP (ROS 2 `PoseStamped`, CDR): the sample
//! generator's output and the tests' fixtures.

use std::collections::BTreeMap;
use std::io::{Seek, Write};

use mcap::records::MessageHeader;

use crate::load::decode::ros2::{POSE_STAMPED_SCHEMA, encode_oriented_pose_stamped};

/// One topic to write: every sample is `(stamp_ns, position)`; the stamp
/// is used as both header stamp and log time.
pub struct TopicSamples<'a> {
    /// The topic name, e.g. `/demo_01`.
    pub topic: &'a str,
    /// The header frame id.
    pub frame_id: &'a str,
    /// Samples in the order they should be written.
    pub samples: &'a [(i64, [f64; 3])],
    /// One orientation `[x, y, z, w]` per sample (`None`: identity).
    pub orientations: Option<&'a [[f64; 4]]>,
}

/// A bulky topic of another schema (camera frames, say), to make large
/// recordings in which the poses are a small part.
#[derive(Clone, Copy, Debug)]
pub struct BulkTopic<'a> {
    /// The topic name.
    pub topic: &'a str,
    /// Bytes per message.
    pub message_bytes: usize,
    /// Number of messages.
    pub messages: usize,
}

/// Writes the topics as `geometry_msgs/msg/PoseStamped` into an MCAP file
/// (zstd-compressed chunks when `compress`), topic after topic, each topic's
/// samples in the order given (so tests can write out-of-order stamps).
pub fn write_pose_stamped<W: Write + Seek>(
    out: W,
    topics: &[TopicSamples<'_>],
    compress: bool,
) -> mcap::McapResult<W> {
    write_pose_stamped_with_bulk(out, topics, compress, None)
}

/// As [`write_pose_stamped`], then a bulky `sensor_msgs/msg/Image` topic of
/// opaque bytes.
pub fn write_pose_stamped_with_bulk<W: Write + Seek>(
    out: W,
    topics: &[TopicSamples<'_>],
    compress: bool,
    bulk: Option<BulkTopic<'_>>,
) -> mcap::McapResult<W> {
    let compression = if compress {
        Some(mcap::Compression::Zstd)
    } else {
        None
    };
    let mut writer = mcap::WriteOptions::new()
        .compression(compression)
        .profile("ros2")
        .library(concat!("dmpscope/", env!("CARGO_PKG_VERSION")))
        .create(out)?;
    let schema = writer.add_schema(
        "geometry_msgs/msg/PoseStamped",
        "ros2msg",
        POSE_STAMPED_SCHEMA.as_bytes(),
    )?;
    for topic in topics {
        let channel_id = writer.add_channel(schema, topic.topic, "cdr", &BTreeMap::new())?;
        for (sequence, &(stamp, position)) in topic.samples.iter().enumerate() {
            let time = u64::try_from(stamp).unwrap_or(0);
            writer.write_to_known_channel(
                &MessageHeader {
                    channel_id,
                    sequence: sequence as u32,
                    log_time: time,
                    publish_time: time,
                },
                &encode_oriented_pose_stamped(
                    stamp,
                    topic.frame_id,
                    position,
                    topic
                        .orientations
                        .and_then(|q| q.get(sequence).copied())
                        .unwrap_or([0.0, 0.0, 0.0, 1.0]),
                ),
            )?;
        }
    }
    if let Some(bulk) = bulk {
        let schema = writer.add_schema("sensor_msgs/msg/Image", "ros2msg", b"")?;
        let channel_id = writer.add_channel(schema, bulk.topic, "cdr", &BTreeMap::new())?;
        let mut payload = vec![0u8; bulk.message_bytes];
        for (sequence, byte) in payload.iter_mut().enumerate() {
            *byte = (sequence * 7 % 251) as u8;
        }
        for sequence in 0..bulk.messages {
            let time = 1_700_000_000_000_000_000 + sequence as u64 * 33_000_000;
            writer.write_to_known_channel(
                &MessageHeader {
                    channel_id,
                    sequence: sequence as u32,
                    log_time: time,
                    publish_time: time,
                },
                &payload,
            )?;
        }
    }
    writer.finish()?;
    Ok(writer.into_inner())
}
