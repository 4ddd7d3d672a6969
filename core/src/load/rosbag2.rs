//! Folders: a rosbag2 bag is one recording, however many files it was split
//! into (its `metadata.yaml` lists them in order; without one, files named
//! `<folder>_<N>.mcap` are its splits, ordered by N), so a reach across a
//! split stays one stream. Any other folder holds recordings: each `.mcap`
//! file on its own, and each sub-folder walked the same way (a folder of
//! bags). File-compressed bags (`.mcap.zstd`) are decompressed as they are
//! read; message-compressed ones in the MCAP reader.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::error::{Error, Result};
use crate::load::collect::Loaded;
use crate::load::demo::RawDemo;
use crate::load::formats;
use crate::load::formats::Reader;
use crate::load::mcap::{READ_PIECE, load_reader};
use crate::load::options::LoadOptions;

/// The file name that marks a rosbag2 folder.
pub const ROSBAG2_METADATA: &str = "metadata.yaml";

/// What a folder is.
#[derive(Debug, PartialEq)]
pub enum Folder {
    /// A rosbag2 bag: its files in recording order.
    Bag(Vec<PathBuf>),
    /// A folder of recordings: its `.mcap` files and sub-folders, by name.
    Recordings {
        /// The `.mcap` (and `.mcap.zstd`) files.
        files: Vec<PathBuf>,
        /// The sub-folders.
        folders: Vec<PathBuf>,
    },
}

/// Whether a path names a file a folder of recordings is walked for (the
/// registry's [`formats::walked`]: MCAP, plain or zstd-compressed).
pub fn is_mcap(path: &Path) -> bool {
    formats::by_name(&path.to_string_lossy())
        .is_some_and(|f| matches!(f.reader, Reader::Mcap | Reader::ZstdMcap))
}

/// Whether a file name says zstd-compressed MCAP.
pub fn is_zstd(name: &str) -> bool {
    formats::by_name(name).is_some_and(|f| f.reader == Reader::ZstdMcap)
}

/// Looks at a folder: a bag or a folder of recordings.
pub fn classify(folder: &Path) -> Result<Folder> {
    let io = |reason| Error::Io {
        file: folder.display().to_string(),
        reason,
    };
    let mut files = Vec::new();
    let mut folders = Vec::new();
    let mut db3 = false;
    for entry in std::fs::read_dir(folder).map_err(io)? {
        let path = entry.map_err(io)?.path();
        if path.is_dir() {
            folders.push(path);
        } else if formats::walked(&path) {
            files.push(path);
        } else if path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("db3"))
        {
            db3 = true;
        }
    }
    files.sort();
    folders.sort();
    let metadata = folder.join(ROSBAG2_METADATA);
    if metadata.is_file() {
        let text = std::fs::read_to_string(&metadata).map_err(|reason| Error::Io {
            file: metadata.display().to_string(),
            reason,
        })?;
        let listed = listed_files(&text);
        if !listed.is_empty() {
            let mut bag = Vec::new();
            for name in listed {
                let path = folder.join(&name);
                if !path.is_file() {
                    return Err(Error::Source {
                        path: metadata.display().to_string(),
                        reason: format!("lists {name}, which is not in the folder"),
                    });
                }
                if !is_mcap(&path) {
                    return Err(Error::Source {
                        path: path.display().to_string(),
                        reason: "a rosbag2 file that is not MCAP (SQLite .db3?): convert the bag \
                                 with `ros2 bag convert` to MCAP storage"
                            .to_owned(),
                    });
                }
                bag.push(path);
            }
            return Ok(Folder::Bag(bag));
        }
        if !files.is_empty() && files.iter().all(|f| is_mcap(f)) {
            return Ok(Folder::Bag(by_split_index(files)));
        }
    }
    if !files.is_empty() && files.iter().all(|f| split_index(folder, f).is_some()) {
        return Ok(Folder::Bag(by_split_index(files)));
    }
    if files.is_empty() && folders.is_empty() {
        let reason = if db3 {
            "holds a rosbag2 recording in SQLite (.db3), which dmpscope does not read: \
             convert it with `ros2 bag convert` to MCAP storage"
        } else {
            "folder holds no .mcap file (nor .mcap.zstd, ROS 1 .bag or .csv)"
        };
        return Err(Error::Source {
            path: folder.display().to_string(),
            reason: reason.to_owned(),
        });
    }
    Ok(Folder::Recordings { files, folders })
}

/// The split index N of `<folder>_<N>.mcap` in `folder`.
fn split_index(folder: &Path, file: &Path) -> Option<u64> {
    let stem = folder.file_name()?.to_string_lossy().into_owned();
    let name = file.file_name()?.to_string_lossy().into_owned();
    let rest = name.strip_prefix(&stem)?.strip_prefix('_')?;
    let digits: String = rest.chars().take_while(char::is_ascii_digit).collect();
    let tail = &rest[digits.len()..];
    if digits.is_empty() || !is_mcap(Path::new(&format!("x{tail}"))) {
        return None;
    }
    digits.parse().ok()
}

fn by_split_index(mut files: Vec<PathBuf>) -> Vec<PathBuf> {
    let index = |p: &PathBuf| {
        let name = p.file_name().map(|n| n.to_string_lossy().into_owned());
        let digits: String = name
            .unwrap_or_default()
            .rsplit('_')
            .next()
            .unwrap_or_default()
            .chars()
            .take_while(char::is_ascii_digit)
            .collect();
        digits.parse::<u64>().unwrap_or(u64::MAX)
    };
    files.sort_by_key(|p| (index(p), p.clone()));
    files
}

