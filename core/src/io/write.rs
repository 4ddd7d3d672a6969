//! Writing demonstrations as MCAP (ROS 2 `PoseStamped`, CDR): the sample
//! generator's output and the tests' fixtures.

use std::collections::BTreeMap;
use std::io::{Seek, Write};

use mcap::records::MessageHeader;

use super::ros2::{POSE_STAMPED_SCHEMA, encode_pose_stamped};

/// One topic to write: every sample is `(stamp_ns, position)`; the stamp
/// is used as both header stamp and log time.
pub struct TopicSamples<'a> {
    /// The topic name, e.g. `/demo_01`.
    pub topic: &'a str,
    /// The header frame id.
    pub frame_id: &'a str,
    /// Samples in the order they should be written.
    pub samples: &'a [(i64, [f64; 3])],
}

/// Writes the topics as `geometry_msgs/msg/PoseStamped` into an MCAP file
/// (zstd-compressed chunks when `compress`), topic after topic, each topic's
/// samples in the order given (so tests can write out-of-order stamps).
pub fn write_pose_stamped<W: Write + Seek>(
    out: W,
    topics: &[TopicSamples<'_>],
    compress: bool,
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
                &encode_pose_stamped(stamp, topic.frame_id, position),
            )?;
        }
    }
    writer.finish()?;
    Ok(writer.into_inner())
}
