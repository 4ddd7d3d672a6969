//! The browser build's entry point (`web/build.sh`): wasm-bindgen calls
//! `main` when the module loads, which starts the app on the page's
//! canvas. Natively there is nothing to run: the desktop app and the
//! command line are the `dmpscope` binary.

/// Starts the app in the browser.
#[cfg(target_arch = "wasm32")]
fn main() {
    dmpscope::web::start();
}

/// Natively: says where the app is.
#[cfg(not(target_arch = "wasm32"))]
fn main() {
    eprintln!("dmpscope-web is the browser build's entry (web/build.sh); the app is `dmpscope`");
}
