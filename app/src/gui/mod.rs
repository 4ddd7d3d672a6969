//! The app's window (eframe): the session's state drawn as panels, views
//! and dialogs.
//!
//! `app.rs` is [`DmpApp`] (settings, session, view state, dialogs) and the
//! frame; `panels/` holds the panels, functions of a `PanelCtx` that push [`Command`]s;
//! `heatmap.rs`, `plots.rs`, `target_plots.rs`, `forcing.rs`, `tradeoff.rs` and
//! `view3d/` (a custom wgpu pipeline) are the views; `view_state.rs` what the views remember; `file_dialog.rs` the
//! dialogs (with the app's own browser where the system has none);
//! `export.rs` the heat maps as PNG; `testing.rs` (feature `testing`) the
//! browser tests' hook.

mod app;
#[cfg(target_arch = "wasm32")]
mod blob_source;
mod busy;
mod cached_lines;
mod commands;
mod export;
mod file_dialog;
mod forcing;
mod frame_log;
mod heatmap;
mod panels;
mod pins;
mod playback;
mod plots;
mod target_plots;
#[cfg(feature = "testing")]
mod test_hooks;
#[cfg(feature = "testing")]
mod testing;
mod thinning;
mod timeline;
mod tradeoff;
mod view3d;
mod view_state;

pub use app::DmpApp;
#[cfg(target_arch = "wasm32")]
pub use blob_source::prefetch_dropped;
pub use commands::{Command, Export, Map};
pub use pins::{Pin, Pins};
#[cfg(feature = "testing")]
pub use test_hooks::{SharedHooks, TestHooks};
pub use view_state::{RlChoices, ViewState};

/// Opens the app window on `files` (the bundled sample when empty), with
/// the gain sets `pins` names pinned once they are known.
#[cfg(not(target_arch = "wasm32"))]
pub fn run(files: Vec<std::path::PathBuf>, pins: Option<String>) -> anyhow::Result<()> {
    use eframe::egui;
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_inner_size([1280.0, 800.0])
            .with_title("dmpscope"),
        ..Default::default()
    };
    eframe::run_native(
        "dmpscope",
        options,
        Box::new(move |cc| {
            let ctx = cc.egui_ctx.clone();
            let runner = crate::session::Runner::background(move || ctx.request_repaint());
            Ok(Box::new(DmpApp::new(cc, files, runner).with_pins(pins)))
        }),
    )
    .map_err(|e| anyhow::anyhow!("cannot open the app window: {e}"))
}
