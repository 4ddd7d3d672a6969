//! File dialogs, off the frame: "Open" picks recordings (files, or a folder
//! such as a rosbag2 bag; paths natively, names and bytes in the browser,
//! through `rfd`'s async dialogs) and "Save" writes an export.
//!
//! Natively `rfd` needs an xdg-desktop-portal on the session bus or
//! `zenity`; without either its dialogs return nothing at once. dmpscope
//! then opens its own file browser (`egui_file`) in the window instead of
//! doing nothing: when neither is there to begin with, when the system
//! dialog answered "nothing" faster than a person could cancel it, or when
//! asked to (`DMPSCOPE_FILE_BROWSER=app`, or [`Dialogs::app_browser_only`]
//! in tests, which never open a system dialog). The browser starts in the
//! folder of the last recording opened.

use std::sync::Arc;
use std::sync::mpsc::{Receiver, Sender, channel};

use dmpscope_core::Notice;
use eframe::egui;

use crate::session::Source;

/// A system dialog that answers "nothing" this fast did not show itself.
#[cfg(not(target_arch = "wasm32"))]
const TOO_FAST_TO_CANCEL: std::time::Duration = std::time::Duration::from_millis(300);

/// What a dialog gave back.
pub enum Answer {
    /// Recordings picked to open.
    Open(Vec<Source>),
    /// A message for the user (an export written, or why not).
    Say(Notice),
    /// The system has no open dialog: use the app's own browser.
    NoOpenDialog {
        /// A folder was asked for.
        folder: bool,
    },
    /// The system has no save dialog: use the app's own browser.
    NoSaveDialog {
        /// The suggested file name.
        name: String,
        /// What to write.
        bytes: Vec<u8>,
    },
}

/// The app's own file browser, natively.
#[cfg(not(target_arch = "wasm32"))]
struct Browser {
    dialog: egui_file::FileDialog,
    /// What to write when saving; `None` when opening.
    save: Option<Vec<u8>>,
}

/// Dialogs under way and their answers.
pub struct Dialogs {
    tx: Sender<Answer>,
    rx: Receiver<Answer>,
    /// Use the app's own browser even where the system has a dialog.
    app_only: bool,
    #[cfg(not(target_arch = "wasm32"))]
    browser: Option<Browser>,
    /// Where the app's browser starts.
    #[cfg(not(target_arch = "wasm32"))]
    start: Option<std::path::PathBuf>,
}

impl Default for Dialogs {
    fn default() -> Self {
        let (tx, rx) = channel();
        let app_only =
            std::env::var("DMPSCOPE_FILE_BROWSER").is_ok_and(|v| v.eq_ignore_ascii_case("app"));
        Self {
            tx,
            rx,
            app_only,
            #[cfg(not(target_arch = "wasm32"))]
            browser: None,
            #[cfg(not(target_arch = "wasm32"))]
            start: None,
        }
    }
}

impl Dialogs {
    /// Dialogs that always use the app's own browser (tests; users set
    /// `DMPSCOPE_FILE_BROWSER=app`), starting in `start`.
    pub fn app_browser_only(start: Option<std::path::PathBuf>) -> Self {
        let mut d = Self {
            app_only: true,
            ..Self::default()
        };
        d.remember(start);
        d
    }

    /// The folder the app's browser starts in next: `path`'s, if any.
    pub fn remember(&mut self, path: Option<std::path::PathBuf>) {
        #[cfg(not(target_arch = "wasm32"))]
        if let Some(p) = path {
            self.start = if p.is_dir() {
                Some(p)
            } else {
                p.parent().map(ToOwned::to_owned)
            };
        }
        #[cfg(target_arch = "wasm32")]
        let _ = path;
    }

    fn system(&self) -> bool {
        !self.app_only && system_dialogs()
    }

    /// Answers that have arrived since the last call.
    pub fn poll(&self) -> Vec<Answer> {
        self.rx.try_iter().collect()
    }

    /// Opens the "Open recordings" dialog (a folder when `folder`); `wake`
    /// repaints when it answers.
    pub fn open(&mut self, folder: bool, wake: impl Fn() + Send + Sync + 'static) {
        let wake: Wake = Arc::new(wake);
        if !self.system() {
            let _ = self.tx.send(Answer::NoOpenDialog { folder });
            wake();
            return;
        }
        let tx = self.tx.clone();
        let dialog = rfd::AsyncFileDialog::new().set_title("Open recordings");
        spawn(
            self.tx.clone(),
            Answer::NoOpenDialog { folder },
            async move {
                let started = web_time::Instant::now();
                let picked = if folder {
                    pick_folder(dialog).await
                } else {
                    dialog
                        .add_filter(
                            "recordings",
                            &dmpscope_core::load::formats::dialog_extensions(),
                        )
                        .add_filter("all files", &["*"])
                        .pick_files()
                        .await
                };
                let answer = match picked {
                    Some(files) => {
                        let mut sources = Vec::new();
                        for f in files {
                            sources.push(source_of(f, &wake).await);
                        }
                        Answer::Open(sources)
                    }
                    None if too_fast(started) => Answer::NoOpenDialog { folder },
                    None => return,
                };
                let _ = tx.send(answer);
                wake();
            },
        );
    }

