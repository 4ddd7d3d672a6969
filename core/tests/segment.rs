//! Segmentation of one continuous recording into demonstrations, and the
//! other groupings (per topic, per file).

use dmpscope_core::arrange::group::group;
use dmpscope_core::arrange::segment::{find_segments, split};
use dmpscope_core::load::options::Grouping;
use dmpscope_core::load::options::SegmentSettings;
use dmpscope_core::rng::Rng;
use dmpscope_core::synth::vive::reach_demos;
use dmpscope_core::{RawDemo, TimeSource};

/// One take: `count` reaches back and forth with `rest_s` of rest (with
/// tracker noise) between them, at ~90 Hz. Returns the take and the true
/// (start, end) stamps of each movement.
fn continuous_take(count: usize, rest_s: f64) -> (RawDemo, Vec<(i64, i64)>) {
    let demos = reach_demos(3, count, 0);
    let mut rng = Rng::new(11);
    let mut stamps = Vec::new();
    let mut positions: Vec<[f64; 3]> = Vec::new();
    let mut truth = Vec::new();
    let mut t = 1_000_000_000_000i64;
    let period = 11_111_111i64;
    let mut offset = [0.0; 3];
    for (i, d) in demos.iter().enumerate() {
        // Rest where the hand is, then the reach (shifted to continue from there,
        // reversed every other time so the hand goes back and forth).
        let here = positions.last().copied().unwrap_or(d.samples[0].1);
        let rest = (rest_s * 90.0) as usize;
        for _ in 0..rest {
            stamps.push(t);
            positions.push(here.map(|v| v + 0.0005 * rng.normal()));
            t += period;
        }
        let mut path: Vec<[f64; 3]> = d.samples.iter().map(|s| s.1).collect();
        if i % 2 == 1 {
            path.reverse();
        }
        offset = std::array::from_fn(|ax| here[ax] - path[0][ax] + 0.0 * offset[ax]);
        let start = t;
        for p in path {
            stamps.push(t);
            positions.push(std::array::from_fn(|ax| p[ax] + offset[ax]));
            t += period;
        }
        truth.push((start, t - period));
    }
    let here = positions.last().copied().unwrap_or([0.0; 3]);
    for _ in 0..(rest_s * 90.0) as usize {
        stamps.push(t);
        positions.push(here.map(|v| v + 0.0005 * rng.normal()));
        t += period;
    }
    let take = RawDemo {
        name: "take.mcap:/tracker".into(),
        file: "take.mcap".into(),
        topic: "/tracker".into(),
        stamps_ns: stamps,
        positions: positions.into_iter().map(Into::into).collect(),
        orientations: None,
        time_source: TimeSource::HeaderStamp,
    };
    (take, truth)
}

#[test]
fn a_take_of_ten_reaches_splits_into_ten_demos_at_the_rests() {
    let (take, truth) = continuous_take(10, 1.0);
    let found = find_segments(&take, &SegmentSettings::default()).expect("segments");
    assert_eq!(found.len(), 10, "{found:?}");
    for (seg, (start, end)) in found.iter().zip(&truth) {
        // Each segment covers its movement, give or take the rest margins
        // (the demos have 0.08-0.15 s of rest of their own at both ends).
        assert!(
            (seg.start_ns - start).abs() < 300_000_000,
            "{seg:?} vs {start}"
        );
        assert!((seg.end_ns - end).abs() < 300_000_000, "{seg:?} vs {end}");
    }
    let demos = split(&take, &SegmentSettings::default()).expect("split");
    assert_eq!(demos[0].name, "take.mcap:/tracker#1");
    assert_eq!(demos[9].name, "take.mcap:/tracker#10");
    for d in &demos {
        let info = d.info();
        assert!((0.5..2.0).contains(&info.duration_s), "{info:?}");
    }
}

#[test]
fn short_rests_do_not_split_and_short_fragments_are_dropped() {
    let (take, _) = continuous_take(4, 0.1);
    let settings = SegmentSettings {
        min_rest_s: 0.6,
        ..SegmentSettings::default()
    };
    // Rests of 0.1 s (plus the demos' own 0.16-0.3 s) never reach 0.6 s: one
    // segment holds all four reaches.
    assert_eq!(find_segments(&take, &settings).expect("segments").len(), 1);
    let strict = SegmentSettings {
        min_segment_s: 100.0,
        ..SegmentSettings::default()
    };
    assert!(find_segments(&take, &strict).expect("segments").is_empty());
}

#[test]
fn a_take_that_never_rests_is_one_segment_and_bad_settings_are_errors() {
    let demos = reach_demos(5, 1, 0);
    let raw = RawDemo {
        name: "one".into(),
        file: "one.mcap".into(),
        topic: "/t".into(),
        stamps_ns: demos[0].samples.iter().map(|s| s.0).collect(),
        positions: demos[0].samples.iter().map(|s| s.1.into()).collect(),
        orientations: None,
        time_source: TimeSource::HeaderStamp,
    };
    let found = find_segments(&raw, &SegmentSettings::default()).expect("segments");
    assert_eq!(found.len(), 1);
    let bad = SegmentSettings {
        rest_speed: f64::NAN,
        ..SegmentSettings::default()
    };
    assert!(find_segments(&raw, &bad).is_err());
}

#[test]
fn groupings_per_topic_per_file_and_segmented() {
    let (take, _) = continuous_take(3, 1.0);
    let mut other = take.clone();
    other.topic = "/other".into();
    other.name = "take.mcap:/other".into();
    let mut second_file = take.clone();
    second_file.file = "b.mcap".into();
    second_file.name = "b.mcap:/tracker".into();
    let streams = vec![take, other, second_file];
    assert_eq!(
        group(streams.clone(), &Grouping::PerTopic)
            .expect("topic")
            .len(),
        3
    );
    let per_file = group(streams.clone(), &Grouping::PerFile).expect("file");
    assert_eq!(per_file.len(), 2);
    assert_eq!(per_file[0].name, "take.mcap");
    assert_eq!(per_file[0].topic, "/tracker");
    let segmented = group(streams, &Grouping::Segmented(SegmentSettings::default())).expect("seg");
    assert_eq!(segmented.len(), 9);
}
