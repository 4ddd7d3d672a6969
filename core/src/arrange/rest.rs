//! Rests at the ends of a demonstration (method.md section 1): the time the
//! hand stands still before the motion starts and after it ends, common in
//! kinesthetic teaching. A rest is what the segmentation calls one: speed
//! below its rest speed for at least its rest time. Rests are measured and
//! reported always; cut only when asked (`--trim-rest`), since cutting
//! changes what unit time spans and so every number after it.

use crate::arrange::segment::speeds;
use crate::load::demo::RawDemo;
use crate::load::options::SegmentSettings;
use crate::notice::Notice;

/// The rests found at a demo's ends.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct EndRests {
    /// Seconds at rest at the start (0: none as long as the rest time).
    pub lead_s: f64,
    /// Seconds at rest at the end.
    pub trail_s: f64,
    /// The demo's duration, seconds.
    pub duration_s: f64,
    /// The motion's first and last sample in time order (after
    /// de-duplication): the samples kept by a trim.
    pub first: usize,
    /// See [`EndRests::first`].
    pub last: usize,
}

impl EndRests {
    /// Whether either end rests.
    pub fn any(&self) -> bool {
        self.lead_s > 0.0 || self.trail_s > 0.0
    }

    /// The rests in words: "0.42 s at rest at its start (8 % of its
    /// duration), 0.30 s at its end (6 %)".
    pub fn describe(&self) -> String {
        let pct = |s: f64| 100.0 * s / self.duration_s.max(1e-12);
        let mut parts = Vec::new();
        if self.lead_s > 0.0 {
            parts.push(format!(
                "{:.2} s at rest at its start ({:.0} % of its duration)",
                self.lead_s,
                pct(self.lead_s)
            ));
        }
        if self.trail_s > 0.0 {
            parts.push(format!(
                "{:.2} s at rest at its end ({:.0} %)",
                self.trail_s,
                pct(self.trail_s)
            ));
        }
        parts.join(", ")
    }
}

/// Measures the rests at a demo's ends.
pub fn end_rests(demo: &RawDemo, settings: &SegmentSettings) -> EndRests {
    let (stamps, positions) = demo.sorted_unique();
    let n = stamps.len();
    if n < 3 {
        return EndRests {
            last: n.saturating_sub(1),
            ..EndRests::default()
        };
    }
    let speed = speeds(&stamps, &positions, settings.speed_window_s);
    let moving = |i: &usize| speed[*i] >= settings.rest_speed;
    let Some(start) = (0..n).find(moving) else {
        // Never moves: no motion to keep, nothing to call a rest at an end.
        return EndRests {
            last: n - 1,
            ..EndRests::default()
        };
    };
    let end = (0..n).rev().find(moving).unwrap_or(n - 1);
    let secs = |a: usize, b: usize| (stamps[b] - stamps[a]) as f64 * 1e-9;
    let (lead, trail) = (secs(0, start), secs(end, n - 1));
    let long = |s: f64| s >= settings.min_rest_s;
    EndRests {
        lead_s: if long(lead) { lead } else { 0.0 },
        trail_s: if long(trail) { trail } else { 0.0 },
        duration_s: secs(0, n - 1),
        // The last sample of the rest before and the first after, as the
        // segmentation keeps them.
        first: if long(lead) {
            start.saturating_sub(1)
        } else {
            0
        },
        last: if long(trail) {
            (end + 1).min(n - 1)
        } else {
            n - 1
        },
    }
}

/// Up to this many demos with rests are named one line each; more are one
/// line with their count and range (each demo as a detail).
pub const RESTS_LISTED: usize = 3;

