//! ROS 1 bags (format 2.0), read over random access
//! ([`crate::load::access`]), so the same code serves a file, a folder of
//! bags and a browser's file read in slices.
//!
//! A bag is a sequence of records, each a header (fields `name=value`, one
//! of them the opcode `op`) and data. Chunks (uncompressed, bz2 or lz4) hold
//! the connection records (topic, message type, message definition) and the
//! messages; the index section at the end repeats the connections and lists
//! the chunks with the connections each holds. Where the bag has its index
//! the reader reads it first and then only the chunks that hold a
//! connection dmpscope reads (of an uncompressed chunk only those
//! messages, from the index records after it); without one (a recording
//! killed: no index, a last chunk cut short) it walks the records in order,
//! as far as they are valid, with a warning. Each connection becomes a
//! channel of the shared [`Collector`], whose ROS 1 decoders, TF buffer
//! and stream finishing are the MCAP reader's.

use std::borrow::Cow;
use std::collections::BTreeMap;
use std::io::Read;

use crate::error::{Error, Location, Result};
use crate::load::access::{ReadAt, SliceAt, block_on};
use crate::load::collect::{Collector, Loaded};
use crate::load::mcap::RECORD_LENGTH_LIMIT;
use crate::load::mcap::linear::Window;
use crate::load::options::LoadOptions;

/// The first bytes of a format 2.0 bag.
pub const BAG_MAGIC: &[u8] = b"#ROSBAG V2.0\n";

/// Record opcodes (the `op` header field).
mod op {
    pub const MESSAGE_DATA: u8 = 0x02;
    pub const BAG_HEADER: u8 = 0x03;
    pub const INDEX_DATA: u8 = 0x04;
    pub const CHUNK: u8 = 0x05;
    pub const CHUNK_INFO: u8 = 0x06;
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
    block_on(read_bag(label, &mut SliceAt(bytes), options))
}

/// The bytes of the record at `pos`, through a window on the source, and
/// the position after it; `Cut::Short` where the source ends inside it.
async fn record_bytes<'w, R: ReadAt>(
    w: &'w mut Window,
    access: &mut R,
    pos: u64,
) -> std::result::Result<&'w [u8], Cut> {
    let short = |_| Cut::Short;
    let head = w.get(access, pos, 4).await.map_err(short)?;
    let header_len = le32(head, 0).ok_or(Cut::Short)?;
    if header_len > RECORD_LENGTH_LIMIT {
        return Err(Cut::Bad(format!(
            "a record header declares {header_len} bytes, more than the limit"
        )));
    }
    let head = w.get(access, pos, 8 + header_len).await.map_err(short)?;
    let data_len = le32(head, 4 + header_len).ok_or(Cut::Short)?;
    if data_len > RECORD_LENGTH_LIMIT {
        return Err(Cut::Bad(format!(
            "a record declares {data_len} bytes of data, more than the limit"
        )));
    }
    let total = 8 + header_len + data_len;
    let bytes = w.get(access, pos, total).await.map_err(short)?;
    if bytes.len() < total {
        return Err(Cut::Short);
    }
    Ok(bytes)
}

/// Reads the demos of the ROS 1 bag `access` holds; `label` names the file.
pub async fn read_bag<R: ReadAt>(
    label: &str,
    access: &mut R,
    options: &LoadOptions,
) -> Result<Loaded> {
    let at = || Location::file(label);
    let magic = access
        .read_at(0, BAG_MAGIC.len())
        .await
        .map_err(|reason| Error::Io {
            file: label.to_owned(),
            reason,
        })?;
    if magic != BAG_MAGIC {
        return Err(Error::Bag {
            at: at(),
            reason: if magic.starts_with(b"#ROSBAG V1") {
                "a ROS 1 bag of format 1.x; `rosbag reindex`/`rosbag fix` writes format 2.0"
                    .to_owned()
            } else {
                "not a ROS 1 bag: it does not start with #ROSBAG V2.0".to_owned()
            },
        });
    }
    let mut c = Collector::new(label, options);
    if let Some(index) = bag_index(access).await {
        let mut walk = Walk::default();
        read_indexed(&mut c, &mut walk, access, &index)
            .await
            .map_err(|reason| Error::Bag { at: at(), reason })?;
        if let Some(e) = c.take_pending() {
            return Err(e);
        }
        return finish(c, walk, None, label);
    }
    walk_bag(c, access, label).await
}

