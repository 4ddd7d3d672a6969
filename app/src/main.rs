//! `dmpscope`: the desktop app (no subcommand: `dmpscope [FILES...]`) and
//! the command line (subcommands). Results go to stdout (or `--out`),
//! diagnostics and progress to stderr, as the `mcap` CLI does.

#[cfg(not(target_arch = "wasm32"))]
mod cli;

/// In the browser wasm-bindgen calls `main` when the module loads.
#[cfg(target_arch = "wasm32")]
fn main() {
    dmpscope::web::start();
}

#[cfg(not(target_arch = "wasm32"))]
fn main() -> std::process::ExitCode {
    use clap::Parser as _;
    use std::process::ExitCode;
    let args = cli::Cli::parse();
    let result = match args.command {
        None => dmpscope::gui::run(args.files),
        Some(_) => cli::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(err) => {
            eprintln!("error: {err:#}");
            ExitCode::FAILURE
        }
    }
}
