//! One entry point for every recording a user can name: an MCAP file, a CSV
//! file, a folder (a rosbag2 folder with `metadata.yaml`, or any folder of
//! `.mcap` files), or the bytes of a file a browser handed over. The CLI and
//! the app both load through [`crate::arrange::streams::load_source`], so the same file with the same
//! [`LoadOptions`] gives the same demonstrations in both.

use std::path::Path;

use crate::error::{Error, Result};
use crate::load::access::{FileAt, ForwardAt, ReadAt, SliceAt, block_on};
use crate::load::collect::Loaded;
use crate::load::csv::load_csv;
use crate::load::demo::RawDemo;
use crate::load::formats;
use crate::load::formats::Reader;
use crate::load::mcap::{RECORD_LENGTH_LIMIT, read_mcap};
use crate::load::motive;
use crate::load::options::{LoadOptions, UpAxis};
use crate::load::rosbag1::read_bag;
use crate::load::rosbag2;
use crate::load::rosbag2::{Folder, ROSBAG2_METADATA};
use crate::notice::Notice;

/// Up to this many skipped topics are named one line each; more are one
/// line with their count (the names as details).
pub const SKIPPED_LISTED: usize = 3;

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
pub struct SourceStreams {
    /// The demonstrations (streams, before [`crate::arrange::streams::load_source`] groups them).
    pub demos: Vec<RawDemo>,
    /// Topics skipped, a truncated file's lost tail, and the like.
    pub notices: Vec<Notice>,
    /// Topics the reader did not read, with why (their schema, or what
    /// they are).
    pub skipped: Vec<(String, String)>,
}

/// Loads the streams of a source (one per topic and key), with the frame
/// filter, up axis and units of `options` applied but not its grouping
/// (whose demos get a warning when their size suggests other units).
pub fn load_streams(
    name: &str,
    data: SourceData<'_>,
    options: &LoadOptions,
) -> Result<SourceStreams> {
    let mut loaded = read_streams(name, data, options)?;
    for demo in &mut loaded.demos {
        options.units.apply(demo);
    }
    Ok(loaded)
}

fn read_streams(name: &str, data: SourceData<'_>, options: &LoadOptions) -> Result<SourceStreams> {
    match data {
        SourceData::Bytes(bytes) => block_on(read_source(name, &mut SliceAt(bytes), options)),
        SourceData::Path(path) => {
            let path = folder_of_metadata(path).unwrap_or(path);
            if path.is_dir() {
                return load_folder(path, options);
            }
            read_file(path, name, options)
        }
    }
}

/// Loads the streams of one recording file through `access` (its bytes
/// wherever they are: memory, a file, a browser's `File` read in slices),
/// as [`load_streams`] does: `name`'s suffix picks the reader, else the
/// first bytes do.
pub async fn load_streams_at<R: ReadAt>(
    name: &str,
    access: &mut R,
    options: &LoadOptions,
) -> Result<SourceStreams> {
    let mut loaded = read_source(name, access, options).await?;
    for demo in &mut loaded.demos {
        options.units.apply(demo);
    }
    Ok(loaded)
}

/// The streams of one recording file read through `access`.
async fn read_source<R: ReadAt>(
    name: &str,
    access: &mut R,
    options: &LoadOptions,
) -> Result<SourceStreams> {
    let io = |reason| Error::Io {
        file: name.to_owned(),
        reason,
    };
    let head = access.read_at(0, 16).await.map_err(io)?;
    match formats::detect(name, &head).reader {
        Reader::Csv => {
            let bytes = whole(name, access).await?;
            let text = std::str::from_utf8(&bytes).map_err(|e| Error::Source {
                path: name.to_owned(),
                reason: format!("not UTF-8 text: {e}"),
            })?;
            csv_demo(name, text, options)
        }
        Reader::ZstdMcap => {
            let bytes = whole(name, access).await?;
            let decoder =
                zstd::stream::read::Decoder::new(&bytes[..]).map_err(|e| not_zstd(name, &e))?;
            let loaded = read_mcap(name, &mut ForwardAt::new(decoder), options).await;
            Ok(from_mcap(
                name,
                loaded.map_err(|e| match e {
                    Error::Io { reason, .. } => not_zstd(name, &reason),
                    other => other,
                })?,
            ))
        }
        Reader::Mcap => Ok(from_mcap(name, read_mcap(name, access, options).await?)),
        Reader::Bag => Ok(from_mcap(name, read_bag(name, access, options).await?)),
    }
}

