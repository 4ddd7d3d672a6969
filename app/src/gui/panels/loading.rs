//! How recordings are read, as on the command line (`--y-up`, `--units`,
//! `--frame`, `--fixed-frame`, `--topic`, `--exclude`, `--min-extent`,
//! `--demos`, `--segments`, `--rest-speed`, `--min-rest`, `--min-demo`,
//! `--gaps`, `--trim-rest`): changing the up axis, the units, the frame
//! filter or the fixed frame reads the recordings again; the rest only
//! rearranges what was read.

use dmpscope_core::load::options::GapPolicy;
use dmpscope_core::load::options::Grouping;
use dmpscope_core::load::options::UpAxis;
use dmpscope_core::load::options::{Cut, SegmentPick, SegmentSettings};
use dmpscope_core::load::units::Units;
use eframe::egui;

use super::PanelCtx;

/// The Loading section.
pub fn loading_ui(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>) {
    let (load, view) = (&mut cx.settings.load, &mut *cx.view);
    egui::Grid::new("loading").show(ui, |ui| {
        loading_up_axis_ui(ui, &mut load.up);
        loading_units_ui(ui, &mut load.units);
        list_field(
            ui,
            "frames",
            &mut view.frames_text,
            &mut load.frames,
            "all (or: hand_left, 1, ...)",
            "TF child frames or pose indices to keep, comma separated; Enter applies",
        );
        loading_fixed_frame_ui(ui, &mut view.fixed_frame_text, &mut load.fixed_frame);
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
        loading_min_extent_ui(ui, &mut load.streams.min_extent_m);
        loading_grouping_ui(ui, &mut load.demos, view.segment);
        loading_gaps_ui(ui, &mut load.gaps);
        if let Grouping::Segmented(seg) = &mut load.demos {
            loading_segment_ui(ui, seg);
            loading_segment_pick_ui(ui, &mut seg.keep);
            view.segment = *seg;
        }
        loading_rests_ui(ui, load);
        // A rest is the segmentation's, whatever a demo is (as the CLI's
        // --rest-speed and --min-rest).
        load.rest = SegmentSettings {
            keep: SegmentPick::All,
            ..view.segment
        };
    });
}

/// The units row.
fn loading_units_ui(ui: &mut egui::Ui, units: &mut Units) {
    ui.label("units");
    ui.horizontal(|ui| {
        for u in Units::ALL {
            ui.radio_value(units, u, u.name())
                .on_hover_text("the unit of the files' positions, converted to metres");
        }
    });
    ui.end_row();
}

/// Which segments of each recording are demos.
fn loading_segment_pick_ui(ui: &mut egui::Ui, keep: &mut SegmentPick) {
    ui.label("keep segments");
    ui.horizontal(|ui| {
        for (pick, name) in [
            (SegmentPick::All, "all"),
            (SegmentPick::First, "first"),
            (SegmentPick::Last, "last"),
            (SegmentPick::Out, "out"),
            (SegmentPick::Back, "back"),
        ] {
            ui.radio_value(keep, pick, name);
        }
        let mut n = match *keep {
            SegmentPick::Nth(n) => n,
            _ => 2,
        };
        let nth = matches!(keep, SegmentPick::Nth(_));
        if ui.radio(nth, "number").clicked() {
            *keep = SegmentPick::Nth(n);
        }
        if nth
            && ui
                .add(egui::DragValue::new(&mut n).range(1..=100))
                .changed()
        {
            *keep = SegmentPick::Nth(n);
        }
    })
    .response
    .on_hover_text(
        "e.g. first: the reach of each reach-and-return trial; out: the movements that leave \
         the recording's home (where it rests most), the reaches of a take of reaches and \
         returns; back: those that return home",
    );
    ui.end_row();
}

