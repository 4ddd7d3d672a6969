//! Time that goes wrong inside a stream (method.md section 13): a clock that
//! jumps back, or a dropout, found in file order. A break is a step between
//! consecutive stamps longer than `max(0.1 s, 10 x the median interval)`
//! either way (small reorderings, which the stable sort of preparation
//! fixes, stay below it). By default the stream is split there and each
//! part is judged as a demo on its own; [`GapPolicy::Keep`] bridges it.
//! Either way the user is told where and how long.

use crate::load::demo::RawDemo;
use crate::load::options::GapPolicy;
use crate::notice::Notice;

/// The shortest step that is a break, seconds.
pub const MIN_GAP_S: f64 = 0.1;
/// A break is also at least this many median intervals long.
pub const GAP_INTERVALS: f64 = 10.0;

/// One break in a stream.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Break {
    /// The sample (file order) that starts the new part.
    pub index: usize,
    /// When the break starts: seconds from the stream's first stamp.
    pub at_s: f64,
    /// The step's length in seconds, negative for a clock jumping back.
    pub step_s: f64,
}

impl Break {
    fn describe(&self) -> String {
        if self.step_s < 0.0 {
            format!(
                "the clock jumps back {:.3} s at {:.3} s (sample {})",
                -self.step_s, self.at_s, self.index
            )
        } else {
            format!(
                "a {:.3} s gap at {:.3} s (sample {})",
                self.step_s, self.at_s, self.index
            )
        }
    }
}

/// The breaks of a stream, in file order.
pub fn breaks(demo: &RawDemo) -> Vec<Break> {
    let s = &demo.stamps_ns;
    if s.len() < 3 {
        return Vec::new();
    }
    let mut steps: Vec<i64> = s
        .windows(2)
        .map(|w| w[1] - w[0])
        .filter(|&d| d > 0)
        .collect();
    if steps.is_empty() {
        return Vec::new();
    }
    steps.sort_unstable();
    let median_s = steps[steps.len() / 2] as f64 * 1e-9;
    let limit_s = MIN_GAP_S.max(GAP_INTERVALS * median_s);
    let first = s[0];
    s.windows(2)
        .enumerate()
        .filter_map(|(i, w)| {
            let step_s = (w[1] - w[0]) as f64 * 1e-9;
            (step_s.abs() > limit_s).then(|| Break {
                index: i + 1,
                at_s: (w[0] - first) as f64 * 1e-9,
                step_s,
            })
        })
        .collect()
}

/// Applies `policy` to every stream: the streams (split or whole) and a
/// warning per stream with breaks, naming file, topic, where and how long.
pub fn apply(streams: Vec<RawDemo>, policy: GapPolicy) -> (Vec<RawDemo>, Vec<Notice>) {
    let mut out = Vec::with_capacity(streams.len());
    let mut notices = Vec::new();
    for stream in streams {
        let found = breaks(&stream);
        if found.is_empty() {
            out.push(stream);
            continue;
        }
        let what: Vec<String> = found.iter().map(Break::describe).collect();
        let what = what.join("; ");
        match policy {
            GapPolicy::Keep => {
                notices.push(Notice::warning(format!(
                    "{}: {}: {what}: bridged (--gaps keep); the demo's time runs across it",
                    stream.file, stream.topic
                )));
                out.push(stream);
            }
            GapPolicy::Split => {
                let parts = found.len() + 1;
                notices.push(Notice::warning(format!(
                    "{}: {}: {what}: split into {parts} demos (--gaps keep bridges it)",
                    stream.file, stream.topic
                )));
                let mut starts: Vec<usize> = found.iter().map(|b| b.index).collect();
                starts.insert(0, 0);
                starts.push(stream.stamps_ns.len());
                for (k, w) in starts.windows(2).enumerate() {
                    out.push(stream.part(
                        w[0]..w[1],
                        format!("{} part {}/{parts}", stream.name, k + 1),
                        stream.topic.clone(),
                    ));
                }
            }
        }
    }
    (out, notices)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::load::demo::TimeSource;

    fn stream(stamps_ns: Vec<i64>) -> RawDemo {
        let positions = (0..stamps_ns.len())
            .map(|i| [i as f64 * 1e-3, 0.0, 0.0].into())
            .collect();
        RawDemo {
            name: "f.mcap:/hand".into(),
            file: "f.mcap".into(),
            topic: "/hand".into(),
            stamps_ns,
            positions,
            orientations: None,
            time_source: TimeSource::HeaderStamp,
        }
    }

    const MS: i64 = 1_000_000;

    #[test]
    fn a_clock_jumping_back_and_a_dropout_are_found_where_they_are() {
        // 90 Hz-ish: 11 ms steps, then 1 h back at sample 50, a 0.5 s gap
        // at sample 80, and a small swap (fixed by sorting) at 20.
        let mut t = 0;
        let mut stamps = Vec::new();
        for i in 0..120 {
            if i == 50 {
                t -= 3_600_000 * MS;
            }
            if i == 80 {
                t += 500 * MS;
            }
            stamps.push(t);
            t += 11 * MS;
        }
        stamps.swap(20, 21);
        let found = breaks(&stream(stamps));
        assert_eq!(found.len(), 2, "{found:?}");
        assert_eq!(found[0].index, 50);
        assert!((found[0].step_s + 3599.989).abs() < 1e-9);
        assert!((found[0].at_s - 0.539).abs() < 1e-9);
        assert_eq!(found[1].index, 80);
        assert!((found[1].step_s - 0.511).abs() < 1e-9);
    }

    #[test]
    fn split_makes_parts_named_uniquely_and_keep_bridges_with_a_warning() {
        let mut stamps: Vec<i64> = (0..60).map(|i| i * 11 * MS).collect();
        for s in &mut stamps[30..] {
            *s += 400 * MS;
        }
        let (split, said) = apply(vec![stream(stamps.clone())], GapPolicy::Split);
        assert_eq!(split.len(), 2);
        assert_eq!(split[0].name, "f.mcap:/hand part 1/2");
        assert_eq!(split[1].name, "f.mcap:/hand part 2/2");
        assert_eq!(
            (split[0].stamps_ns.len(), split[1].stamps_ns.len()),
            (30, 30)
        );
        assert_eq!(said.len(), 1);
        assert!(
            said[0]
                .text
                .contains("a 0.411 s gap at 0.319 s (sample 30)"),
            "{}",
            said[0].text
        );
        assert!(said[0].text.contains("f.mcap: /hand"));
        let (kept, said) = apply(vec![stream(stamps)], GapPolicy::Keep);
        assert_eq!(kept.len(), 1);
        assert!(said[0].text.contains("bridged"));
        // A stream without breaks passes untouched and silent.
        let plain: Vec<i64> = (0..60).map(|i| i * 11 * MS).collect();
        let (same, said) = apply(vec![stream(plain.clone())], GapPolicy::Split);
        assert_eq!(same[0].stamps_ns, plain);
        assert!(said.is_empty());
    }
}
