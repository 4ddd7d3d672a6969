//! The registry of recording formats: each file format dmpscope reads is
//! declared once here (its name, the file-name suffixes that identify it,
//! its reader, and the suffixes folders are walked for),
//! and every place that picks a reader asks this table: [`crate::load::source`]
//! for paths and bytes (the CLI, the app, the browser), folder walking
//! ([`crate::load::rosbag2`]) and the app's file dialogs. Adding a format is an
//! entry here and its reader.

use std::path::Path;

/// How a format's files become streams.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reader {
    /// MCAP, read in pieces by the sans-IO reader.
    Mcap,
    /// MCAP compressed as a whole file with zstd (rosbag2's file
    /// compression), decompressed as it is read.
    ZstdMcap,
    /// Plain `t,x,y,z` text.
    Csv,
    /// A ROS 1 bag (format 2.0), read from its bytes.
    Bag,
}

/// A file format dmpscope reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Format {
    /// Its name in messages.
    pub name: &'static str,
    /// File-name suffixes that identify it (lower case, with the dot).
    pub suffixes: &'static [&'static str],
    /// Its reader.
    pub reader: Reader,
    /// The suffixes of its files that a folder of recordings is walked
    /// for (empty: none).
    pub walk: &'static [&'static str],
    /// The bytes its files start with (empty: none), which identify a file
    /// whose name does not.
    pub magic: &'static [u8],
}

/// Every format, in the order they are tried by name.
pub const FORMATS: [Format; 4] = [
    Format {
        name: "MCAP",
        suffixes: &[".mcap"],
        reader: Reader::Mcap,
        walk: &[".mcap"],
        magic: b"\x89MCAP",
    },
    Format {
        name: "zstd-compressed MCAP",
        suffixes: &[".mcap.zstd", ".mcap.zst", ".zstd", ".zst"],
        reader: Reader::ZstdMcap,
        walk: &[".mcap.zstd", ".mcap.zst"],
        magic: &[0x28, 0xB5, 0x2F, 0xFD],
    },
    Format {
        name: "CSV",
        suffixes: &[".csv"],
        reader: Reader::Csv,
        walk: &[".csv"],
        magic: &[],
    },
    Format {
        name: "ROS 1 bag",
        // `.bag.active`: what `rosbag record` leaves when it is killed.
        suffixes: &[".bag", ".bag.active"],
        reader: Reader::Bag,
        walk: &[".bag", ".bag.active"],
        magic: b"#ROSBAG",
    },
];

/// The format a file name says (its suffix, case-insensitive).
pub fn by_name(name: &str) -> Option<&'static Format> {
    let name = name.to_ascii_lowercase();
    FORMATS
        .iter()
        .find(|f| f.suffixes.iter().any(|s| name.ends_with(s)))
}

/// The format whose magic bytes `head` (a file's first bytes) starts with.
pub fn by_magic(head: &[u8]) -> Option<&'static Format> {
    FORMATS
        .iter()
        .find(|f| !f.magic.is_empty() && head.starts_with(f.magic))
}

/// The format of a file by its name, else by its first bytes, else MCAP
/// (whose reader then says what the file is not, by its magic bytes).
pub fn detect(name: &str, head: &[u8]) -> &'static Format {
    by_name(name)
        .or_else(|| by_magic(head))
        .unwrap_or(&FORMATS[0])
}

/// Whether a file in a folder of recordings is read.
pub fn walked(path: &Path) -> bool {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    FORMATS
        .iter()
        .flat_map(|f| f.walk.iter())
        .any(|s| name.ends_with(s))
}

/// The extensions an open dialog offers (without the dot), with
/// `metadata.yaml`'s, which stands for its rosbag2 folder.
pub fn dialog_extensions() -> Vec<&'static str> {
    let mut out: Vec<&'static str> = FORMATS
        .iter()
        .flat_map(|f| f.suffixes.iter())
        .filter_map(|s| s.rsplit('.').next())
        .collect();
    out.push("yaml");
    out.dedup();
    let mut seen = Vec::new();
    out.retain(|e| {
        let new = !seen.contains(e);
        seen.push(*e);
        new
    });
    out
}

/// The channel metadata key holding a demo's name: loading an export gives
/// the demo back under it.
pub const NAME_KEY: &str = "dmpscope.name";

/// The channel metadata key saying what a path is (`demonstration`,
/// `regenerated`); a regenerated path is not loaded as a demo.
pub const ROLE_KEY: &str = "dmpscope.role";

/// The role of a regenerated path.
pub const ROLE_REGENERATED: &str = "regenerated";

/// The role of an exported ROS trajectory (`nav_msgs/msg/Path`,
/// `MultiDOFJointTrajectory`); never loaded as a demo.
pub const ROLE_TRAJECTORY: &str = "trajectory";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_pick_the_reader() {
        assert_eq!(by_name("a/B.MCAP").map(|f| f.reader), Some(Reader::Mcap));
        assert_eq!(
            by_name("bag_0.mcap.zstd").map(|f| f.reader),
            Some(Reader::ZstdMcap)
        );
        assert_eq!(by_name("t.csv").map(|f| f.reader), Some(Reader::Csv));
        assert_eq!(by_name("run.BAG").map(|f| f.reader), Some(Reader::Bag));
        assert_eq!(by_name("notes.txt"), None);
        assert_eq!(detect("upload", b"").reader, Reader::Mcap);
        assert_eq!(detect("notes.txt", b"").reader, Reader::Mcap);
        // A file no name identifies, by its first bytes.
        assert_eq!(detect("upload", b"#ROSBAG V2.0\n").reader, Reader::Bag);
        assert_eq!(
            detect("upload", &[0x28, 0xB5, 0x2F, 0xFD, 0]).reader,
            Reader::ZstdMcap
        );
        assert_eq!(detect("upload", b"\x89MCAP0\r\n").reader, Reader::Mcap);
    }

    #[test]
    fn folders_walk_mcap_files_plain_or_compressed_bags_and_csv() {
        assert!(walked(Path::new("/x/run_0.mcap")));
        assert!(walked(Path::new("/x/run_0.MCAP.zstd")));
        assert!(walked(Path::new("/x/run_0.mcap.zst")));
        assert!(!walked(Path::new("/x/notes.zst")));
        assert!(walked(Path::new("/x/trial_04.CSV")));
        assert!(walked(Path::new("/x/demo_3.bag")));
        assert!(walked(Path::new("/x/demo_4.bag.active")));
        assert!(!walked(Path::new("/x/metadata.yaml")));
    }

    #[test]
    fn dialogs_offer_each_extension_once() {
        assert_eq!(
            dialog_extensions(),
            ["mcap", "zstd", "zst", "csv", "bag", "active", "yaml"]
        );
    }
}
