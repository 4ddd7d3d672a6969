//! The timeline of a continuous take (the Recording section, demos per
//! segment): the hand's speed over time, the rest speed as a line, and the
//! segments found shaded, so the thresholds can be tuned by eye. The speed
//! and the segments are computed once per stream and thresholds
//! (`TimelineCache`), the speed reduced to at most [`MAX_POINTS`] points
//! (each the largest of its run, so no peak is lost).

use dmpscope_core::RawDemo;
use dmpscope_core::arrange::segment::{find_segments, speeds};
use dmpscope_core::load::options::SegmentSettings;
use eframe::egui::{self, Color32};
use egui_plot::{HLine, Line, Plot, PlotPoints, Span};

/// The most points drawn of one speed curve.
pub const MAX_POINTS: usize = 2000;

/// What identifies a computed timeline.
#[derive(Clone, Debug, PartialEq)]
struct Key {
    source: usize,
    topic: String,
    samples: usize,
    first_ns: Option<i64>,
    settings: SegmentSettings,
}

/// One stream's timeline, ready to draw.
struct Timeline {
    key: Key,
    speed: Vec<[f64; 2]>,
    /// Segments as (start, end) seconds from the stream's first stamp.
    segments: Vec<(f64, f64)>,
}

/// The timelines computed, one per stream shown.
#[derive(Default)]
pub struct TimelineCache {
    entries: Vec<Timeline>,
}

impl TimelineCache {
    fn get(&mut self, key: Key, stream: &RawDemo) -> &Timeline {
        if let Some(i) = self.entries.iter().position(|t| t.key == key) {
            return &self.entries[i];
        }
        self.entries
            .retain(|t| t.key.source != key.source || t.key.topic != key.topic);
        let (stamps, positions) = stream.sorted_unique();
        let first = stamps.first().copied().unwrap_or(0);
        let v = speeds(&stamps, &positions, key.settings.speed_window_s);
        let stride = v.len().div_ceil(MAX_POINTS).max(1);
        let speed = v
            .chunks(stride)
            .zip(stamps.chunks(stride))
            .map(|(vs, ts)| {
                let top = vs.iter().copied().fold(0.0, f64::max);
                [(ts[0] - first) as f64 * 1e-9, top]
            })
            .collect();
        let segments = find_segments(stream, &key.settings)
            .map(|found| {
                found
                    .iter()
                    .map(|s| {
                        (
                            (s.start_ns - first) as f64 * 1e-9,
                            (s.end_ns - first) as f64 * 1e-9,
                        )
                    })
                    .collect()
            })
            .unwrap_or_default();
        self.entries.push(Timeline {
            key,
            speed,
            segments,
        });
        let last = self.entries.len() - 1;
        &self.entries[last]
    }
}

/// Draws the timeline of `stream` (of recording `source`) at `settings`.
pub fn timeline_ui(
    ui: &mut egui::Ui,
    cache: &mut TimelineCache,
    source: usize,
    stream: &RawDemo,
    settings: SegmentSettings,
) {
    let key = Key {
        source,
        topic: stream.topic.clone(),
        samples: stream.stamps_ns.len(),
        first_ns: stream.stamps_ns.first().copied(),
        settings,
    };
    let t = cache.get(key, stream);
    ui.label(format!(
        "speed [m/s] over time [s]: {} segments (shaded), rest below the line",
        t.segments.len()
    ));
    Plot::new(("timeline", source, &stream.topic))
        .height(90.0)
        .allow_scroll(false)
        .show(ui, |plot| {
            for (k, &(a, b)) in t.segments.iter().enumerate() {
                plot.span(
                    Span::new(format!("segment {}", k + 1), a..=b)
                        .fill(Color32::from_rgba_unmultiplied(90, 160, 90, 40))
                        .border_width(0.0),
                );
            }
            plot.line(
                Line::new("speed", PlotPoints::from(t.speed.clone()))
                    .color(Color32::from_rgb(120, 170, 230)),
            );
            plot.hline(
                HLine::new("rest speed", settings.rest_speed)
                    .color(Color32::from_rgb(240, 180, 80))
                    .width(1.0),
            );
        });
}
