//! The subcommands, one file each, and what they share: loading inputs
//! ([`inputs`]) and writing outputs ([`output`]).

mod bench;
mod bench_ingest;
mod bench_read;
mod compare;
mod extract;
mod gen_sample;
mod info;
mod inputs;
mod landscape;
mod output;
mod regen;
mod rl;
mod rl_table;

use clap::{CommandFactory, Parser, Subcommand};

/// Turn recordings of human hand motion into DMP gains. Without a
/// subcommand, opens the app on FILES (the bundled sample when none).
#[derive(Debug, Parser)]
#[command(name = "dmpscope", version, about, long_about = None, args_conflicts_with_subcommands = true)]
pub struct Cli {
    /// What to do; without one, open the app.
    #[command(subcommand)]
    pub command: Option<Command>,
    /// Recordings to open in the app.
    #[arg(value_name = "FILES")]
    pub files: Vec<std::path::PathBuf>,
    /// Gain sets to pin in the app once they are known: Table I's row
    /// names or D/M:K/M, comma separated (as `compare --gains`).
    #[arg(long, value_name = "GAINS")]
    pub pin: Option<String>,
    /// Print details too (each skipped topic of a file that has many).
    #[arg(short, long, global = true)]
    pub verbose: bool,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// List the demonstrations found in recordings.
    Info(info::Args),
    /// Compute sum d, S and J over a grid of gains and write them as JSON.
    Landscape(landscape::Args),
    /// Extract the gains minimising J and compare them with the paper's.
    Extract(extract::Args),
    /// Regenerate every demo at one gain pair.
    Regen(regen::Args),
    /// Compare gain sets side by side (numbers, settling, a new target) and
    /// draw their regenerations.
    Compare(compare::Args),
    /// Train an RL agent whose action is the DMP forcing term (PPO).
    Rl(rl::Args),
    /// Measure the landscape and operating-point speed.
    Bench(bench::Args),
    /// Write the bundled synthetic sample recording.
    GenSample(gen_sample::Args),
}

/// Runs the parsed command line.
pub fn run(cli: Cli) -> anyhow::Result<()> {
    output::set_verbose(cli.verbose);
    match cli.command {
        None => {
            Cli::command().print_help()?;
            Ok(())
        }
        Some(Command::Info(a)) => info::run(a),
        Some(Command::Landscape(a)) => landscape::run(a),
        Some(Command::Extract(a)) => extract::run(a),
        Some(Command::Regen(a)) => regen::run(a),
        Some(Command::Compare(a)) => compare::run(a),
        Some(Command::Rl(a)) => rl::run(a),
        Some(Command::Bench(a)) => bench::run(a),
        Some(Command::GenSample(a)) => gen_sample::run(a),
    }
}
