//! What every recording reader feeds: channels (a topic, a schema, a
//! decoder) and messages, collected into one stream per topic and key, then
//! finished into [`RawDemo`]s with their time source, orientations and TF
//! frames (method.md sections 1 and 2.1-2.2). The MCAP reader
//! ([`crate::load::mcap`]) and the ROS 1 bag reader ([`crate::load::rosbag1`])
//! differ only in how they find channels and messages in the bytes.

use std::collections::BTreeMap;

use crate::error::{Error, Location, Result};
use crate::load::decode::{ChannelSchema, MessageDecoder, PoseSample, decoder_for};
use crate::load::demo::RawDemo;
use crate::load::options::LoadOptions;
use crate::load::streams::{
    Keyed, Stream, cut_short, finish_stream, in_fixed_frames, unmatched_frames,
};

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
    /// A channel of `ch` read by `decoder`, named by its dmpscope metadata
    /// where it has one.
    fn new(
        ch: &mcap::records::Channel,
        decoder: Box<dyn MessageDecoder>,
        regenerated: bool,
    ) -> Self {
        Self {
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
        }
    }
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

    /// The file's name in errors.
    pub(crate) fn label(&self) -> &'o str {
        self.label
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
    /// Whether messages of channel `id` are read (it was declared, and
    /// dmpscope decodes its schema).
    pub(crate) fn reads(&self, id: u16) -> bool {
        matches!(self.channels.get(&id), Some(Some(_)))
    }

    /// Whether channel `id` was declared (read or not).
    pub(crate) fn declared(&self, id: u16) -> bool {
        self.channels.contains_key(&id)
    }

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
        if let Some(why) = self.not_a_demo(&ch, name, regenerated) {
            self.skipped.push((ch.topic.clone(), why));
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
            self.streams.push(Channel::new(&ch, decoder, regenerated));
            self.by_topic.insert(merge_key, self.streams.len() - 1);
            self.streams.len() - 1
        });
        self.channels.insert(ch.id, entry);
        Ok(())
    }

    /// Why a channel that dmpscope wrote is not a demonstration (an
    /// exported trajectory; a regenerated path not asked for by `--topic`).
    fn not_a_demo(
        &self,
        ch: &mcap::records::Channel,
        name: &str,
        regenerated: bool,
    ) -> Option<String> {
        let exported_trajectory = ch
            .metadata
            .get(crate::load::formats::ROLE_KEY)
            .map(String::as_str)
            == Some(crate::load::formats::ROLE_TRAJECTORY);
        if exported_trajectory {
            return Some(format!(
                "a trajectory dmpscope exported ({name}), not a demonstration"
            ));
        }
        let asked = self
            .options
            .streams
            .topics
            .iter()
            .any(|p| crate::load::options::matches_stream(p, &ch.topic));
        (regenerated && !asked).then(|| {
            "a path dmpscope regenerated, not a demonstration; --topic '/regen/*' loads it"
                .to_owned()
        })
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
        let data: std::borrow::Cow<'_, [u8]> = if channel.cdr && data.starts_with(&ZSTD_MAGIC) {
            channel.compressed += 1;
            match inflate(data) {
                Ok(bytes) => bytes.into(),
                Err(reason) => {
                    self.pending = Some(Error::Decode {
                        at: Location::file(label).topic(&channel.topic).sample(index),
                        reason,
                    });
                    return Ok(());
                }
            }
        } else {
            data.into()
        };
        let Channel {
            topic,
            decoder,
            unkeyed,
            keyed,
            ..
        } = channel;
        let mut sink = Sink {
            options,
            keys_seen: &mut self.keys_seen,
            tf: self.tf.as_mut(),
            log_time: i64::try_from(header.log_time).unwrap_or(i64::MAX),
            is_static: topic.ends_with("tf_static"),
            index,
            unkeyed,
            keyed,
            bad: None,
        };
        let decoded = decoder.decode(&data, &mut |sample| sink.take(sample));
        let bad = sink.bad;
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
        let (mut streams, names, notes) = gather(label, c.streams);
        let lost = match (&options.fixed_frame, c.tf.as_mut()) {
            (Some(fixed), Some(buffer)) => in_fixed_frames(
                &mut streams,
                buffer,
                fixed,
                options.up,
                label,
                &mut warnings,
            ),
            _ => Vec::new(),
        };
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
        if let Some(what) = unmatched_frames(&options.frames, &demos, &c.keys_seen) {
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

/// A message compressed by rosbag2's message compression (zstd), inflated.
fn inflate(data: &[u8]) -> std::result::Result<Vec<u8>, String> {
    zstd::stream::decode_all(data).map_err(|e| {
        format!(
            "the message is zstd-compressed (rosbag2 message compression) but does not \
             decompress ({e}); `ros2 bag decompress` writes an uncompressed copy"
        )
    })
}

/// Every channel's streams (keyed ones after their channel's own), sorted
/// by topic and key; the names dmpscope's own exports gave them; a note
/// per channel whose messages were compressed.
fn gather(
    label: &str,
    channels: Vec<Channel>,
) -> (Vec<Keyed>, BTreeMap<String, String>, Vec<String>) {
    let mut notes = Vec::new();
    let mut streams: Vec<Keyed> = Vec::new();
    let mut names: BTreeMap<String, String> = BTreeMap::new();
    for channel in channels {
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
    (streams, names, notes)
}

/// Where one message's samples go: the TF buffer, the stream of their key
/// (or the channel's own), each position and orientation turned z-up.
struct Sink<'a> {
    options: &'a LoadOptions,
    keys_seen: &'a mut std::collections::BTreeSet<String>,
    tf: Option<&'a mut crate::load::tf::TfBuffer>,
    log_time: i64,
    is_static: bool,
    /// The message's index on its channel.
    index: usize,
    unkeyed: &'a mut Stream,
    keyed: &'a mut BTreeMap<String, Stream>,
    /// The first sample with a non-finite position: its key and axis.
    bad: Option<(Option<String>, usize)>,
}

impl Sink<'_> {
    /// Takes one decoded sample.
    fn take(&mut self, sample: PoseSample<'_>) {
        let options = self.options;
        if let (Some(buffer), Some(parent), Some(child)) =
            (self.tf.as_deref_mut(), &sample.parent, &sample.key)
            && sample
                .position
                .iter()
                .chain(sample.orientation.iter().flatten())
                .all(|v| v.is_finite())
        {
            buffer.add(
                parent,
                child,
                sample.stamp_ns.unwrap_or(self.log_time),
                sample.position,
                sample.orientation.unwrap_or([0.0; 4]),
                self.is_static,
            );
        }
        if let Some(k) = &sample.key
            && !options.frames.is_empty()
        {
            if !self.keys_seen.contains(k.as_ref()) && self.keys_seen.len() < KEYS_NAMED {
                self.keys_seen.insert(k.clone().into_owned());
            }
            if !options.frames.iter().any(|f| f == k) {
                return;
            }
        }
        if let Some(axis) = sample.position.iter().position(|v| !v.is_finite()) {
            self.bad
                .get_or_insert((sample.key.map(|k| k.into_owned()), axis));
            return;
        }
        let stream = match sample.key {
            None => &mut *self.unkeyed,
            Some(k) => {
                if !self.keyed.contains_key(k.as_ref()) {
                    self.keyed.insert(k.clone().into_owned(), Stream::default());
                }
                match self.keyed.get_mut(k.as_ref()) {
                    Some(s) => s,
                    None => return,
                }
            }
        };
        stream.tf |= sample.parent.is_some();
        stream.stamps.push(sample.stamp_ns);
        stream.log_times.push(self.log_time);
        stream
            .positions
            .push(options.up.to_z_up(sample.position).into());
        let orientation = sample.orientation.and_then(crate::geom::quat_from_xyzw);
        stream
            .turns
            .record(self.index, sample.orientation, orientation.is_some());
        stream
            .orientations
            .push(orientation.map(|q| options.up.orientation_to_z_up(q)));
    }
}
