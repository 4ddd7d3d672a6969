//! An MCAP file without an index (no summary, a summary without chunk
//! indexes, a file cut short, a stream), walked record by record from the
//! start in pieces: a message on a channel that holds no pose is passed
//! over by its length without being read, every chunk is opened (nothing
//! says which channels it holds), several at once on every core. A file
//! that ends inside a record keeps what its complete records gave.

use crate::error::{Error, Result};
use crate::load::access::ReadAt;
use crate::load::collect::{Collector, Loaded};
use crate::load::mcap::chunk::ChunkHead;
use crate::load::mcap::{MAGIC, READ_PIECE, RECORD_LENGTH_LIMIT, WINDOW, open_all};

/// A window on a source read forward: the bytes from `start`.
pub(crate) struct Window {
    buf: Vec<u8>,
    start: u64,
    scratch: Vec<u8>,
    piece: usize,
}

impl Window {
    /// An empty window at the start of the source, reading in pieces of
    /// [`READ_PIECE`].
    pub(crate) fn new() -> Self {
        Self::with_piece(READ_PIECE)
    }

    /// An empty window reading in pieces of at least `piece` bytes.
    pub(crate) fn with_piece(piece: usize) -> Self {
        Self {
            buf: Vec::new(),
            start: 0,
            scratch: Vec::new(),
            piece,
        }
    }

    /// Up to `len` bytes at `pos` (fewer only where the source ends),
    /// reading forward in pieces of at least its piece; what lies
    /// before `pos` is dropped when more must be read (once a piece, not
    /// once a record: a piece of 30,000 small records would otherwise move
    /// its rest 30,000 times).
    pub(crate) async fn get<R: ReadAt>(
        &mut self,
        access: &mut R,
        pos: u64,
        len: usize,
    ) -> std::io::Result<&[u8]> {
        let end = self.start + self.buf.len() as u64;
        if pos < self.start || pos > end {
            self.buf.clear();
            self.start = pos;
        }
        let at = (pos - self.start) as usize;
        if self.buf.len() - at < len {
            self.buf.drain(..at);
            self.start = pos;
            while self.buf.len() < len {
                let from = self.start + self.buf.len() as u64;
                let want = (len - self.buf.len()).max(self.piece);
                access.read_into(from, want, &mut self.scratch).await?;
                if self.scratch.is_empty() {
                    break;
                }
                self.buf.extend_from_slice(&self.scratch);
            }
        }
        let at = (pos - self.start) as usize;
        let have = self.buf.len() - at;
        Ok(&self.buf[at..at + len.min(have)])
    }
}

/// Chunks read and waiting to be opened together, in file order: each
/// chunk's header and a buffer holding its records at an offset. The
/// buffers (and those the chunks decompress into) are reused batch after
/// batch: fresh gigabytes of allocations cost more than the decompression.
#[derive(Default)]
pub(crate) struct Batch {
    chunks: Vec<(ChunkHead, Vec<u8>, usize)>,
    outputs: Vec<Vec<u8>>,
    spare: Vec<Vec<u8>>,
    bytes: usize,
}

impl Batch {
    /// A buffer to read a chunk into.
    pub(crate) fn buffer(&mut self) -> Vec<u8> {
        self.spare.pop().unwrap_or_default()
    }

    /// Adds a chunk whose records are `buf[at..]`; `true` when the batch is
    /// full.
    pub(crate) fn push(&mut self, head: ChunkHead, buf: Vec<u8>, at: usize) -> bool {
        self.bytes += head.records_len + head.uncompressed_size as usize;
        self.chunks.push((head, buf, at));
        self.bytes >= WINDOW
    }

    /// Opens every chunk (on every core) and hands their records to the
    /// collector in order; the first chunk that does not open is the error.
    pub(crate) fn flush(&mut self, c: &mut Collector<'_>) -> Result<()> {
        self.flush_each(c).into_iter().collect()
    }

