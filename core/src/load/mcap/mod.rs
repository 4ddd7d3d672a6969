//! The MCAP reader (method.md sections 1 and 2.1-2.2), over random access
//! ([`crate::load::access`]): where the file ends with a summary that
//! indexes its chunks it reads the summary first, picks the channels that
//! hold poses and reads only the chunks that hold them, and of an
//! uncompressed chunk only those messages ([`indexed`]); without one it
//! walks the file record by record, skipping the messages of channels it
//! does not read ([`linear`]). Each chunk is opened by [`chunk`] (bounded
//! decompression, checked walk, CRC), messages are routed to their
//! decoders, one demo per topic and key. A file that ends early keeps the
//! messages of its complete chunks, with a warning; so does a file one of
//! whose chunks is corrupt where others hold demos.

pub mod chunk;
pub mod indexed;
pub mod linear;

use mcap::records::{Record, op};

use crate::error::{Error, Result};
use crate::load::access::{FileAt, ForwardAt, ReadAt, SliceAt, block_on};
use crate::load::collect::{Collector, Loaded};
use crate::load::options::LoadOptions;
use chunk::{ChunkError, ChunkHead, lengths_fit};

/// The largest single record the loader accepts, and the largest chunk it
/// decompresses; a declared length beyond it is an error, never an
/// allocation.
pub const RECORD_LENGTH_LIMIT: usize = 256 << 20;

/// The most bytes read from the input at once when walking a file.
pub(crate) const READ_PIECE: usize = 1 << 20;

/// The bytes a batch of chunks may hold in memory at once (compressed and
/// decompressed), unless one chunk alone is larger.
pub(crate) const WINDOW: usize = 64 << 20;

/// The first bytes of every MCAP file.
pub const MAGIC: &[u8; 8] = b"\x89MCAP0\r\n";

/// Loads the demos of the MCAP file at `path` with default options.
pub fn load_path(path: &std::path::Path) -> Result<Loaded> {
    load_path_with(path, &LoadOptions::default())
}

/// Loads the demos of the MCAP file at `path` (named by its path in errors).
pub fn load_path_with(path: &std::path::Path, options: &LoadOptions) -> Result<Loaded> {
    let label = path.display().to_string();
    let mut file = FileAt::open(path).map_err(|reason| Error::Io {
        file: label.clone(),
        reason,
    })?;
    block_on(read_mcap(&label, &mut file, options))
}

/// Loads the demos of an MCAP file held in memory with default options.
pub fn load_bytes(label: &str, bytes: &[u8]) -> Result<Loaded> {
    load_bytes_with(label, bytes, &LoadOptions::default())
}

/// Loads the demos of an MCAP file held in memory (a test, a bundled sample).
pub fn load_bytes_with(label: &str, bytes: &[u8], options: &LoadOptions) -> Result<Loaded> {
    block_on(read_mcap(label, &mut SliceAt(bytes), options))
}

/// Loads the demos of an MCAP stream read forward only (a zstd-compressed
/// file); `label` names the file in errors and in the demo names.
pub fn load_reader<R: std::io::Read + Send>(
    label: &str,
    input: R,
    options: &LoadOptions,
) -> Result<Loaded> {
    block_on(read_mcap(label, &mut ForwardAt::new(input), options))
}

/// Reads the demos of the MCAP file `access` holds; `label` names it in
/// errors and in the demo names (`file:topic`, `file:topic:key`, with only
/// the file name of a path).
pub async fn read_mcap<R: ReadAt>(
    label: &str,
    access: &mut R,
    options: &LoadOptions,
) -> Result<Loaded> {
    let c = Collector::new(label, options);
    let index = match access.size() {
        Some(size) => indexed::summary(label, access, size).await?,
        None => None,
    };
    match index {
        Some(index) => indexed::read(c, access, index).await,
        None => linear::read(c, access).await,
    }
}

