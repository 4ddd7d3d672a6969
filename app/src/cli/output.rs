//! Where results go: a file named by `--out`, or stdout.

use std::io::Write;
use std::path::Path;

use anyhow::Context;
use std::sync::atomic::{AtomicBool, Ordering};

use dmpscope_core::{Level, Notice};

/// Writes `text` to `out` (stdout when `None` or `-`).
pub fn write_text(out: Option<&Path>, text: &str) -> anyhow::Result<()> {
    match out {
        Some(path) if path != Path::new("-") => {
            std::fs::write(path, text).with_context(|| format!("{}: cannot write", path.display()))
        }
        _ => {
            let mut stdout = std::io::stdout().lock();
            stdout.write_all(text.as_bytes())?;
            stdout.flush()?;
            Ok(())
        }
    }
}

/// A progress bar on stderr, drawn only when stderr is a terminal.
pub fn progress_bar(total: u64, what: &str) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::with_draw_target(
        Some(total),
        indicatif::ProgressDrawTarget::stderr(),
    );
    if let Ok(style) =
        indicatif::ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} points ({elapsed})")
    {
        bar.set_style(style.progress_chars("=> "));
    }
    bar.set_message(what.to_owned());
    bar
}

/// A progress bar of bytes read on stderr, for reading `what` (hidden where
/// stderr is not a terminal; never on stdout, where `--json` goes).
pub fn byte_bar(total: u64, what: &str) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::with_draw_target(
        Some(total),
        indicatif::ProgressDrawTarget::stderr(),
    );
    if let Ok(style) = indicatif::ProgressStyle::with_template(
        "reading {msg} [{bar:40}] {bytes}/{total_bytes} ({elapsed})",
    ) {
        bar.set_style(style.progress_chars("=> "));
    }
    bar.set_message(what.to_owned());
    bar
}

static VERBOSE: AtomicBool = AtomicBool::new(false);

/// Whether details are printed (`-v`).
pub fn set_verbose(on: bool) {
    VERBOSE.store(on, Ordering::Relaxed);
}

/// Prints notices on stderr, one line each (`note: ...`, `warning: ...`);
/// details only with `-v`.
pub fn print_notices(notices: &[Notice]) {
    let verbose = VERBOSE.load(Ordering::Relaxed);
    for n in notices {
        if n.level != Level::Detail || verbose {
            eprintln!("{n}");
        }
    }
}
