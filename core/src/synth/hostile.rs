//! Hostile recordings: files whose declared sizes lie, whose chunks are
//! decompression bombs, whose indexes flood the reader. Each is small and
//! built record by record here; the tests (`core/tests/hostile.rs`), the
//! CLI (`dmpscope gen-sample --hostile DIR`) and the browser test load
//! them and expect, within a second, a clear message naming the file (or,
//! where the file is usable despite its lie, its demos).

use std::io::Write;

/// A hostile file: its name, its bytes, and whether it should load (its
/// lie is harmless) or end in an error.
#[derive(Clone, Debug)]
pub struct Hostile {
    /// The file's name (its suffix picks the reader).
    pub name: &'static str,
    /// What is wrong with it.
    pub what: &'static str,
    /// Its bytes.
    pub bytes: Vec<u8>,
    /// Whether it loads (with its demos) rather than failing.
    pub loads: bool,
}

const GIB: u64 = 1 << 30;

fn rec(op: u8, body: &[u8]) -> Vec<u8> {
    let mut r = vec![op];
    r.extend_from_slice(&(body.len() as u64).to_le_bytes());
    r.extend_from_slice(body);
    r
}

fn string(s: &str) -> Vec<u8> {
    let mut v = (s.len() as u32).to_le_bytes().to_vec();
    v.extend_from_slice(s.as_bytes());
    v
}

fn header() -> Vec<u8> {
    [string(""), string("dmpscope hostile")].concat()
}

fn schema() -> Vec<u8> {
    let text = crate::load::decode::ros2::POSE_STAMPED_SCHEMA.as_bytes();
    let mut b = 1u16.to_le_bytes().to_vec();
    b.extend(string("geometry_msgs/msg/PoseStamped"));
    b.extend(string("ros2msg"));
    b.extend_from_slice(&(text.len() as u32).to_le_bytes());
    b.extend_from_slice(text);
    b
}

fn channel(id: u16, topic: &str) -> Vec<u8> {
    let mut b = id.to_le_bytes().to_vec();
    b.extend_from_slice(&1u16.to_le_bytes());
    b.extend(string(topic));
    b.extend(string("cdr"));
    b.extend_from_slice(&0u32.to_le_bytes());
    b
}

/// A PoseStamped message on channel 1 at `k` ms.
fn message(k: u64) -> Vec<u8> {
    let stamp = 1_700_000_000_000_000_000 + k * 1_000_000;
    let mut m = 1u16.to_le_bytes().to_vec();
    m.extend_from_slice(&(k as u32).to_le_bytes());
    m.extend_from_slice(&stamp.to_le_bytes());
    m.extend_from_slice(&stamp.to_le_bytes());
    let p = [0.001 * k as f64, 0.0, 0.1];
    let mut cdr = vec![0, 1, 0, 0];
    cdr.extend_from_slice(&((stamp / 1_000_000_000) as i32).to_le_bytes());
    cdr.extend_from_slice(&((stamp % 1_000_000_000) as u32).to_le_bytes());
    cdr.extend(string("w\0"));
    while cdr.len() % 8 != 4 {
        cdr.push(0);
    }
    for v in p.iter().chain(&[0.0, 0.0, 0.0, 1.0]) {
        cdr.extend_from_slice(&v.to_le_bytes());
    }
    m.extend(cdr);
    m
}

/// The records of a pose channel with `n` messages.
fn pose_records(n: u64) -> Vec<u8> {
    let mut r = rec(0x03, &schema());
    r.extend(rec(0x04, &channel(1, "/pose")));
    for k in 0..n {
        r.extend(rec(0x05, &message(k)));
    }
    r
}

fn chunk(uncompressed_size: u64, crc: u32, compression: &str, records: &[u8]) -> Vec<u8> {
    let mut b = 0u64.to_le_bytes().to_vec();
    b.extend_from_slice(&u64::MAX.to_le_bytes());
    b.extend_from_slice(&uncompressed_size.to_le_bytes());
    b.extend_from_slice(&crc.to_le_bytes());
    b.extend(string(compression));
    b.extend_from_slice(&(records.len() as u64).to_le_bytes());
    b.extend_from_slice(records);
    rec(0x06, &b)
}

