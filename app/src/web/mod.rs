//! The browser entry: starts the same [`DmpApp`] as the desktop on the
//! page's canvas with eframe's web runner (wgpu: WebGPU where the browser
//! has it, WebGL2 otherwise). With the `testing` feature (the browser
//! tests' build) it also publishes `window.dmpscope_state()`, returning the
//! app's state as JSON, and `window.dmpscope_train(steps, seed)`, which
//! starts RL training as the RL panel's Train button does (the extracted
//! gains, the selected demo), so the test can compare the browser's
//! learning curve with the native CLI's, `window.dmpscope_grid(n)`,
//! which sets an n x n grid as the grid settings do, and
//! `window.dmpscope_hide(mask)`, which leaves parts of the window out for
//! `web/tests/frame_probe.mjs` (the bits: `gui::app`'s `part`).
//!
//! The app's work runs on [`WebExecutor`]: jobs in slices on the page's
//! event loop, and the landscape's tiles, the diagnostics' resampled
//! extractions and RL runs handed out by the session to Web Workers
//! (`transport.rs`: the page's side of the messages, [`worker`]: the
//! worker's, `web/worker.js` the glue), each with its own instance of this
//! module; the page's thread moves messages and draws.

mod executor;
mod transport;
pub mod worker;

use eframe::wasm_bindgen::JsCast as _;
use eframe::wasm_bindgen::prelude::Closure;
use eframe::web_sys;

use crate::gui::DmpApp;
use crate::session::Runner;
pub use executor::WebExecutor;

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

/// Installs `window.dmpscope_state()`, `dmpscope_train()`,
/// `dmpscope_grid()`, `dmpscope_pin()` and `dmpscope_hide()` over `hooks` (the app reads the
/// requests and writes the state every frame).
#[cfg(feature = "testing")]
fn install_hooks(hooks: &crate::gui::SharedHooks) {
    let h = hooks.clone();
    let state = Closure::<dyn Fn() -> String>::new(move || h.borrow().state.clone());
    let h = hooks.clone();
    let train = Closure::<dyn Fn(f64, f64)>::new(move |steps: f64, seed: f64| {
        h.borrow_mut().train.push((steps as usize, seed as u64));
        wake_app();
    });
    let h = hooks.clone();
    let hide = Closure::<dyn Fn(f64)>::new(move |mask: f64| {
        h.borrow_mut().hide = mask as u32;
        wake_app();
    });
    let h = hooks.clone();
    let grid = Closure::<dyn Fn(f64)>::new(move |n: f64| {
        h.borrow_mut().grid.push(n as usize);
        wake_app();
    });
    let h = hooks.clone();
    let pin = Closure::<dyn Fn(String)>::new(move |text: String| {
        h.borrow_mut().pin.push(text);
        wake_app();
    });
    if let Some(window) = web_sys::window() {
        let _ = js_sys::Reflect::set(&window, &"dmpscope_hide".into(), &hide.into_js_value());
        let _ = js_sys::Reflect::set(&window, &"dmpscope_grid".into(), &grid.into_js_value());
        let _ = js_sys::Reflect::set(&window, &"dmpscope_pin".into(), &pin.into_js_value());
        let _ = js_sys::Reflect::set(&window, &"dmpscope_state".into(), &state.into_js_value());
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
    let hooks = {
        let hooks = crate::gui::SharedHooks::default();
        install_hooks(&hooks);
        hooks
    };
    let Some(canvas) = document
        .get_element_by_id("dmpscope_canvas")
        .and_then(|e| e.dyn_into::<web_sys::HtmlCanvasElement>().ok())
    else {
        return;
    };
    executor::start_pool();
    // A drop's small files are asked for at the drop (capture phase: before
    // eframe's own listener hands the drop to the app's next frame).
    let prefetch = Closure::<dyn Fn(web_sys::DragEvent)>::new(|event: web_sys::DragEvent| {
        crate::gui::prefetch_dropped(&event)
    });
    if let Some(window) = web_sys::window() {
        let _ = window.add_event_listener_with_callback_and_bool(
            "drop",
            prefetch.as_ref().unchecked_ref(),
            true,
        );
    }
    prefetch.forget();
    wasm_bindgen_futures::spawn_local(async move {
        let started = eframe::WebRunner::new()
            .start(
                canvas,
                eframe::WebOptions::default(),
                Box::new(|cc| {
                    cc.egui_ctx.set_fonts(web_fonts());
                    #[cfg(feature = "testing")]
                    CONTEXT.with(|c| *c.borrow_mut() = Some(cc.egui_ctx.clone()));
                    let ctx = cc.egui_ctx.clone();
                    let executor = WebExecutor::new(move || ctx.request_repaint());
                    let app =
                        DmpApp::new(cc, Vec::new(), Runner::new(std::sync::Arc::new(executor)));
                    #[cfg(feature = "testing")]
                    let app = app.with_test_hooks(hooks);
                    Ok(Box::new(app))
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

/// The browser's fonts: Ubuntu-Light for proportional and monospace text,
/// egui's icons as the fallback (egui's defaults add Hack for monospace,
/// 150 KB of the gzipped download).
fn web_fonts() -> eframe::egui::FontDefinitions {
    use eframe::egui::{FontData, FontDefinitions, FontFamily, FontTweak};
    let mut fonts = FontDefinitions::empty();
    fonts.font_data.insert(
        "Ubuntu-Light".to_owned(),
        std::sync::Arc::new(FontData::from_static(epaint_default_fonts::UBUNTU_LIGHT)),
    );
    fonts.font_data.insert(
        "egui-icons".to_owned(),
        std::sync::Arc::new(
            FontData::from_static(epaint_default_fonts::EGUI_ICONS).tweak(FontTweak {
                scale: 0.90,
                ..Default::default()
            }),
        ),
    );
    let family = vec!["Ubuntu-Light".to_owned(), "egui-icons".to_owned()];
    fonts
        .families
        .insert(FontFamily::Proportional, family.clone());
    fonts.families.insert(FontFamily::Monospace, family);
    fonts
}
