//! The records inside a chunk, read without trusting the chunk's lengths.
//!
//! mcap 0.26's linear reader underflows (a panic with overflow checks on, a
//! wrapped counter without) when a record inside an *uncompressed* chunk
//! declares more bytes than the chunk holds; the fuzzer found it. The loader
//! therefore takes whole chunk records from the outer reader and opens them
//! here: uncompressed chunks with a bounds-checked walk and the chunk CRC,
//! compressed chunks with a fresh linear reader of their own, whose
//! decompressing path checks its bounds.

use mcap::McapError;
use mcap::records::ChunkHeader;
use mcap::sans_io::linear_reader::{LinearReadEvent, LinearReader, LinearReaderOptions};

/// Why a chunk could not be opened.
#[derive(Debug)]
pub enum ChunkError {
    /// The reader's own error.
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
}

/// Calls `record(opcode, body)` for every record in a chunk, given the
/// chunk record's body as it stands in the file.
pub fn for_each_record(
    chunk_body: &[u8],
    limit: usize,
    record: &mut dyn FnMut(u8, &[u8]),
) -> Result<(), ChunkError> {
    lengths_fit(mcap::records::op::CHUNK, chunk_body).map_err(ChunkError::Malformed)?;
    match mcap::parse_record(mcap::records::op::CHUNK, chunk_body).map_err(ChunkError::Mcap)? {
        mcap::records::Record::Chunk { header, data } if header.compression.is_empty() => {
            plain(&header, &data, record)
        }
        _ => compressed(chunk_body, limit, record),
    }
}

fn plain(
    header: &ChunkHeader,
    data: &[u8],
    record: &mut dyn FnMut(u8, &[u8]),
) -> Result<(), ChunkError> {
    if header.uncompressed_crc != 0 {
        let calculated = crc32fast::hash(data);
        if calculated != header.uncompressed_crc {
            return Err(ChunkError::Mcap(McapError::BadChunkCrc {
                saved: header.uncompressed_crc,
                calculated,
            }));
        }
    }
    let mut rest = data;
    while !rest.is_empty() {
        let Some((head, body)) = rest.split_at_checked(9) else {
            return Err(ChunkError::Mcap(McapError::UnexpectedEoc));
        };
        let opcode = head[0];
        let mut len_bytes = [0u8; 8];
        len_bytes.copy_from_slice(&head[1..9]);
        let len = u64::from_le_bytes(len_bytes);
        let Some((this, next)) = usize::try_from(len)
            .ok()
            .and_then(|l| body.split_at_checked(l))
        else {
            return Err(ChunkError::Overrun {
                opcode,
                len,
                left: body.len(),
            });
        };
        record(opcode, this);
        rest = next;
    }
    Ok(())
}

fn compressed(
    chunk_body: &[u8],
    limit: usize,
    record: &mut dyn FnMut(u8, &[u8]),
) -> Result<(), ChunkError> {
    // The chunk record as it stood in the file, for a reader of its own.
    let mut bytes = Vec::with_capacity(chunk_body.len() + 9);
    bytes.push(mcap::records::op::CHUNK);
    bytes.extend_from_slice(&(chunk_body.len() as u64).to_le_bytes());
    bytes.extend_from_slice(chunk_body);
    let options = LinearReaderOptions::default()
        .with_skip_start_magic(true)
        .with_skip_end_magic(true)
        .with_validate_chunk_crcs(true)
        .with_record_length_limit(limit);
    let mut reader = LinearReader::new_with_options(options);
    let mut input: &[u8] = &bytes;
    while let Some(event) = reader.next_event() {
        match event.map_err(ChunkError::Mcap)? {
            LinearReadEvent::ReadRequest(need) => {
                let n = need.min(input.len());
                reader.insert(n).copy_from_slice(&input[..n]);
                reader.notify_read(n);
                input = &input[n..];
            }
            LinearReadEvent::Record { opcode, data } => record(opcode, data),
        }
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
        // start time, end time, uncompressed size, CRC; then the compression.
        op::CHUNK => (28, &["compression"]),
        _ => return Ok(()),
    };
    for &what in fields {
        let len = u32_at(pos).ok_or(what)?;
        pos = pos + 4 + len as usize;
        if pos > body.len() {
            return Err(what);
        }
    }
    if opcode == op::CHUNK {
        let size = body
            .get(pos..pos + 8)
            .and_then(|b| <[u8; 8]>::try_from(b).ok())
            .map(u64::from_le_bytes)
            .ok_or("compressed size")?;
        if size > (body.len() - pos - 8) as u64 {
            return Err("records");
        }
    }
    Ok(())
}