    /// Opens every chunk (on every core) and hands their records to the
    /// collector in order: each chunk's result.
    pub(crate) fn flush_each(&mut self, c: &mut Collector<'_>) -> Vec<Result<()>> {
        let chunks = std::mem::take(&mut self.chunks);
        self.bytes = 0;
        self.outputs
            .resize_with(self.outputs.len().max(chunks.len()), Vec::new);
        let opened = open_all(&chunks, &mut self.outputs[..chunks.len()]);
        let results = chunks
            .iter()
            .zip(&self.outputs)
            .zip(opened)
            .map(|(((head, buf, at), out), opened)| match opened {
                Ok(true) => c.chunk_records(out),
                Ok(false) => c.chunk_records(&buf[*at..*at + head.records_len]),
                Err(e) => Err(c.chunk_error(e)),
            })
            .collect();
        self.spare.extend(chunks.into_iter().map(|(_, buf, _)| buf));
        results
    }
}

/// Walks the MCAP file `access` holds from its start.
pub(crate) async fn read<R: ReadAt>(mut c: Collector<'_>, access: &mut R) -> Result<Loaded> {
    let label = c.label();
    let io = |reason| Error::Io {
        file: label.to_owned(),
        reason,
    };
    let mut w = Window::new();
    if w.get(access, 0, MAGIC.len()).await.map_err(io)? != MAGIC {
        return Err(c.mcap_error(&mcap::McapError::BadMagic));
    }
    let mut pos = MAGIC.len() as u64;
    let mut batch = Batch::default();
    let cut = loop {
        let head = w.get(access, pos, 9).await.map_err(io)?;
        let Some((opcode, len)) = record_head(head) else {
            break true;
        };
        if len > RECORD_LENGTH_LIMIT as u64 {
            batch.flush(&mut c)?;
            return Err(c.mcap_error(&mcap::McapError::RecordTooLarge { opcode, len }));
        }
        let total = 9 + len as usize;
        if opcode == mcap::records::op::MESSAGE && len >= 2 {
            let head = w.get(access, pos, 11).await.map_err(io)?;
            if let Some(id) = head.get(9..11).map(|b| u16::from_le_bytes([b[0], b[1]]))
                && c.declared(id)
                && !c.reads(id)
            {
                if access.size().is_some_and(|size| pos + total as u64 > size) {
                    break true;
                }
                pos += total as u64;
                continue;
            }
        }
        let record = w.get(access, pos, total).await.map_err(io)?;
        if record.len() < total {
            break true;
        }
        let body = &record[9..];
        match opcode {
            // A file is whole when its end magic follows the footer.
            mcap::records::op::FOOTER => {
                let end = pos + total as u64;
                break w.get(access, end, MAGIC.len()).await.map_err(io)? != MAGIC;
            }
            mcap::records::op::CHUNK => {
                let head =
                    ChunkHead::parse(body, body.len() as u64).map_err(|e| c.chunk_error(e))?;
                let mut buf = batch.buffer();
                buf.clear();
                buf.extend_from_slice(&body[head.records_at..head.records_at + head.records_len]);
                if batch.push(head, buf, 0) {
                    batch.flush(&mut c)?;
                }
            }
            _ => {
                batch.flush(&mut c)?;
                c.record(opcode, body)?;
            }
        }
        pos += total as u64;
    };
    batch.flush(&mut c)?;
    let truncated = if cut {
        if c.has_pending() || c.samples() == 0 {
            let e = c.mcap_error(&mcap::McapError::UnexpectedEof);
            return Err(c.take_pending().unwrap_or(e));
        }
        Some(format!(
            "{label}: the file is truncated (it ends inside a record after {pos} bytes); \
             kept the {} messages of its complete chunks, the rest is lost",
            c.samples()
        ))
    } else {
        None
    };
    c.finish(truncated, Vec::new())
}

/// A record's opcode and declared length, when the bytes hold its head.
pub(crate) fn record_head(head: &[u8]) -> Option<(u8, u64)> {
    let len: [u8; 8] = head.get(1..9)?.try_into().ok()?;
    Some((head[0], u64::from_le_bytes(len)))
}
