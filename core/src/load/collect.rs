//! What every recording reader feeds: channels (a topic, a schema, a
//! decoder) and messages, collected into one stream per topic and key, then
//! finished into [`RawDemo`]s with their time source, orientations and TF
//! frames (method.md sections 1 and 2.1-2.2). The MCAP reader
//! ([`crate::load::mcap`]) and the ROS 1 bag reader ([`crate::load::rosbag1`])
//! differ only in how they find channels and messages in the bytes.

use std::collections::BTreeMap;

use crate::error::{Error, Location, Result};
use crate::geom::{Quat, Vec3};
use crate::load::decode::{ChannelSchema, MessageDecoder, decoder_for};
use crate::load::demo::{RawDemo, TimeSource};
use crate::load::options::{LoadOptions, UpAxis};
use crate::load::orientation_check::OrientationCounts;

/// What one file gave.
#[derive(Clone, Debug, Default)]
pub struct Loaded {
    /// Demos in topic-name order, then key order.
    pub demos: Vec<RawDemo>,
    /// Topics seen but not read, with their schema names.
    pub skipped: Vec<(String, String)>,
    /// Things the user should know that did not stop the load (a truncated
    /// file's lost tail, a `--frame` that matches nothing).
    pub warnings: Vec<String>,
    /// Things worth knowing (messages that were compressed).
    pub notes: Vec<String>,
}

/// The first bytes of a zstd frame.
const ZSTD_MAGIC: [u8; 4] = [0x28, 0xB5, 0x2F, 0xFD];

/// The most keys (TF frames) remembered to name when `--frame` matches none.
const KEYS_NAMED: usize = 64;

/// One demo being collected: a topic, or one key of a multi-pose topic.
#[derive(Default)]
pub(crate) struct Stream {
    /// Its samples are TF transforms (they have a parent frame).
    tf: bool,
    stamps: Vec<Option<i64>>,
    log_times: Vec<i64>,
    positions: Vec<Vec3>,
    /// Each sample's orientation, already in dmpscope's z-up frame; `None`
    /// where the message has none or an unusable one.
    orientations: Vec<Option<Quat>>,
    /// What its orientations say about themselves.
    turns: OrientationCounts,
}

/// One stream of messages: the channels of one topic and schema (a merged
/// recording declares a topic again on a new channel).
pub(crate) struct Channel {
    topic: String,
    /// The demo's name, when the file says it (a dmpscope export).
    name: Option<String>,
    decoder: Box<dyn MessageDecoder>,
    /// CDR messages, which rosbag2 may have zstd-compressed one by one.
    cdr: bool,
    /// Messages that came zstd-compressed.
    compressed: usize,
    /// Messages seen, the sample index of errors.
    messages: usize,
    /// The stream of single-pose messages.
    unkeyed: Stream,
    /// The streams of multi-pose messages, by key (looked up without
    /// allocating; a key is copied once, when first seen).
    keyed: BTreeMap<String, Stream>,
}

impl Channel {
    fn samples(&self) -> usize {
        self.unkeyed.positions.len()
            + self
                .keyed
                .values()
                .map(|s| s.positions.len())
                .sum::<usize>()
    }
}

/// Everything gathered from the records so far.
pub(crate) struct Collector<'o> {
    label: &'o str,
    options: &'o LoadOptions,
    schemas: BTreeMap<u16, (String, String, Vec<u8>)>,
    /// Channel id -> its stream in `streams` (`None`: not read).
    channels: BTreeMap<u16, Option<usize>>,
    streams: Vec<Channel>,
    /// (topic, schema name) -> its stream.
    by_topic: BTreeMap<(String, String), usize>,
    /// Every key seen in multi-pose messages, filtered or not (to name them
    /// when `--frame` matches none).
    keys_seen: std::collections::BTreeSet<String>,
    /// The transforms, when a fixed frame was asked for.
    tf: Option<crate::load::tf::TfBuffer>,
    skipped: Vec<(String, String)>,
    /// The first message that failed to decode. It is reported once the file
    /// is read, unless its chunk fails its CRC first (then the file is
    /// reported corrupt instead).
    pending: Option<Error>,
}

