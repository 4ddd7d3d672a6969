//! Playback as in a viewer (egui_kittest, frames stepped with a fixed time
//! of 50 ms): Play moves the cursor by real time at the chosen speed, the
//! cursor reaches the end and starts again (loop), the space bar pauses
//! it, and without loop it stops at the end.

mod support;

use dmpscope::gui::DmpApp;
use dmpscope::session::{Runner, Settings, Source};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

const DT: f64 = 0.05;

fn harness() -> Harness<'static, DmpApp> {
    let settings = Settings::with_grid_points(16);
    let sources = vec![Source::Path(support::sample_path())];
    let mut h = Harness::builder()
        .with_size([1280.0, 800.0])
        .with_step_dt(DT as f32)
        .build_eframe(move |_cc| DmpApp::with_runner(settings, sources, Runner::inline()));
    h.run_steps(2);
    h
}

fn t(h: &Harness<'_, DmpApp>) -> f64 {
    h.state().view().t
}

#[test]
fn play_moves_the_cursor_by_real_time_loops_and_pauses() {
    let mut h = harness();
    let duration = h.state().session().model().expect("model").demos()[0].duration_s;
    let start = t(&h);
    h.get_by_label("Play").click();
    h.step();
    h.step();
    let one = t(&h);
    assert!(one > start, "the cursor moves: {start} -> {one}");
    h.step();
    let two = t(&h);
    // One frame of 50 ms at 1x is 0.05 s of the demo's own duration.
    assert!(
        ((two - one) * duration - DT).abs() < 1e-6,
        "{one} -> {two} over {duration} s"
    );
    // On to the end and past it: it starts again.
    let mut wrapped = false;
    let mut last = two;
    for _ in 0..(duration / DT) as usize + 4 {
        h.step();
        wrapped |= t(&h) < last;
        last = t(&h);
    }
    assert!(wrapped, "the cursor loops at the end");
    assert!(h.state().view().playback.playing);
    // The space bar pauses.
    h.key_press(egui::Key::Space);
    h.step();
    let paused = t(&h);
    h.run_steps(3);
    assert!(!h.state().view().playback.playing);
    assert_eq!(t(&h), paused, "paused: the cursor stays");
}

#[test]
fn without_loop_playback_stops_at_the_end() {
    let mut h = harness();
    h.get_by_label("loop").click();
    h.step();
    assert!(!h.state().view().playback.looping);
    h.get_by_label("Play").click();
    let duration = h.state().session().model().expect("model").demos()[0].duration_s;
    for _ in 0..(duration / DT) as usize + 4 {
        h.step();
    }
    assert_eq!(t(&h), 1.0, "at the end");
    assert!(!h.state().view().playback.playing, "stopped there");
}
