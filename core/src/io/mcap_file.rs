//! The MCAP loader: one pass over the file with mcap's sans-IO
//! [`LinearReader`], chunk CRCs checked, messages routed to their decoders,
//! one demo per topic (method.md sections 1 and 2.1-2.2).

use std::collections::BTreeMap;
use std::io::Read;

use mcap::records::Record;
use mcap::sans_io::linear_reader::{LinearReadEvent, LinearReader, LinearReaderOptions};

use super::{Decoder, decoder_for};
use crate::demo::{RawDemo, TimeSource};
use crate::error::{Error, Location, Result};

/// The largest single record the loader accepts; a declared length beyond it
/// is an error, never an allocation.
pub const RECORD_LENGTH_LIMIT: usize = 256 << 20;

/// The most bytes read from the input at once.
const READ_PIECE: usize = 1 << 20;

/// What one file gave.
#[derive(Clone, Debug, Default)]
pub struct Loaded {
    /// Demos in topic-name order.
    pub demos: Vec<RawDemo>,
    /// Topics seen but not read, with their schema names.
    pub skipped: Vec<(String, String)>,
}

/// Loads the demos of the MCAP file at `path`; `label` names it in errors.
pub fn load_path(path: &std::path::Path) -> Result<Loaded> {
    let label = path.display().to_string();
    let file = std::fs::File::open(path).map_err(|source| Error::Io {
        file: label.clone(),
        source,
    })?;
    load_reader(&label, std::io::BufReader::with_capacity(1 << 20, file))
}

/// Loads the demos of an MCAP file held in memory (a browser upload, a test).
pub fn load_bytes(label: &str, bytes: &[u8]) -> Result<Loaded> {
    load_reader(label, bytes)
}

struct TopicAcc {
    topic: String,
    decoder: Decoder,
    stamps: Vec<Option<i64>>,
    log_times: Vec<i64>,
    positions: Vec<[f64; 3]>,
}