/// A zstd-compressed file that does not decompress, in words.
fn not_zstd(name: &str, e: &dyn std::fmt::Display) -> Error {
    Error::Source {
        path: name.to_owned(),
        reason: format!(
            "a zstd-compressed file that does not decompress ({e}); `zstd -d` \
             writes an uncompressed copy"
        ),
    }
}

/// The whole of a file that is read whole (CSV text, a zstd-compressed
/// MCAP), within the limit of one record.
async fn whole<R: ReadAt>(name: &str, access: &mut R) -> Result<Vec<u8>> {
    let size = access.size().unwrap_or(0);
    if size > RECORD_LENGTH_LIMIT as u64 {
        return Err(Error::Source {
            path: name.to_owned(),
            reason: format!(
                "{size} bytes, more than the {RECORD_LENGTH_LIMIT} bytes a CSV or a \
                 zstd-compressed file may hold (decompress it, or split it)"
            ),
        });
    }
    access
        .read_at(0, size as usize)
        .await
        .map_err(|reason| Error::Io {
            file: name.to_owned(),
            reason,
        })
}

fn load_folder(folder: &Path, options: &LoadOptions) -> Result<SourceStreams> {
    match rosbag2::classify(folder)? {
        Folder::Bag(files) => {
            let label = folder.display().to_string();
            Ok(from_mcap(
                &label,
                rosbag2::read_bag(folder, &files, options)?,
            ))
        }
        Folder::Recordings { files, folders } => {
            let mut out = SourceStreams::default();
            let mut no_poses = Vec::new();
            for file in files {
                let label = file.display().to_string();
                let is_csv = formats::by_name(&label).is_some_and(|f| f.reader == Reader::Csv);
                let loaded = match read_file(&file, &label, options) {
                    Ok(loaded) => loaded,
                    // A CSV beside the recordings that is not a demo (a
                    // table, notes) does not stop the folder.
                    Err(e @ (Error::Decode { .. } | Error::NonFinite { .. })) if is_csv => {
                        out.notices.push(Notice::warning(format!(
                            "{e}: skipped (not a t,x,y,z demonstration nor a readable Motive export)"
                        )));
                        continue;
                    }
                    // A recording of other things (joint states, flags)
                    // beside the demonstrations does not stop the folder.
                    Err(e @ Error::NoDemos { .. }) => {
                        no_poses.push(e.to_string());
                        out.notices.push(Notice::warning(format!("{e}: skipped")));
                        continue;
                    }
                    Err(e) => return Err(e),
                };
                out.demos.extend(loaded.demos);
                out.notices.extend(loaded.notices);
                out.skipped.extend(loaded.skipped);
            }
            for sub in folders {
                match load_folder(&sub, options) {
                    Ok(loaded) => {
                        out.demos.extend(loaded.demos);
                        out.notices.extend(loaded.notices);
                        out.skipped.extend(loaded.skipped);
                    }
                    // A sub-folder without recordings is not an error of the
                    // folder the user named.
                    Err(Error::Source { path, reason }) => {
                        out.notices
                            .push(Notice::info(format!("{path}: skipped: {reason}")));
                    }
                    Err(e) => return Err(e),
                }
            }
            if out.demos.is_empty() {
                let mut reason = "holds no recording with a pose topic (its files and \
                                  sub-folders were read; see the notes)"
                    .to_owned();
                if !no_poses.is_empty() {
                    let more = no_poses.len().saturating_sub(3);
                    reason = format!(
                        "holds no recording with a pose topic: {}{}",
                        no_poses[..no_poses.len().min(3)].join("; "),
                        if more > 0 {
                            format!("; and {more} more")
                        } else {
                            String::new()
                        }
                    );
                }
                return Err(Error::Source {
                    path: folder.display().to_string(),
                    reason,
                });
            }
            Ok(out)
        }
    }
}