/// The rests-at-the-ends row: trim them or keep them (reported either way;
/// a rest is the segmentation's, below its rest speed for its rest time).
fn loading_rests_ui(ui: &mut egui::Ui, load: &mut dmpscope_core::load::options::LoadOptions) {
    ui.label("cut");
    let mut farthest = load.cut == Cut::Farthest;
    if ui
        .checkbox(&mut farthest, "each demo at its farthest point")
        .on_hover_text(
            "keep each demo from its start to its farthest point from the start: the reach \
             of an out-and-back with no rest at its far end (docs/method.md section 13)",
        )
        .changed()
    {
        load.cut = if farthest { Cut::Farthest } else { Cut::None };
    }
    ui.end_row();
    ui.label("rests at the ends");
    ui.checkbox(&mut load.trim_rest, "trim").on_hover_text(
        "cut each demo's standing still before and after the motion (changes what unit \
             time spans); the Recording panel's notes say how much either way",
    );
    ui.end_row();
    ui.label("bad orientations");
    ui.checkbox(&mut load.drop_bad_orientation, "drop")
        .on_hover_text(
            "beyond the method: a stream with a zero or non-finite quaternion loads its \
         positions without orientation, with a warning, instead of the error naming the \
         sample (docs/method.md section 12)",
        );
    ui.end_row();
}

/// The up axis row.
fn loading_up_axis_ui(ui: &mut egui::Ui, up: &mut UpAxis) {
    ui.label("up axis");
    ui.horizontal(|ui| {
        ui.radio_value(up, UpAxis::ZUp, "z")
            .on_hover_text("z up: ROS (REP 103), Foxglove");
        ui.radio_value(up, UpAxis::YUp, "y (OpenVR)")
            .on_hover_text("y up: OpenVR's native frame, turned to z up");
    });
    ui.end_row();
}

/// The fixed frame row: `text` as typed, applied to `fixed_frame` on Enter.
fn loading_fixed_frame_ui(ui: &mut egui::Ui, text: &mut String, fixed_frame: &mut Option<String>) {
    let l = ui.label("fixed frame");
    let typed = ui
        .add(
            egui::TextEdit::singleline(text)
                .hint_text("each transform's parent (or: world)")
                .desired_width(160.0),
        )
        .labelled_by(l.id)
        .on_hover_text(
            "express every TF frame in this frame, composing /tf and /tf_static; Enter \
             applies",
        );
    if typed.lost_focus() {
        let f = text.trim();
        *fixed_frame = (!f.is_empty()).then(|| f.to_owned());
    } else if !typed.has_focus() {
        *text = fixed_frame.clone().unwrap_or_default();
    }
    ui.end_row();
}

/// The least movement row (`min_extent_m` shown in millimetres).
fn loading_min_extent_ui(ui: &mut egui::Ui, min_extent_m: &mut f64) {
    let l = ui.label("least movement");
    let mut mm = *min_extent_m * 1e3;
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
        *min_extent_m = mm * 1e-3;
    }
    ui.end_row();
}

/// The "a demo is" row: a topic, a file or a segment (with `segment`'s thresholds).
fn loading_grouping_ui(ui: &mut egui::Ui, demos: &mut Grouping, segment: SegmentSettings) {
    ui.label("a demo is");
    ui.horizontal(|ui| {
        let segmented = matches!(*demos, Grouping::Segmented(_));
        if ui
            .radio(*demos == Grouping::PerTopic, "a topic")
            .on_hover_text("one per topic, TF child frame or pose index")
            .clicked()
        {
            *demos = Grouping::PerTopic;
        }
        if ui
            .radio(*demos == Grouping::PerFile, "a file")
            .on_hover_text("each file's stream that moves most")
            .clicked()
        {
            *demos = Grouping::PerFile;
        }
        if ui
            .radio(segmented, "a segment")
            .on_hover_text("continuous recordings cut at rest periods")
            .clicked()
        {
            *demos = Grouping::Segmented(segment);
        }
    });
    ui.end_row();
}

/// The breaks in time row: split the stream or bridge the break.
fn loading_gaps_ui(ui: &mut egui::Ui, gaps: &mut GapPolicy) {
    ui.label("breaks in time");
    ui.horizontal(|ui| {
        ui.radio_value(gaps, GapPolicy::Split, "split")
            .on_hover_text(
                "a clock jump or a dropout (over max(0.1 s, 10 intervals)) splits the \
                 stream: each part is a demo",
            );
        ui.radio_value(gaps, GapPolicy::Keep, "bridge")
            .on_hover_text("keep the stream whole across it (a warning names it)");
    });
    ui.end_row();
}

/// The segmentation thresholds' rows.
fn loading_segment_ui(ui: &mut egui::Ui, seg: &mut SegmentSettings) {
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
