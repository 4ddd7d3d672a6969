//! From a source's streams to its demonstrations (method.md section 13):
//! the streams the user chose (`--topic` / `--exclude` patterns), split at
//! breaks in time ([`crate::gaps`]), screened (a stream whose stamp never
//! advances or whose positions span less than [`StreamFilter::min_extent_m`]
//! is skipped), then grouped ([`crate::group`]). Every stream is listed with
//! what happened to it ([`StreamInfo`]), which the app's Recording panel
//! shows; every skip is a notice naming file, topic and why. The CLI (through
//! [`crate::arrange::streams::load_source`]) and the app both arrange here.

use std::collections::{BTreeMap, HashMap};

use serde::Serialize;

use crate::arrange::gaps;
use crate::arrange::group::group_noting;
use crate::arrange::segment::find_segments;
use crate::error::Result;
use crate::load::demo::RawDemo;
use crate::load::options::GapPolicy;
use crate::load::options::Grouping;
use crate::load::options::SegmentSettings;
use crate::load::options::{Cut, LoadOptions, StreamFilter, matches_stream};
use crate::load::source::{SourceData, SourceStreams, load_streams};
use crate::notice::Notice;

/// What happened to a stream.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case", tag = "status", content = "detail")]
pub enum StreamStatus {
    /// It gave demonstrations.
    Kept,
    /// The user left it out (an `--exclude` pattern, or the app's checkbox).
    Excluded(String),
    /// No `--topic` pattern matches it.
    NotSelected,
    /// Its stamps never advance (one sample, or all at one time).
    NoTime,
    /// It does not move: its positions span this many metres.
    Still(f64),
}

impl StreamStatus {
    /// Whether the stream gave demonstrations.
    pub fn kept(&self) -> bool {
        matches!(self, Self::Kept)
    }

    /// Why the stream was skipped, in words (empty when kept).
    pub fn reason(&self, min_extent_m: f64) -> String {
        match self {
            Self::Kept => String::new(),
            Self::Excluded(by) => format!("excluded ({by})"),
            Self::NotSelected => "no --topic pattern matches it".to_owned(),
            Self::NoTime => "its stamp never advances (no duration)".to_owned(),
            Self::Still(span) => format!(
                "it does not move (its positions span {:.1} mm, less than {:.1} mm)",
                span * 1e3,
                min_extent_m * 1e3
            ),
        }
    }
}

/// One stream of a source and what happened to it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StreamInfo {
    /// The file or folder it came from.
    pub file: String,
    /// Its topic (and key: `/tf:hand`).
    pub topic: String,
    /// Samples as recorded.
    pub samples: usize,
    /// Last minus first stamp, seconds.
    pub duration_s: f64,
    /// The diagonal of its positions' bounding box, metres.
    pub extent_m: f64,
    /// Kept or skipped, and why.
    pub status: StreamStatus,
    /// The demonstrations it gave (parts after a break, segments).
    pub demos: usize,
}

/// The user's choice for one stream, over the filter: include it even when
/// the filter would skip it (`true`) or leave it out (`false`). Keyed by the
/// stream's topic.
pub type Overrides = BTreeMap<String, bool>;

/// A source's demonstrations and the account of every stream.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Arranged {
    /// The demonstrations, in load order.
    pub demos: Vec<RawDemo>,
    /// Every stream, in load order.
    pub streams: Vec<StreamInfo>,
    /// What the user should be told (skips, breaks, hints).
    pub notices: Vec<Notice>,
}

/// How streams become demonstrations: the part of the loading options that
/// works on streams already read.
#[derive(Clone, Debug, PartialEq)]
pub struct Arrangement {
    /// Which streams.
    pub filter: StreamFilter,
    /// What a break in time does.
    pub gaps: GapPolicy,
    /// What a demonstration is.
    pub demos: Grouping,
    /// Cut each demo's rests at its ends (reported either way).
    pub trim_rest: bool,
    /// What a rest is.
    pub rest: SegmentSettings,
    /// Where each demo is cut.
    pub cut: Cut,
    /// The unit the positions were read in (for the warning when their
    /// size suggests another).
    pub units: crate::load::units::Units,
}