/// A file of `records` between the magic and a footer with no summary.
fn mcap(records: &[u8]) -> Vec<u8> {
    let mut f = crate::load::mcap::MAGIC.to_vec();
    f.extend(rec(0x01, &header()));
    f.extend_from_slice(records);
    f.extend(rec(0x0F, &0u32.to_le_bytes()));
    let mut footer = 0u64.to_le_bytes().to_vec();
    footer.extend_from_slice(&0u64.to_le_bytes());
    footer.extend_from_slice(&0u32.to_le_bytes());
    f.extend(rec(0x02, &footer));
    f.extend_from_slice(crate::load::mcap::MAGIC);
    f
}

/// `times` zstd frames of 64 MiB of zeros each (about 2 KB each).
fn zstd_zeros(times: usize) -> Vec<u8> {
    let frame = zstd::bulk::compress(&vec![0u8; 64 << 20], 1).unwrap_or_default();
    frame.repeat(times)
}

/// An lz4 frame of `mib` MiB of zeros.
fn lz4_zeros(mib: usize) -> Vec<u8> {
    let mut enc = lz4_flex::frame::FrameEncoder::new(Vec::new());
    let zeros = vec![0u8; 1 << 20];
    for _ in 0..mib {
        let _ = enc.write_all(&zeros);
    }
    enc.finish().unwrap_or_default()
}

/// A valid MCAP with a summary whose chunk indexes are `copies` copies of
/// the one real chunk's, and `channels` channels declared in it.
fn indexed(copies: usize, channels: u16, summary_start_lie: Option<u64>) -> Vec<u8> {
    let records = pose_records(50);
    let mut f = crate::load::mcap::MAGIC.to_vec();
    f.extend(rec(0x01, &header()));
    let chunk_at = f.len() as u64;
    let chunk = chunk(records.len() as u64, 0, "", &records);
    f.extend_from_slice(&chunk);
    f.extend(rec(0x0F, &0u32.to_le_bytes()));
    let summary_start = f.len() as u64;
    f.extend(rec(0x03, &schema()));
    for id in 1..=channels.max(1) {
        f.extend(rec(
            0x04,
            &channel(
                id,
                &format!(
                    "/pose{}",
                    if id == 1 {
                        String::new()
                    } else {
                        id.to_string()
                    }
                ),
            ),
        ));
    }
    let mut ci = 0u64.to_le_bytes().to_vec();
    ci.extend_from_slice(&u64::MAX.to_le_bytes());
    ci.extend_from_slice(&chunk_at.to_le_bytes());
    ci.extend_from_slice(&(chunk.len() as u64).to_le_bytes());
    ci.extend_from_slice(&0u32.to_le_bytes()); // no message indexes
    ci.extend_from_slice(&0u64.to_le_bytes());
    ci.extend(string(""));
    ci.extend_from_slice(&(records.len() as u64).to_le_bytes());
    ci.extend_from_slice(&(records.len() as u64).to_le_bytes());
    let ci = rec(0x08, &ci);
    for _ in 0..copies {
        f.extend_from_slice(&ci);
    }
    let mut footer = summary_start_lie
        .unwrap_or(summary_start)
        .to_le_bytes()
        .to_vec();
    footer.extend_from_slice(&0u64.to_le_bytes());
    footer.extend_from_slice(&0u32.to_le_bytes());
    f.extend(rec(0x02, &footer));
    f.extend_from_slice(crate::load::mcap::MAGIC);
    f
}

/// A ROS 1 bag of one chunk holding `data` (compressed as `compression`)
/// that declares `size` bytes of records.
fn bag(compression: &str, size: u32, data: &[u8]) -> Vec<u8> {
    let field = |name: &str, value: &[u8]| {
        let mut f = ((name.len() + 1 + value.len()) as u32)
            .to_le_bytes()
            .to_vec();
        f.extend_from_slice(name.as_bytes());
        f.push(b'=');
        f.extend_from_slice(value);
        f
    };
    let record = |header: Vec<u8>, data: &[u8]| {
        let mut r = (header.len() as u32).to_le_bytes().to_vec();
        r.extend(header);
        r.extend_from_slice(&(data.len() as u32).to_le_bytes());
        r.extend_from_slice(data);
        r
    };
    let mut f = crate::load::rosbag1::BAG_MAGIC.to_vec();
    let bag_header = [
        field("op", &[0x03]),
        field("index_pos", &0u64.to_le_bytes()),
        field("conn_count", &1u32.to_le_bytes()),
        field("chunk_count", &1u32.to_le_bytes()),
    ]
    .concat();
    f.extend(record(bag_header, &[b' '; 64]));
    let chunk_header = [
        field("op", &[0x05]),
        field("compression", compression.as_bytes()),
        field("size", &size.to_le_bytes()),
    ]
    .concat();
    f.extend(record(chunk_header, data));
    f
}

