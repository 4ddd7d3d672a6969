#![doc = include_str!("../README.md")]

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