impl Arrangement {
    /// The arrangement of loading options.
    pub fn of(options: &LoadOptions) -> Self {
        Self {
            filter: options.streams.clone(),
            gaps: options.gaps,
            demos: options.demos,
            trim_rest: options.trim_rest,
            rest: options.rest,
            cut: options.cut,
            units: options.units,
        }
    }
}

/// Arranges the streams of one source (all from one file or folder).
pub fn arrange(
    streams: Vec<RawDemo>,
    how: &Arrangement,
    overrides: &Overrides,
) -> Result<Arranged> {
    let mut out = Arranged::default();
    let mut chosen = Vec::new();
    for stream in streams {
        let index = out.streams.len();
        let parts = out.screen(stream, how, overrides);
        chosen.extend(parts.into_iter().map(|p| (index, p)));
    }
    if !matches!(how.demos, Grouping::Segmented(_)) {
        out.notices
            .extend(movement_hints(chosen.iter().map(|(_, p)| p)));
    }
    let (owners, parts): (Vec<usize>, Vec<RawDemo>) = chosen.into_iter().unzip();
    let (demos, said) = group_noting(parts, &how.demos)?;
    out.demos = demos;
    out.notices.extend(said);
    if !matches!(how.demos, Grouping::PerTopic) {
        out.recount(&owners);
    }
    if how.cut == Cut::Farthest {
        for demo in &mut out.demos {
            if let Some((kept, said)) = crate::arrange::shape::cut_farthest(demo) {
                *demo = kept;
                out.notices.push(said);
            }
        }
    }
    let rests = crate::arrange::rest::apply(&mut out.demos, &how.rest, how.trim_rest);
    out.notices.extend(rests);
    let loops = out
        .demos
        .iter()
        .filter_map(|d| crate::arrange::shape::loop_notice(d, how.filter.min_extent_m));
    out.notices.extend(loops.collect::<Vec<_>>());
    // Only demos: a map frame or an odometry stream far from the origin
    // that was skipped says nothing about the units.
    let odd_size = out
        .demos
        .iter()
        .filter_map(|d| crate::load::units::suspect(d, how.units));
    out.notices.extend(odd_size.collect::<Vec<_>>());
    Ok(out)
}

impl Arranged {
    /// Lists `stream` with what became of it, and gives its parts that are
    /// demos: none when it is skipped, one or more when a break in time
    /// splits it (a part judged as a demo on its own).
    fn screen(
        &mut self,
        stream: RawDemo,
        how: &Arrangement,
        overrides: &Overrides,
    ) -> Vec<RawDemo> {
        let min = how.filter.min_extent_m;
        let mut info = StreamInfo {
            file: stream.file.clone(),
            topic: stream.topic.clone(),
            samples: stream.stamps_ns.len(),
            duration_s: stream.duration_s(),
            extent_m: stream.extent_m(),
            status: StreamStatus::Kept,
            demos: 0,
        };
        info.status = match overrides.get(&stream.topic) {
            Some(true) => StreamStatus::Kept,
            Some(false) => StreamStatus::Excluded("unticked".to_owned()),
            None => judge(&stream, &info, &how.filter),
        };
        if !info.status.kept() {
            let level = match info.status {
                StreamStatus::Excluded(_) | StreamStatus::NotSelected => Notice::info,
                _ => Notice::warning,
            };
            self.notices.push(level(format!(
                "{}: {}: skipped: {}",
                info.file,
                info.topic,
                info.status.reason(min)
            )));
            self.streams.push(info);
            return Vec::new();
        }
        let forced = overrides.get(&stream.topic) == Some(&true);
        let (parts, said) = gaps::apply(vec![stream], how.gaps);
        self.notices.extend(said);
        let split = parts.len() > 1;
        let mut kept = Vec::new();
        for part in parts {
            let still = part.extent_m() < min;
            if split && !forced && (still || no_time(&part)) {
                // A part of a split stream is judged as a demo on its own.
                let why = if still {
                    StreamStatus::Still(part.extent_m())
                } else {
                    StreamStatus::NoTime
                };
                self.notices.push(Notice::warning(format!(
                    "{}: {}: skipped: {}",
                    part.file,
                    part.name,
                    why.reason(min)
                )));
                continue;
            }
            kept.push(part);
        }
        info.demos = kept.len();
        self.streams.push(info);
        kept
    }

