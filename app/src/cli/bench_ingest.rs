//! `dmpscope bench --ingest N`: how fast recordings load, next to the raw
//! speed of mcap's own `MessageStream` over the same bytes.

use std::time::Instant;

use dmpscope_core::export::write::{TopicSamples, write_pose_stamped};
use dmpscope_core::load::demo::median;
use dmpscope_core::load::mcap::load_bytes;

/// A recording of `messages` PoseStamped messages on 10 topics.
fn recording(messages: usize, compress: bool) -> anyhow::Result<Vec<u8>> {
    let per_topic = messages.div_ceil(10);
    let samples: Vec<Vec<(i64, [f64; 3])>> = (0..10)
        .map(|t| {
            (0..per_topic)
                .map(|k| {
                    let s = k as f64 * 1e-3;
                    (
                        1_700_000_000_000_000_000 + (t * per_topic + k) as i64 * 11_111_111,
                        [s.sin(), s.cos(), 0.9 + 0.1 * (t as f64)],
                    )
                })
                .collect()
        })
        .collect();
    let names: Vec<String> = (0..10).map(|t| format!("/tracker_{t}")).collect();
    let topics: Vec<TopicSamples<'_>> = names
        .iter()
        .zip(&samples)
        .map(|(topic, samples)| TopicSamples {
            orientations: None,
            topic,
            frame_id: "world",
            samples,
        })
        .collect();
    Ok(write_pose_stamped(std::io::Cursor::new(Vec::new()), &topics, compress)?.into_inner())
}

/// Prints MB/s of dmpscope's loader and of mcap's `MessageStream`.
pub fn run(messages: usize, repeat: usize) -> anyhow::Result<()> {
    println!("ingest of {messages} PoseStamped messages (10 topics), median of {repeat}:");
    for compress in [false, true] {
        let bytes = recording(messages, compress)?;
        let mb = bytes.len() as f64 / 1e6;
        let mut ours = Vec::new();
        let mut raw = Vec::new();
        for _ in 0..repeat.max(1) {
            let t = Instant::now();
            let loaded = load_bytes("bench.mcap", &bytes)?;
            ours.push(t.elapsed().as_secs_f64());
            let n: usize = loaded.demos.iter().map(|d| d.positions.len()).sum();
            anyhow::ensure!(n == messages.div_ceil(10) * 10, "loaded {n} samples");
            let t = Instant::now();
            let mut count = 0usize;
            for message in mcap::MessageStream::new(&bytes)? {
                std::hint::black_box(message?);
                count += 1;
            }
            raw.push(t.elapsed().as_secs_f64());
            anyhow::ensure!(count == n, "MessageStream saw {count} messages");
        }
        let (ours, raw) = (median(&ours), median(&raw));
        println!(
            "  {:<12} {mb:8.1} MB   dmpscope load {:7.1} MB/s   mcap MessageStream {:7.1} MB/s   ratio {:.2}",
            if compress { "zstd" } else { "uncompressed" },
            mb / ours,
            mb / raw,
            raw / ours
        );
    }
    Ok(())
}
