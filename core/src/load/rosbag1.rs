//! ROS 1 bags (format 2.0), read from bytes so the same code serves a file,
//! a folder of bags and a browser upload.
//!
//! A bag is a sequence of records, each a header (fields `name=value`, one
//! of them the opcode `op`) and data. The reader walks them in order: chunks
//! (uncompressed, bz2 or lz4) hold the connection records (topic, message
//! type, message definition) and the messages; the index section at the end
//! repeats the connections and lists the chunks. Walking in order needs no
//! index, so a bag whose recording was killed (no index, a last chunk cut
//! short) is read as far as it is valid, with a warning. Each connection
//! becomes a channel of the shared [`Collector`], whose ROS 1 decoders, TF
//! buffer and stream finishing are the MCAP reader's.

use std::borrow::Cow;
use std::collections::BTreeMap;
use std::io::Read;

use crate::error::{Error, Location, Result};
use crate::load::collect::Collector;
use crate::load::collect::Loaded;
use crate::load::mcap::RECORD_LENGTH_LIMIT;
use crate::load::options::LoadOptions;

/// The first bytes of a format 2.0 bag.
pub const BAG_MAGIC: &[u8] = b"#ROSBAG V2.0\n";

/// Record opcodes (the `op` header field).
mod op {
    pub const MESSAGE_DATA: u8 = 0x02;
    pub const BAG_HEADER: u8 = 0x03;
    pub const CHUNK: u8 = 0x05;
    pub const CONNECTION: u8 = 0x07;
}

/// One record: its header fields and its data.
struct Record<'a> {
    header: BTreeMap<&'a [u8], &'a [u8]>,
    data: &'a [u8],
}

/// Why a record could not be taken at some position.
enum Cut {
    /// The bytes end inside it (a recording killed mid-write).
    Short,
    /// It is malformed: the reason.
    Bad(String),
}

impl Record<'_> {
    fn op(&self) -> Option<u8> {
        self.header.get(&b"op"[..]).and_then(|v| v.first().copied())
    }

    fn u32(&self, name: &str) -> std::result::Result<u32, String> {
        let v = self.field(name)?;
        let bytes: [u8; 4] = v
            .try_into()
            .map_err(|_| format!("header field {name} has {} bytes, not 4", v.len()))?;
        Ok(u32::from_le_bytes(bytes))
    }

    fn u64(&self, name: &str) -> std::result::Result<u64, String> {
        let v = self.field(name)?;
        let bytes: [u8; 8] = v
            .try_into()
            .map_err(|_| format!("header field {name} has {} bytes, not 8", v.len()))?;
        Ok(u64::from_le_bytes(bytes))
    }

    fn text(&self, name: &str) -> std::result::Result<String, String> {
        Ok(String::from_utf8_lossy(self.field(name)?).into_owned())
    }

    fn field(&self, name: &str) -> std::result::Result<&[u8], String> {
        self.header
            .get(name.as_bytes())
            .copied()
            .ok_or_else(|| format!("the record has no {name} field"))
    }
}

/// A little-endian u32 at `at`, if the bytes hold one.
fn le32(bytes: &[u8], at: usize) -> Option<usize> {
    let b: [u8; 4] = bytes.get(at..at.checked_add(4)?)?.try_into().ok()?;
    Some(u32::from_le_bytes(b) as usize)
}

/// The record at `at` and the position after it.
fn record_at(bytes: &[u8], at: usize) -> std::result::Result<(Record<'_>, usize), Cut> {
    let header_len = le32(bytes, at).ok_or(Cut::Short)?;
    if header_len > RECORD_LENGTH_LIMIT {
        return Err(Cut::Bad(format!(
            "a record header declares {header_len} bytes, more than the limit"
        )));
    }
    let header_start = at + 4;
    let header = bytes
        .get(header_start..header_start + header_len)
        .ok_or(Cut::Short)?;
    let data_len = le32(bytes, header_start + header_len).ok_or(Cut::Short)?;
    if data_len > RECORD_LENGTH_LIMIT {
        return Err(Cut::Bad(format!(
            "a record declares {data_len} bytes of data, more than the limit"
        )));
    }
    let data_start = header_start + header_len + 4;
    let data = bytes
        .get(data_start..data_start + data_len)
        .ok_or(Cut::Short)?;
    let header = fields(header).map_err(Cut::Bad)?;
    Ok((Record { header, data }, data_start + data_len))
}

