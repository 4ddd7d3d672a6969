//! The whole window rendered with wgpu on Mesa's lavapipe (Vulkan on the
//! CPU), compared with baselines in `tests/snapshots/` (update them with
//! `UPDATE_SNAPSHOTS=1 cargo test --test gui_render`). One backend is pinned
//! because thin lines rasterise differently on GL and Vulkan.
//!
//! Without lavapipe these tests fail under CI (`CI` set: CI installs
//! `mesa-vulkan-drivers`), and elsewhere print one notice and pass, so the
//! README's test command passes on a machine with only the Rust toolchain.

mod support;

use std::sync::{Arc, Once};

use dmpscope::gui::DmpApp;
use dmpscope::session::{Runner, Settings};
use dmpscope_core::geom::Vec3;
use eframe::egui_wgpu::{WgpuSetup, WgpuSetupCreateNew};
use eframe::wgpu;
use egui_kittest::kittest::Queryable;
use egui_kittest::{Harness, SnapshotOptions};

/// Vulkan on lavapipe, or a panic that says what to install.
fn lavapipe() -> WgpuSetup {
    let mut setup = WgpuSetupCreateNew::without_display_handle();
    setup.instance_descriptor.backends = wgpu::Backends::VULKAN;
    setup.native_adapter_selector = Some(Arc::new(|adapters, _surface| {
        adapters
            .iter()
            .find(|a| {
                let info = a.get_info();
                info.device_type == wgpu::DeviceType::Cpu && info.name.contains("llvmpipe")
            })
            .cloned()
            .ok_or_else(|| {
                "no Mesa lavapipe Vulkan adapter: install mesa-vulkan-drivers".to_owned()
            })
    }));
    WgpuSetup::CreateNew(setup)
}

/// Whether Mesa's lavapipe is there. Without it: a panic under CI, else
/// one notice for the whole run and `false` (the test returns, passing).
fn have_lavapipe() -> bool {
    let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
    desc.backends = wgpu::Backends::VULKAN;
    let instance = wgpu::Instance::new(desc);
    let adapters = pollster::block_on(instance.enumerate_adapters(wgpu::Backends::VULKAN));
    let found = adapters.iter().any(|a| {
        let info = a.get_info();
        info.device_type == wgpu::DeviceType::Cpu && info.name.contains("llvmpipe")
    });
    let ci = std::env::var("CI").is_ok_and(|v| !v.is_empty() && v != "false" && v != "0");
    if !found && ci {
        panic!("no Mesa lavapipe Vulkan adapter under CI: install mesa-vulkan-drivers");
    }
    if !found {
        static NOTICE: Once = Once::new();
        // Straight to the process's stderr: the test harness captures
        // `eprintln!` of passing tests, and this notice must be seen.
        NOTICE.call_once(|| {
            use std::io::Write as _;
            let _ = writeln!(
                std::io::stderr(),
                "gui_render: skipped: install mesa-vulkan-drivers to run the rendered-window tests"
            );
        });
    }
    found
}

fn harness() -> Harness<'static, DmpApp> {
    let settings = Settings::with_grid_points(32);
    let mut h = Harness::builder()
        .with_size([1280.0, 800.0])
        .wgpu_setup(lavapipe())
        .with_options(SnapshotOptions::new().output_path("tests/snapshots"))
        .build_eframe(move |cc| {
            DmpApp::with_runner(settings, Vec::new(), Runner::inline())
                .with_render_state(cc.wgpu_render_state.as_ref())
        });
    h.run_steps(5);
    h
}

/// Pixels in `rect` (points; the harness renders at 1 pixel per point)
/// that are neither the 3D view's background nor grey (grid, text).
fn coloured_pixels(image: &image::RgbaImage, rect: egui::Rect) -> usize {
    let mut n = 0;
    for y in rect.top() as u32..rect.bottom() as u32 {
        for x in rect.left() as u32..rect.right() as u32 {
            let [r, g, b, _] = image.get_pixel(x, y).0;
            let (lo, hi) = (r.min(g).min(b), r.max(g).max(b));
            if hi - lo > 40 {
                n += 1;
            }
        }
    }
    n
}

#[test]
fn the_window_matches_its_baseline() {
    if !have_lavapipe() {
        return;
    }
    let mut h = harness();
    h.snapshot("window_sample");
    h.get_by_role_and_label(egui::accesskit::Role::Button, "Hrstc4")
        .click();
    h.run_steps(3);
    h.snapshot("window_hrstc4");
}

