//! An MCAP file read through its index: the footer and the summary first
//! (schemas, channels, chunk indexes), then only the chunks whose message
//! indexes name a channel that holds poses, in file order. A compressed
//! chunk is read whole and opened (several at once on every core); of an
//! uncompressed one only the pose messages' bytes are read, located by
//! the chunk's message indexes (a camera's images beside a tracker's
//! poses are never read: their CRC cannot be checked then). Every declared
//! size and offset is checked against the file before it is used; a
//! summary that does not hold together sends the reader to the walk of
//! [`super::linear`]. A chunk that is corrupt is skipped with a warning
//! when other chunks hold demos; the error when none does.

use std::collections::BTreeMap;

use mcap::records::{ChunkIndex, op};

use crate::error::{Error, Result};
use crate::load::access::ReadAt;
use crate::load::collect::{Collector, Loaded};
use crate::load::mcap::chunk::{self, ChunkHead, lengths_fit};
use crate::load::mcap::linear::{Batch, Window, record_head};
use crate::load::mcap::{MAGIC, RECORD_LENGTH_LIMIT};

/// The footer record with the end magic: opcode, length, summary start,
/// summary offset start, summary CRC, magic.
const FOOTER_LEN: u64 = 1 + 8 + 8 + 8 + 4 + 8;

/// Bytes read at once around an uncompressed chunk's pose messages.
const MESSAGE_WINDOW: usize = 8 << 10;

/// An uncompressed chunk at least this long is read message by message;
/// a shorter one is read whole (one read, and its CRC checked).
const PARTIAL_FROM: u64 = 1 << 20;

/// What the summary says: the schemas and channels, and the chunks.
pub(crate) struct Index {
    size: u64,
    schemas: BTreeMap<u16, (String, String, Vec<u8>)>,
    channels: BTreeMap<u16, mcap::records::Channel>,
    chunks: Vec<ChunkIndex>,
}

/// The summary of the file, or `None` when it has none that indexes its
/// chunks (or one that does not hold together).
pub(crate) async fn summary<R: ReadAt>(
    label: &str,
    access: &mut R,
    size: u64,
) -> Result<Option<Index>> {
    let io = |reason| Error::Io {
        file: label.to_owned(),
        reason,
    };
    if size < MAGIC.len() as u64 + FOOTER_LEN {
        return Ok(None);
    }
    let footer_at = size - FOOTER_LEN;
    let footer = access
        .read_at(footer_at, FOOTER_LEN as usize)
        .await
        .map_err(io)?;
    let start = access.read_at(0, MAGIC.len()).await.map_err(io)?;
    if footer.len() != FOOTER_LEN as usize
        || &footer[29..] != MAGIC
        || start != MAGIC
        || record_head(&footer) != Some((op::FOOTER, 20))
    {
        return Ok(None);
    }
    // The header record must hold together too, though nothing is read
    // of it: a file is either whole or read as the walk reads it.
    let header = access.read_at(MAGIC.len() as u64, 9).await.map_err(io)?;
    match record_head(&header) {
        Some((opcode, len)) if len > RECORD_LENGTH_LIMIT as u64 => {
            return Err(Error::Mcap {
                at: crate::error::Location::file(label),
                reason: super::describe(&mcap::McapError::RecordTooLarge { opcode, len }),
            });
        }
        Some((op::HEADER, len)) if MAGIC.len() as u64 + 9 + len <= footer_at => {}
        _ => return Ok(None),
    }
    let u64_at = |pos: usize| u64::from_le_bytes(footer[pos..pos + 8].try_into().unwrap_or([0; 8]));
    let summary_start = u64_at(9);
    let crc = u32::from_le_bytes(footer[25..29].try_into().unwrap_or([0; 4]));
    if summary_start < MAGIC.len() as u64
        || summary_start >= footer_at
        || footer_at - summary_start > RECORD_LENGTH_LIMIT as u64
    {
        return Ok(None);
    }
    let bytes = access
        .read_at(summary_start, (footer_at - summary_start) as usize)
        .await
        .map_err(io)?;
    if crc != 0 {
        let mut hasher = crc32fast::Hasher::new();
        hasher.update(&bytes);
        hasher.update(&footer[..25]);
        if hasher.finalize() != crc {
            return Ok(None);
        }
    }
    Ok(parse_summary(&bytes, size))
}