impl Collector<'_> {
    pub(crate) fn mcap_error(&self, e: &mcap::McapError) -> Error {
        Error::Mcap {
            at: self.at(),
            reason: describe(e),
        }
    }

    /// Takes one record (from the file or from inside a chunk). Only
    /// schemas, channels and messages are parsed, and only once their
    /// length fields fit the record: mcap's parser reserves whatever a string
    /// length says, so a 300-byte record could ask for 4 GiB. A message on a
    /// channel that is declared but not read is passed over unparsed.
    pub(crate) fn record(&mut self, opcode: u8, data: &[u8]) -> Result<()> {
        if opcode == op::MESSAGE
            && let Some(id) = data.get(..2).map(|b| u16::from_le_bytes([b[0], b[1]]))
            && self.declared(id)
            && !self.reads(id)
        {
            return Ok(());
        }
        if ![op::SCHEMA, op::CHANNEL, op::MESSAGE].contains(&opcode) {
            return Ok(());
        }
        if let Err(field) = lengths_fit(opcode, data) {
            return Err(Error::Mcap {
                at: self.at(),
                reason: format!(
                    "a record (opcode {opcode:#04x}) is malformed: its {field} runs past the record's {} bytes",
                    data.len()
                ),
            });
        }
        match mcap::parse_record(opcode, data).map_err(|e| self.mcap_error(&e))? {
            Record::Schema { header, data } => {
                self.schema(header.id, header.name, header.encoding, data.into_owned());
            }
            Record::Channel(ch) => self.channel(ch)?,
            Record::Message { header, data } => self.message(&header, &data)?,
            _ => {}
        }
        Ok(())
    }

    /// Takes the records of a chunk opened by [`chunk::open`].
    pub(crate) fn chunk_records(&mut self, records: &[u8]) -> Result<()> {
        // The whole chunk is checked first: a corrupt chunk gives nothing.
        if let Err(e) = chunk::walk(records, &mut |_, _, _| {}) {
            return Err(self.chunk_error(e));
        }
        let mut failed = None;
        let walked = chunk::walk(records, &mut |opcode, _, data| {
            if failed.is_none()
                && let Err(e) = self.record(opcode, data)
            {
                failed = Some(e);
            }
        });
        match walked {
            Ok(()) => failed.map_or(Ok(()), Err),
            Err(e) => Err(self.chunk_error(e)),
        }
    }

    /// A chunk's error in words, naming the file.
    pub(crate) fn chunk_error(&mut self, e: ChunkError) -> Error {
        match e {
            ChunkError::Mcap(e @ mcap::McapError::BadChunkCrc { .. }) => self.mcap_error(&e),
            ChunkError::Mcap(e) => self.take_pending().unwrap_or_else(|| self.mcap_error(&e)),
            ChunkError::Malformed(field) => Error::Mcap {
                at: self.at(),
                reason: format!("a chunk record is malformed: its {field} runs past the record"),
            },
            ChunkError::Overrun { opcode, len, left } => Error::Mcap {
                at: self.at(),
                reason: format!(
                    "a record (opcode {opcode:#04x}) inside a chunk declares {len} bytes but the chunk has {left} left: the file is corrupt"
                ),
            },
            ChunkError::NotRecords(what) => Error::Mcap {
                at: self.at(),
                reason: format!("a chunk is corrupt: {what}"),
            },
        }
    }
}

/// Opens the chunks of a batch into `outputs` (one per chunk), on every
/// core where there are several: each chunk's [`chunk::open_into`].
pub(crate) fn open_all(
    batch: &[(ChunkHead, Vec<u8>, usize)],
    outputs: &mut [Vec<u8>],
) -> Vec<std::result::Result<bool, ChunkError>> {
    let open = |((head, buf, at), out): (&(ChunkHead, Vec<u8>, usize), &mut Vec<u8>)| {
        chunk::open_into(
            head,
            &buf[*at..*at + head.records_len],
            RECORD_LENGTH_LIMIT,
            out,
        )
    };
    #[cfg(feature = "parallel")]
    if batch.len() > 1 {
        use rayon::prelude::*;
        return batch
            .par_iter()
            .zip(outputs.par_iter_mut())
            .map(open)
            .collect();
    }
    batch.iter().zip(outputs.iter_mut()).map(open).collect()
}

/// The reader's error in words a user can act on.
pub(crate) fn describe(e: &mcap::McapError) -> String {
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
        E::ChunkTooLarge(len) => format!(
            "a chunk declares {len} bytes of records, more than the {RECORD_LENGTH_LIMIT}-byte limit"
        ),
        other => other.to_string(),
    }
}