#[test]
fn pinned_sets_are_drawn_in_their_colours() {
    if !have_lavapipe() {
        return;
    }
    let mut h = harness();
    h.state_mut().pin_by_text("extracted, Hrstc1, Hrstc4");
    h.run_steps(3);
    h.get_by_label("Compare gain sets (3 pinned)").click();
    h.run_steps(2);
    h.get_by_role_and_label(egui::accesskit::Role::CheckBox, "comparison table")
        .click();
    h.run_steps(3);
    h.snapshot("window_pinned");
}

#[test]
fn the_3d_view_draws_the_demos_and_hides_them_on_request() {
    if !have_lavapipe() {
        return;
    }
    let mut h = harness();
    // The view is below its row of toggles ("show" 1 ... 8 "regenerated").
    let row = h.get_by_label("show").rect();
    let view = egui::Rect::from_min_max(
        egui::pos2(row.left(), row.bottom() + 40.0),
        egui::pos2(row.left() + 500.0, row.bottom() + 200.0),
    );
    let shown = coloured_pixels(&h.render().expect("render"), view);
    assert!(
        shown > 500,
        "the 3D view draws the demos: {shown} coloured pixels"
    );
    let demos = h.state().session().demos().len();
    assert_eq!(demos, 8, "the app opens on planted8");
    for i in 1..=demos {
        h.get_by_role_and_label(egui::accesskit::Role::Button, &i.to_string())
            .click();
        h.run_steps(1);
    }
    h.run_steps(2);
    let hidden = coloured_pixels(&h.render().expect("render"), view);
    assert!(
        hidden * 10 < shown,
        "hiding every demo clears the view: {hidden} vs {shown} coloured pixels"
    );
}

#[test]
fn the_diagnostics_forcing_terms_and_trade_off_match_their_baselines() {
    if !have_lavapipe() {
        return;
    }
    let mut h = harness();
    h.get_by_role_and_label(egui::accesskit::Role::Button, "Samples")
        .click();
    h.run_steps(2);
    h.get_by_role_and_label(egui::accesskit::Role::Button, "planted8.mcap")
        .click();
    h.run_steps(5);
    assert!(
        h.state()
            .session()
            .diagnostics()
            .is_some_and(|d| d.complete())
    );
    h.get_by_role_and_label(egui::accesskit::Role::Button, "Forcing terms")
        .click();
    h.run_steps(3);
    h.snapshot("window_planted_forcing");
    h.get_by_role_and_label(egui::accesskit::Role::Button, "Trade-off")
        .click();
    h.run_steps(3);
    h.snapshot("window_planted_tradeoff");
}

/// Drags the primary button from `from` to `to` in five moves, holding
/// `modifiers`.
fn drag(h: &mut Harness<'_, DmpApp>, from: egui::Pos2, to: egui::Pos2, modifiers: egui::Modifiers) {
    h.input_mut()
        .events
        .push(egui::Event::ModifiersChanged(modifiers));
    h.input_mut().events.push(egui::Event::PointerMoved(from));
    h.step();
    h.input_mut().events.push(egui::Event::PointerButton {
        pos: from,
        button: egui::PointerButton::Primary,
        pressed: true,
        modifiers,
    });
    h.step();
    for i in 1..=5 {
        let p = from + (to - from) * (i as f32 / 5.0);
        h.input_mut().events.push(egui::Event::PointerMoved(p));
        h.step();
    }
    h.input_mut().events.push(egui::Event::PointerButton {
        pos: to,
        button: egui::PointerButton::Primary,
        pressed: false,
        modifiers,
    });
    h.step();
    h.input_mut()
        .events
        .push(egui::Event::ModifiersChanged(egui::Modifiers::NONE));
    h.run_steps(2);
}

/// Opens a new target and runs the DMP there; the run's own start and goal.
fn open_a_new_target(h: &mut Harness<'_, DmpApp>) -> (Vec3, Vec3) {
    h.get_by_role_and_label(egui::accesskit::Role::Button, "New target")
        .click();
    h.run_steps(2);
    h.get_by_label("Run the DMP at a new target").click();
    h.run_steps(4);
    let g = support::run_at_new_target(h);
    assert_eq!(g.out.warnings, Vec::<String>::new());
    (g.out.start, g.out.goal)
}

