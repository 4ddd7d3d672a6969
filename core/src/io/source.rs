//! One entry point for every recording a user can name: an MCAP file, a CSV
//! file, a folder (a rosbag2 folder with `metadata.yaml`, or any folder of
//! `.mcap` files), or the bytes of a file a browser handed over. The CLI and
//! the app both load through [`load_source`], so the same file with the same
//! [`LoadOptions`] gives the same demonstrations in both.

use std::path::{Path, PathBuf};

use super::csv::load_csv;
use super::mcap_file::{
    LoadOptions, Loaded, READ_PIECE, load_bytes_with, load_path_with, load_reader,
};
use crate::demo::RawDemo;
use crate::error::{Error, Result};
use crate::group::group;
use crate::notice::Notice;

/// The file name that marks a rosbag2 folder.
pub const ROSBAG2_METADATA: &str = "metadata.yaml";

/// Where a recording's contents are.
#[derive(Clone, Copy, Debug)]
pub enum SourceData<'a> {
    /// A file or a folder on disk.
    Path(&'a Path),
    /// A file's contents in memory (a browser upload or drop, a test); its
    /// name's extension picks the reader.
    Bytes(&'a [u8]),
}

/// What one source gave: its demonstrations in load order (files by name,
/// then topic and key), and what the user should be told.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SourceDemos {
    /// The demonstrations (streams, before [`load_source`] groups them).
    pub demos: Vec<RawDemo>,
    /// Topics skipped, a truncated file's lost tail, and the like.
    pub notices: Vec<Notice>,
}

/// Loads the streams of a source (one per topic and key), with the frame
/// filter and up axis of `options` applied but not its grouping.
pub fn load_streams(
    name: &str,
    data: SourceData<'_>,
    options: &LoadOptions,
) -> Result<SourceDemos> {
    match data {
        SourceData::Bytes(bytes) if is_csv(name) => {
            let text = std::str::from_utf8(bytes).map_err(|e| Error::Source {
                path: name.to_owned(),
                reason: format!("not UTF-8 text: {e}"),
            })?;
            Ok(csv_demo(name, text, options)?)
        }
        SourceData::Bytes(bytes) => Ok(from_mcap(name, load_bytes_with(name, bytes, options)?)),
        SourceData::Path(path) => {
            let path = folder_of_metadata(path).unwrap_or(path);
            if path.is_dir() {
                return load_folder(path, options);
            }
            if is_csv(name) || has_extension(path, "csv") {
                let text = std::fs::read_to_string(path).map_err(|source| Error::Io {
                    file: name.to_owned(),
                    source,
                })?;
                return csv_demo(name, &text, options);
            }
            let file = std::fs::File::open(path).map_err(|source| Error::Io {
                file: name.to_owned(),
                source,
            })?;
            let reader = std::io::BufReader::with_capacity(READ_PIECE, file);
            Ok(from_mcap(name, load_reader(name, reader, options)?))
        }
    }
}

/// Loads a source, splits its streams at breaks in time (or bridges them)
/// as `options.gaps` says, and groups them into demonstrations as
/// `options.demos` says (method.md sections 1 and 11). Neither crosses
/// files, so loading sources one by one and pooling them gives the same
/// demonstrations as loading them together.
pub fn load_source(name: &str, data: SourceData<'_>, options: &LoadOptions) -> Result<SourceDemos> {
    let mut loaded = load_streams(name, data, options)?;
    let (streams, said) = crate::gaps::apply(std::mem::take(&mut loaded.demos), options.gaps);
    loaded.notices.extend(said);
    loaded.demos = group(streams, &options.demos)?;
    Ok(loaded)
}

/// The `.mcap` files a folder holds, sorted by name (a rosbag2 folder's
/// split files included); an error naming the folder when there is none.
pub fn folder_files(folder: &Path) -> Result<Vec<PathBuf>> {
    let io = |source| Error::Io {
        file: folder.display().to_string(),
        source,
    };
    let mut mcap = Vec::new();
    let mut db3 = false;
    for entry in std::fs::read_dir(folder).map_err(io)? {
        let path = entry.map_err(io)?.path();
        if has_extension(&path, "mcap") {
            mcap.push(path);
        } else if has_extension(&path, "db3") {
            db3 = true;
        }
    }
    mcap.sort();
    if mcap.is_empty() {
        let reason = if db3 {
            "holds a rosbag2 recording in SQLite (.db3), which dmpscope does not read: \
             convert it with `ros2 bag convert` to MCAP storage"
        } else {
            "folder holds no .mcap file"
        };
        return Err(Error::Source {
            path: folder.display().to_string(),
            reason: reason.to_owned(),
        });
    }
    Ok(mcap)
}

fn load_folder(folder: &Path, options: &LoadOptions) -> Result<SourceDemos> {
    let mut out = SourceDemos::default();
    for file in folder_files(folder)? {
        let label = file.display().to_string();
        let loaded = from_mcap(&label, load_path_with(&file, options)?);
        out.demos.extend(loaded.demos);
        out.notices.extend(loaded.notices);
    }
    Ok(out)
}

/// A path naming a rosbag2 folder's `metadata.yaml` stands for the folder.
fn folder_of_metadata(path: &Path) -> Option<&Path> {
    let is_metadata = path
        .file_name()
        .is_some_and(|n| n.eq_ignore_ascii_case(ROSBAG2_METADATA));
    is_metadata.then(|| path.parent()).flatten()
}

fn csv_demo(name: &str, text: &str, options: &LoadOptions) -> Result<SourceDemos> {
    let mut demo = load_csv(name, text)?;
    for p in &mut demo.positions {
        *p = options.up.to_z_up(*p);
    }
    Ok(SourceDemos {
        demos: vec![demo],
        notices: Vec::new(),
    })
}

fn from_mcap(file: &str, loaded: Loaded) -> SourceDemos {
    let mut notices: Vec<Notice> = loaded
        .skipped
        .iter()
        .map(|(topic, schema)| Notice::info(format!("{file}: skipped topic {topic} ({schema})")))
        .collect();
    notices.extend(loaded.warnings.into_iter().map(Notice::warning));
    SourceDemos {
        demos: loaded.demos,
        notices,
    }
}

fn is_csv(name: &str) -> bool {
    has_extension(Path::new(name), "csv")
}

fn has_extension(path: &Path, ext: &str) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case(ext))
}