/// The `name=value` fields of a record header (or of a connection's data).
fn fields(mut bytes: &[u8]) -> std::result::Result<BTreeMap<&[u8], &[u8]>, String> {
    let mut out = BTreeMap::new();
    while !bytes.is_empty() {
        let len = le32(bytes, 0).ok_or("a header field's length is cut short")?;
        let end = len
            .checked_add(4)
            .ok_or("a header field's length overflows")?;
        let field = bytes
            .get(4..end)
            .ok_or_else(|| format!("a header field declares {len} bytes past the header's end"))?;
        let eq = field
            .iter()
            .position(|&b| b == b'=')
            .ok_or("a header field has no '='")?;
        out.insert(&field[..eq], &field[eq + 1..]);
        bytes = &bytes[end..];
    }
    Ok(out)
}

/// What the walk found besides messages.
#[derive(Default)]
struct Walk {
    chunks: usize,
    messages: usize,
    /// The bag header's index position (0: no index) and chunk count.
    index_pos: u64,
    chunk_count: u64,
    /// Connection id -> the collector's channel id.
    ids: BTreeMap<u32, u16>,
    warnings: Vec<String>,
}

/// Loads the demos of a ROS 1 bag held in memory; `label` names the file.
pub fn load_bag_bytes(label: &str, bytes: &[u8], options: &LoadOptions) -> Result<Loaded> {
    let at = || Location::file(label);
    if !bytes.starts_with(BAG_MAGIC) {
        return Err(Error::Bag {
            at: at(),
            reason: if bytes.starts_with(b"#ROSBAG V1") {
                "a ROS 1 bag of format 1.x; `rosbag reindex`/`rosbag fix` writes format 2.0"
                    .to_owned()
            } else {
                "not a ROS 1 bag: it does not start with #ROSBAG V2.0".to_owned()
            },
        });
    }
    let mut c = Collector::new(label, options);
    let mut walk = Walk::default();
    let mut pos = BAG_MAGIC.len();
    let mut truncated = None;
    while pos < bytes.len() {
        let (record, next) = match record_at(bytes, pos) {
            Ok(r) => r,
            Err(Cut::Short) => {
                truncated = Some(pos);
                break;
            }
            // Past an open chunk of a killed recording the bytes are its
            // compressed contents, not records: the tail.
            Err(Cut::Bad(_)) if walk.index_pos == 0 && walk.messages > 0 => {
                truncated = Some(pos);
                break;
            }
            Err(Cut::Bad(reason)) => {
                return Err(Error::Bag {
                    at: at(),
                    reason: format!("{reason} (byte {pos}): the bag is corrupt"),
                });
            }
        };
        if walk.index_pos == 0 && open_compressed_chunk(&record) {
            // rosbag writes a chunk's header with size 0 and fills it in
            // when the chunk closes: this one never closed.
            truncated = Some(pos);
            break;
        }
        let taken = take(&mut c, &mut walk, &record).map_err(|reason| Error::Bag {
            at: at(),
            reason: format!("{reason} (the record at byte {pos}); the bag is corrupt"),
        });
        match taken {
            // A last chunk that does not open in a bag whose recording was
            // killed is the cut-off tail.
            Err(_) if walk.index_pos == 0 && record.op() == Some(op::CHUNK) => {
                truncated = Some(pos);
                break;
            }
            other => other?,
        }
        pos = next;
    }
    if let Some(e) = c.take_pending() {
        return Err(e);
    }
    finish(c, walk, truncated, label)
}

/// A compressed chunk whose header still says size 0 and holds no data (a
/// recording killed while writing it). An uncompressed one's records follow
/// its header as plain records, which the walk reads on.
fn open_compressed_chunk(record: &Record<'_>) -> bool {
    record.op() == Some(op::CHUNK)
        && record.data.is_empty()
        && record.text("compression").is_ok_and(|c| c != "none")
}

/// The warnings of the walk, then the collector's demos.
fn finish(
    c: Collector<'_>,
    mut walk: Walk,
    truncated: Option<usize>,
    label: &str,
) -> Result<Loaded> {
    if walk.index_pos == 0 {
        walk.warnings.push(format!(
            "{label}: the bag has no index (its recording was not closed: killed, or still \
             being written); read as far as it is valid: {} chunks, {} messages",
            walk.chunks, walk.messages
        ));
    } else if (walk.chunks as u64) < walk.chunk_count {
        walk.warnings.push(format!(
            "{label}: the bag header lists {} chunks, {} were found",
            walk.chunk_count, walk.chunks
        ));
    }
    let cut = truncated.map(|pos| {
        format!(
            "{label}: the bag is truncated (it ends inside a record at byte {pos}); kept the \
             {} messages before it, the rest is lost",
            walk.messages
        )
    });
    if cut.is_some() && walk.messages == 0 {
        return Err(Error::Bag {
            at: Location::file(label),
            reason: "the bag is truncated before its first message".to_owned(),
        });
    }
    c.finish(cut, walk.warnings)
}