/// Walks the records of a bag in order, as far as they are valid.
async fn walk_bag<R: ReadAt>(mut c: Collector<'_>, access: &mut R, label: &str) -> Result<Loaded> {
    let at = || Location::file(label);
    let mut walk = Walk::default();
    let mut pos = BAG_MAGIC.len() as u64;
    let mut truncated = None;
    let mut w = Window::new();
    loop {
        if w.get(access, pos, 1).await.map_or(true, <[u8]>::is_empty) {
            break;
        }
        let bytes = match record_bytes(&mut w, access, pos).await {
            Ok(b) => b,
            Err(Cut::Short) => {
                truncated = Some(pos as usize);
                break;
            }
            // Past an open chunk of a killed recording the bytes are its
            // compressed contents, not records: the tail.
            Err(Cut::Bad(_)) if walk.index_pos == 0 && walk.messages > 0 => {
                truncated = Some(pos as usize);
                break;
            }
            Err(Cut::Bad(reason)) => {
                return Err(Error::Bag {
                    at: at(),
                    reason: format!("{reason} (byte {pos}): the bag is corrupt"),
                });
            }
        };
        let (record, len) = match record_at(bytes, 0) {
            Ok(r) => r,
            Err(Cut::Bad(reason)) if walk.index_pos != 0 || walk.messages == 0 => {
                return Err(Error::Bag {
                    at: at(),
                    reason: format!("{reason} (byte {pos}): the bag is corrupt"),
                });
            }
            Err(_) => {
                truncated = Some(pos as usize);
                break;
            }
        };
        if walk.index_pos == 0 && open_compressed_chunk(&record) {
            // rosbag writes a chunk's header with size 0 and fills it in
            // when the chunk closes: this one never closed.
            truncated = Some(pos as usize);
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
                truncated = Some(pos as usize);
                break;
            }
            other => other?,
        }
        pos += len as u64;
    }
    if let Some(e) = c.take_pending() {
        return Err(e);
    }
    finish(c, walk, truncated, label)
}

/// What a bag's index section says: its connections (their records'
/// bytes) and its chunks (position, and the connections each holds).
struct BagIndex {
    connections: Vec<Vec<u8>>,
    chunks: Vec<(u64, Vec<u32>)>,
    index_pos: u64,
    chunk_count: u64,
}

/// The bag's index, when it has one that holds together (else the walk
/// reads it).
async fn bag_index<R: ReadAt>(access: &mut R) -> Option<BagIndex> {
    let size = access.size()?;
    let mut w = Window::new();
    let header = record_bytes(&mut w, access, BAG_MAGIC.len() as u64)
        .await
        .ok()?;
    let (record, _) = record_at(header, 0).ok()?;
    if record.op() != Some(op::BAG_HEADER) {
        return None;
    }
    let index_pos = record.u64("index_pos").ok()?;
    let chunk_count = u64::from(record.u32("chunk_count").ok()?);
    if index_pos == 0 || index_pos >= size || size - index_pos > RECORD_LENGTH_LIMIT as u64 {
        return None;
    }
    let bytes = access
        .read_at(index_pos, (size - index_pos) as usize)
        .await
        .ok()?;
    let mut index = BagIndex {
        connections: Vec::new(),
        chunks: Vec::new(),
        index_pos,
        chunk_count,
    };
    let mut pos = 0;
    while pos < bytes.len() {
        let (record, next) = record_at(&bytes, pos).ok()?;
        match record.op() {
            Some(op::CONNECTION) => index.connections.push(bytes[pos..next].to_vec()),
            Some(op::CHUNK_INFO) => {
                let chunk_pos = record.u64("chunk_pos").ok()?;
                let conns = record
                    .data
                    .chunks_exact(8)
                    .filter_map(|e| le32(e, 0).map(|c| c as u32))
                    .collect();
                index.chunks.push((chunk_pos, conns));
            }
            _ => {}
        }
        pos = next;
    }
    index.chunks.sort_by_key(|c| c.0);
    let fits = index
        .chunks
        .iter()
        .all(|&(p, _)| p > BAG_MAGIC.len() as u64 && p < index_pos);
    (fits && !index.chunks.is_empty()).then_some(index)
}

