//! A browser's `File` as a recording read where it is (wasm32 only): the
//! core's reader asks for byte ranges ([`RemoteAt`]), each answered with
//! `Blob.slice(start, end).arrayBuffer()`, awaited on the page's event
//! loop. Nothing holds the whole file: the window in memory is what the
//! reader keeps (at most a few chunks) plus the poses. The load runs as a
//! task of its own on the page, its result put where the session's job
//! waits for it; its reads are counted in, and stopped by, the session's
//! meter (progress, Cancel).

use std::sync::{Arc, Mutex, PoisonError};

use dmpscope_core::load::access::{Exchange, Meter, Metered, RemoteAt, poll_once};
use dmpscope_core::load::options::LoadOptions;
use dmpscope_core::load::source::{SourceStreams, load_streams_at};
use dmpscope_session::{LoadSlot, RemoteFile, RemoteLoad, Source};
use send_wrapper::SendWrapper;
use wasm_bindgen_futures::JsFuture;

/// A `File` the page reads in slices.
pub struct BlobFile {
    file: SendWrapper<web_sys::File>,
    name: String,
    wake: Arc<dyn Fn() + Send + Sync>,
}

impl std::fmt::Debug for BlobFile {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "BlobFile({})", self.name)
    }
}

/// The source of a browser's `File`; `wake` asks for a frame as bytes
/// arrive (every 8 reads: the progress line).
pub fn source_of_file(file: web_sys::File, wake: Arc<dyn Fn() + Send + Sync>) -> Source {
    let name = file.name();
    let size = file.size() as u64;
    Source::Remote(RemoteFile {
        name: name.clone(),
        size,
        loader: Arc::new(BlobFile {
            file: SendWrapper::new(file),
            name,
            wake,
        }),
    })
}

impl RemoteLoad for BlobFile {
    fn start(&self, options: LoadOptions, meter: Arc<Meter>) -> LoadSlot {
        let slot: LoadSlot = Arc::default();
        let out = Arc::clone(&slot);
        let file = (*self.file).clone();
        let (name, wake) = (self.name.clone(), Arc::clone(&self.wake));
        wasm_bindgen_futures::spawn_local(async move {
            let result = load(&name, &file, options, meter, &*wake).await;
            // No frame asked for here: the session's load job takes the
            // result at its next slice (a few ms on) and asks for the frame
            // that shows it; a frame asked for now would come first and,
            // under a software rasteriser, hold the page's thread for
            // 150-250 ms before that slice runs (`hostile_probe.mjs`).
            *out.lock().unwrap_or_else(PoisonError::into_inner) = Some(result);
        });
        slot
    }
}

/// Loads `file`'s streams, answering the reader's requests one by one.
async fn load(
    name: &str,
    file: &web_sys::File,
    options: LoadOptions,
    meter: Arc<Meter>,
    wake: &(dyn Fn() + Send + Sync),
) -> Result<SourceStreams, String> {
    let size = file.size() as u64;
    let exchange = Arc::new(Mutex::new(Exchange::default()));
    let mut access = Metered::new(RemoteAt::new(size, Arc::clone(&exchange)), meter);
    let mut reading = Box::pin(load_streams_at(name, &mut access, &options));
    let mut ahead = ReadAhead::default();
    let mut reads = 0u64;
    loop {
        if let Some(result) = poll_once(&mut reading) {
            return result.map_err(|e| e.to_string());
        }
        let request = exchange
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .request;
        let Some((offset, len)) = request else {
            return Err(format!(
                "{name}: the reader stopped without asking for bytes"
            ));
        };
        let answer = match ahead.answer(offset, len, size) {
            Some(bytes) => Ok(bytes),
            None => {
                reads += 1;
                if reads.is_multiple_of(8) {
                    wake();
                }
                ahead.fetch(file, offset, len, size).await
            }
        };
        exchange
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .answer = Some(answer);
    }
}

thread_local! {
    /// The small files of the last drop and the promises of their bytes,
    /// asked for at the drop ([`prefetch_dropped`]), and the drop's number.
    static DROPPED: std::cell::RefCell<(u64, Vec<(web_sys::File, js_sys::Promise)>)> =
        const { std::cell::RefCell::new((0, Vec::new())) };
}

/// How long a dropped file's bytes asked for at the drop are kept for the
/// app to read (it reads them within a frame or two; a file it does not
/// read, such as one of an unknown kind, is not kept longer).
const DROPPED_KEPT_MS: i32 = 30_000;