/// Reads one recording file: CSV text, a ROS 1 bag (by its name or its
/// first bytes) from its bytes, else MCAP, plain or compressed (rosbag2's
/// reader tells them apart), which also says what a file of no known format
/// is not.
fn read_file(path: &Path, label: &str, options: &LoadOptions) -> Result<SourceStreams> {
    let io = |reason| Error::Io {
        file: label.to_owned(),
        reason,
    };
    let mut head = [0u8; 16];
    let n = std::fs::File::open(path)
        .and_then(|mut f| std::io::Read::read(&mut f, &mut head))
        .map_err(io)?;
    let format = formats::by_name(label)
        .or_else(|| formats::by_name(&path.to_string_lossy()))
        .or_else(|| formats::by_magic(&head[..n]));
    match format.map(|f| f.reader) {
        Some(Reader::Csv) => {
            let text = std::fs::read_to_string(path).map_err(io)?;
            csv_demo(label, &text, options)
        }
        Some(Reader::Bag) => {
            let mut file = FileAt::open(path).map_err(io)?;
            Ok(from_mcap(
                label,
                block_on(read_bag(label, &mut file, options))?,
            ))
        }
        _ => Ok(from_mcap(label, rosbag2::read_file(path, label, options)?)),
    }
}

/// A path naming a rosbag2 folder's `metadata.yaml` stands for the folder.
pub fn folder_of_metadata(path: &Path) -> Option<&Path> {
    let is_metadata = path
        .file_name()
        .is_some_and(|n| n.eq_ignore_ascii_case(ROSBAG2_METADATA));
    is_metadata.then(|| path.parent()).flatten()
}

/// A CSV file's demos: Motive's export (a stream per rigid body) or a
/// plain `t,x,y,z` file (one demo).
fn csv_demo(name: &str, text: &str, options: &LoadOptions) -> Result<SourceStreams> {
    let (mut demos, notices) = if motive::is_motive(text) {
        let (demos, mut notices) = motive::load_motive(name, text)?;
        if options.up == UpAxis::ZUp {
            notices.push(Notice::info(format!(
                "{name}: read z-up; Motive exports y-up unless set otherwise: --y-up \
                 (the app's Loading: up axis) turns it z-up"
            )));
        }
        (demos, notices)
    } else {
        (vec![load_csv(name, text)?], Vec::new())
    };
    for demo in &mut demos {
        for p in &mut demo.positions {
            *p = options.up.to_z_up((*p).into()).into();
        }
        for q in demo.orientations.iter_mut().flatten() {
            *q = options.up.orientation_to_z_up(*q);
        }
    }
    Ok(SourceStreams {
        demos,
        notices,
        ..SourceStreams::default()
    })
}

fn from_mcap(file: &str, loaded: Loaded) -> SourceStreams {
    let each =
        |(topic, schema): &(String, String)| format!("{file}: skipped topic {topic} ({schema})");
    let mut notices: Vec<Notice> = if loaded.skipped.len() > SKIPPED_LISTED {
        let mut n = vec![Notice::info(format!(
            "{file}: skipped {} topics that are not demonstrations (-v names each and why)",
            loaded.skipped.len()
        ))];
        n.extend(loaded.skipped.iter().map(|s| Notice::detail(each(s))));
        n
    } else {
        loaded
            .skipped
            .iter()
            .map(|s| Notice::info(each(s)))
            .collect()
    };
    notices.extend(loaded.notes.into_iter().map(Notice::info));
    notices.extend(loaded.warnings.into_iter().map(Notice::warning));
    SourceStreams {
        demos: loaded.demos,
        notices,
        skipped: loaded.skipped,
    }
}