    /// Asks where to save `bytes` (suggesting `name`) and writes them; in
    /// the browser, downloads them.
    pub fn save(&mut self, name: &str, bytes: Vec<u8>, wake: impl Fn() + Send + 'static) {
        if !self.system() {
            let _ = self.tx.send(Answer::NoSaveDialog {
                name: name.to_owned(),
                bytes,
            });
            wake();
            return;
        }
        let tx = self.tx.clone();
        let name = name.to_owned();
        let dialog = rfd::AsyncFileDialog::new()
            .set_title("Export")
            .set_file_name(&name);
        let failed = Answer::Say(Notice::error(format!(
            "cannot open the save dialog for {name}"
        )));
        spawn(self.tx.clone(), failed, async move {
            let started = web_time::Instant::now();
            let answer = match dialog.save_file().await {
                Some(handle) => Answer::Say(match handle.write(&bytes).await {
                    Ok(()) => Notice::info(format!("exported {}", handle.file_name())),
                    Err(e) => Notice::error(format!("could not write {}: {e}", handle.file_name())),
                }),
                None if too_fast(started) => Answer::NoSaveDialog { name, bytes },
                None => return,
            };
            let _ = tx.send(answer);
            wake();
        });
    }

    /// Reads files dropped on the page (browser: asynchronously) and
    /// answers with them as an [`Answer::Open`]; natively the paths are
    /// taken directly and this is not used.
    pub fn read_dropped(
        &self,
        files: Vec<egui::DroppedFileHandle>,
        wake: impl Fn() + Send + Sync + 'static,
    ) -> Vec<Source> {
        let wake: Wake = Arc::new(wake);
        // A browser's `File` is a source at once (read in slices later).
        let mut now = Vec::new();
        let mut later = Vec::new();
        for f in files {
            match dropped_source(&f, &wake) {
                Some(source) => now.push(source),
                None => later.push(f),
            }
        }
        let files = later;
        if files.is_empty() {
            return now;
        }
        let tx = self.tx.clone();
        let failed = Answer::Say(Notice::error("cannot read the dropped files"));
        spawn(self.tx.clone(), failed, async move {
            let mut sources = Vec::new();
            for f in files {
                let name = f.path().display().to_string();
                match read_dropped(&f).await {
                    Ok(bytes) => sources.push(Source::Bytes {
                        name,
                        bytes: bytes.into(),
                    }),
                    Err(e) => {
                        let _ = tx.send(Answer::Say(Notice::error(format!("{name}: {e}"))));
                    }
                }
            }
            let _ = tx.send(Answer::Open(sources));
            wake();
        });
        now
    }
}

#[cfg(not(target_arch = "wasm32"))]
impl Dialogs {
    /// Opens the app's own browser to pick recordings (a folder when
    /// `folder`).
    pub fn browse(&mut self, folder: bool) {
        let mut dialog = if folder {
            egui_file::FileDialog::select_folder().title("Open a folder of recordings")
        } else {
            egui_file::FileDialog::open_file()
                .title("Open recordings")
                .multi_select(true)
        };
        if let Some(start) = &self.start {
            dialog = dialog.initial_path(start.clone());
        }
        dialog.open();
        self.browser = Some(Browser { dialog, save: None });
    }

    /// Opens the app's own browser to save `bytes`, suggesting `name`.
    pub fn browse_save(&mut self, name: &str, bytes: Vec<u8>) {
        let mut dialog = egui_file::FileDialog::save_file()
            .title("Export")
            .default_filename(name);
        if let Some(start) = &self.start {
            dialog = dialog.initial_path(start.clone());
        }
        dialog.open();
        self.browser = Some(Browser {
            dialog,
            save: Some(bytes),
        });
    }

    /// Shows the app's browser while it is open; its answer, once given.
    pub fn show_browser(&mut self, ctx: &egui::Context) -> Vec<Answer> {
        let Some(browser) = &mut self.browser else {
            return Vec::new();
        };
        let dialog = &mut browser.dialog;
        dialog.show(ctx);
        let answer = match dialog.state() {
            egui_file::State::Open => return Vec::new(),
            egui_file::State::Selected => match (&browser.save, dialog.path()) {
                (Some(bytes), Some(path)) => Some(Answer::Say(match std::fs::write(path, bytes) {
                    Ok(()) => Notice::info(format!("exported {}", path.display())),
                    Err(e) => Notice::error(format!("could not write {}: {e}", path.display())),
                })),
                (None, _) => {
                    let mut picked: Vec<_> = dialog
                        .selection()
                        .into_iter()
                        .map(ToOwned::to_owned)
                        .collect();
                    if picked.is_empty() {
                        picked.extend(dialog.path().map(ToOwned::to_owned));
                    }
                    Some(Answer::Open(picked.into_iter().map(Source::Path).collect()))
                }
                (Some(_), None) => None,
            },
            egui_file::State::Cancelled | egui_file::State::Closed => None,
        };
        self.browser = None;
        answer.into_iter().collect()
    }
}