/// Reads the chunks of an indexed bag that hold a connection the collector
/// reads: an error names the chunk (1-based, in file order).
async fn read_indexed<R: ReadAt>(
    c: &mut Collector<'_>,
    walk: &mut Walk,
    access: &mut R,
    index: &BagIndex,
) -> std::result::Result<(), String> {
    walk.index_pos = index.index_pos;
    walk.chunk_count = index.chunk_count;
    for bytes in &index.connections {
        let (record, _) =
            record_at(bytes, 0).map_err(|_| "a connection record is cut short".to_owned())?;
        connection(c, walk, &record).map_err(|e| e.to_string())?;
    }
    let mut w = Window::new();
    for (k, (chunk_pos, conns)) in index.chunks.iter().enumerate() {
        // `take` counts a chunk it opens; the others are counted here.
        walk.chunks = k;
        let wanted = conns.is_empty()
            || conns
                .iter()
                .any(|conn| walk.ids.get(conn).is_none_or(|&id| c.reads(id)));
        if wanted {
            let next = index.chunks.get(k + 1).map_or(index.index_pos, |n| n.0);
            read_chunk(c, walk, access, &mut w, *chunk_pos, next)
                .await
                .map_err(|e| {
                    format!(
                        "chunk {}: {e} (the record at byte {chunk_pos}); the bag is corrupt",
                        k + 1
                    )
                })?;
        }
        walk.chunks = k + 1;
    }
    Ok(())
}

/// Reads one chunk at `pos` (its index records end at `next`): an
/// uncompressed chunk's wanted messages where its index records list them,
/// else the whole chunk.
async fn read_chunk<R: ReadAt>(
    c: &mut Collector<'_>,
    walk: &mut Walk,
    access: &mut R,
    w: &mut Window,
    pos: u64,
    next: u64,
) -> std::result::Result<(), String> {
    let head = w.get(access, pos, 4).await.map_err(|e| e.to_string())?;
    let header_len = le32(head, 0).ok_or("cut short")?;
    if header_len > RECORD_LENGTH_LIMIT {
        return Err("its header declares more bytes than the limit".into());
    }
    let head = w
        .get(access, pos, 8 + header_len)
        .await
        .map_err(|e| e.to_string())?;
    let header = fields(head.get(4..4 + header_len).ok_or("cut short")?)?;
    let compression = header
        .get(&b"compression"[..])
        .map(|v| String::from_utf8_lossy(v).into_owned());
    let data_len = le32(head, 4 + header_len).ok_or("cut short")? as u64;
    let data_at = pos + 8 + header_len as u64;
    let end = data_at + data_len;
    if compression.as_deref() == Some("none") && end <= next {
        let read: BTreeMap<u32, bool> = walk
            .ids
            .iter()
            .map(|(&conn, &id)| (conn, c.reads(id)))
            .collect();
        let offsets = wanted_offsets(&read, access, end, next).await?;
        if let Some(offsets) = offsets {
            return plain_messages(c, walk, access, w, data_at, data_len, offsets).await;
        }
    }
    let bytes = record_bytes(w, access, pos)
        .await
        .map_err(|cut| match cut {
            Cut::Short => "the bag ends inside it".to_owned(),
            Cut::Bad(reason) => reason,
        })?;
    let (record, _) = record_at(bytes, 0).map_err(|_| "cut short".to_owned())?;
    let prefix = format!("chunk {}: ", walk.chunks + 1);
    take(c, walk, &record).map_err(|e| e.trim_start_matches(&prefix).to_owned())
}

