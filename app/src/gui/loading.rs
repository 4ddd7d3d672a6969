//! Files to demos for the app: MCAP (streamed from a path, or from bytes a
//! browser handed over) or CSV, errors kept as text to show, never a crash.
//! Loading runs off the frame ([`PendingLoad`]).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use dmpscope_core::io::{LoadOptions, csv::load_csv, load_bytes_with, load_path_with};
use dmpscope_core::{DemoInfo, RawDemo};

use super::task::Task;

/// A demo in the demos panel.
#[derive(Clone, Debug)]
pub struct DemoEntry {
    /// The demo as loaded.
    pub raw: RawDemo,
    /// Its summary for the panel, computed once at load (not per frame).
    pub info: DemoInfo,
    /// Whether it takes part in the model.
    pub included: bool,
}

/// What loading some files gave: demos, and messages for the user.
#[derive(Default)]
pub struct LoadResult {
    /// The demos found.
    pub demos: Vec<DemoEntry>,
    /// Errors (a file that could not be read) and warnings.
    pub messages: Vec<String>,
}

/// The bundled sample, built into the program (native and web alike).
pub fn sample_source() -> Source {
    static SAMPLE: &[u8] = include_bytes!("../../../assets/reach10.mcap");
    Source::Bytes {
        name: "reach10.mcap".into(),
        bytes: Arc::from(SAMPLE),
    }
}

/// A recording to load: a file on disk, or bytes with a name (a browser
/// upload or drop).
#[derive(Clone, Debug)]
pub enum Source {
    /// A path.
    Path(PathBuf),
    /// Bytes and the file's name.
    Bytes {
        /// The file name (shown, and its extension picks the reader).
        name: String,
        /// The contents.
        bytes: Arc<[u8]>,
    },
}

impl Source {
    /// The name shown for the source.
    pub fn name(&self) -> String {
        match self {
            Self::Path(p) => p.display().to_string(),
            Self::Bytes { name, .. } => name.clone(),
        }
    }

    fn is_csv(&self) -> bool {
        Path::new(&self.name())
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("csv"))
    }

    fn load(&self) -> Result<(Vec<RawDemo>, Vec<String>), String> {
        let name = self.name();
        let options = LoadOptions::default();
        if self.is_csv() {
            let text = match self {
                Self::Path(p) => std::fs::read_to_string(p).map_err(|e| format!("{name}: {e}"))?,
                Self::Bytes { bytes, .. } => String::from_utf8(bytes.to_vec())
                    .map_err(|e| format!("{name}: not UTF-8 text: {e}"))?,
            };
            return load_csv(&name, &text)
                .map(|d| (vec![d], Vec::new()))
                .map_err(|e| e.to_string());
        }
        let loaded = match self {
            Self::Path(p) => load_path_with(p, &options),
            Self::Bytes { bytes, .. } => load_bytes_with(&name, bytes, &options),
        };
        loaded
            .map(|l| (l.demos, l.warnings))
            .map_err(|e| e.to_string())
    }
}

/// Loads every source; one that fails adds a message and nothing else.
pub fn load_sources(sources: &[Source]) -> LoadResult {
    let mut out = LoadResult::default();
    for source in sources {
        match source.load() {
            Ok((demos, warnings)) => {
                out.messages.extend(warnings);
                out.demos.extend(demos.into_iter().map(|raw| DemoEntry {
                    info: raw.info(),
                    raw,
                    included: true,
                }));
            }
            Err(message) => out.messages.push(message),
        }
    }
    out
}

/// Sources being loaded off the frame ([`Task`]).
pub struct PendingLoad(Task<LoadResult>);

impl PendingLoad {
    /// Starts loading `sources`; `wake` is called when done.
    pub fn start(sources: Vec<Source>, wake: impl Fn() + Send + 'static) -> Self {
        Self(Task::start("loading", move || load_sources(&sources), wake))
    }

    /// The result once loading is done.
    pub fn poll(&mut self) -> Option<LoadResult> {
        self.0.poll().map(|r| {
            r.unwrap_or_else(|message| LoadResult {
                demos: Vec::new(),
                messages: vec![message],
            })
        })
    }
}
