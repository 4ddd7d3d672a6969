//! `dmpscope bench --read FILE`: how fast a recording's demos are read,
//! against the PyPI `mcap` reader iterating the pose topic of the same file
//! and against reading the file's bytes once (the page cache's speed), in
//! alternation, as medians; with the share of the file dmpscope read and
//! its peak memory (each read runs in a process of its own:
//! `bench --read-once`).

use std::path::Path;
use std::process::Command;
use std::sync::Arc;
use std::time::Instant;

use anyhow::Context;
use dmpscope_core::load::access::{FileAt, Meter, Metered, block_on};
use dmpscope_core::load::demo::median;
use dmpscope_core::load::options::LoadOptions;
use dmpscope_core::load::source::load_streams_at;
use serde::{Deserialize, Serialize};

/// What one read in a process of its own gave.
#[derive(Debug, Serialize, Deserialize)]
pub struct ReadOnce {
    /// Wall time of the read, seconds.
    pub seconds: f64,
    /// Bytes read of the file.
    pub bytes_read: u64,
    /// The file's size.
    pub size: u64,
    /// The process's peak resident memory, bytes (`VmHWM`).
    pub peak_rss: u64,
    /// Demos (streams) found and their samples.
    pub streams: usize,
    /// Samples in all.
    pub samples: usize,
}

/// Reads `path` once and prints what it took as JSON (the child's side).
pub fn read_once(path: &Path) -> anyhow::Result<()> {
    let meter = Arc::new(Meter::default());
    let file = FileAt::open(path).with_context(|| format!("{}: cannot open", path.display()))?;
    let size = dmpscope_core::load::access::ReadAt::size(&file).unwrap_or(0);
    let mut access = Metered::new(file, Arc::clone(&meter));
    let name = path.display().to_string();
    let start = Instant::now();
    let loaded = block_on(load_streams_at(&name, &mut access, &LoadOptions::default()))?;
    let seconds = start.elapsed().as_secs_f64();
    let once = ReadOnce {
        seconds,
        bytes_read: meter.bytes_read(),
        size,
        peak_rss: peak_rss(),
        streams: loaded.demos.len(),
        samples: loaded.demos.iter().map(|d| d.positions.len()).sum(),
    };
    println!("{}", serde_json::to_string(&once)?);
    Ok(())
}

/// The process's peak resident memory (`VmHWM` in `/proc/self/status`),
/// bytes; 0 where there is none.
fn peak_rss() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1))
                .and_then(|kb| kb.parse::<u64>().ok())
        })
        .map_or(0, |kb| kb * 1024)
}

/// The Python that runs the PyPI reader: `DMPSCOPE_PYTHON`, else `python3`.
fn python() -> String {
    std::env::var("DMPSCOPE_PYTHON").unwrap_or_else(|_| "python3".to_owned())
}

/// The PyPI `mcap` reader iterating `topic` of `path` (no decoding): its
/// own time for the iteration, seconds, and the messages it gave.
fn python_read(path: &Path, topic: &str) -> anyhow::Result<(f64, usize)> {
    let script = [
        "import sys, time",
        "from mcap.reader import make_reader",
        "t = time.perf_counter()",
        "n = 0",
        "with open(sys.argv[1], 'rb') as f:",
        "    for _ in make_reader(f).iter_messages(topics=[sys.argv[2]]):",
        "        n += 1",
        "print(time.perf_counter() - t, n)",
    ]
    .join("\n");
    let out = Command::new(python())
        .arg("-c")
        .arg(script)
        .arg(path)
        .arg(topic)
        .output()
        .context("running Python (DMPSCOPE_PYTHON)")?;
    if !out.status.success() {
        anyhow::bail!(
            "the PyPI mcap reader failed (pip install mcap zstandard lz4): {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    let text = String::from_utf8_lossy(&out.stdout);
    let mut parts = text.split_whitespace();
    let secs = parts
        .next()
        .and_then(|s| s.parse().ok())
        .context("Python's time")?;
    let n = parts
        .next()
        .and_then(|s| s.parse().ok())
        .context("Python's count")?;
    Ok((secs, n))
}

/// `dmpscope` reading `path` in a process of its own.
fn dmpscope_read(path: &Path) -> anyhow::Result<ReadOnce> {
    let exe = std::env::current_exe().context("this program's path")?;
    let out = Command::new(exe)
        .args(["bench", "--read-once"])
        .arg(path)
        .output()
        .context("running `dmpscope bench --read-once`")?;
    if !out.status.success() {
        anyhow::bail!("{}", String::from_utf8_lossy(&out.stderr));
    }
    Ok(serde_json::from_slice(&out.stdout)?)
}

/// Reads the whole file once in pieces of 8 MiB: seconds.
fn cat(path: &Path) -> anyhow::Result<f64> {
    use std::io::Read;
    let start = Instant::now();
    let mut f = std::fs::File::open(path)?;
    let mut buf = vec![0u8; 8 << 20];
    while f.read(&mut buf)? > 0 {}
    Ok(start.elapsed().as_secs_f64())
}

/// Alternates the three reads `repeat` times and prints their medians.
pub fn run(path: &Path, topic: &str, repeat: usize, python_too: bool) -> anyhow::Result<()> {
    let (mut ours, mut theirs, mut cats) = (Vec::new(), Vec::new(), Vec::new());
    let mut last = None;
    for _ in 0..repeat.max(1) {
        cats.push(cat(path)?);
        let once = dmpscope_read(path)?;
        ours.push(once.seconds);
        last = Some(once);
        if python_too {
            theirs.push(python_read(path, topic)?.0);
        }
    }
    let once = last.context("no read")?;
    let (ours, cats) = (median(&ours), median(&cats));
    println!(
        "{}: {:.2} GB, {} streams, {} samples",
        path.display(),
        once.size as f64 * 1e-9,
        once.streams,
        once.samples
    );
    println!(
        "read the file's bytes once (page cache): {:.3} s (median of {repeat})",
        cats
    );
    println!(
        "dmpscope: {:.3} s (median of {repeat}), read {:.1} MB = {:.2} % of the file, peak RSS {:.0} MB",
        ours,
        once.bytes_read as f64 * 1e-6,
        100.0 * once.bytes_read as f64 / once.size.max(1) as f64,
        once.peak_rss as f64 * 1e-6
    );
    if python_too {
        let theirs = median(&theirs);
        println!(
            "PyPI mcap reader, topic {topic}: {theirs:.3} s (median of {repeat}): dmpscope is {:.2}x as fast",
            theirs / ours
        );
    }
    Ok(())
}
