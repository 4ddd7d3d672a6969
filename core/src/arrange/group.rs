//! What a demonstration is: one per topic (and per key of multi-pose
//! topics such as TF child frames), one per file, or the segments of
//! continuous recordings.

use crate::arrange::segment::{split, split_counted};
use crate::error::Result;
use crate::load::demo::RawDemo;
use crate::load::options::Grouping;
use crate::notice::Notice;

/// Applies a grouping to streams in load order (files, then names).
pub fn group(streams: Vec<RawDemo>, grouping: &Grouping) -> Result<Vec<RawDemo>> {
    group_noting(streams, grouping).map(|(demos, _)| demos)
}

/// [`group`], with a notice for every recording whose segments were not
/// all kept (`--segments`).
pub fn group_noting(
    streams: Vec<RawDemo>,
    grouping: &Grouping,
) -> Result<(Vec<RawDemo>, Vec<Notice>)> {
    let mut notices = Vec::new();
    if let Grouping::Segmented(settings) = grouping {
        let mut out = Vec::new();
        for s in &streams {
            let (all, n) = split_counted(s, settings)?;
            let kept = settings.keep.pick(all);
            if kept.len() < n {
                notices.push(Notice::info(format!(
                    "{}: {}: {n} segments, kept {} (--segments {}): {}",
                    s.file,
                    s.topic,
                    kept.len(),
                    settings.keep.name(),
                    kept.iter()
                        .map(|d| d.name.as_str())
                        .collect::<Vec<_>>()
                        .join(", ")
                )));
            }
            out.extend(kept);
        }
        return Ok((out, notices));
    }
    group_whole(streams, grouping).map(|d| (d, notices))
}

fn group_whole(streams: Vec<RawDemo>, grouping: &Grouping) -> Result<Vec<RawDemo>> {
    match grouping {
        Grouping::PerTopic => Ok(streams),
        Grouping::PerFile => {
            let mut out: Vec<(f64, RawDemo)> = Vec::new();
            for s in streams {
                let extent = s.extent_m();
                match out.last_mut() {
                    Some((best, d)) if d.file == s.file => {
                        if extent > *best {
                            *best = extent;
                            *d = s;
                        }
                    }
                    _ => out.push((extent, s)),
                }
            }
            Ok(out
                .into_iter()
                .map(|(_, mut demo)| {
                    demo.name = file_name(&demo.file);
                    demo
                })
                .collect())
        }
        Grouping::Segmented(settings) => {
            let mut out = Vec::new();
            for s in &streams {
                out.extend(split(s, settings)?);
            }
            Ok(out)
        }
    }
}

fn file_name(label: &str) -> String {
    std::path::Path::new(label)
        .file_name()
        .map_or_else(|| label.to_owned(), |n| n.to_string_lossy().into_owned())
}
