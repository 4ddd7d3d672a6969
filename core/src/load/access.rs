//! Random access to a recording's bytes: the one thing every reader needs
//! of where the bytes are. [`ReadAt`] gives a source's size and the bytes
//! at an offset; it is implemented over a slice ([`SliceAt`]), a file
//! ([`FileAt`], natively), a stream read forward only ([`ForwardAt`]: a
//! zstd-compressed file), and bytes that arrive later ([`RemoteAt`]: a
//! browser's `File`, read through `Blob.slice` by the page, which answers
//! the requests [`Exchange`] holds). The readers are `async` over it and
//! own no I/O: natively [`block_on`] runs them (a file's read is ready at
//! once), in the browser the session polls them between frames while the
//! page fetches the bytes they asked for. [`Metered`] counts what was read
//! (progress, and the bench's share of the file read) and stops a read the
//! user cancelled.

use std::future::Future;
use std::io;
use std::pin::pin;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex, PoisonError};
use std::task::{Context, Poll, Waker};

/// Random access to a recording's bytes.
pub trait ReadAt: Send {
    /// The size in bytes; `None` for a stream read forward only (no index
    /// can be found at its end: it is read linearly).
    fn size(&self) -> Option<u64>;

    /// `len` bytes at `offset` into `buf` (its contents replaced, its
    /// capacity reused): fewer only where the source ends. A forward-only
    /// source accepts only offsets at or past the last read's end.
    fn read_into(
        &mut self,
        offset: u64,
        len: usize,
        buf: &mut Vec<u8>,
    ) -> impl Future<Output = io::Result<()>> + Send;

    /// `len` bytes at `offset`, in a new buffer.
    fn read_at(
        &mut self,
        offset: u64,
        len: usize,
    ) -> impl Future<Output = io::Result<Vec<u8>>> + Send {
        async move {
            let mut buf = Vec::new();
            self.read_into(offset, len, &mut buf).await?;
            Ok(buf)
        }
    }
}

/// The bytes of a slice.
#[derive(Clone, Copy, Debug)]
pub struct SliceAt<'a>(pub &'a [u8]);

impl ReadAt for SliceAt<'_> {
    fn size(&self) -> Option<u64> {
        Some(self.0.len() as u64)
    }

    fn read_into(
        &mut self,
        offset: u64,
        len: usize,
        buf: &mut Vec<u8>,
    ) -> impl Future<Output = io::Result<()>> + Send {
        let start = usize::try_from(offset)
            .unwrap_or(usize::MAX)
            .min(self.0.len());
        let end = start.saturating_add(len).min(self.0.len());
        buf.clear();
        buf.extend_from_slice(&self.0[start..end]);
        std::future::ready(Ok(()))
    }
}

/// A file on disk, read where asked (`pread` on Unix; a seek and a read
/// elsewhere).
#[derive(Debug)]
pub struct FileAt {
    file: std::fs::File,
    size: u64,
}

impl FileAt {
    /// Opens the file at `path`.
    pub fn open(path: &std::path::Path) -> io::Result<Self> {
        let file = std::fs::File::open(path)?;
        let size = file.metadata()?.len();
        Ok(Self { file, size })
    }

    fn read_blocking(&mut self, offset: u64, len: usize, buf: &mut Vec<u8>) -> io::Result<()> {
        let len = usize::try_from(self.size.saturating_sub(offset))
            .unwrap_or(usize::MAX)
            .min(len);
        buf.clear();
        buf.resize(len, 0);
        let mut done = 0;
        while done < len {
            match read_file_at(&mut self.file, &mut buf[done..], offset + done as u64) {
                Ok(0) => break,
                Ok(n) => done += n,
                Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
                Err(e) => return Err(e),
            }
        }
        buf.truncate(done);
        Ok(())
    }
}

#[cfg(unix)]
fn read_file_at(file: &mut std::fs::File, buf: &mut [u8], offset: u64) -> io::Result<usize> {
    std::os::unix::fs::FileExt::read_at(file, buf, offset)
}

#[cfg(not(unix))]
fn read_file_at(file: &mut std::fs::File, buf: &mut [u8], offset: u64) -> io::Result<usize> {
    use std::io::{Read, Seek};
    file.seek(io::SeekFrom::Start(offset))?;
    file.read(buf)
}

impl ReadAt for FileAt {
    fn size(&self) -> Option<u64> {
        Some(self.size)
    }

    fn read_into(
        &mut self,
        offset: u64,
        len: usize,
        buf: &mut Vec<u8>,
    ) -> impl Future<Output = io::Result<()>> + Send {
        std::future::ready(self.read_blocking(offset, len, buf))
    }
}

/// A stream read forward only: a skip reads and drops the bytes between.
#[derive(Debug)]
pub struct ForwardAt<R> {
    inner: R,
    pos: u64,
}

impl<R: io::Read> ForwardAt<R> {
    /// The stream `inner`, at its start.
    pub fn new(inner: R) -> Self {
        Self { inner, pos: 0 }
    }

