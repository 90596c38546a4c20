//! Headless commands: the model usable and checkable without a terminal UI.

mod basin;
mod batch;
mod merge;
mod presets;
mod roll;
mod shard;
mod slurm;
mod trace;
mod tui;

use crate::preset::{Preset, Store};
use clap::{Args, Parser, Subcommand};
use std::process::ExitCode;

/// A die rolling on a table as a rigid body (Chin & Li, 2019).
#[derive(Debug, Parser)]
#[command(name = "dicesim", version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Roll once from the initial condition and print the outcome.
    Roll(roll::RollArgs),
    /// Print a roll's trajectory and energies as CSV.
    Trace(trace::TraceArgs),
    /// List, show and save presets (TOML setups; see `presets path`).
    Presets(presets::PresetsArgs),
    /// Roll many dice in parallel: per-roll results and face statistics.
    Batch(batch::BatchArgs),
    /// Map the outcome over a grid of two setup values (CSV, PNG or SVG).
    Basin(basin::BasinArgs),
    /// Put the shards of a sweep (`batch --shard`, `basin --shard`) back together.
    Merge(merge::MergeArgs),
    /// Write (and submit) a Slurm job array for a sweep, one task per shard, and its merge.
    Slurm(slurm::SlurmArgs),
    /// The terminal explorer: a live die, energy plots, parameters and outcomes (the default).
    Tui(tui::TuiArgs),
}

/// The setup every simulating command starts from.
#[derive(Debug, Clone, Default, Args)]
pub struct SetupArgs {
    /// Start from this preset: a name (the user's folder, then the shipped set) or a path
    /// to a `.toml` file. Without it, the shipped `paper` preset.
    #[arg(long, value_name = "NAME|PATH")]
    pub preset: Option<String>,
    /// Override one preset value, e.g. `ground.stiffness=600000` or
    /// `initial.angular_velocity=[10,0,3]` (repeatable, applied in order).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
}

impl SetupArgs {
    /// The preset with every override applied and validated.
    pub fn resolve(&self) -> Result<Preset, CliError> {
        let (preset, _) = Store::from_env().load_or_default(self.preset.as_deref())?;
        Ok(preset.with_overrides(&self.set)?)
    }
}

/// A command's failure: bad input (exit status 2) or a failure while running (status 1).
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    #[error("{0}")]
    Input(String),
    #[error("{0}")]
    Run(String),
}

impl CliError {
    /// The same error, its message led by `prefix` (e.g. the option it came from).
    pub fn prefixed(self, prefix: &str) -> CliError {
        match self {
            CliError::Input(m) => CliError::Input(format!("{prefix}{m}")),
            CliError::Run(m) => CliError::Run(format!("{prefix}{m}")),
        }
    }
}

impl From<crate::preset::PresetError> for CliError {
    fn from(e: crate::preset::PresetError) -> Self {
        CliError::Input(e.to_string())
    }
}

impl From<crate::output::OutputError> for CliError {
    fn from(e: crate::output::OutputError) -> Self {
        if e.is_refusal() {
            CliError::Input(e.to_string())
        } else {
            CliError::Run(e.to_string())
        }
    }
}

impl From<std::io::Error> for CliError {
    fn from(e: std::io::Error) -> Self {
        CliError::Run(e.to_string())
    }
}

pub use crate::output::printable;

/// The most threads `--jobs` takes: more than a few per core only adds switching.
pub fn max_jobs() -> usize {
    4 * crate::experiment::batch::thread_count(0)
}

/// `--jobs J` checked against [`max_jobs`]; no value means one thread per core.
pub fn checked_jobs(jobs: Option<u64>) -> Result<usize, CliError> {
    match jobs {
        None => Ok(crate::experiment::batch::thread_count(0)),
        Some(j) if j as usize <= max_jobs() && j > 0 => Ok(j as usize),
        Some(j) => Err(CliError::Input(format!(
            "--jobs {j}: at most {} (4 × the {} cores here)",
            max_jobs(),
            crate::experiment::batch::thread_count(0)
        ))),
    }
}

/// Parses the command line, runs the command and turns its result into an exit status.
pub fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Some(Command::Roll(args)) => roll::run(&args),
        Some(Command::Trace(args)) => trace::run(&args),
        Some(Command::Presets(args)) => presets::run(&args),
        Some(Command::Batch(args)) => batch::run(&args),
        Some(Command::Basin(args)) => basin::run(&args),
        Some(Command::Merge(args)) => merge::run(&args),
        Some(Command::Slurm(args)) => slurm::run(&args),
        Some(Command::Tui(args)) => tui::run(&args),
        None => tui::run(&tui::TuiArgs::default()),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(CliError::Run(msg)) if msg.contains("Broken pipe") => ExitCode::SUCCESS,
        Err(e @ CliError::Input(_)) => {
            eprintln!("dicesim: {}", printable(&e.to_string()));
            ExitCode::from(2)
        }
        Err(e) => {
            eprintln!("dicesim: {}", printable(&e.to_string()));
            ExitCode::FAILURE
        }
    }
}
