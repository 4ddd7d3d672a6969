//! The records inside a chunk, read without trusting the chunk's lengths.
//!
//! A chunk's header is read field by field against the record's bounds; its
//! declared uncompressed size is checked against the limit before anything
//! is allocated, decompression stops at that size (a zstd or lz4 bomb ends
//! there), and the records are walked with every length checked against
//! what is left. A record stream begins with a real opcode: an opcode of
//! 0x00 (a chunk of zeros, the usual bomb) is refused at the first record,
//! not walked nine bytes at a time through gigabytes. (mcap 0.26's own
//! linear reader underflows when a record inside an uncompressed chunk
//! declares more bytes than the chunk holds; the fuzzer found it.)

use std::borrow::Cow;

use mcap::McapError;

/// Why a chunk could not be opened.
#[derive(Debug)]
pub enum ChunkError {
    /// The reader's own error (a CRC that does not match, a chunk that
    /// ends inside a record).
    Mcap(McapError),
    /// A length field of the chunk's header runs past the chunk record.
    Malformed(&'static str),
    /// A record inside the chunk runs past its end.
    Overrun {
        /// The record's opcode.
        opcode: u8,
        /// Its declared length.
        len: u64,
        /// Bytes left in the chunk.
        left: usize,
    },
    /// The chunk's contents are not records: what was found.
    NotRecords(String),
}

/// A chunk record's header: what is needed to open it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ChunkHead {
    /// The declared size of its records once decompressed.
    pub uncompressed_size: u64,
    /// CRC-32 of the decompressed records (0: not computed by the writer).
    pub uncompressed_crc: u32,
    /// `""`, `"zstd"` or `"lz4"`.
    pub compression: String,
    /// Where the (compressed) records start in the chunk record's body.
    pub records_at: usize,
    /// Their (compressed) length.
    pub records_len: usize,
}

impl ChunkHead {
    /// Reads the header of a chunk record's body (or of its first bytes:
    /// `body_len` is the whole body's length).
    pub fn parse(body: &[u8], body_len: u64) -> Result<Self, ChunkError> {
        let u64_at = |pos: usize| {
            body.get(pos..pos + 8)
                .and_then(|b| <[u8; 8]>::try_from(b).ok())
                .map(u64::from_le_bytes)
        };
        // start time, end time, uncompressed size, CRC; then the compression.
        let uncompressed_size = u64_at(16).ok_or(ChunkError::Malformed("uncompressed size"))?;
        let crc = body
            .get(24..28)
            .and_then(|b| <[u8; 4]>::try_from(b).ok())
            .map(u32::from_le_bytes)
            .ok_or(ChunkError::Malformed("CRC"))?;
        let name_len = body
            .get(28..32)
            .and_then(|b| <[u8; 4]>::try_from(b).ok())
            .map(|b| u32::from_le_bytes(b) as usize)
            .ok_or(ChunkError::Malformed("compression"))?;
        let name = body
            .get(32..32 + name_len)
            .ok_or(ChunkError::Malformed("compression"))?;
        let records_len = u64_at(32 + name_len).ok_or(ChunkError::Malformed("compressed size"))?;
        let records_at = 32 + name_len + 8;
        if records_len > body_len.saturating_sub(records_at as u64) {
            return Err(ChunkError::Malformed("records"));
        }
        Ok(Self {
            uncompressed_size,
            uncompressed_crc: crc,
            compression: String::from_utf8_lossy(name).into_owned(),
            records_at,
            records_len: records_len as usize,
        })
    }

    /// The number of bytes of a chunk record's body that hold its header.
    pub const MAX_PREFIX: usize = 32 + 64 + 8;
}

/// Opens a chunk's records: decompressed into `out` (at most to the size
/// its header declares, which must be within `limit`; `Ok(true)`), or
/// left where they are when the chunk is uncompressed (`Ok(false)`);
/// CRC-checked either way.
pub fn open_into(
    head: &ChunkHead,
    records: &[u8],
    limit: usize,
    out: &mut Vec<u8>,
) -> Result<bool, ChunkError> {
    let size = usize::try_from(head.uncompressed_size)
        .ok()
        .filter(|&s| s <= limit)
        .ok_or(ChunkError::Mcap(McapError::ChunkTooLarge(
            head.uncompressed_size,
        )))?;
    match head.compression.as_str() {
        "" => {
            check_crc(head.uncompressed_crc, records)?;
            return Ok(false);
        }
        "zstd" => {
            first_record(zstd::stream::read::Decoder::new(records).ok(), size)?;
            inflate_zstd(records, size, out)?;
        }
        "lz4" => {
            first_record(Some(lz4_flex::frame::FrameDecoder::new(records)), size)?;
            inflate_lz4(records, size, out)?;
        }
        other => {
            return Err(ChunkError::NotRecords(format!(
                "a chunk compressed with {other:?}, which MCAP readers do not know"
            )));
        }
    }
    check_crc(head.uncompressed_crc, out)?;
    Ok(true)
}

/// A chunk's records, decompressed and CRC-checked (see [`open_into`]).
pub fn open<'a>(
    head: &ChunkHead,
    records: &'a [u8],
    limit: usize,
) -> Result<Cow<'a, [u8]>, ChunkError> {
    let mut out = Vec::new();
    Ok(if open_into(head, records, limit, &mut out)? {
        Cow::Owned(out)
    } else {
        Cow::Borrowed(records)
    })
}

