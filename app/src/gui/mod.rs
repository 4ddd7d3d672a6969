//! The desktop app: demos, the d / S / J heat maps with a draggable
//! operating point, time plots and Table I, all live.
//!
//! `app.rs` holds the state, `frame.rs` lays out the frame and `side.rs`
//! the side panel; `worker.rs` fills the landscape off the frame;
//! `heatmap.rs`, `plots.rs`, `table.rs` and `view3d/` (a custom wgpu
//! pipeline) are the views; `settings.rs` what is persisted; `loading.rs`
//! turns files into demos.

mod app;
mod export;
mod file_dialog;
mod frame;
mod frame_log;
mod heatmap;
mod loading;
mod plots;
mod rl_panel;
mod rl_run;
mod settings;
mod side;
mod table;
mod task;
mod top_bar;
mod view3d;
mod worker;

pub use app::DmpApp;
pub use rl_panel::RlChoices;
pub use rl_run::Progress as RlProgress;
pub use settings::Settings;

/// Opens the app window on `files` (the bundled sample when empty).
#[cfg(not(target_arch = "wasm32"))]
pub fn run(files: Vec<std::path::PathBuf>) -> anyhow::Result<()> {
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
        Box::new(move |cc| Ok(Box::new(DmpApp::new(cc, files)))),
    )
    .map_err(|e| anyhow::anyhow!("cannot open the app window: {e}"))
}