/// Measures every demo's end rests; with `trim`, cuts them. Says which
/// demos rest and how much (file, demo, seconds and share of the duration).
pub fn apply(demos: &mut [RawDemo], settings: &SegmentSettings, trim: bool) -> Vec<Notice> {
    let mut found: Vec<(String, String, EndRests)> = Vec::new();
    for demo in demos.iter_mut() {
        let rests = end_rests(demo, settings);
        if !rests.any() {
            continue;
        }
        if trim {
            let sorted = demo.sorted();
            *demo = sorted.part(
                rests.first..rests.last + 1,
                demo.name.clone(),
                demo.topic.clone(),
            );
        }
        found.push((demo.file.clone(), demo.name.clone(), rests));
    }
    let action = if trim {
        "trimmed (--trim-rest); unit time spans the motion only"
    } else {
        "part of the unit-time motion; --trim-rest (the app's Loading: rests at the ends) \
         cuts it"
    };
    let each = |(file, name, r): &(String, String, EndRests)| {
        format!("{file}: {name}: {}: {action}", r.describe())
    };
    if found.len() <= RESTS_LISTED {
        return found.iter().map(|f| Notice::info(each(f))).collect();
    }
    let range = |v: Vec<f64>| {
        let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
        (lo, v.into_iter().fold(0.0, f64::max))
    };
    let (s0, s1) = range(found.iter().map(|f| f.2.lead_s + f.2.trail_s).collect());
    let (p0, p1) = range(
        found
            .iter()
            .map(|f| 100.0 * (f.2.lead_s + f.2.trail_s) / f.2.duration_s.max(1e-12))
            .collect(),
    );
    // One file's name, or how many files (a folder of recordings).
    let files: std::collections::BTreeSet<&str> = found.iter().map(|f| f.0.as_str()).collect();
    let whose = match files.first() {
        Some(one) if files.len() == 1 => (*one).to_owned(),
        _ => format!("{} files", files.len()),
    };
    let mut out = vec![Notice::info(format!(
        "{whose}: {} demos rest at their ends, {s0:.2}-{s1:.2} s ({p0:.0}-{p1:.0} % of their \
         durations): {action} (-v names each)",
        found.len()
    ))];
    out.extend(found.iter().map(|f| Notice::detail(each(f))));
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::load::demo::TimeSource;

    /// 0.5 s still, a 1 s move of 0.3 m, 0.25 s still, at 100 Hz.
    fn rested() -> RawDemo {
        let mut stamps = Vec::new();
        let mut positions = Vec::new();
        for i in 0..=175 {
            let t = i as f64 * 0.01;
            let u = ((t - 0.5) / 1.0).clamp(0.0, 1.0);
            let s = u * u * u * (10.0 - 15.0 * u + 6.0 * u * u);
            stamps.push(i * 10_000_000);
            positions.push([0.3 * s, 0.0, 1.0].into());
        }
        RawDemo {
            name: "arm.mcap:/ee".into(),
            file: "arm.mcap".into(),
            topic: "/ee".into(),
            stamps_ns: stamps,
            positions,
            orientations: None,
            time_source: TimeSource::HeaderStamp,
        }
    }

    #[test]
    fn rests_at_both_ends_are_measured_and_trimmed_only_when_asked() {
        let settings = SegmentSettings::default();
        let r = end_rests(&rested(), &settings);
        // The min-jerk profile is below 0.05 m/s for a little while past
        // 0.5 s too: the rests are a bit longer than the still parts.
        assert!((0.5..0.65).contains(&r.lead_s), "{r:?}");
        assert!((0.25..0.4).contains(&r.trail_s), "{r:?}");
        assert!(r.describe().contains("at rest at its start"));
        let mut demos = vec![rested()];
        let said = apply(&mut demos, &settings, false);
        assert_eq!(demos[0], rested());
        assert!(
            said[0].text.contains("arm.mcap: arm.mcap:/ee") && said[0].text.contains("--trim-rest")
        );
        // Many demos: one line and the details.
        let mut many = vec![rested(); 5];
        let many_said = apply(&mut many, &settings, false);
        assert_eq!(many_said.len(), 6);
        assert!(
            many_said[0]
                .text
                .contains("arm.mcap: 5 demos rest at their ends"),
            "{}",
            many_said[0].text
        );
        // Demos from several files: the summary names no one file.
        let mut spread: Vec<RawDemo> = (0..5)
            .map(|i| RawDemo {
                file: format!("trial_{i}.csv"),
                ..rested()
            })
            .collect();
        let spread_said = apply(&mut spread, &settings, false);
        assert!(
            spread_said[0]
                .text
                .starts_with("5 files: 5 demos rest at their ends"),
            "{}",
            spread_said[0].text
        );
        let said = apply(&mut demos, &settings, true);
        assert!(said[0].text.contains("trimmed"));
        let d = demos[0].duration_s();
        assert!((0.8..1.3).contains(&d), "{d}");
        // A trimmed demo has no rests left.
        assert!(!end_rests(&demos[0], &settings).any());
    }
}