/// Checks the first record of a compressed chunk before the rest is
/// decompressed: a record stream begins with a real opcode and a length
/// that fits the declared size (a chunk of zeros, the usual bomb, is
/// refused here, at its first bytes).
fn first_record<R: std::io::Read>(decoder: Option<R>, size: usize) -> Result<(), ChunkError> {
    if size == 0 {
        return Ok(());
    }
    let mut head = [0u8; 9];
    let read = decoder.map(|mut d| d.read_exact(&mut head));
    if !matches!(read, Some(Ok(()))) {
        return Err(ChunkError::NotRecords(
            "it does not decompress to a record".to_owned(),
        ));
    }
    let len = u64::from_le_bytes(head[1..9].try_into().unwrap_or([0xFF; 8]));
    if head[0] == 0 || len > size as u64 - 9.min(size as u64) {
        return Err(ChunkError::NotRecords(format!(
            "it begins with a record of opcode {:#04x} and {len} bytes in {size} declared: not a record stream",
            head[0]
        )));
    }
    Ok(())
}

thread_local! {
    /// A zstd decompression context per thread, reused chunk after chunk.
    static ZSTD: std::cell::RefCell<Option<zstd::bulk::Decompressor<'static>>> =
        const { std::cell::RefCell::new(None) };
}

fn inflate_zstd(records: &[u8], size: usize, out: &mut Vec<u8>) -> Result<(), ChunkError> {
    out.clear();
    out.reserve(size);
    let written = ZSTD.with(|cell| {
        let mut cell = cell.borrow_mut();
        if cell.is_none() {
            *cell = zstd::bulk::Decompressor::new().ok();
        }
        match cell.as_mut() {
            Some(d) => d.decompress_to_buffer(records, out),
            None => Err(std::io::Error::other("no zstd context")),
        }
    });
    let written = written.map_err(|e| {
        ChunkError::NotRecords(format!(
            "a zstd chunk does not decompress to its declared {size} bytes ({e})"
        ))
    })?;
    if written != size {
        return Err(ChunkError::NotRecords(format!(
            "a zstd chunk decompresses to {written} bytes, its header says {size}"
        )));
    }
    Ok(())
}

fn inflate_lz4(records: &[u8], size: usize, out: &mut Vec<u8>) -> Result<(), ChunkError> {
    use std::io::Read;
    out.clear();
    out.reserve(size.min(records.len().saturating_mul(255)));
    lz4_flex::frame::FrameDecoder::new(records)
        .take(size as u64 + 1)
        .read_to_end(out)
        .map_err(|e| ChunkError::NotRecords(format!("an lz4 chunk does not decompress ({e})")))?;
    if out.len() != size {
        return Err(ChunkError::NotRecords(format!(
            "an lz4 chunk decompresses to {} bytes, its header says {size}",
            out.len()
        )));
    }
    Ok(())
}

fn check_crc(saved: u32, data: &[u8]) -> Result<(), ChunkError> {
    if saved != 0 {
        let calculated = crc32fast::hash(data);
        if calculated != saved {
            return Err(ChunkError::Mcap(McapError::BadChunkCrc {
                saved,
                calculated,
            }));
        }
    }
    Ok(())
}

/// Calls `record(opcode, offset, body)` for every record of a chunk's
/// (decompressed) records, `offset` the record's position among them.
pub fn walk(data: &[u8], record: &mut dyn FnMut(u8, usize, &[u8])) -> Result<(), ChunkError> {
    let mut pos = 0;
    while pos < data.len() {
        let Some((head, body)) = data[pos..].split_at_checked(9) else {
            return Err(ChunkError::Mcap(McapError::UnexpectedEoc));
        };
        let opcode = head[0];
        if opcode == 0 {
            return Err(ChunkError::NotRecords(format!(
                "its records hold an opcode 0x00 at byte {pos} of {}: not a record stream",
                data.len()
            )));
        }
        let mut len_bytes = [0u8; 8];
        len_bytes.copy_from_slice(&head[1..9]);
        let len = u64::from_le_bytes(len_bytes);
        let Some(this) = usize::try_from(len).ok().and_then(|l| body.get(..l)) else {
            return Err(ChunkError::Overrun {
                opcode,
                len,
                left: body.len(),
            });
        };
        record(opcode, pos, this);
        pos += 9 + this.len();
    }
    Ok(())
}

/// Checks that every length field of a schema, channel or chunk record fits
/// inside the record, before mcap's parser (which reserves whatever a length
/// says) sees it; `Err` names the first field that does not.
pub fn lengths_fit(opcode: u8, body: &[u8]) -> Result<(), &'static str> {
    use mcap::records::op;
    let u32_at = |pos: usize| {
        body.get(pos..pos + 4)
            .and_then(|b| <[u8; 4]>::try_from(b).ok())
            .map(u32::from_le_bytes)
    };
    let (mut pos, fields): (usize, &[&'static str]) = match opcode {
        op::SCHEMA => (2, &["name", "encoding", "data"]),
        op::CHANNEL => (4, &["topic", "message encoding", "metadata"]),
        op::CHUNK => {
            return ChunkHead::parse(body, body.len() as u64)
                .map(|_| ())
                .map_err(|e| match e {
                    ChunkError::Malformed(f) => f,
                    _ => "records",
                });
        }
        _ => return Ok(()),
    };
    for &what in fields {
        let len = u32_at(pos).ok_or(what)?;
        pos = pos + 4 + len as usize;
        if pos > body.len() {
            return Err(what);
        }
    }
    Ok(())
}
