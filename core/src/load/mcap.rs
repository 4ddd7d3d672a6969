//! The MCAP loader: one pass over the file with mcap's sans-IO
//! [`LinearReader`], each chunk opened and CRC-checked by [`crate::load::chunks`],
//! messages routed to their decoders, one demo per topic and key (method.md
//! sections 1 and 2.1-2.2). A file that ends early keeps the messages of its
//! complete chunks, with a warning.

use std::io::Read;

use mcap::records::Record;
use mcap::sans_io::linear_reader::{LinearReadEvent, LinearReader, LinearReaderOptions};

use crate::error::{Error, Result};
use crate::load::chunks::{ChunkError, for_each_record, lengths_fit};
use crate::load::collect::{Collector, Loaded};
use crate::load::options::LoadOptions;

/// The largest single record the loader accepts; a declared length beyond it
/// is an error, never an allocation.
pub const RECORD_LENGTH_LIMIT: usize = 256 << 20;

/// The most bytes read from the input at once.
pub(crate) const READ_PIECE: usize = 1 << 20;

/// Loads the demos of the MCAP file at `path` with default options.
pub fn load_path(path: &std::path::Path) -> Result<Loaded> {
    load_path_with(path, &LoadOptions::default())
}

/// Loads the demos of the MCAP file at `path` (named by its path in errors).
pub fn load_path_with(path: &std::path::Path, options: &LoadOptions) -> Result<Loaded> {
    let label = path.display().to_string();
    let file = std::fs::File::open(path).map_err(|reason| Error::Io {
        file: label.clone(),
        reason,
    })?;
    load_reader(
        &label,
        std::io::BufReader::with_capacity(READ_PIECE, file),
        options,
    )
}

/// Loads the demos of an MCAP file held in memory with default options.
pub fn load_bytes(label: &str, bytes: &[u8]) -> Result<Loaded> {
    load_reader(label, bytes, &LoadOptions::default())
}

/// Loads the demos of an MCAP file held in memory (a browser upload, a test).
pub fn load_bytes_with(label: &str, bytes: &[u8], options: &LoadOptions) -> Result<Loaded> {
    load_reader(label, bytes, options)
}

impl Collector<'_> {
    fn mcap_error(&self, e: &mcap::McapError) -> Error {
        Error::Mcap {
            at: self.at(),
            reason: describe(e),
        }
    }

    /// Takes one record (from the file or from inside a chunk). Only
    /// schemas, channels and messages are parsed, and only once their
    /// length fields fit the record: mcap's parser reserves whatever a string
    /// length says, so a 300-byte record could ask for 4 GiB.
    fn record(&mut self, opcode: u8, data: &[u8]) -> Result<()> {
        use mcap::records::op;
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

    /// Opens a chunk record and takes its records.
    fn chunk(&mut self, body: &[u8]) -> Result<()> {
        let mut failed = None;
        let walked = for_each_record(body, RECORD_LENGTH_LIMIT, &mut |opcode, data| {
            if failed.is_none()
                && let Err(e) = self.record(opcode, data)
            {
                failed = Some(e);
            }
        });
        match walked {
            Err(ChunkError::Mcap(e @ mcap::McapError::BadChunkCrc { .. })) => {
                Err(self.mcap_error(&e))
            }
            Err(ChunkError::Mcap(e)) => {
                Err(self.take_pending().unwrap_or_else(|| self.mcap_error(&e)))
            }
            Err(ChunkError::Malformed(field)) => Err(Error::Mcap {
                at: self.at(),
                reason: format!("a chunk record is malformed: its {field} runs past the record"),
            }),
            Err(ChunkError::Overrun { opcode, len, left }) => Err(Error::Mcap {
                at: self.at(),
                reason: format!(
                    "a record (opcode {opcode:#04x}) inside a chunk declares {len} bytes but the chunk has {left} left: the file is corrupt"
                ),
            }),
            Ok(()) => failed.map_or(Ok(()), Err),
        }
    }
}

/// Loads the demos of an MCAP stream; `label` names the file in errors and
/// in the demo names (`file:topic`, `file:topic:key`, with only the file name
/// of a path).
pub fn load_reader<R: Read>(label: &str, mut input: R, options: &LoadOptions) -> Result<Loaded> {
    // Whole chunks come out of the outer reader and are opened by
    // `chunks::for_each_record` (see there for why). Their CRCs are checked
    // as each is opened.
    let reader_options = LinearReaderOptions::default()
        .with_emit_chunks(true)
        .with_record_length_limit(RECORD_LENGTH_LIMIT);
    let mut reader = LinearReader::new_with_options(reader_options);
    let mut c = Collector::new(label, options);
    let mut truncated = None;
    let mut bytes_read: u64 = 0;
    while let Some(event) = reader.next_event() {
        let event = match event {
            Ok(event) => event,
            Err(mcap::McapError::UnexpectedEof) if !c.has_pending() && c.samples() > 0 => {
                truncated = Some(format!(
                    "{label}: the file is truncated (it ends inside a record after {bytes_read} bytes); \
                     kept the {} messages of its complete chunks, the rest is lost",
                    c.samples()
                ));
                break;
            }
            Err(e) => return Err(c.take_pending().unwrap_or_else(|| c.mcap_error(&e))),
        };
        match event {
            LinearReadEvent::ReadRequest(need) => {
                // `insert` zero-fills what it is asked for: ask in bounded
                // pieces so a declared length is never allocated up front.
                let buf = reader.insert(need.min(READ_PIECE));
                let n = read_some(&mut input, buf).map_err(|reason| Error::Io {
                    file: label.to_owned(),
                    reason,
                })?;
                bytes_read += n as u64;
                reader.notify_read(n);
            }
            LinearReadEvent::Record { opcode, data } if opcode == mcap::records::op::CHUNK => {
                c.chunk(data)?;
            }
            LinearReadEvent::Record { opcode, data } => c.record(opcode, data)?,
        }
    }
    c.finish(truncated, Vec::new())
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