/// Asks the browser for the bytes of each file of at most [`WHOLE`] bytes
/// dropped on the page, at the drop, before the app's frame that takes the
/// drop: the read then runs while that frame is drawn (under a software
/// rasteriser the page's thread is held 150-250 ms per frame, and a read
/// asked for inside the frame is answered only after it and the frame egui
/// draws next). Called by a listener on the window (`web::start`).
pub fn prefetch_dropped(event: &web_sys::DragEvent) {
    let Some(files) = event.data_transfer().and_then(|d| d.files()) else {
        return;
    };
    let drop = DROPPED.with(|dropped| {
        let (drop, dropped) = &mut *dropped.borrow_mut();
        *drop += 1;
        dropped.clear();
        for file in (0..files.length()).filter_map(|i| files.get(i)) {
            if file.size() as u64 <= WHOLE {
                let bytes = file.array_buffer();
                dropped.push((file, bytes));
            }
        }
        *drop
    });
    wasm_bindgen_futures::spawn_local(async move {
        let kept = js_sys::Promise::new(&mut |resolve, _| {
            if let Some(w) = web_sys::window() {
                let _ = w.set_timeout_with_callback_and_timeout_and_arguments_0(
                    &resolve,
                    DROPPED_KEPT_MS,
                );
            }
        });
        let _ = JsFuture::from(kept).await;
        DROPPED.with(|dropped| {
            let (last, dropped) = &mut *dropped.borrow_mut();
            if *last == drop {
                dropped.clear();
            }
        });
    });
}

/// The bytes asked for at the drop of `file`, if it was dropped.
fn take_dropped(file: &web_sys::File) -> Option<js_sys::Promise> {
    DROPPED.with(|dropped| {
        let (_, dropped) = &mut *dropped.borrow_mut();
        let same = |f: &web_sys::File| {
            f.name() == file.name()
                && f.size() == file.size()
                && f.last_modified() == file.last_modified()
        };
        let i = dropped.iter().position(|(f, _)| same(f))?;
        Some(dropped.swap_remove(i).1)
    })
}

/// The least a read from the browser fetches: each read waits for the
/// page's event loop (behind a frame, under a software rasteriser), so
/// small reads (a record's head, a footer) are served from one larger one.
const AHEAD: usize = 4 << 20;

/// A file up to this size is fetched whole at its first read (a hostile
/// file's footer, summary and chunks then cost one wait, not five).
const WHOLE: u64 = 16 << 20;

/// The bytes last fetched, to answer the reads that fall inside them.
#[derive(Default)]
struct ReadAhead {
    start: u64,
    bytes: Vec<u8>,
}

impl ReadAhead {
    /// The answer to a read inside the bytes fetched last (fewer at the
    /// file's end, as [`read_slice`] answers, when they reach it).
    fn answer(&self, offset: u64, len: usize, size: u64) -> Option<Vec<u8>> {
        let from = usize::try_from(offset.checked_sub(self.start)?).ok()?;
        let to = from.checked_add(len)?;
        let end = self.bytes.len();
        if self.start + end as u64 == size {
            // The window reaches the file's end: a read past it gets what
            // there is.
            return Some(self.bytes[from.min(end)..to.min(end)].to_vec());
        }
        self.bytes.get(from..to).map(<[u8]>::to_vec)
    }

    /// Fetches at least [`AHEAD`] bytes around `offset` and answers the
    /// read from them: from `offset` on, or the file's last [`AHEAD`]
    /// bytes where the read is among them (a reader reads an MCAP's footer
    /// and summary, then its start); a file of at most [`WHOLE`] bytes
    /// whole.
    async fn fetch(
        &mut self,
        file: &web_sys::File,
        offset: u64,
        len: usize,
        size: u64,
    ) -> Result<Vec<u8>, String> {
        // A small file comes whole: each read waits for the page's event
        // loop, which under a software rasteriser is a frame.
        let want = if size <= WHOLE {
            WHOLE as usize
        } else {
            len.max(AHEAD)
        };
        let start = offset.min(size.saturating_sub(want as u64));
        let dropped = if size <= WHOLE {
            take_dropped(file)
        } else {
            None
        };
        let bytes = match dropped {
            // The whole file, asked for at its drop (`start` is 0).
            Some(bytes) => buffer_bytes(bytes).await?,
            None => read_slice(file, start, want, size).await?,
        };
        self.start = start;
        self.bytes = bytes;
        self.answer(offset, len, size)
            .ok_or_else(|| format!("the browser gave too few bytes at offset {offset}"))
    }
}

/// The bytes of a promised `ArrayBuffer`.
async fn buffer_bytes(promise: js_sys::Promise) -> Result<Vec<u8>, String> {
    let buffer = JsFuture::from(promise)
        .await
        .map_err(|e| format!("the browser cannot read the file: {e:?}"))?;
    Ok(js_sys::Uint8Array::new(&buffer).to_vec())
}

/// `len` bytes of `file` at `offset` (fewer at its end).
async fn read_slice(
    file: &web_sys::File,
    offset: u64,
    len: usize,
    size: u64,
) -> Result<Vec<u8>, String> {
    let end = offset.saturating_add(len as u64).min(size);
    let blob = file
        .slice_with_f64_and_f64(offset as f64, end.max(offset) as f64)
        .map_err(|e| format!("{e:?}"))?;
    let buffer = JsFuture::from(blob.array_buffer())
        .await
        .map_err(|e| format!("the browser cannot read the file: {e:?}"))?;
    Ok(js_sys::Uint8Array::new(&buffer).to_vec())
}