/// The offsets (in the chunk's records) of the messages on connections the
/// collector reads, from the index records between `from` and `to`;
/// `None` when they do not hold together (the chunk is then read whole).
async fn wanted_offsets<R: ReadAt>(
    read: &BTreeMap<u32, bool>,
    access: &mut R,
    from: u64,
    to: u64,
) -> std::result::Result<Option<Vec<u32>>, String> {
    if to - from > RECORD_LENGTH_LIMIT as u64 {
        return Ok(None);
    }
    let bytes = access
        .read_at(from, (to - from) as usize)
        .await
        .map_err(|e| e.to_string())?;
    let mut offsets = Vec::new();
    let mut pos = 0;
    while pos < bytes.len() {
        let Ok((record, next)) = record_at(&bytes, pos) else {
            return Ok(None);
        };
        if record.op() != Some(op::INDEX_DATA) {
            return Ok(None);
        }
        let Ok(conn) = record.u32("conn") else {
            return Ok(None);
        };
        match read.get(&conn) {
            Some(false) => {}
            Some(true) => offsets.extend(
                record
                    .data
                    .chunks_exact(12)
                    .filter_map(|e| le32(e, 8).map(|o| o as u32)),
            ),
            None => return Ok(None),
        }
        pos = next;
    }
    offsets.sort_unstable();
    offsets.dedup();
    Ok(Some(offsets))
}

/// The messages at `offsets` in an uncompressed chunk's records.
#[allow(clippy::too_many_arguments)]
async fn plain_messages<R: ReadAt>(
    c: &mut Collector<'_>,
    walk: &mut Walk,
    access: &mut R,
    w: &mut Window,
    data_at: u64,
    data_len: u64,
    offsets: Vec<u32>,
) -> std::result::Result<(), String> {
    for off in offsets {
        let off = u64::from(off);
        if off >= data_len {
            return Err(format!(
                "an index record points at byte {off} of {data_len}"
            ));
        }
        let bytes = record_bytes(w, access, data_at + off)
            .await
            .map_err(|cut| match cut {
                Cut::Short => "the bag ends inside it".to_owned(),
                Cut::Bad(reason) => reason,
            })?;
        if off + bytes.len() as u64 > data_len {
            return Err(format!("a message at byte {off} runs past the chunk"));
        }
        let (record, _) = record_at(bytes, 0).map_err(|_| "cut short".to_owned())?;
        if record.op() != Some(op::MESSAGE_DATA) {
            return Err(format!(
                "an index record points at byte {off}, which is not a message"
            ));
        }
        take_inner(c, walk, &record)?;
    }
    Ok(())
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
    first_bag_record(&compression, data, size)?;
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

/// Checks the first record of a compressed chunk before the rest is
/// decompressed: its header's length is neither zero nor past the declared
/// size (a chunk of zeros, the usual bomb, is refused at its first bytes).
fn first_bag_record(
    compression: &str,
    data: &[u8],
    size: usize,
) -> std::result::Result<(), String> {
    let mut head = [0u8; 4];
    let read = match compression {
        "bz2" => bzip2::read::BzDecoder::new(data).read_exact(&mut head),
        "lz4" => lz4_flex::frame::FrameDecoder::new(data).read_exact(&mut head),
        _ => return Ok(()),
    };
    if size == 0 {
        return Ok(());
    }
    read.map_err(|e| format!("a {compression} chunk does not decompress ({e})"))?;
    let header_len = u32::from_le_bytes(head) as usize;
    if header_len == 0 || header_len.saturating_add(8) > size {
        return Err(format!(
            "a {compression} chunk begins with a record header of {header_len} bytes in {size} \
             declared: not a record stream"
        ));
    }
    Ok(())
}
