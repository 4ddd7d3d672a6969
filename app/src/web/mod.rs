//! The browser entry: starts the same [`DmpApp`] as the desktop on the
//! page's canvas with eframe's web runner (wgpu: WebGPU where the browser
//! has it, WebGL2 otherwise). With the `testing` feature (the browser
//! tests' build) it also publishes `window.dmpscope_state()`, returning the
//! app's state as JSON, and `window.dmpscope_train(steps, seed)`, which
//! starts RL training as the RL panel's Train button does (the extracted
//! gains, the selected demo), so the test can compare the browser's
//! learning curve with the native CLI's, and `window.dmpscope_grid(n)`,
//! which sets an n x n grid as the grid settings do.
//!
//! The landscape and the diagnostics' resampled extractions are computed
//! by Web Workers ([`pool`] and [`fills`]: the page's side, [`worker`]: the
//! worker's, `web/worker.js` the glue), each with its own instance of this
//! module; the page's thread moves messages and draws.

pub mod fills;
pub mod pool;
pub mod rl;
pub mod worker;

use eframe::wasm_bindgen::JsCast as _;
use eframe::web_sys;

use crate::gui::DmpApp;

#[cfg(feature = "testing")]
thread_local! {
    /// The JSON the test hook returns, written by the app every frame.
    static STATE: std::cell::RefCell<String> = std::cell::RefCell::new("{}".to_owned());
}

/// Replaces what `window.dmpscope_state()` returns.
#[cfg(feature = "testing")]
pub fn publish_state(json: String) {
    STATE.with(|s| *s.borrow_mut() = json);
}

#[cfg(feature = "testing")]
thread_local! {
    /// Training runs the test asked for, `(steps, seed)`, not yet started.
    static TRAIN: std::cell::RefCell<Vec<(usize, u64)>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// The training runs the test asked for since the last call.
#[cfg(feature = "testing")]
pub fn take_train_requests() -> Vec<(usize, u64)> {
    TRAIN.with(|t| std::mem::take(&mut *t.borrow_mut()))
}

#[cfg(feature = "testing")]
thread_local! {
    /// Grid sizes the test asked for (points per axis), not yet applied.
    static GRID: std::cell::RefCell<Vec<usize>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// The grid sizes the test asked for since the last call.
#[cfg(feature = "testing")]
pub fn take_grid_requests() -> Vec<usize> {
    GRID.with(|g| std::mem::take(&mut *g.borrow_mut()))
}

#[cfg(feature = "testing")]
thread_local! {
    /// The app's context, so that a hook's request is read at once (a
    /// frame), not whenever the page next repaints.
    static CONTEXT: std::cell::RefCell<Option<eframe::egui::Context>> = const { std::cell::RefCell::new(None) };
}

/// Asks for a frame, in which the app reads the hooks' requests.
#[cfg(feature = "testing")]
fn wake_app() {
    CONTEXT.with(|c| {
        if let Some(ctx) = &*c.borrow() {
            ctx.request_repaint();
        }
    });
}

#[cfg(feature = "testing")]
fn install_hook() {
    use eframe::wasm_bindgen::prelude::Closure;
    let hook = Closure::<dyn Fn() -> String>::new(|| STATE.with(|s| s.borrow().clone()));
    let train = Closure::<dyn Fn(f64, f64)>::new(|steps: f64, seed: f64| {
        TRAIN.with(|t| t.borrow_mut().push((steps as usize, seed as u64)));
        wake_app();
    });
    let grid = Closure::<dyn Fn(f64)>::new(|n: f64| {
        GRID.with(|g| g.borrow_mut().push(n as usize));
        wake_app();
    });
    if let Some(window) = web_sys::window() {
        let _ = js_sys::Reflect::set(&window, &"dmpscope_grid".into(), &grid.into_js_value());
        let _ = js_sys::Reflect::set(&window, &"dmpscope_state".into(), &hook.into_js_value());
        let _ = js_sys::Reflect::set(&window, &"dmpscope_train".into(), &train.into_js_value());
    }
}

/// Starts the app on the canvas `dmpscope_canvas` (and, for the browser
/// tests, installs the hook).
pub fn start() {
    eframe::WebLogger::init(log::LevelFilter::Warn).ok();
    let Some(document) = web_sys::window().and_then(|w| w.document()) else {
        return;
    };
    #[cfg(feature = "testing")]
    install_hook();
    let Some(canvas) = document
        .get_element_by_id("dmpscope_canvas")
        .and_then(|e| e.dyn_into::<web_sys::HtmlCanvasElement>().ok())
    else {
        return;
    };
    wasm_bindgen_futures::spawn_local(async move {
        let started = eframe::WebRunner::new()
            .start(
                canvas,
                eframe::WebOptions::default(),
                Box::new(|cc| {
                    #[cfg(feature = "testing")]
                    CONTEXT.with(|c| *c.borrow_mut() = Some(cc.egui_ctx.clone()));
                    Ok(Box::new(DmpApp::new(cc, Vec::new())))
                }),
            )
            .await;
        if let Err(e) = started {
            let message = format!("dmpscope could not start: {e:?}");
            if let Some(el) = document.get_element_by_id("dmpscope_error") {
                el.set_text_content(Some(&message));
            }
        }
    });
}
