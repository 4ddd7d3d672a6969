//! The Recording section: every stream each opened recording holds, kept or
//! skipped and why (method.md section 13), with a tick to include a stream
//! the filter skipped or leave out one it kept; the topics not read
//! and a source's load error; for demos per segment, the thresholds as
//! sliders and each kept stream's timeline of speed with its segments. A
//! tick regroups what was read (nothing is read
//! again); the demos, the model and the landscape follow.

use dmpscope_core::Level;
use dmpscope_core::arrange::streams::{StreamInfo, StreamStatus};
use dmpscope_core::load::options::SegmentSettings;
use eframe::egui;

use dmpscope_core::load::options::Grouping;

use super::super::timeline::{TimelineCache, timeline_ui};
use super::PanelCtx;
use super::demos::level_colour;
use crate::session;
use crate::session::sources::SourceSlot;

/// The Recording section.
pub fn recording_ui(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>) {
    let session = cx.session;
    let min = cx.settings.load.streams.min_extent_m;
    if session.recordings().is_empty() {
        ui.label("No recording is open.");
        return;
    }
    if let Grouping::Segmented(seg) = &mut cx.settings.load.demos {
        recording_thresholds_ui(ui, seg);
        cx.view.segment = *seg;
    }
    let segmenting = match cx.settings.load.demos {
        Grouping::Segmented(seg) => Some(seg),
        _ => None,
    };
    for (source, slot) in session.recordings().iter().enumerate() {
        let rows = SourceRows {
            source,
            slot,
            segmenting,
            min,
        };
        recording_source_ui(ui, rows, cx);
    }
}

/// The segmentation thresholds as sliders.
fn recording_thresholds_ui(ui: &mut egui::Ui, seg: &mut SegmentSettings) {
    // The thresholds beside the timelines they cut (as in Loading).
    let rows: [(&str, &mut f64, std::ops::RangeInclusive<f64>, &str); 3] = [
        ("rest speed", &mut seg.rest_speed, 0.005..=0.5, " m/s"),
        ("shortest rest", &mut seg.min_rest_s, 0.02..=3.0, " s"),
        ("shortest demo", &mut seg.min_segment_s, 0.05..=5.0, " s"),
    ];
    for (name, value, range, unit) in rows {
        ui.add(
            egui::Slider::new(value, range)
                .logarithmic(true)
                .text(name)
                .suffix(unit),
        );
    }
}

/// One opened recording as the section lists it.
#[derive(Clone, Copy)]
struct SourceRows<'a> {
    /// Its index among the recordings.
    source: usize,
    /// The recording.
    slot: &'a SourceSlot,
    /// The segmentation thresholds when demos are segments.
    segmenting: Option<SegmentSettings>,
    /// The least movement of a kept stream, metres.
    min: f64,
}

/// One recording's header: its load error, its streams and the topics not read.
fn recording_source_ui(ui: &mut egui::Ui, rows: SourceRows<'_>, cx: &mut PanelCtx<'_>) {
    let (source, slot) = (rows.source, rows.slot);
    let name = slot.source.name();
    let kept = slot.streams().iter().filter(|s| s.status.kept()).count();
    let title = if slot.loading() {
        format!("{name} (reading...)")
    } else {
        format!("{name}: {kept} of {} streams kept", slot.streams().len())
    };
    egui::CollapsingHeader::new(title)
        .id_salt(("recording", source))
        .default_open(true)
        .show(ui, |ui| {
            if let Some(e) = slot.error() {
                ui.colored_label(level_colour(Level::Error), e);
            }
            // One stream a row and its account below, wrapped: the side
            // panel keeps its width whatever the reasons say.
            for stream in slot.streams() {
                let forced = slot.overrides.get(&stream.topic).copied();
                recording_stream_tick_ui(ui, source, stream, forced, cx);
                recording_stream_account_ui(ui, rows, stream, &mut cx.view.timelines);
            }
            let skipped = slot.skipped_topics();
            if !skipped.is_empty() {
                ui.collapsing(format!("{} topics not read", skipped.len()), |ui| {
                    for (topic, why) in skipped {
                        ui.label(format!("{topic} ({why})"));
                    }
                });
            }
        });
}

/// A stream's tick (over the filter) and, when `forced`, its "as filtered" button.
fn recording_stream_tick_ui(
    ui: &mut egui::Ui,
    source: usize,
    stream: &StreamInfo,
    forced: Option<bool>,
    cx: &mut PanelCtx<'_>,
) {
    ui.horizontal(|ui| {
        let mut on = stream.status.kept();
        let tick = ui.checkbox(&mut on, &stream.topic).on_hover_text(
            "tick to use this stream, untick to leave it out, over the \
             Loading filter",
        );
        if tick.changed() {
            cx.push(session::Command::SetStreamIncluded {
                source,
                topic: stream.topic.clone(),
                included: Some(on),
            });
        }
        if forced.is_some()
            && ui
                .small_button("as filtered")
                .on_hover_text("forget the tick: the Loading filter decides")
                .clicked()
        {
            cx.push(session::Command::SetStreamIncluded {
                source,
                topic: stream.topic.clone(),
                included: None,
            });
        }
    });
}

/// A stream's account: its timeline when segmenting, its statistics, why it was skipped.
fn recording_stream_account_ui(
    ui: &mut egui::Ui,
    rows: SourceRows<'_>,
    stream: &StreamInfo,
    timelines: &mut TimelineCache,
) {
    let (source, slot) = (rows.source, rows.slot);
    ui.indent(("stream", source, &stream.topic), |ui| {
        if let Some(seg) = rows.segmenting
            && stream.status.kept()
            && let Some(raw) = slot.raw_streams().iter().find(|r| r.topic == stream.topic)
        {
            timeline_ui(ui, timelines, source, raw, seg);
        }
        let stats = format!(
            "{} sample{}, {:.2} s, spans {:.0} mm",
            stream.samples,
            if stream.samples == 1 { "" } else { "s" },
            stream.duration_s,
            stream.extent_m * 1e3
        );
        match &stream.status {
            StreamStatus::Kept => {
                let demos = match stream.demos {
                    1 => "1 demo".to_owned(),
                    n => format!("{n} demos"),
                };
                ui.add(egui::Label::new(format!("{stats}: {demos}")).wrap());
            }
            other => {
                ui.add(egui::Label::new(stats).wrap());
                ui.add(
                    egui::Label::new(
                        egui::RichText::new(format!("skipped: {}", other.reason(rows.min)))
                            .color(level_colour(Level::Warning)),
                    )
                    .wrap(),
                );
            }
        }
    });
}