fn bz2_zeros(mib: usize) -> Vec<u8> {
    let mut enc = bzip2::write::BzEncoder::new(Vec::new(), bzip2::Compression::fast());
    let zeros = vec![0u8; 1 << 20];
    for _ in 0..mib {
        let _ = enc.write_all(&zeros);
    }
    enc.finish().unwrap_or_default()
}

/// A hostile file's entry.
fn h(name: &'static str, what: &'static str, bytes: Vec<u8>, loads: bool) -> Hostile {
    Hostile {
        name,
        what,
        bytes,
        loads,
    }
}

/// Every hostile file.
pub fn hostile_files() -> Vec<Hostile> {
    [bombs(), lies_and_floods()].concat()
}

/// Chunks that decompress to far more than they should.
fn bombs() -> Vec<Hostile> {
    let bomb = zstd_zeros(48);
    vec![
        h(
            "zstd_bomb.mcap",
            "a 100 KB zstd chunk of 3 GiB of zeros that says so",
            mcap(&chunk(3 * GIB, 0, "zstd", &bomb)),
            false,
        ),
        h(
            "zstd_bomb_lying.mcap",
            "the same chunk declaring 200 MiB",
            mcap(&chunk(200 << 20, 0, "zstd", &bomb)),
            false,
        ),
        h(
            "zstd_bomb_small.mcap",
            "the same chunk declaring 1 KiB",
            mcap(&chunk(1 << 10, 0, "zstd", &bomb)),
            false,
        ),
        h(
            "lz4_bomb.mcap",
            "an lz4 chunk of 64 MiB of zeros declaring 3 GiB",
            mcap(&chunk(3 * GIB, 0, "lz4", &lz4_zeros(64))),
            false,
        ),
        h(
            "lz4_bomb_lying.mcap",
            "the same chunk declaring 100 MiB",
            mcap(&chunk(100 << 20, 0, "lz4", &lz4_zeros(64))),
            false,
        ),
        h(
            "bz2_bomb.bag",
            "a bz2 chunk of 64 MiB of zeros declaring 3 GiB",
            bag("bz2", 3 << 30, &bz2_zeros(64)),
            false,
        ),
        h(
            "bz2_bomb_lying.bag",
            "the same chunk declaring 200 MiB",
            bag("bz2", 200 << 20, &bz2_zeros(64)),
            false,
        ),
    ]
}

/// Sizes that lie and floods of records.
fn lies_and_floods() -> Vec<Hostile> {
    let plain = pose_records(20);
    let mut top_huge = rec(0x05, &message(0));
    top_huge[1..9].copy_from_slice(&(1u64 << 60).to_le_bytes());
    vec![
        h(
            "record_2e60.mcap",
            "a record declaring 2^60 bytes",
            mcap(&[pose_records(0), top_huge].concat()),
            false,
        ),
        h(
            "chunk_lies.mcap",
            "an uncompressed chunk declaring 2^60 bytes of records",
            {
                let mut c = chunk(plain.len() as u64, 0, "", &plain);
                let at = 9 + 8 + 8 + 8 + 4 + 4;
                c[at..at + 8].copy_from_slice(&(1u64 << 60).to_le_bytes());
                mcap(&c)
            },
            false,
        ),
        h(
            "summary_lies.mcap",
            "a footer whose summary starts at byte 2^60",
            indexed(1, 1, Some(1 << 60)),
            true,
        ),
        h(
            "chunk_index_flood.mcap",
            "200,000 chunk indexes of one chunk",
            indexed(200_000, 1, None),
            true,
        ),
        h(
            "channel_flood.mcap",
            "65,000 channels",
            indexed(1, 65_000, None),
            true,
        ),
        h(
            "channel_flood_cut.mcap",
            "the same cut at 1 MiB: no summary, 27,000 channels walked",
            {
                let mut f = indexed(1, 65_000, None);
                f.truncate(1 << 20);
                f
            },
            true,
        ),
    ]
}