/// The `relative_file_paths` list of a rosbag2 `metadata.yaml` (block
/// style, as rosbag2 and the `rosbags` library write it; flow style
/// `[a, b]` too).
pub fn listed_files(yaml: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut lines = yaml.lines();
    while let Some(line) = lines.next() {
        let Some(rest) = line.trim().strip_prefix("relative_file_paths:") else {
            continue;
        };
        let rest = rest.trim();
        if let Some(flow) = rest.strip_prefix('[') {
            let flow = flow.trim_end_matches(']');
            out.extend(flow.split(',').map(unquote).filter(|s| !s.is_empty()));
            return out;
        }
        for item in lines.by_ref() {
            let item = item.trim();
            match item.strip_prefix("- ") {
                Some(name) => out.push(unquote(name)),
                None if item.is_empty() => {}
                None => break,
            }
        }
        return out;
    }
    out
}

fn unquote(s: &str) -> String {
    s.trim().trim_matches(|c| c == '"' || c == '\'').to_owned()
}

/// Reads one MCAP file, decompressing a `.mcap.zstd` as it goes.
pub fn read_file(path: &Path, label: &str, options: &LoadOptions) -> Result<Loaded> {
    let file = std::fs::File::open(path).map_err(|reason| Error::Io {
        file: label.to_owned(),
        reason,
    })?;
    let buffered = std::io::BufReader::with_capacity(READ_PIECE, file);
    if is_zstd(label) {
        let decoder =
            zstd::stream::read::Decoder::with_buffer(buffered).map_err(|e| Error::Source {
                path: label.to_owned(),
                reason: format!(
                    "a zstd-compressed file that does not open ({e}); `ros2 bag decompress` \
                     or `zstd -d` writes an uncompressed copy"
                ),
            })?;
        return load_reader(label, decoder, options);
    }
    drop(buffered);
    let mut file = crate::load::access::FileAt::open(path).map_err(|reason| Error::Io {
        file: label.to_owned(),
        reason,
    })?;
    crate::load::access::block_on(crate::load::mcap::read_mcap(label, &mut file, options))
}

/// Reads a bag's files as one recording: the streams of each topic joined
/// across the files in order, named `<bag folder>:<topic>`.
pub fn read_bag(folder: &Path, files: &[PathBuf], options: &LoadOptions) -> Result<Loaded> {
    let label = folder.display().to_string();
    let bag_name = folder
        .file_name()
        .map_or_else(|| label.clone(), |n| n.to_string_lossy().into_owned());
    let mut joined: BTreeMap<String, RawDemo> = BTreeMap::new();
    let mut out = Loaded::default();
    let mut empty = Vec::new();
    for file in files {
        let file_label = file.display().to_string();
        let loaded = match read_file(file, &file_label, options) {
            Ok(l) => l,
            Err(Error::NoDemos { skipped, .. }) if files.len() > 1 => {
                empty.push(file_label);
                out.skipped.extend(skipped);
                continue;
            }
            Err(e) => return Err(e),
        };
        out.skipped.extend(loaded.skipped);
        out.warnings.extend(loaded.warnings);
        out.notes.extend(loaded.notes);
        for demo in loaded.demos {
            match joined.get_mut(&demo.topic) {
                Some(stream) => stream.extend(demo),
                None => {
                    let topic = demo.topic.clone();
                    joined.insert(
                        topic.clone(),
                        RawDemo {
                            name: format!("{bag_name}:{topic}"),
                            file: label.clone(),
                            ..demo
                        },
                    );
                }
            }
        }
    }
    out.skipped.sort();
    out.skipped.dedup();
    if joined.is_empty() {
        return Err(Error::NoDemos {
            file: label,
            skipped: out.skipped,
        });
    }
    if files.len() > 1 {
        out.notes.push(format!(
            "{label}: a rosbag2 bag split into {} files, read as one recording{}",
            files.len(),
            if empty.is_empty() {
                String::new()
            } else {
                format!(" ({} hold no pose topic)", empty.join(", "))
            }
        ));
    }
    out.demos = joined.into_values().collect();
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn metadata_lists_files_in_block_and_flow_style() {
        let yaml = "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: mcap\n  \
                    relative_file_paths:\n    - bag_0.mcap\n    - \"bag_1.mcap\"\n  duration:\n    \
                    nanoseconds: 5\n";
        assert_eq!(listed_files(yaml), ["bag_0.mcap", "bag_1.mcap"]);
        assert_eq!(
            listed_files("relative_file_paths: [a_0.mcap.zstd, 'a_1.mcap.zstd']\n"),
            ["a_0.mcap.zstd", "a_1.mcap.zstd"]
        );
        assert!(listed_files("files: []").is_empty());
    }

    #[test]
    fn split_names_are_ordered_by_their_number() {
        let folder = Path::new("/x/run");
        assert_eq!(
            split_index(folder, Path::new("/x/run/run_10.mcap")),
            Some(10)
        );
        assert_eq!(
            split_index(folder, Path::new("/x/run/run_2.mcap.zstd")),
            Some(2)
        );
        assert_eq!(split_index(folder, Path::new("/x/run/other_1.mcap")), None);
        let files = vec![
            PathBuf::from("/x/run/run_10.mcap"),
            PathBuf::from("/x/run/run_2.mcap"),
        ];
        assert_eq!(by_split_index(files)[0], PathBuf::from("/x/run/run_2.mcap"));
    }
}