impl<'o> Collector<'o> {
    /// An empty collector for the file `label`.
    pub(crate) fn new(label: &'o str, options: &'o LoadOptions) -> Self {
        Collector {
            label,
            options,
            schemas: BTreeMap::new(),
            channels: BTreeMap::new(),
            streams: Vec::new(),
            by_topic: BTreeMap::new(),
            keys_seen: std::collections::BTreeSet::new(),
            tf: options
                .fixed_frame
                .as_ref()
                .map(|_| crate::load::tf::TfBuffer::default()),
            skipped: Vec::new(),
            pending: None,
        }
    }

    pub(crate) fn at(&self) -> Location {
        Location::file(self.label)
    }

    /// Registers a schema (an MCAP schema record, a bag connection's
    /// message definition) for the channels that name it.
    pub(crate) fn schema(&mut self, id: u16, name: String, encoding: String, data: Vec<u8>) {
        self.schemas.insert(id, (name, encoding, data));
    }

    /// The first message that failed to decode, taken.
    pub(crate) fn take_pending(&mut self) -> Option<Error> {
        self.pending.take()
    }

    /// Whether a message failed to decode.
    pub(crate) fn has_pending(&self) -> bool {
        self.pending.is_some()
    }

    pub(crate) fn samples(&self) -> usize {
        self.streams.iter().map(Channel::samples).sum()
    }

    pub(crate) fn channel(&mut self, ch: mcap::records::Channel) -> Result<()> {
        if self.channels.contains_key(&ch.id) {
            return Ok(());
        }
        let (name, encoding, data) = self
            .schemas
            .get(&ch.schema_id)
            .map(|(n, e, d)| (n.as_str(), e.as_str(), d.as_slice()))
            .unwrap_or(("", "", &[]));
        let schema = ChannelSchema {
            message_encoding: &ch.message_encoding,
            schema_name: name,
            schema_encoding: encoding,
            schema_data: data,
        };
        let regenerated = ch
            .metadata
            .get(crate::load::formats::ROLE_KEY)
            .map(String::as_str)
            == Some(crate::load::formats::ROLE_REGENERATED);
        let asked = |t: &str| {
            self.options
                .streams
                .topics
                .iter()
                .any(|p| crate::load::options::matches_stream(p, t))
        };
        let exported_trajectory = ch
            .metadata
            .get(crate::load::formats::ROLE_KEY)
            .map(String::as_str)
            == Some(crate::load::formats::ROLE_TRAJECTORY);
        if exported_trajectory {
            self.skipped.push((
                ch.topic.clone(),
                format!("a trajectory dmpscope exported ({name}), not a demonstration"),
            ));
            self.channels.insert(ch.id, None);
            return Ok(());
        }
        if regenerated && !asked(&ch.topic) {
            self.skipped.push((
                ch.topic.clone(),
                "a path dmpscope regenerated, not a demonstration; --topic '/regen/*' loads it"
                    .to_owned(),
            ));
            self.channels.insert(ch.id, None);
            return Ok(());
        }
        let merge_key = (ch.topic.clone(), name.to_owned());
        if let Some(&index) = self.by_topic.get(&merge_key) {
            self.channels.insert(ch.id, Some(index));
            return Ok(());
        }
        let decoder = match decoder_for(&schema) {
            Some(Ok(decoder)) => Some(decoder),
            Some(Err(reason)) => {
                return Err(Error::Decode {
                    at: self.at().topic(&ch.topic),
                    reason: format!("unusable schema {name}: {reason}"),
                });
            }
            None => {
                let what = if name.is_empty() {
                    format!("no schema, {}", ch.message_encoding)
                } else {
                    name.to_owned()
                };
                self.skipped.push((ch.topic.clone(), what));
                None
            }
        };
        let entry = decoder.map(|decoder| {
            self.streams.push(Channel {
                topic: ch.topic.clone(),
                name: ch.metadata.get(crate::load::formats::NAME_KEY).map(|n| {
                    if regenerated {
                        format!("{n} (regenerated)")
                    } else {
                        n.clone()
                    }
                }),
                decoder,
                cdr: ch.message_encoding == "cdr",
                compressed: 0,
                messages: 0,
                unkeyed: Stream::default(),
                keyed: BTreeMap::new(),
            });
            self.by_topic.insert(merge_key, self.streams.len() - 1);
            self.streams.len() - 1
        });
        self.channels.insert(ch.id, entry);
        Ok(())
    }