    /// Counts each stream's demos again after a grouping that does not map
    /// parts one-to-one to demos (segments, one per file).
    fn recount(&mut self, owners: &[usize]) {
        for &i in owners {
            self.streams[i].demos = 0;
        }
        for demo in &self.demos {
            // A segment's topic is its stream's with `#k`.
            let stream_topic = demo
                .topic
                .rsplit_once('#')
                .filter(|(_, k)| k.parse::<usize>().is_ok())
                .map_or(demo.topic.as_str(), |(head, _)| head);
            if let Some(s) = self.streams.iter_mut().find(|s| {
                (s.topic == demo.topic || s.topic == stream_topic)
                    && s.file == demo.file
                    && s.status.kept()
            }) {
                s.demos += 1;
            }
        }
    }
}

/// A hint for each part that holds several movements between rests.
fn movement_hints<'a>(parts: impl Iterator<Item = &'a RawDemo>) -> Vec<Notice> {
    parts
        .filter_map(|part| {
            let n = movements(part).filter(|&n| n > 1)?;
            Some(Notice::info(format!(
                "{}: {}: holds {n} movements between rest periods: --demos segment \
                 (the app's Loading: demos per segment) cuts it into demos",
                part.file, part.topic
            )))
        })
        .collect()
}

fn judge(stream: &RawDemo, info: &StreamInfo, filter: &StreamFilter) -> StreamStatus {
    if let Some(p) = filter
        .exclude
        .iter()
        .find(|p| matches_stream(p, &stream.topic))
    {
        return StreamStatus::Excluded(format!("--exclude {p}"));
    }
    if !filter.topics.is_empty()
        && !filter
            .topics
            .iter()
            .any(|p| matches_stream(p, &stream.topic))
    {
        return StreamStatus::NotSelected;
    }
    if no_time(stream) {
        return StreamStatus::NoTime;
    }
    if info.extent_m < filter.min_extent_m {
        return StreamStatus::Still(info.extent_m);
    }
    StreamStatus::Kept
}

fn no_time(stream: &RawDemo) -> bool {
    stream
        .stamps_ns
        .first()
        .is_none_or(|first| stream.stamps_ns.iter().all(|t| t == first))
}

/// How many movements between rest periods a stream holds (default
/// segmentation), when that can be said.
fn movements(stream: &RawDemo) -> Option<usize> {
    let settings = SegmentSettings::default();
    let total = stream.duration_s();
    // A single reach has no room for two movements and a rest between.
    if total < 2.0 * settings.min_segment_s + settings.min_rest_s {
        return None;
    }
    find_segments(stream, &settings).ok().map(|s| s.len())
}

/// What one source gave, arranged: its demonstrations in load order, what
/// the user should be told, every stream with what became of it, and the
/// topics the reader did not read.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SourceDemos {
    /// The demonstrations.
    pub demos: Vec<RawDemo>,
    /// Topics skipped, a truncated file's lost tail, and the like.
    pub notices: Vec<Notice>,
    /// Every stream and what became of it.
    pub streams: Vec<StreamInfo>,
    /// Topics the reader did not read, with why (their schema, or what
    /// they are).
    pub skipped: Vec<(String, String)>,
}

