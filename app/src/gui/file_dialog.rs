//! The system file dialogs, off the frame: "Open" picks recordings (paths
//! natively; names and bytes in the browser, through `rfd`'s async dialog)
//! and "Save" writes an export. Tests never open a dialog: they call the
//! app's `add_sources` and the export functions directly.

use std::sync::mpsc::{Receiver, Sender, channel};

use eframe::egui;

use super::loading::Source;

/// Dialogs under way and their answers.
pub struct Dialogs {
    tx: Sender<Answer>,
    rx: Receiver<Answer>,
}

/// What a dialog gave back.
pub enum Answer {
    /// Recordings picked to open.
    Open(Vec<Source>),
    /// A message for the user (an export written, or why not).
    Message(String),
}

impl Default for Dialogs {
    fn default() -> Self {
        let (tx, rx) = channel();
        Self { tx, rx }
    }
}

impl Dialogs {
    /// Answers that have arrived since the last call.
    pub fn poll(&self) -> Vec<Answer> {
        self.rx.try_iter().collect()
    }

    /// Opens the "Open recordings" dialog; `wake` repaints when it answers.
    pub fn open(&self, wake: impl Fn() + Send + 'static) {
        let tx = self.tx.clone();
        let dialog = rfd::AsyncFileDialog::new()
            .set_title("Open recordings")
            .add_filter("recordings", &["mcap", "csv"])
            .add_filter("all files", &["*"]);
        spawn(async move {
            let Some(files) = dialog.pick_files().await else {
                return;
            };
            let mut sources = Vec::new();
            for f in files {
                sources.push(source_of(f).await);
            }
            let _ = tx.send(Answer::Open(sources));
            wake();
        });
    }

    /// Asks where to save `bytes` (suggesting `name`) and writes them; in
    /// the browser, downloads them.
    pub fn save(&self, name: &str, bytes: Vec<u8>, wake: impl Fn() + Send + 'static) {
        let tx = self.tx.clone();
        let dialog = rfd::AsyncFileDialog::new()
            .set_title("Export")
            .set_file_name(name);
        spawn(async move {
            let Some(handle) = dialog.save_file().await else {
                return;
            };
            let message = match handle.write(&bytes).await {
                Ok(()) => format!("exported {}", handle.file_name()),
                Err(e) => format!("could not write {}: {e}", handle.file_name()),
            };
            let _ = tx.send(Answer::Message(message));
            wake();
        });
    }
}

impl Dialogs {
    /// Reads files dropped on the page (browser: asynchronously) and
    /// answers with them as an [`Answer::Open`]; natively the paths are
    /// taken directly and this is not used.
    pub fn read_dropped(
        &self,
        files: Vec<egui::DroppedFileHandle>,
        wake: impl Fn() + Send + 'static,
    ) {
        if files.is_empty() {
            return;
        }
        let tx = self.tx.clone();
        spawn(async move {
            let mut sources = Vec::new();
            for f in files {
                let name = f.path().display().to_string();
                match read_dropped(&f).await {
                    Ok(bytes) => sources.push(Source::Bytes {
                        name,
                        bytes: bytes.into(),
                    }),
                    Err(e) => {
                        let _ = tx.send(Answer::Message(format!("{name}: {e}")));
                    }
                }
            }
            let _ = tx.send(Answer::Open(sources));
            wake();
        });
    }
}

#[cfg(not(target_arch = "wasm32"))]
async fn read_dropped(f: &egui::DroppedFileHandle) -> Result<Vec<u8>, String> {
    f.bytes()
}

#[cfg(target_arch = "wasm32")]
async fn read_dropped(f: &egui::DroppedFileHandle) -> Result<Vec<u8>, String> {
    f.bytes_async().await
}

#[cfg(not(target_arch = "wasm32"))]
async fn source_of(f: rfd::FileHandle) -> Source {
    Source::Path(f.path().to_path_buf())
}

#[cfg(target_arch = "wasm32")]
async fn source_of(f: rfd::FileHandle) -> Source {
    Source::Bytes {
        name: f.file_name(),
        bytes: f.read().await.into(),
    }
}

/// Runs a dialog's future: on a thread natively (the portal dialog blocks),
/// on the browser's event loop on the web.
#[cfg(not(target_arch = "wasm32"))]
fn spawn(future: impl Future<Output = ()> + Send + 'static) {
    let _ = std::thread::Builder::new()
        .name("dmpscope dialog".into())
        .spawn(move || pollster::block_on(future));
}

#[cfg(target_arch = "wasm32")]
fn spawn(future: impl Future<Output = ()> + 'static) {
    wasm_bindgen_futures::spawn_local(future);
}
