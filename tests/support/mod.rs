//! What the end-to-end tests share: the repository, the binary, temp files.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The repository root.
pub fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The bundled sample recording.
pub fn sample_path() -> PathBuf {
    repo().join("assets/reach10.mcap")
}

/// Runs `dmpscope` from the repository root.
pub fn dmpscope(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_dmpscope"))
        .args(args)
        .current_dir(repo())
        .output()
        .expect("run dmpscope")
}

/// Bytes as text, lossily.
pub fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// A path in a temp folder of this test process.
pub fn tmp_path(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("dmpscope-e2e-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir.join(name)
}