#[cfg(target_arch = "wasm32")]
impl Dialogs {
    /// The browser has no file system to browse: its own dialog is used.
    pub fn browse(&mut self, _folder: bool) {}

    /// The browser's download always exists.
    pub fn browse_save(&mut self, _name: &str, _bytes: Vec<u8>) {}

    /// Nothing to show in the browser.
    pub fn show_browser(&mut self, _ctx: &egui::Context) -> Vec<Answer> {
        Vec::new()
    }
}

/// Whether a system dialog can show itself: natively an xdg-desktop-portal
/// reached over the session bus, or `zenity`; in the browser always.
fn system_dialogs() -> bool {
    #[cfg(not(target_arch = "wasm32"))]
    {
        let on_path = |exe: &str| {
            std::env::var_os("PATH")
                .is_some_and(|p| std::env::split_paths(&p).any(|d| d.join(exe).is_file()))
        };
        let bus = std::env::var_os("DBUS_SESSION_BUS_ADDRESS").is_some()
            || std::env::var_os("XDG_RUNTIME_DIR")
                .is_some_and(|d| std::path::Path::new(&d).join("bus").exists());
        bus || on_path("zenity")
    }
    #[cfg(target_arch = "wasm32")]
    true
}

#[cfg(not(target_arch = "wasm32"))]
fn too_fast(started: web_time::Instant) -> bool {
    started.elapsed() < TOO_FAST_TO_CANCEL
}

#[cfg(target_arch = "wasm32")]
fn too_fast(_started: web_time::Instant) -> bool {
    false
}

#[cfg(not(target_arch = "wasm32"))]
async fn read_dropped(f: &egui::DroppedFileHandle) -> Result<Vec<u8>, String> {
    f.bytes()
}

#[cfg(target_arch = "wasm32")]
async fn read_dropped(f: &egui::DroppedFileHandle) -> Result<Vec<u8>, String> {
    f.bytes_async().await
}

/// A dropped file as a source: in the browser its `File`, read in slices
/// (never whole); natively (and where the browser gives no `File`) `None`.
#[cfg(target_arch = "wasm32")]
fn dropped_source(f: &egui::DroppedFileHandle, wake: &Wake) -> Option<Source> {
    f.web_file()
        .map(|file| super::blob_source::source_of_file(file.clone(), Arc::clone(wake)))
}

#[cfg(not(target_arch = "wasm32"))]
fn dropped_source(_f: &egui::DroppedFileHandle, _wake: &Wake) -> Option<Source> {
    None
}

/// What asks for a frame.
type Wake = Arc<dyn Fn() + Send + Sync>;

#[cfg(not(target_arch = "wasm32"))]
async fn source_of(f: rfd::FileHandle, _wake: &Wake) -> Source {
    Source::Path(f.path().to_path_buf())
}

#[cfg(target_arch = "wasm32")]
async fn source_of(f: rfd::FileHandle, wake: &Wake) -> Source {
    super::blob_source::source_of_file(f.inner().clone(), Arc::clone(wake))
}

#[cfg(not(target_arch = "wasm32"))]
async fn pick_folder(dialog: rfd::AsyncFileDialog) -> Option<Vec<rfd::FileHandle>> {
    dialog.pick_folder().await.map(|f| vec![f])
}

#[cfg(target_arch = "wasm32")]
async fn pick_folder(dialog: rfd::AsyncFileDialog) -> Option<Vec<rfd::FileHandle>> {
    dialog.pick_files().await
}

/// Runs a dialog's future: on a thread natively (the portal dialog blocks),
/// on the browser's event loop on the web. When no thread can be started,
/// `failed` is the answer.
#[cfg(not(target_arch = "wasm32"))]
fn spawn(tx: Sender<Answer>, failed: Answer, future: impl Future<Output = ()> + Send + 'static) {
    let started = std::thread::Builder::new()
        .name("dmpscope dialog".into())
        .spawn(move || pollster::block_on(future));
    if started.is_err() {
        let _ = tx.send(failed);
    }
}

#[cfg(target_arch = "wasm32")]
fn spawn(_tx: Sender<Answer>, _failed: Answer, future: impl Future<Output = ()> + 'static) {
    wasm_bindgen_futures::spawn_local(future);
}
