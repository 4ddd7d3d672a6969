//! From collected streams to raw demonstrations (method.md sections 1, 12
//! and 13): a stream per topic and key, gathered from the channels and
//! sorted, TF streams re-expressed in the fixed frame, each stream
//! finished into a [`RawDemo`] with its time source, and what a file cut
//! short kept.

use crate::geom::{Quat, Vec3};
use crate::load::demo::{RawDemo, TimeSource};
use crate::load::options::UpAxis;
use crate::load::orientation_check::OrientationCounts;

/// One demo being collected: a topic, or one key of a multi-pose topic.
#[derive(Default)]
pub(crate) struct Stream {
    /// Its samples are TF transforms (they have a parent frame).
    pub(crate) tf: bool,
    pub(crate) stamps: Vec<Option<i64>>,
    pub(crate) log_times: Vec<i64>,
    pub(crate) positions: Vec<Vec3>,
    /// Each sample's orientation, already in dmpscope's z-up frame; `None`
    /// where the message has none or an unusable one.
    pub(crate) orientations: Vec<Option<Quat>>,
    /// What its orientations say about themselves.
    pub(crate) turns: OrientationCounts,
}

/// A stream as finishing sees it: its topic, its key and its samples.
pub(crate) type Keyed = (String, Option<String>, Stream);

/// Re-expresses every TF stream in `fixed`, with a warning where
/// transforms were held; the streams that cannot be are left out, and
/// listed.
pub(crate) fn in_fixed_frames(
    streams: &mut Vec<Keyed>,
    buffer: &mut crate::load::tf::TfBuffer,
    fixed: &str,
    up: UpAxis,
    label: &str,
    warnings: &mut Vec<String>,
) -> Vec<String> {
    let mut lost = Vec::new();
    streams.retain_mut(|(topic, key, s)| match key {
        Some(k) if s.tf => match in_fixed_frame(buffer, fixed, k, s, up) {
            Ok(None) => true,
            Ok(Some(note)) => {
                warnings.push(format!("{label}: {topic}:{k}: {note}"));
                true
            }
            Err(why) => {
                lost.push(format!("{topic}:{k}: not expressed in {fixed}: {why}"));
                false
            }
        },
        _ => true,
    });
    lost
}

/// What to say when a `--frame` matches no demo's key, naming the keys
/// seen (`None`: every frame matched, or there were no keys).
pub(crate) fn unmatched_frames(
    frames: &[String],
    demos: &[RawDemo],
    keys_seen: &std::collections::BTreeSet<String>,
) -> Option<String> {
    let unmatched: Vec<&String> = frames
        .iter()
        .filter(|f| {
            !demos
                .iter()
                .any(|d| d.topic.rsplit_once(':').is_some_and(|(_, k)| k == *f))
        })
        .collect();
    if unmatched.is_empty() || keys_seen.is_empty() {
        return None;
    }
    let names: Vec<&str> = keys_seen.iter().map(String::as_str).collect();
    Some(format!(
        "--frame {} matches no frame here; the frames are: {}",
        unmatched
            .iter()
            .map(|f| f.as_str())
            .collect::<Vec<_>>()
            .join(", "),
        names.join(", ")
    ))
}

/// Re-expresses a TF stream in `fixed` (method.md section 13): each sample
/// becomes the frame's origin and orientation in `fixed` at its stamp. Gives a note when
/// transforms were held past their recorded span.
pub(crate) fn in_fixed_frame(
    buffer: &mut crate::load::tf::TfBuffer,
    fixed: &str,
    frame: &str,
    s: &mut Stream,
    up: UpAxis,
) -> Result<Option<String>, String> {
    let mut held = 0;
    for i in 0..s.positions.len() {
        let stamp = s.stamps[i].unwrap_or(s.log_times[i]);
        let (p, q, h) = buffer.pose_in(fixed, frame, stamp)?;
        held += usize::from(h);
        s.positions[i] = up.to_z_up(p).into();
        s.orientations[i] = crate::geom::quat_from_xyzw(q).map(|q| up.orientation_to_z_up(q));
    }
    Ok((held > 0).then(|| {
        format!(
            "{held} samples lie outside the recorded span of a transform to {fixed}: the \
             nearest transform was held there (tf2 would refuse them)"
        )
    }))
}

/// The streams a truncated file cut short: those still sending when it
/// ends (their last message within max(1 s, 10 of their intervals) of the
/// file's last one).
pub(crate) fn cut_short(demos: &[RawDemo]) -> String {
    let last = |d: &RawDemo| d.stamps_ns.iter().copied().max();
    let Some(end) = demos.iter().filter_map(last).max() else {
        return String::new();
    };
    let names: Vec<String> = demos
        .iter()
        .filter(|d| {
            let h = crate::load::demo::median(&crate::load::demo::stamp_intervals_s(
                &d.sorted_unique().0,
            ));
            let window = (1.0f64).max(10.0 * h);
            last(d).is_some_and(|t| (end - t) as f64 * 1e-9 <= window)
        })
        .map(|d| format!("{} ({} samples)", d.topic, d.stamps_ns.len()))
        .collect();
    if names.is_empty() {
        String::new()
    } else {
        format!("; cut short: {}", names.join(", "))
    }
}

/// Chooses the time source of one stream (method.md section 2.1): header
/// stamps, unless one is missing or all are zero, then log time.
pub(crate) fn finish_stream(
    label: &str,
    file_name: &str,
    topic: String,
    key: Option<String>,
    s: Stream,
) -> RawDemo {
    let stamps: Option<Vec<i64>> = s.stamps.iter().copied().collect();
    let (stamps_ns, time_source) = match stamps {
        Some(v) if v.iter().any(|&t| t != 0) => (v, TimeSource::HeaderStamp),
        _ => (s.log_times, TimeSource::LogTime),
    };
    let source = match key {
        Some(k) => format!("{topic}:{k}"),
        None => topic,
    };
    RawDemo {
        name: format!("{file_name}:{source}"),
        file: label.to_owned(),
        topic: source,
        stamps_ns,
        positions: s.positions,
        orientations: s.orientations.into_iter().collect(),
        time_source,
    }
}