/// Takes one top-level record.
fn take(
    c: &mut Collector<'_>,
    walk: &mut Walk,
    record: &Record<'_>,
) -> std::result::Result<(), String> {
    match record.op() {
        Some(op::BAG_HEADER) => {
            walk.index_pos = record.u64("index_pos")?;
            walk.chunk_count = u64::from(record.u32("chunk_count")?);
        }
        Some(op::CHUNK) => {
            walk.chunks += 1;
            let inflated = open_chunk(record).map_err(|e| format!("chunk {}: {e}", walk.chunks))?;
            let mut pos = 0;
            while pos < inflated.len() {
                let (inner, next) = record_at(&inflated, pos).map_err(|cut| match cut {
                    Cut::Short => format!("chunk {} ends inside a record", walk.chunks),
                    Cut::Bad(reason) => format!("chunk {}: {reason}", walk.chunks),
                })?;
                take_inner(c, walk, &inner)?;
                pos = next;
            }
        }
        // Connections again in the index section; messages outside chunks
        // (not written by rosbag, but valid).
        Some(op::CONNECTION | op::MESSAGE_DATA) => take_inner(c, walk, record)?,
        _ => {}
    }
    Ok(())
}

/// Takes a connection or a message.
fn take_inner(
    c: &mut Collector<'_>,
    walk: &mut Walk,
    record: &Record<'_>,
) -> std::result::Result<(), String> {
    match record.op() {
        Some(op::CONNECTION) => connection(c, walk, record).map_err(|e| e.to_string()),
        Some(op::MESSAGE_DATA) => {
            let conn = record.u32("conn")?;
            let time = record.u64("time")?;
            // `time` is seconds then nanoseconds, each a little-endian u32.
            let ns = (time & 0xffff_ffff) * 1_000_000_000 + (time >> 32);
            let Some(&channel_id) = walk.ids.get(&conn) else {
                return Err(format!(
                    "a message on connection {conn}, which was never declared"
                ));
            };
            walk.messages += 1;
            let header = mcap::records::MessageHeader {
                channel_id,
                sequence: 0,
                log_time: ns,
                publish_time: ns,
            };
            c.message(&header, record.data).map_err(|e| e.to_string())
        }
        _ => Ok(()),
    }
}

/// Declares a connection as a channel with its own schema (its type and
/// message definition), once.
fn connection(c: &mut Collector<'_>, walk: &mut Walk, record: &Record<'_>) -> Result<()> {
    let bad = |reason: String| Error::Bag {
        at: c.at(),
        reason: format!("a connection record: {reason}"),
    };
    let conn = record.u32("conn").map_err(bad)?;
    if walk.ids.contains_key(&conn) {
        return Ok(());
    }
    let id =
        u16::try_from(walk.ids.len()).map_err(|_| bad("more than 65535 connections".into()))?;
    let topic = record.text("topic").map_err(bad)?;
    let data = fields(record.data).map_err(bad)?;
    let get = |name: &str| {
        data.get(name.as_bytes())
            .map(|v| String::from_utf8_lossy(v).into_owned())
            .unwrap_or_default()
    };
    c.schema(
        id,
        get("type"),
        "ros1msg".into(),
        get("message_definition").into_bytes(),
    );
    walk.ids.insert(conn, id);
    c.channel(mcap::records::Channel {
        id,
        schema_id: id,
        topic,
        message_encoding: "ros1".into(),
        metadata: BTreeMap::new(),
    })
}

/// A chunk's records, decompressed (at most the size its header states);
/// an uncompressed chunk's are its own bytes.
fn open_chunk<'a>(record: &Record<'a>) -> std::result::Result<Cow<'a, [u8]>, String> {
    let compression = record.text("compression")?;
    let size = record.u32("size")? as usize;
    if size > RECORD_LENGTH_LIMIT {
        return Err(format!(
            "a chunk declares {size} bytes, more than the limit"
        ));
    }
    let data = record.data;
    // Reserve what the compressed bytes can plausibly give, not what a
    // header claims.
    let mut out = Vec::with_capacity(size.min(data.len().saturating_mul(16)));
    let read = match compression.as_str() {
        "none" => return Ok(Cow::Borrowed(data)),
        "bz2" => bzip2::read::BzDecoder::new(data)
            .take(size as u64 + 1)
            .read_to_end(&mut out),
        "lz4" => lz4_flex::frame::FrameDecoder::new(data)
            .take(size as u64 + 1)
            .read_to_end(&mut out),
        other => {
            return Err(format!(
                "a chunk compressed with {other:?}, which ROS 1 does not write"
            ));
        }
    };
    read.map_err(|e| format!("a {compression} chunk does not decompress ({e})"))?;
    if out.len() != size {
        return Err(format!(
            "a {compression} chunk decompresses to {} bytes, its header says {size}",
            out.len()
        ));
    }
    Ok(Cow::Owned(out))
}