/// Loads a source and arranges its streams into demonstrations
/// ([`crate::arrange`]: the topic patterns, breaks in time split or
/// bridged, still and timeless streams skipped, the grouping; method.md
/// sections 1 and 11). Nothing crosses sources, so loading sources one by
/// one and pooling them gives the same demonstrations as loading them
/// together (pooled names are made unique by
/// [`crate::arrange::streams::unique_names`]).
pub fn load_source(name: &str, data: SourceData<'_>, options: &LoadOptions) -> Result<SourceDemos> {
    arrange_source(load_streams(name, data, options)?, options)
}

/// Arranges a source's streams into its demonstrations as
/// [`load_source`] does (for streams read some other way: in slices, with
/// progress).
pub fn arrange_source(loaded: SourceStreams, options: &LoadOptions) -> Result<SourceDemos> {
    let arranged = arrange(loaded.demos, &Arrangement::of(options), &Overrides::new())?;
    let mut notices = loaded.notices;
    notices.extend(arranged.notices);
    Ok(SourceDemos {
        demos: arranged.demos,
        notices,
        streams: arranged.streams,
        skipped: loaded.skipped,
    })
}

/// Makes demonstration names unique across everything loaded: names that
/// collide are qualified by the shortest run of parent folders that tells
/// their files apart (`a/bag.mcap:/hand`, `b/bag.mcap:/hand`); names that
/// still collide (the same file twice) get ` (2)`, ` (3)`.
pub fn unique_names(demos: &mut [RawDemo]) {
    let mut by_name: HashMap<String, Vec<usize>> = HashMap::new();
    for (i, d) in demos.iter().enumerate() {
        by_name.entry(d.name.clone()).or_default().push(i);
    }
    let mut groups: Vec<Vec<usize>> = by_name.into_values().filter(|g| g.len() > 1).collect();
    groups.sort();
    for group in groups {
        let files: Vec<Vec<String>> = group
            .iter()
            .map(|&i| {
                std::path::Path::new(&demos[i].file)
                    .components()
                    .map(|c| c.as_os_str().to_string_lossy().into_owned())
                    .collect()
            })
            .collect();
        let depth = files.iter().map(Vec::len).max().unwrap_or(1);
        let qualified = |k: usize| -> Vec<String> {
            files
                .iter()
                .map(|parts| parts[parts.len().saturating_sub(k)..].join("/"))
                .collect()
        };
        let mut chosen = None;
        for k in 2..=depth {
            let q = qualified(k);
            let mut seen = q.clone();
            seen.sort();
            seen.dedup();
            if seen.len() == q.len() {
                chosen = Some(q);
                break;
            }
        }
        for (n, &i) in group.iter().enumerate() {
            let demo = &mut demos[i];
            let file_name = files[n].last().cloned().unwrap_or_default();
            match &chosen {
                Some(q) if demo.name.starts_with(&file_name) => {
                    demo.name = format!("{}{}", q[n], &demo.name[file_name.len()..]);
                }
                _ if n > 0 => demo.name = format!("{} ({})", demo.name, n + 1),
                _ => {}
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::load::demo::TimeSource;

    fn stream(file: &str, topic: &str, extent: f64, n: usize) -> RawDemo {
        RawDemo {
            name: format!("{}:{topic}", file.rsplit('/').next().unwrap_or(file)),
            file: file.into(),
            topic: topic.into(),
            stamps_ns: (0..n as i64).map(|i| i * 11_000_000).collect(),
            positions: (0..n)
                .map(|i| [extent * i as f64 / (n.max(2) - 1) as f64, 0.0, 0.0].into())
                .collect(),
            orientations: None,
            time_source: TimeSource::HeaderStamp,
        }
    }

    fn how(filter: StreamFilter, demos: Grouping) -> Arrangement {
        Arrangement {
            filter,
            gaps: GapPolicy::Split,
            demos,
            trim_rest: false,
            rest: SegmentSettings::default(),
            cut: Cut::None,
            units: crate::load::units::Units::M,
        }
    }

    #[test]
    fn still_static_and_unchosen_streams_are_skipped_each_with_a_reason() {
        let streams = vec![
            stream("bag.mcap", "/hand", 0.4, 200),
            stream("bag.mcap", "/tf:base_link", 0.002, 200),
            stream("bag.mcap", "/tf_static:cam", 0.0, 1),
            stream("bag.mcap", "/goal_pose", 0.3, 1),
            stream("bag.mcap", "/other", 0.4, 200),
        ];
        let filter = StreamFilter {
            exclude: vec!["/other".into()],
            ..StreamFilter::default()
        };
        let got = arrange(streams, &how(filter, Grouping::PerTopic), &Overrides::new())
            .expect("arranged");
        assert_eq!(got.demos.len(), 1);
        assert_eq!(got.demos[0].topic, "/hand");
        let status: Vec<&StreamStatus> = got.streams.iter().map(|s| &s.status).collect();
        assert_eq!(status[0], &StreamStatus::Kept);
        assert!(matches!(status[1], StreamStatus::Still(s) if (s - 0.002).abs() < 1e-12));
        assert_eq!(status[2], &StreamStatus::NoTime);
        assert_eq!(status[3], &StreamStatus::NoTime);
        assert_eq!(
            status[4],
            &StreamStatus::Excluded("--exclude /other".into())
        );
        assert_eq!(got.notices.len(), 4);
        assert!(
            got.notices[0]
                .text
                .contains("bag.mcap: /tf:base_link: skipped: it does not move"),
            "{}",
            got.notices[0].text
        );
        assert!(got.notices[1].text.contains("stamp never advances"));
        // An override brings a still stream back, and unticks a kept one.
        let overrides = Overrides::from([
            ("/tf:base_link".to_owned(), true),
            ("/hand".to_owned(), false),
        ]);
        let streams = vec![
            stream("bag.mcap", "/hand", 0.4, 200),
            stream("bag.mcap", "/tf:base_link", 0.002, 200),
        ];
        let got = arrange(
            streams,
            &how(StreamFilter::default(), Grouping::PerTopic),
            &overrides,
        )
        .expect("arranged");
        assert_eq!(got.demos.len(), 1);
        assert_eq!(got.demos[0].topic, "/tf:base_link");
    }

    #[test]
    fn topic_patterns_choose_and_per_file_takes_the_stream_that_moves_most() {
        let streams = vec![
            stream("a.mcap", "/tf:base", 0.02, 200),
            stream("a.mcap", "/tf:hand", 0.5, 200),
            stream("a.mcap", "/vive/left", 0.3, 200),
        ];
        let filter = StreamFilter {
            topics: vec!["/tf".into()],
            ..StreamFilter::default()
        };
        let got = arrange(
            streams.clone(),
            &how(filter, Grouping::PerTopic),
            &Overrides::new(),
        )
        .expect("arranged");
        assert_eq!(got.demos.len(), 2);
        assert_eq!(got.streams[2].status, StreamStatus::NotSelected);
        let got = arrange(
            streams,
            &how(StreamFilter::default(), Grouping::PerFile),
            &Overrides::new(),
        )
        .expect("arranged");
        assert_eq!(got.demos.len(), 1);
        assert_eq!(got.demos[0].topic, "/tf:hand");
        assert_eq!(got.demos[0].name, "a.mcap");
        assert_eq!(got.streams[1].demos, 1);
        assert_eq!(got.streams[0].demos, 0);
    }

    #[test]
    fn colliding_names_are_qualified_by_the_shortest_distinguishing_folder() {
        let mut demos = vec![
            stream("/data/day1/reach.mcap", "/hand", 0.4, 10),
            stream("/data/day2/reach.mcap", "/hand", 0.4, 10),
            stream("/data/day2/other.mcap", "/hand", 0.4, 10),
            stream("/data/day2/other.mcap", "/hand", 0.4, 10),
        ];
        unique_names(&mut demos);
        let names: Vec<&str> = demos.iter().map(|d| d.name.as_str()).collect();
        assert_eq!(
            names,
            [
                "day1/reach.mcap:/hand",
                "day2/reach.mcap:/hand",
                "other.mcap:/hand",
                "other.mcap:/hand (2)"
            ]
        );
    }
}