    fn read_blocking(&mut self, offset: u64, len: usize, buf: &mut Vec<u8>) -> io::Result<()> {
        buf.clear();
        if offset < self.pos {
            return Err(io::Error::other(format!(
                "a stream read forward only was asked for byte {offset} after byte {}",
                self.pos
            )));
        }
        let skipped = io::copy(
            &mut io::Read::take(&mut self.inner, offset - self.pos),
            &mut io::sink(),
        )?;
        self.pos += skipped;
        if self.pos < offset {
            return Ok(());
        }
        io::Read::read_to_end(&mut io::Read::take(&mut self.inner, len as u64), buf)?;
        self.pos += buf.len() as u64;
        Ok(())
    }
}

impl<R: io::Read + Send> ReadAt for ForwardAt<R> {
    fn size(&self) -> Option<u64> {
        None
    }

    fn read_into(
        &mut self,
        offset: u64,
        len: usize,
        buf: &mut Vec<u8>,
    ) -> impl Future<Output = io::Result<()>> + Send {
        std::future::ready(self.read_blocking(offset, len, buf))
    }
}

/// The requests of a [`RemoteAt`] and their answers, shared with whoever
/// fetches the bytes (the browser's page).
#[derive(Debug, Default)]
pub struct Exchange {
    /// The read asked for and not answered yet: offset and length.
    pub request: Option<(u64, usize)>,
    /// The answer to it: the bytes, or why they could not be read.
    pub answer: Option<Result<Vec<u8>, String>>,
}

/// Bytes that arrive later: each read puts its request in the shared
/// [`Exchange`] and waits until an answer is there.
#[derive(Clone, Debug)]
pub struct RemoteAt {
    size: u64,
    exchange: Arc<Mutex<Exchange>>,
}

impl RemoteAt {
    /// A source of `size` bytes fetched through `exchange`.
    pub fn new(size: u64, exchange: Arc<Mutex<Exchange>>) -> Self {
        Self { size, exchange }
    }
}

impl ReadAt for RemoteAt {
    fn size(&self) -> Option<u64> {
        Some(self.size)
    }

    fn read_into(
        &mut self,
        offset: u64,
        len: usize,
        buf: &mut Vec<u8>,
    ) -> impl Future<Output = io::Result<()>> + Send {
        let exchange = Arc::clone(&self.exchange);
        let mut asked = false;
        std::future::poll_fn(move |_| {
            let mut e = exchange.lock().unwrap_or_else(PoisonError::into_inner);
            if !asked {
                e.request = Some((offset, len));
                e.answer = None;
                asked = true;
                return Poll::Pending;
            }
            match e.answer.take() {
                Some(Ok(bytes)) => {
                    e.request = None;
                    *buf = bytes;
                    Poll::Ready(Ok(()))
                }
                Some(Err(why)) => {
                    e.request = None;
                    Poll::Ready(Err(io::Error::other(why)))
                }
                None => Poll::Pending,
            }
        })
    }
}

/// How far a read has come and whether the user stopped it, shared with
/// whoever shows it.
#[derive(Debug, Default)]
pub struct Meter {
    /// Bytes read so far.
    pub read: AtomicU64,
    /// Set to stop the read: the next read fails as cancelled.
    pub cancel: AtomicBool,
}

impl Meter {
    /// Bytes read so far.
    pub fn bytes_read(&self) -> u64 {
        self.read.load(Ordering::Relaxed)
    }
}

/// A source whose reads are counted in a [`Meter`], and refused once it
/// is cancelled.
#[derive(Debug)]
pub struct Metered<R> {
    inner: R,
    meter: Arc<Meter>,
}

impl<R: ReadAt> Metered<R> {
    /// `inner`, counted in `meter`.
    pub fn new(inner: R, meter: Arc<Meter>) -> Self {
        Self { inner, meter }
    }
}

impl<R: ReadAt> ReadAt for Metered<R> {
    fn size(&self) -> Option<u64> {
        self.inner.size()
    }

    fn read_into(
        &mut self,
        offset: u64,
        len: usize,
        buf: &mut Vec<u8>,
    ) -> impl Future<Output = io::Result<()>> + Send {
        let meter = Arc::clone(&self.meter);
        let cancelled = meter.cancel.load(Ordering::Relaxed);
        let inner = &mut self.inner;
        async move {
            if cancelled {
                return Err(io::Error::new(io::ErrorKind::Interrupted, "cancelled"));
            }
            inner.read_into(offset, len, buf).await?;
            meter.read.fetch_add(buf.len() as u64, Ordering::Relaxed);
            Ok(())
        }
    }
}

/// Runs a reader over a source whose reads are ready at once (a slice, a
/// file, a stream) to its end. A read that waits for bytes from elsewhere
/// ([`RemoteAt`]) is polled step by step by its owner instead.
pub fn block_on<F: Future>(future: F) -> F::Output {
    let mut future = pin!(future);
    let mut cx = Context::from_waker(Waker::noop());
    loop {
        if let Poll::Ready(out) = future.as_mut().poll(&mut cx) {
            return out;
        }
    }
}

/// Polls a reader once: its output, or `None` while it waits for bytes.
pub fn poll_once<F: Future + Unpin>(future: &mut F) -> Option<F::Output> {
    let mut cx = Context::from_waker(Waker::noop());
    match std::pin::Pin::new(future).poll(&mut cx) {
        Poll::Ready(out) => Some(out),
        Poll::Pending => None,
    }
}
