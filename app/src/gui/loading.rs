//! Files to demos for the app: MCAP (streamed) or CSV, errors kept as text
//! to show, never a crash.

use std::path::{Path, PathBuf};

use dmpscope_core::io::{LoadOptions, csv::load_csv, load_path_with};
use dmpscope_core::{DemoInfo, RawDemo};

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

/// The bundled sample, next to the executable's source tree or in the
/// working directory.
pub fn sample_path() -> PathBuf {
    let here = Path::new("assets/reach10.mcap");
    if here.exists() {
        return here.to_path_buf();
    }
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/reach10.mcap")
}

/// Loads every file; a file that fails adds a message and nothing else.
pub fn load_files(files: &[PathBuf]) -> LoadResult {
    let mut out = LoadResult::default();
    for path in files {
        let is_csv = path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("csv"));
        let loaded = if is_csv {
            std::fs::read_to_string(path)
                .map_err(|e| format!("{}: {e}", path.display()))
                .and_then(|text| {
                    load_csv(&path.display().to_string(), &text).map_err(|e| e.to_string())
                })
                .map(|d| (vec![d], Vec::new()))
        } else {
            load_path_with(path, &LoadOptions::default())
                .map(|l| (l.demos, l.warnings))
                .map_err(|e| e.to_string())
        };
        match loaded {
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