/// Where the 3D view drew the start and goal handles.
fn handles(h: &Harness<'_, DmpApp>) -> [egui::Pos2; 2] {
    h.state()
        .view()
        .view3d
        .handles_on_screen()
        .expect("handles drawn")
}

/// Drags the goal handle and checks the goal moved on its plane and the path follows.
fn drag_the_goal_on_its_plane(h: &mut Harness<'_, DmpApp>, goal: egui::Pos2, own_goal: Vec3) {
    // The goal moves on the horizontal plane through it.
    drag(
        h,
        goal,
        goal + egui::vec2(-90.0, 25.0),
        egui::Modifiers::NONE,
    );
    let spec = *h.state().session().generalise_spec().expect("on");
    let moved = spec.target.goal.expect("the drag set a goal");
    let shift = ((moved[0] - own_goal[0]).powi(2) + (moved[1] - own_goal[1]).powi(2)).sqrt();
    assert!(
        shift > 0.02,
        "the goal moved {shift} m: {moved:?} from {:?}",
        own_goal
    );
    assert!((moved[2] - own_goal[2]).abs() < 1e-5, "at the same height");
    let g = support::run_at_new_target(h);
    assert_eq!(g.out.goal, moved);
    assert!(
        g.out.final_error < 0.05,
        "the path follows: {}",
        g.out.final_error
    );
}

/// Drags the start handle with Shift and checks the start moved up only.
fn drag_the_start_up(h: &mut Harness<'_, DmpApp>, start: egui::Pos2, own_start: Vec3) {
    // With Shift the start moves up only.
    drag(
        h,
        start,
        start + egui::vec2(0.0, -40.0),
        egui::Modifiers::SHIFT,
    );
    let spec = *h.state().session().generalise_spec().expect("on");
    let up = spec.target.start.expect("the drag set a start");
    assert!(
        up[2] - own_start[2] > 0.01,
        "up by {}",
        up[2] - own_start[2]
    );
    assert!((up[0] - own_start[0]).abs() < 1e-5 && (up[1] - own_start[1]).abs() < 1e-5);
}

/// Clicks Reset and checks the target is the demo's again.
fn reset_returns_to_the_demo(h: &mut Harness<'_, DmpApp>) {
    // Reset returns to the demo.
    h.get_by_role_and_label(egui::accesskit::Role::Button, "Reset")
        .click();
    h.run_steps(2);
    let spec = *h.state().session().generalise_spec().expect("on");
    assert_eq!((spec.target.start, spec.target.goal), (None, None));
}

/// Drags across the goal with Ctrl and checks the goal turned and the run turns to it.
fn turn_the_goal_with_ctrl(h: &mut Harness<'_, DmpApp>) {
    // With Ctrl (Cmd) a drag across the goal turns its orientation about the
    // vertical, and the run turns to it (method.md section 12).
    let [_, goal] = handles(h);
    drag(
        h,
        goal,
        goal + egui::vec2(60.0, 0.0),
        egui::Modifiers::COMMAND,
    );
    let spec = *h.state().session().generalise_spec().expect("on");
    assert_eq!(spec.target.goal, None, "the goal did not move");
    let turned = spec
        .target
        .goal_orientation
        .expect("the drag turned the goal");
    let g = support::run_at_new_target(h);
    let own_goal = h.state().session().model().expect("model").demos()[0]
        .orientation
        .as_ref()
        .expect("planted8 turns")
        .goal;
    let by = dmpscope_core::rotation::angle(turned, own_goal).to_degrees();
    assert!(by > 5.0, "turned by {by} degrees");
    let path = g.out.orientation.as_ref().expect("an orientation path");
    let end = dmpscope_core::rotation::angle(*path.q.last().expect("end"), turned).to_degrees();
    assert!(
        end < by,
        "the run turns towards it: ends {end} degrees away"
    );
}

#[test]
fn the_goal_and_start_of_a_new_target_drag_in_the_3d_view() {
    if !have_lavapipe() {
        return;
    }
    let mut h = harness();
    let (own_start, own_goal) = open_a_new_target(&mut h);
    h.snapshot("window_new_target");
    let [start, goal] = handles(&h);
    drag_the_goal_on_its_plane(&mut h, goal, own_goal);
    drag_the_start_up(&mut h, start, own_start);
    h.snapshot("window_new_target_moved");
    reset_returns_to_the_demo(&mut h);
    turn_the_goal_with_ctrl(&mut h);
}