    pub(crate) fn message(
        &mut self,
        header: &mcap::records::MessageHeader,
        data: &[u8],
    ) -> Result<()> {
        let label = self.label;
        let options = self.options;
        let Some(slot) = self.channels.get(&header.channel_id) else {
            return Err(Error::Mcap {
                at: Location::file(label),
                reason: format!(
                    "message on channel {} that was never declared",
                    header.channel_id
                ),
            });
        };
        let Some(channel) = slot.and_then(|i| self.streams.get_mut(i)) else {
            return Ok(());
        };
        if self.pending.is_some() {
            return Ok(());
        }
        let index = channel.messages;
        channel.messages += 1;
        let inflated;
        let data = if channel.cdr && data.starts_with(&ZSTD_MAGIC) {
            channel.compressed += 1;
            match zstd::stream::decode_all(data) {
                Ok(bytes) => {
                    inflated = bytes;
                    inflated.as_slice()
                }
                Err(e) => {
                    self.pending = Some(Error::Decode {
                        at: Location::file(label).topic(&channel.topic).sample(index),
                        reason: format!(
                            "the message is zstd-compressed (rosbag2 message compression) but \
                             does not decompress ({e}); `ros2 bag decompress` writes an \
                             uncompressed copy"
                        ),
                    });
                    return Ok(());
                }
            }
        } else {
            data
        };
        let keys_seen = &mut self.keys_seen;
        let tf = &mut self.tf;
        let log_time = i64::try_from(header.log_time).unwrap_or(i64::MAX);
        let mut bad: Option<(Option<String>, usize)> = None;
        let Channel {
            topic,
            decoder,
            unkeyed,
            keyed,
            ..
        } = channel;
        let is_static = topic.ends_with("tf_static");
        let decoded = decoder.decode(data, &mut |sample| {
            if let (Some(buffer), Some(parent), Some(child)) =
                (tf.as_mut(), &sample.parent, &sample.key)
                && sample
                    .position
                    .iter()
                    .chain(sample.orientation.iter().flatten())
                    .all(|v| v.is_finite())
            {
                buffer.add(
                    parent,
                    child,
                    sample.stamp_ns.unwrap_or(log_time),
                    sample.position,
                    sample.orientation.unwrap_or([0.0; 4]),
                    is_static,
                );
            }
            if let Some(k) = &sample.key
                && !options.frames.is_empty()
            {
                if !keys_seen.contains(k.as_ref()) && keys_seen.len() < KEYS_NAMED {
                    keys_seen.insert(k.clone().into_owned());
                }
                if !options.frames.iter().any(|f| f == k) {
                    return;
                }
            }
            if let Some(axis) = sample.position.iter().position(|v| !v.is_finite()) {
                bad.get_or_insert((sample.key.map(|k| k.into_owned()), axis));
                return;
            }
            let stream = match sample.key {
                None => &mut *unkeyed,
                Some(k) => {
                    if !keyed.contains_key(k.as_ref()) {
                        keyed.insert(k.clone().into_owned(), Stream::default());
                    }
                    match keyed.get_mut(k.as_ref()) {
                        Some(s) => s,
                        None => return,
                    }
                }
            };
            stream.tf |= sample.parent.is_some();
            stream.stamps.push(sample.stamp_ns);
            stream.log_times.push(log_time);
            stream
                .positions
                .push(options.up.to_z_up(sample.position).into());
            let orientation = sample.orientation.and_then(crate::geom::quat_from_xyzw);
            stream
                .turns
                .record(index, sample.orientation, orientation.is_some());
            stream
                .orientations
                .push(orientation.map(|q| options.up.orientation_to_z_up(q)));
        });
        let at = Location::file(label);
        if let Err(reason) = decoded {
            self.pending = Some(Error::Decode {
                at: at.topic(topic.as_str()).sample(index),
                reason,
            });
        } else if let Some((key, axis)) = bad {
            let name = key.map_or_else(|| topic.clone(), |k| format!("{topic}:{k}"));
            self.pending = Some(Error::NonFinite {
                at: at.topic(name).sample(index),
                field: ["position.x", "position.y", "position.z"][axis],
            });
        }
        Ok(())
    }