/// Loads the demos of an MCAP stream; `label` names the file in errors and
/// in the demo names (`label:topic`, with only the file name of a path).
pub fn load_reader<R: Read>(label: &str, mut input: R) -> Result<Loaded> {
    let at = || Location::file(label);
    let mcap_err = |e: mcap::McapError| Error::Mcap {
        at: at(),
        reason: describe(&e),
    };
    // Chunk CRCs are checked before any of a chunk's messages are handed out,
    // so a corrupt chunk is reported as corrupt, not as a bad message.
    let options = LinearReaderOptions::default()
        .with_prevalidate_chunk_crcs(true)
        .with_record_length_limit(RECORD_LENGTH_LIMIT);
    let mut reader = LinearReader::new_with_options(options);
    // Schema id -> (name, encoding); channel id -> accumulator or skip note.
    let mut schemas: BTreeMap<u16, (String, String)> = BTreeMap::new();
    let mut channels: BTreeMap<u16, Option<TopicAcc>> = BTreeMap::new();
    let mut skipped: Vec<(String, String)> = Vec::new();

    while let Some(event) = reader.next_event() {
        match event.map_err(mcap_err)? {
            LinearReadEvent::ReadRequest(need) => {
                // `insert` zero-fills what it is asked for: ask in bounded
                // pieces so a declared length is never allocated up front.
                let buf = reader.insert(need.min(READ_PIECE));
                let n = read_some(&mut input, buf).map_err(|source| Error::Io {
                    file: label.to_owned(),
                    source,
                })?;
                reader.notify_read(n);
            }
            LinearReadEvent::Record { opcode, data } => {
                match mcap::parse_record(opcode, data).map_err(mcap_err)? {
                    Record::Schema { header, .. } => {
                        schemas.insert(header.id, (header.name, header.encoding));
                    }
                    Record::Channel(ch) => {
                        if channels.contains_key(&ch.id) {
                            continue;
                        }
                        let (schema_name, schema_encoding) =
                            schemas.get(&ch.schema_id).cloned().unwrap_or_default();
                        let acc = decoder_for(&ch.message_encoding, &schema_encoding, &schema_name)
                            .map(|decoder| TopicAcc {
                                topic: ch.topic.clone(),
                                decoder,
                                stamps: Vec::new(),
                                log_times: Vec::new(),
                                positions: Vec::new(),
                            });
                        if acc.is_none() {
                            let schema = if schema_name.is_empty() {
                                format!("no schema, {}", ch.message_encoding)
                            } else {
                                schema_name
                            };
                            skipped.push((ch.topic.clone(), schema));
                        }
                        channels.insert(ch.id, acc);
                    }
                    Record::Message { header, data } => {
                        let Some(slot) = channels.get_mut(&header.channel_id) else {
                            return Err(Error::Mcap {
                                at: at(),
                                reason: format!(
                                    "message on channel {} that was never declared",
                                    header.channel_id
                                ),
                            });
                        };
                        let Some(acc) = slot else { continue };
                        let index = acc.positions.len();
                        let sample = (acc.decoder)(&data).map_err(|reason| Error::Decode {
                            at: at().topic(&acc.topic).sample(index),
                            reason,
                        })?;
                        for (axis, v) in sample.position.iter().enumerate() {
                            if !v.is_finite() {
                                return Err(Error::NonFinite {
                                    at: at().topic(&acc.topic).sample(index),
                                    field: ["position.x", "position.y", "position.z"][axis],
                                });
                            }
                        }
                        acc.stamps.push(sample.stamp_ns);
                        acc.log_times
                            .push(i64::try_from(header.log_time).unwrap_or(i64::MAX));
                        acc.positions.push(sample.position);
                    }
                    _ => {}
                }
            }
        }
    }

    let file_name = std::path::Path::new(label)
        .file_name()
        .map_or_else(|| label.to_owned(), |n| n.to_string_lossy().into_owned());
    let mut demos: Vec<RawDemo> = channels
        .into_values()
        .flatten()
        .filter(|acc| !acc.positions.is_empty())
        .map(|acc| finish_topic(label, &file_name, acc))
        .collect();
    demos.sort_by(|a, b| a.topic.cmp(&b.topic));
    skipped.sort();
    if demos.is_empty() {
        return Err(Error::NoDemos {
            file: label.to_owned(),
            skipped,
        });
    }
    Ok(Loaded { demos, skipped })
}

/// Chooses the time source of one topic (method.md section 2.1): header
/// stamps, unless one is missing or all are zero, then log time.
fn finish_topic(label: &str, file_name: &str, acc: TopicAcc) -> RawDemo {
    let stamps: Option<Vec<i64>> = acc.stamps.iter().copied().collect();
    let (stamps_ns, time_source) = match stamps {
        Some(s) if s.iter().any(|&v| v != 0) => (s, TimeSource::HeaderStamp),
        _ => (acc.log_times, TimeSource::LogTime),
    };
    RawDemo {
        name: format!("{file_name}:{}", acc.topic),
        file: label.to_owned(),
        topic: acc.topic,
        stamps_ns,
        positions: acc.positions,
        time_source,
    }
}

/// Reads what is available, retrying on interruption; 0 means end of input.
fn read_some<R: Read>(input: &mut R, buf: &mut [u8]) -> std::io::Result<usize> {
    loop {
        match input.read(buf) {
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            other => return other,
        }
    }
}

/// The reader's error in words a user can act on.
fn describe(e: &mcap::McapError) -> String {
    use mcap::McapError as E;
    match e {
        E::BadMagic => "it does not start with the MCAP magic bytes".to_owned(),
        E::UnexpectedEof => "the file is truncated (it ends in the middle of a record)".to_owned(),
        E::BadChunkCrc { saved, calculated } => format!(
            "a chunk's CRC does not match (stored {saved:08x}, computed {calculated:08x}): the file is corrupt"
        ),
        E::RecordTooLarge { opcode, len } => format!(
            "a record (opcode {opcode:#04x}) declares {len} bytes, more than the {RECORD_LENGTH_LIMIT}-byte limit"
        ),
        E::ChunkTooLarge(len) => format!("a chunk declares {len} bytes, more than the limit"),
        other => other.to_string(),
    }
}
