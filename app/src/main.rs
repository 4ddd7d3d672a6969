//! `dmpscope`: the command line (and, from a later release, the desktop app).
//!
//! Results go to stdout (or `--out`), diagnostics and progress to stderr, as
//! the `mcap` CLI does. With no subcommand it prints help.

mod cli;

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    let args = cli::Cli::parse();
    match cli::run(args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(err) => {
            eprintln!("error: {err:#}");
            ExitCode::FAILURE
        }
    }
}
