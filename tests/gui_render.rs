//! The whole window rendered with wgpu on Mesa's lavapipe (Vulkan on the
//! CPU), compared with baselines in `tests/snapshots/` (update them with
//! `UPDATE_SNAPSHOTS=1 cargo test --test gui_render`). These tests fail, not
//! skip, without lavapipe: CI installs `mesa-vulkan-drivers`. One backend
//! is pinned because thin lines rasterise differently on GL and Vulkan.

use std::sync::Arc;

use dmpscope::gui::{DmpApp, Settings};
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

fn harness() -> Harness<'static, DmpApp> {
    let settings = Settings {
        grid_n: 32,
        ..Settings::default()
    };
    let mut h = Harness::builder()
        .with_size([1280.0, 800.0])
        .wgpu_setup(lavapipe())
        .with_options(SnapshotOptions::new().output_path("../tests/snapshots"))
        .build_eframe(move |cc| {
            DmpApp::with_settings(settings, Vec::new())
                .with_render_state(cc.wgpu_render_state.as_ref())
        });
    h.run_steps(2);
    let ctx = h.ctx.clone();
    h.state_mut().wait_for_landscape(&ctx);
    h.run_steps(3);
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
    let mut h = harness();
    h.snapshot("window_sample");
    h.get_by_role_and_label(egui::accesskit::Role::Button, "Hrstc4")
        .click();
    h.run_steps(3);
    h.snapshot("window_hrstc4");
}

#[test]
fn the_3d_view_draws_the_demos_and_hides_them_on_request() {
    let mut h = harness();
    // The view is below its row of toggles ("show" 1 ... 10 "regenerated").
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
    for i in 1..=10 {
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