    /// The demos collected, or the first decoding error; `truncated` is the
    /// reader's warning when the file ended early, `warnings` what it
    /// already has to say.
    pub(crate) fn finish(
        self,
        truncated: Option<String>,
        mut warnings: Vec<String>,
    ) -> Result<Loaded> {
        let mut c = self;
        let label = c.label;
        let options = c.options;
        if let Some(err) = c.pending {
            return Err(err);
        }
        let file_name = std::path::Path::new(label)
            .file_name()
            .map_or_else(|| label.to_owned(), |n| n.to_string_lossy().into_owned());
        let mut notes = Vec::new();
        let mut streams: Vec<(String, Option<String>, Stream)> = Vec::new();
        let mut names: BTreeMap<String, String> = BTreeMap::new();
        for channel in c.streams {
            if channel.compressed > 0 {
                notes.push(format!(
                    "{label}: {}: {} messages were zstd-compressed (rosbag2 message compression): \
                     decompressed while reading",
                    channel.topic, channel.compressed
                ));
            }
            if let Some(name) = channel.name {
                names.insert(channel.topic.clone(), name);
            }
            streams.push((channel.topic.clone(), None, channel.unkeyed));
            for (key, stream) in channel.keyed {
                streams.push((channel.topic.clone(), Some(key), stream));
            }
        }
        streams.sort_by(|a, b| (&a.0, &a.1).cmp(&(&b.0, &b.1)));
        let mut lost = Vec::new();
        if let (Some(fixed), Some(buffer)) = (&options.fixed_frame, c.tf.as_mut()) {
            streams.retain_mut(|(topic, key, s)| match key {
                Some(k) if s.tf => match in_fixed_frame(buffer, fixed, k, s, options.up) {
                    Ok(None) => true,
                    Ok(Some(note)) => {
                        warnings.push(format!("{label}: {topic}:{k}: {note}"));
                        true
                    }
                    Err(why) => {
                        lost.push(format!("{topic}:{k}: not expressed in {fixed}: {why}"));
                        false
                    }
                },
                _ => true,
            });
        }
        let mut demos: Vec<RawDemo> = Vec::new();
        for (topic, key, s) in streams {
            if s.positions.is_empty() {
                continue;
            }
            let given = key.is_none().then(|| names.get(&topic).cloned()).flatten();
            let source = key
                .as_deref()
                .map_or_else(|| topic.clone(), |k| format!("{topic}:{k}"));
            let said = s
                .turns
                .verdict(label, &source, options.drop_bad_orientation)?;
            let mut demo = finish_stream(label, &file_name, topic, key, s);
            if let Some(said) = said {
                warnings.push(said);
            }
            if let Some(name) = given {
                demo.name = name;
            }
            demos.push(demo);
        }
        let mut skipped = c.skipped;
        skipped.sort();
        let unmatched: Vec<&String> = options
            .frames
            .iter()
            .filter(|f| {
                !demos
                    .iter()
                    .any(|d| d.topic.rsplit_once(':').is_some_and(|(_, k)| k == *f))
            })
            .collect();
        if !unmatched.is_empty() && !c.keys_seen.is_empty() {
            let names: Vec<&str> = c.keys_seen.iter().map(String::as_str).collect();
            let what = format!(
                "--frame {} matches no frame here; the frames are: {}",
                unmatched
                    .iter()
                    .map(|f| f.as_str())
                    .collect::<Vec<_>>()
                    .join(", "),
                names.join(", ")
            );
            if demos.is_empty() {
                return Err(Error::Source {
                    path: label.to_owned(),
                    reason: what,
                });
            }
            warnings.push(format!("{label}: {what}"));
        }
        if demos.is_empty() && !lost.is_empty() {
            return Err(Error::Source {
                path: label.to_owned(),
                reason: lost.join("; "),
            });
        }
        warnings.extend(lost.iter().map(|l| format!("{label}: {l}: skipped")));
        if demos.is_empty() {
            return Err(Error::NoDemos {
                file: label.to_owned(),
                skipped,
            });
        }
        if let Some(mut text) = truncated {
            text.push_str(&cut_short(&demos));
            warnings.push(text);
        }
        Ok(Loaded {
            demos,
            skipped,
            warnings,
            notes,
        })
    }
}

