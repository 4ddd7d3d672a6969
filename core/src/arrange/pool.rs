//! Several sources loaded into one list of demonstrations, as the CLI's
//! FILES and the Python package's `load(paths)` are: each source read and
//! arranged ([`arrange_source`]) in the order given, its notices handed
//! over before the next is read, the demos pooled and their names made
//! unique ([`unique_names`]).

use std::path::{Path, PathBuf};

use crate::arrange::streams::{arrange_source, unique_names};
use crate::error::{Error, Result};
use crate::load::demo::RawDemo;
use crate::load::options::LoadOptions;
use crate::load::source::{SourceData, SourceStreams, load_streams};
use crate::notice::Notice;

/// Reads one source's streams: its name as the user wrote it, its path and
/// the options ([`read_path`], or a reader with a progress bar).
pub type ReadSource<'a> = dyn FnMut(&str, &Path, &LoadOptions) -> Result<SourceStreams> + 'a;

/// The streams of the file or folder at `path`, named `name` in messages.
pub fn read_path(name: &str, path: &Path, options: &LoadOptions) -> Result<SourceStreams> {
    load_streams(name, SourceData::Path(path), options)
}

/// The demonstrations of every source in `paths`, in order, grouped as
/// `options` say, their names unique; `notify` gets each source's notices
/// as soon as it is read. An error names the source; no demonstration at
/// all is [`Error::NoDemonstration`].
pub fn load_demos(
    paths: &[PathBuf],
    options: &LoadOptions,
    read: &mut ReadSource<'_>,
    notify: &mut dyn FnMut(&[Notice]),
) -> Result<Vec<RawDemo>> {
    let mut demos = Vec::new();
    for path in paths {
        let name = path.display().to_string();
        let arranged = arrange_source(read(&name, path, options)?, options)?;
        notify(&arranged.notices);
        demos.extend(arranged.demos);
    }
    if demos.is_empty() {
        return Err(Error::NoDemonstration);
    }
    unique_names(&mut demos);
    Ok(demos)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_source_is_no_demonstration() {
        let mut seen = 0;
        let got = load_demos(&[], &LoadOptions::default(), &mut read_path, &mut |n| {
            seen += n.len();
        });
        assert!(matches!(got, Err(Error::NoDemonstration)));
        assert_eq!(seen, 0);
    }

    #[test]
    fn a_missing_file_is_named() {
        let path = PathBuf::from("no/such/recording.mcap");
        let got = load_demos(
            std::slice::from_ref(&path),
            &LoadOptions::default(),
            &mut read_path,
            &mut |_| {},
        );
        let message = got.err().map(|e| e.to_string()).unwrap_or_default();
        assert!(message.contains("no/such/recording.mcap"), "{message}");
    }
}
