//! `dmpscope`: the desktop app (no subcommand: `dmpscope [FILES...]`) and
//! the command line (subcommands). Results go to stdout (or `--out`),
//! diagnostics and progress to stderr, as the `mcap` CLI does.

mod cli;

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
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