/// Re-expresses a TF stream in `fixed` (method.md section 13): each sample
/// becomes the frame's origin and orientation in `fixed` at its stamp. Gives a note when
/// transforms were held past their recorded span.
fn in_fixed_frame(
    buffer: &mut crate::load::tf::TfBuffer,
    fixed: &str,
    frame: &str,
    s: &mut Stream,
    up: UpAxis,
) -> std::result::Result<Option<String>, String> {
    let mut held = 0;
    for i in 0..s.positions.len() {
        let stamp = s.stamps[i].unwrap_or(s.log_times[i]);
        let (p, q, h) = buffer.pose_in(fixed, frame, stamp)?;
        held += usize::from(h);
        s.positions[i] = up.to_z_up(p).into();
        s.orientations[i] = crate::geom::quat_from_xyzw(q).map(|q| up.orientation_to_z_up(q));
    }
    Ok((held > 0).then(|| {
        format!(
            "{held} samples lie outside the recorded span of a transform to {fixed}: the \
             nearest transform was held there (tf2 would refuse them)"
        )
    }))
}

/// The streams a truncated file cut short: those still sending when it
/// ends (their last message within max(1 s, 10 of their intervals) of the
/// file's last one).
fn cut_short(demos: &[RawDemo]) -> String {
    let last = |d: &RawDemo| d.stamps_ns.iter().copied().max();
    let Some(end) = demos.iter().filter_map(last).max() else {
        return String::new();
    };
    let names: Vec<String> = demos
        .iter()
        .filter(|d| {
            let h = crate::load::demo::median(&crate::load::demo::stamp_intervals_s(
                &d.sorted_unique().0,
            ));
            let window = (1.0f64).max(10.0 * h);
            last(d).is_some_and(|t| (end - t) as f64 * 1e-9 <= window)
        })
        .map(|d| format!("{} ({} samples)", d.topic, d.stamps_ns.len()))
        .collect();
    if names.is_empty() {
        String::new()
    } else {
        format!("; cut short: {}", names.join(", "))
    }
}

/// Chooses the time source of one stream (method.md section 2.1): header
/// stamps, unless one is missing or all are zero, then log time.
fn finish_stream(
    label: &str,
    file_name: &str,
    topic: String,
    key: Option<String>,
    s: Stream,
) -> RawDemo {
    let stamps: Option<Vec<i64>> = s.stamps.iter().copied().collect();
    let (stamps_ns, time_source) = match stamps {
        Some(v) if v.iter().any(|&t| t != 0) => (v, TimeSource::HeaderStamp),
        _ => (s.log_times, TimeSource::LogTime),
    };
    let source = match key {
        Some(k) => format!("{topic}:{k}"),
        None => topic,
    };
    RawDemo {
        name: format!("{file_name}:{source}"),
        file: label.to_owned(),
        topic: source,
        stamps_ns,
        positions: s.positions,
        orientations: s.orientations.into_iter().collect(),
        time_source,
    }
}
