//! How recordings are read, as on the command line (`--y-up`, `--frame`,
//! `--fixed-frame`, `--topic`, `--exclude`, `--min-extent`, `--demos`,
//! `--rest-speed`, `--min-rest`, `--min-demo`, `--gaps`): changing the up
//! axis, the frame filter or the fixed frame reads the recordings again;
//! the rest only rearranges what was read.

use dmpscope_core::gaps::GapPolicy;
use dmpscope_core::group::Grouping;
use dmpscope_core::io::UpAxis;
use eframe::egui;

use super::super::view_state::ViewState;
use crate::session::Settings;

/// The Loading section.
pub fn loading_ui(ui: &mut egui::Ui, s: &mut Settings, view: &mut ViewState) {
    let load = &mut s.load;
    egui::Grid::new("loading").show(ui, |ui| {
        ui.label("up axis");
        ui.horizontal(|ui| {
            ui.radio_value(&mut load.up, UpAxis::ZUp, "z")
                .on_hover_text("z up: ROS (REP 103), Foxglove");
            ui.radio_value(&mut load.up, UpAxis::YUp, "y (OpenVR)")
                .on_hover_text("y up: OpenVR's native frame, turned to z up");
        });
        ui.end_row();
        list_field(
            ui,
            "frames",
            &mut view.frames_text,
            &mut load.frames,
            "all (or: hand_left, 1, ...)",
            "TF child frames or pose indices to keep, comma separated; Enter applies",
        );
        let l = ui.label("fixed frame");
        let typed = ui
            .add(
                egui::TextEdit::singleline(&mut view.fixed_frame_text)
                    .hint_text("each transform's parent (or: world)")
                    .desired_width(160.0),
            )
            .labelled_by(l.id)
            .on_hover_text(
                "express every TF frame in this frame, composing /tf and /tf_static; Enter \
                 applies",
            );
        if typed.lost_focus() {
            let f = view.fixed_frame_text.trim();
            load.fixed_frame = (!f.is_empty()).then(|| f.to_owned());
        } else if !typed.has_focus() {
            view.fixed_frame_text = load.fixed_frame.clone().unwrap_or_default();
        }
        ui.end_row();
        list_field(
            ui,
            "topics",
            &mut view.topics_text,
            &mut load.streams.topics,
            "all (or: /vive/*, /tf:hand)",
            "streams to use: glob patterns (* and ?) matching a topic, topic:key or key, \
             comma separated; Enter applies",
        );
        list_field(
            ui,
            "exclude",
            &mut view.exclude_text,
            &mut load.streams.exclude,
            "none (or: /tf_static, *_link)",
            "streams to leave out: glob patterns, comma separated; wins over topics",
        );
        let l = ui.label("least movement");
        let mut mm = load.streams.min_extent_m * 1e3;
        if ui
            .add(
                egui::DragValue::new(&mut mm)
                    .speed(0.5)
                    .range(0.0..=1000.0)
                    .suffix(" mm"),
            )
            .labelled_by(l.id)
            .on_hover_text("a stream whose positions span less than this does not move: skipped")
            .changed()
        {
            load.streams.min_extent_m = mm * 1e-3;
        }
        ui.end_row();
        ui.label("a demo is");
        ui.horizontal(|ui| {
            let segmented = matches!(load.demos, Grouping::Segmented(_));
            if ui
                .radio(load.demos == Grouping::PerTopic, "a topic")
                .on_hover_text("one per topic, TF child frame or pose index")
                .clicked()
            {
                load.demos = Grouping::PerTopic;
            }
            if ui
                .radio(load.demos == Grouping::PerFile, "a file")
                .on_hover_text("each file's stream that moves most")
                .clicked()
            {
                load.demos = Grouping::PerFile;
            }
            if ui
                .radio(segmented, "a segment")
                .on_hover_text("continuous recordings cut at rest periods")
                .clicked()
            {
                load.demos = Grouping::Segmented(view.segment);
            }
        });
        ui.end_row();
        ui.label("breaks in time");
        ui.horizontal(|ui| {
            ui.radio_value(&mut load.gaps, GapPolicy::Split, "split")
                .on_hover_text(
                    "a clock jump or a dropout (over max(0.1 s, 10 intervals)) splits the \
                     stream: each part is a demo",
                );
            ui.radio_value(&mut load.gaps, GapPolicy::Keep, "bridge")
                .on_hover_text("keep the stream whole across it (a warning names it)");
        });
        ui.end_row();
        if let Grouping::Segmented(seg) = &mut load.demos {
            let rows: [(&str, &mut f64, f64, &str); 3] = [
                ("rest speed", &mut seg.rest_speed, 0.005, " m/s"),
                ("shortest rest", &mut seg.min_rest_s, 0.01, " s"),
                ("shortest demo", &mut seg.min_segment_s, 0.01, " s"),
            ];
            for (name, value, speed, unit) in rows {
                let l = ui.label(name);
                ui.add(
                    egui::DragValue::new(value)
                        .speed(speed)
                        .range(0.001..=100.0)
                        .suffix(unit),
                )
                .labelled_by(l.id);
                ui.end_row();
            }
            view.segment = *seg;
        }
    });
}

/// A comma-separated list typed into one field, applied on Enter or when
/// the field loses focus (one row of the Loading grid).
fn list_field(
    ui: &mut egui::Ui,
    name: &str,
    text: &mut String,
    list: &mut Vec<String>,
    hint: &str,
    hover: &str,
) {
    let l = ui.label(name);
    let typed = ui
        .add(
            egui::TextEdit::singleline(text)
                .hint_text(hint)
                .desired_width(160.0),
        )
        .labelled_by(l.id)
        .on_hover_text(hover);
    if typed.lost_focus() {
        *list = text
            .split(',')
            .map(str::trim)
            .filter(|f| !f.is_empty())
            .map(str::to_owned)
            .collect();
    } else if !typed.has_focus() {
        *text = list.join(", ");
    }
    ui.end_row();
}