/// The schemas, channels and chunk indexes of a summary section.
fn parse_summary(bytes: &[u8], size: u64) -> Option<Index> {
    let mut index = Index {
        size,
        schemas: BTreeMap::new(),
        channels: BTreeMap::new(),
        chunks: Vec::new(),
    };
    let mut bad = false;
    let walked = chunk::walk(bytes, &mut |opcode, _, body| {
        if bad {
            return;
        }
        match opcode {
            op::SCHEMA | op::CHANNEL if lengths_fit(opcode, body).is_err() => bad = true,
            op::SCHEMA | op::CHANNEL => match mcap::parse_record(opcode, body) {
                Ok(mcap::records::Record::Schema { header, data }) => {
                    let value = (header.name, header.encoding, data.into_owned());
                    index.schemas.insert(header.id, value);
                }
                Ok(mcap::records::Record::Channel(ch)) => {
                    index.channels.insert(ch.id, ch);
                }
                _ => bad = true,
            },
            op::CHUNK_INDEX => match chunk_index(body) {
                Some(ci) => index.chunks.push(ci),
                None => bad = true,
            },
            _ => {}
        }
    });
    let usable = walked.is_ok() && !bad && !index.chunks.is_empty() && !index.channels.is_empty();
    usable.then_some(index)
}

/// A chunk index record, its lengths checked against the record.
fn chunk_index(body: &[u8]) -> Option<ChunkIndex> {
    let u64_at = |pos: usize| Some(u64::from_le_bytes(body.get(pos..pos + 8)?.try_into().ok()?));
    let u32_at = |pos: usize| Some(u32::from_le_bytes(body.get(pos..pos + 4)?.try_into().ok()?));
    let map_len = u32_at(32)? as usize;
    let map = body.get(36..36usize.checked_add(map_len)?)?;
    if !map_len.is_multiple_of(10) {
        return None;
    }
    let message_index_offsets = map
        .chunks_exact(10)
        .map(|e| {
            (
                u16::from_le_bytes([e[0], e[1]]),
                u64::from_le_bytes(e[2..10].try_into().unwrap_or([0; 8])),
            )
        })
        .collect();
    let mut pos = 36 + map_len;
    let message_index_length = u64_at(pos)?;
    pos += 8;
    let name_len = u32_at(pos)? as usize;
    let name = body.get(pos + 4..(pos + 4).checked_add(name_len)?)?;
    pos += 4 + name_len;
    Some(ChunkIndex {
        message_start_time: u64_at(0)?,
        message_end_time: u64_at(8)?,
        chunk_start_offset: u64_at(16)?,
        chunk_length: u64_at(24)?,
        message_index_offsets,
        message_index_length,
        compression: String::from_utf8(name.to_vec()).ok()?,
        compressed_size: u64_at(pos)?,
        uncompressed_size: u64_at(pos + 8)?,
    })
}

/// Why a chunk index cannot be followed, if it cannot: every offset and
/// size inside the file, every size within the limit.
fn check(ci: &ChunkIndex, size: u64) -> std::result::Result<(), String> {
    let end = ci.chunk_start_offset.checked_add(ci.chunk_length);
    let data = ci.compressed_data_offset().ok();
    let data_end = data.and_then(|d| d.checked_add(ci.compressed_size));
    match (end, data_end) {
        (Some(end), Some(data_end)) if end <= size && data_end <= end => {}
        _ => {
            return Err(format!(
                "its index places it at bytes {}..+{} of a {size}-byte file",
                ci.chunk_start_offset, ci.chunk_length
            ));
        }
    }
    if ci.uncompressed_size > RECORD_LENGTH_LIMIT as u64
        || ci.compressed_size > RECORD_LENGTH_LIMIT as u64
    {
        return Err(format!(
            "it declares {} bytes of records ({} compressed), more than the {RECORD_LENGTH_LIMIT}-byte limit",
            ci.uncompressed_size, ci.compressed_size
        ));
    }
    if ci.message_index_length > RECORD_LENGTH_LIMIT as u64 {
        return Err("its message indexes declare more bytes than the limit".to_owned());
    }
    Ok(())
}

