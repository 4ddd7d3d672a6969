//! `dmpscope`: the desktop app (no subcommand: `dmpscope [FILES...]`) and
//! the command line (subcommands). Results go to stdout (or `--out`),
//! diagnostics and progress to stderr, as the `mcap` CLI does.

#[cfg(not(target_arch = "wasm32"))]
mod cli;

/// For wasm32 this binary only builds (the browser build's root is
/// `web/entry`, whose `main` is the same call).
#[cfg(target_arch = "wasm32")]
fn main() {
    dmpscope::web::start();
}

#[cfg(not(target_arch = "wasm32"))]
fn main() -> std::process::ExitCode {
    use clap::Parser as _;
    use std::process::ExitCode;
    quiet_on_closed_stdout();
    let args = cli::Cli::parse();
    let result = match args.command {
        None => dmpscope::gui::run(args.files, args.pin),
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

/// A reader that stops early (`dmpscope info x.mcap | head`) closes stdout;
/// the next `println!` then panics with "failed printing to stdout". That is
/// not an error of dmpscope's: leave quietly, as `cat` does.
#[cfg(not(target_arch = "wasm32"))]
fn quiet_on_closed_stdout() {
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let message = info
            .payload()
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| info.payload().downcast_ref::<&str>().copied())
            .unwrap_or("");
        if message.starts_with("failed printing to stdout") && message.contains("Broken pipe") {
            std::process::exit(0);
        }
        default(info);
    }));
}