/// Reads the chunks that hold the channels the collector reads.
pub(crate) async fn read<R: ReadAt>(
    mut c: Collector<'_>,
    access: &mut R,
    index: Index,
) -> Result<Loaded> {
    for (id, (name, encoding, data)) in index.schemas {
        c.schema(id, name, encoding, data);
    }
    for ch in index.channels.into_values() {
        c.channel(ch)?;
    }
    let mut chunks = index.chunks;
    chunks.sort_by_key(|ci| ci.chunk_start_offset);
    // One read per chunk, however often the summary lists it; chunks that
    // overlap do not hold together (each byte is read at most once).
    chunks.dedup_by(|b, a| a == b);
    let overlap = chunks.windows(2).any(|w| {
        w[0].chunk_start_offset.saturating_add(w[0].chunk_length) > w[1].chunk_start_offset
    });
    if overlap {
        return Err(Error::Mcap {
            at: c.at(),
            reason: "its summary lists chunks that overlap: the file is corrupt".to_owned(),
        });
    }
    let mut reading = Reading::default();
    for ci in &chunks {
        let wanted = ci.message_index_offsets.is_empty()
            || ci
                .message_index_offsets
                .keys()
                .any(|&id| c.reads(id) || !c.declared(id));
        if !wanted {
            continue;
        }
        if let Err(why) = check(ci, index.size) {
            reading.bad(&c, ci, why);
            continue;
        }
        if ci.compression.is_empty()
            && !ci.message_index_offsets.is_empty()
            && ci.compressed_size >= PARTIAL_FROM
        {
            reading.flush(&mut c)?;
            if let Err(e) = plain_messages(&mut c, access, ci).await {
                reading.failed(ci, e);
            }
        } else {
            let mut record = reading.batch.buffer();
            access
                .read_into(ci.chunk_start_offset, ci.chunk_length as usize, &mut record)
                .await
                .map_err(|reason| Error::Io {
                    file: c.label().to_owned(),
                    reason,
                })?;
            match as_indexed(&record, ci) {
                Ok(head) => {
                    let at = 9 + head.records_at;
                    reading.push(&mut c, ci, head, record, at)?;
                }
                Err(why) => reading.bad(&c, ci, why),
            }
        }
    }
    reading.flush(&mut c)?;
    reading.finish(c)
}

/// A chunk record read whole, checked against its index: its opcode, its
/// length, and the sizes and compression of its header; its header and
/// body.
fn as_indexed(record: &[u8], ci: &ChunkIndex) -> std::result::Result<ChunkHead, String> {
    let Some((opcode, len)) = record_head(record) else {
        return Err("the file ends inside it".to_owned());
    };
    if opcode != op::CHUNK || len != ci.chunk_length - 9 || record.len() as u64 != ci.chunk_length {
        return Err(format!(
            "a record of opcode {opcode:#04x} and {len} bytes where the index has a chunk of {} bytes",
            ci.chunk_length
        ));
    }
    let body = &record[9..];
    let head = ChunkHead::parse(body, body.len() as u64).map_err(|e| match e {
        chunk::ChunkError::Malformed(field) => {
            format!("the chunk record is malformed: its {field} runs past the record")
        }
        other => format!("{other:?}"),
    })?;
    if head.uncompressed_size != ci.uncompressed_size
        || head.records_len as u64 != ci.compressed_size
        || head.compression != ci.compression
    {
        return Err(format!(
            "its header ({} bytes of records, {} compressed, {:?}) is not its index's ({}, {}, {:?})",
            head.uncompressed_size,
            head.records_len,
            head.compression,
            ci.uncompressed_size,
            ci.compressed_size,
            ci.compression
        ));
    }
    Ok(head)
}

/// The chunks read so far: a batch waiting to be opened, and the errors
/// of the chunks that did not open.
#[derive(Default)]
struct Reading {
    batch: Batch,
    starts: Vec<u64>,
    skipped: Vec<(u64, Error)>,
}

impl Reading {
    fn push(
        &mut self,
        c: &mut Collector<'_>,
        ci: &ChunkIndex,
        head: ChunkHead,
        buf: Vec<u8>,
        at: usize,
    ) -> Result<()> {
        self.starts.push(ci.chunk_start_offset);
        if self.batch.push(head, buf, at) {
            self.flush(c)?;
        }
        Ok(())
    }

    fn flush(&mut self, c: &mut Collector<'_>) -> Result<()> {
        let starts = std::mem::take(&mut self.starts);
        for (at, result) in starts.into_iter().zip(self.batch.flush_each(c)) {
            if let Err(e) = result {
                self.skipped.push((at, e));
            }
        }
        Ok(())
    }

    /// A chunk whose index cannot be followed.
    fn bad(&mut self, c: &Collector<'_>, ci: &ChunkIndex, why: String) {
        let e = Error::Mcap {
            at: c.at(),
            reason: format!(
                "the chunk at byte {} is corrupt: {why}",
                ci.chunk_start_offset
            ),
        };
        self.skipped.push((ci.chunk_start_offset, e));
    }

    /// A chunk that did not open.
    fn failed(&mut self, ci: &ChunkIndex, e: Error) {
        self.skipped.push((ci.chunk_start_offset, e));
    }

    /// The demos, with a warning per skipped chunk; the first skipped
    /// chunk's error when no demo is left.
    fn finish(self, mut c: Collector<'_>) -> Result<Loaded> {
        if let Some(e) = c.take_pending() {
            return Err(e);
        }
        let mut skipped = self.skipped.into_iter();
        let Some((at, first)) = skipped.next() else {
            return c.finish(None, Vec::new());
        };
        if c.samples() == 0 {
            return Err(first);
        }
        let label = c.label();
        let mut warnings = vec![format!(
            "{label}: the chunk at byte {at} was skipped: {first}"
        )];
        warnings.extend(
            skipped.map(|(at, e)| format!("{label}: the chunk at byte {at} was skipped: {e}")),
        );
        c.finish(None, warnings)
    }
}

/// The pose messages of an uncompressed chunk, read where its message
/// indexes say they are.
async fn plain_messages<R: ReadAt>(
    c: &mut Collector<'_>,
    access: &mut R,
    ci: &ChunkIndex,
) -> Result<()> {
    let label = c.label();
    let io = |reason| Error::Io {
        file: label.to_owned(),
        reason,
    };
    let corrupt = |what: String| Error::Mcap {
        at: crate::error::Location::file(label),
        reason: format!(
            "the chunk at byte {} is corrupt: {what}",
            ci.chunk_start_offset
        ),
    };
    let first = ci
        .message_index_offsets
        .values()
        .copied()
        .min()
        .unwrap_or(0);
    let block = access
        .read_at(first, ci.message_index_length as usize)
        .await
        .map_err(io)?;
    let mut offsets = Vec::new();
    for (&id, &at) in &ci.message_index_offsets {
        if !c.reads(id) {
            continue;
        }
        let entries =
            message_index(&block, at.saturating_sub(first) as usize).ok_or_else(|| {
                corrupt(format!(
                    "the message index of channel {id} does not hold together"
                ))
            })?;
        offsets.extend(entries);
    }
    offsets.sort_unstable();
    offsets.dedup();
    let data_at = ci
        .compressed_data_offset()
        .map_err(|e| corrupt(e.to_string()))?;
    let records_len = ci.compressed_size;
    let mut w = Window::with_piece(MESSAGE_WINDOW);
    for off in offsets {
        if off.checked_add(9).is_none_or(|end| end > records_len) {
            return Err(corrupt(format!(
                "a message index points at byte {off} of {records_len}"
            )));
        }
        let left = (records_len - off) as usize;
        let head = w
            .get(access, data_at + off, MESSAGE_WINDOW.min(left))
            .await
            .map_err(io)?;
        let Some((opcode, len)) = record_head(head) else {
            return Err(io(std::io::ErrorKind::UnexpectedEof.into()));
        };
        if opcode != op::MESSAGE || len > (left - 9) as u64 {
            return Err(corrupt(format!(
                "a message index points at byte {off}, where a record of opcode {opcode:#04x} and {len} bytes is not a message inside the chunk"
            )));
        }
        let total = 9 + len as usize;
        let record = w
            .get(access, data_at + off, total.max(MESSAGE_WINDOW.min(left)))
            .await
            .map_err(io)?;
        if record.len() < total {
            return Err(io(std::io::ErrorKind::UnexpectedEof.into()));
        }
        c.record(op::MESSAGE, &record[9..total])?;
    }
    Ok(())
}

/// The offsets listed by the message index record at `at` in `block`.
fn message_index(block: &[u8], at: usize) -> Option<Vec<u64>> {
    let (opcode, len) = record_head(block.get(at..)?)?;
    if opcode != op::MESSAGE_INDEX {
        return None;
    }
    let body = block.get(at + 9..(at + 9).checked_add(usize::try_from(len).ok()?)?)?;
    let n = u32::from_le_bytes(body.get(2..6)?.try_into().ok()?) as usize;
    let entries = body.get(6..6usize.checked_add(n)?)?;
    if !n.is_multiple_of(16) {
        return None;
    }
    Some(
        entries
            .chunks_exact(16)
            .map(|e| u64::from_le_bytes(e[8..16].try_into().unwrap_or([0; 8])))
            .collect(),
    )
}
