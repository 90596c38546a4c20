//! The command line: the commands, their help, and the dispatch to each.

use super::error::CliError;
use super::slurm::SweepCommand;
use super::{animate, basin, batch, bench, compare, man, merge, predict, presets, roll, slurm, trace, tui};
use clap::{CommandFactory, Parser, Subcommand};
use std::io::Write as _;

/// A die rolling on a table as a rigid body (Chin & Li, 2019).
#[derive(Debug, Parser)]
#[command(
    name = "dicesim",
    version = dicesim_experiment::VERSION_LINE,
    about,
    long_about = None,
    after_help = "Examples:
  dicesim                                   the explorer on the paper's setup
  dicesim roll --set ground.friction=0.3    one roll on a slipperier table
  dicesim batch --rolls 10000               face statistics of random rolls
  dicesim presets list                      the shipped presets and yours

Exit status: 0 success, 1 a failure while running, 2 bad input (nothing was run or written),
128 + N stopped by signal N (130 interrupted by Ctrl-C, 143 SIGTERM; what was done is kept),
101 an internal error."
)]
pub(crate) struct Cli {
    #[command(subcommand)]
    pub(crate) command: Option<CliCommand>,
    /// Never colour the output (the explorer carries meaning by bold and reverse); the
    /// NO_COLOR environment variable does the same.
    #[arg(long, global = true)]
    pub(crate) no_color: bool,
}

#[derive(Debug, Subcommand)]
pub(crate) enum CliCommand {
    /// Roll once from the initial condition and print the outcome.
    #[command(after_help = "Examples:
  dicesim roll
  dicesim roll --preset gentle-drop --json
  dicesim roll --set initial.height=2.5 --set 'initial.angular_velocity=[10,0,3]'")]
    Roll(roll::RollArgs),
    /// Print a roll's trajectory and energies as CSV.
    #[command(after_help = "Examples:
  dicesim trace > roll.csv
  dicesim trace --every 10 --steps 3000 --preset icy-table > icy.csv")]
    Trace(trace::TraceArgs),
    /// Write a roll (or a roll and its chaos twin, or the explorer's presentation view of it)
    /// as an animated GIF or PNG for a slide.
    #[command(after_help = "Examples:
  dicesim animate --out roll.gif
  dicesim animate --preset gentle-drop --fps 30 --size 800x600 --out drop.png
  dicesim animate --twin 1e-6 --out twins.gif --force
  dicesim animate --zoom --size 800x600 --out drop.gif
  dicesim animate --present --size 1280x720 --out present.gif")]
    Animate(animate::AnimateArgs),
    /// List, show and save presets (TOML setups; see `presets path`).
    #[command(after_help = "Examples:
  dicesim presets list
  dicesim presets show paper
  dicesim presets save mine --preset gentle-drop --set initial.height=2.5
  dicesim presets save mine --set ground.friction=0.3 --force")]
    Presets(presets::PresetsArgs),
    /// Roll many dice in parallel: per-roll results and face statistics.
    #[command(after_help = "Examples:
  dicesim batch --rolls 10000
  dicesim batch --rolls 2000 --seed 7 --out rolls.csv
  dicesim batch --ics starts.csv --json
  dicesim batch --rolls 10000 --set ground.friction=0.3 --versus ground.friction=1.2")]
    Batch(batch::BatchArgs),
    /// Map the outcome over a grid of two setup values (CSV, PNG or SVG).
    #[command(after_help = "Examples:
  dicesim basin --x initial.angular_velocity.x:-40:40 --y initial.angular_velocity.y:-40:40 --out map.png
  dicesim basin --x ground.friction:0:2 --y initial.height:2:20 --res 100x50 --out map.csv
  dicesim basin --x initial.height:1:15 --y initial.angular_velocity.x:-60:60 --res 300x1 --layer settle-time")]
    Basin(basin::BasinArgs),
    /// How precisely a throw must be known: P(same face) of random starts beside their
    /// ε-twins, chance and the threshold ε½ (CSV, JSON, PNG).
    #[command(after_help = "Examples:
  dicesim predict --rolls 500
  dicesim predict --vary initial.height=2,5,15 --out curves.png --out curves.csv
  dicesim predict --vary ground.damping=0.001,0.005,0.02 --epsilon 1e-12,1e-9,1e-6,1e-3 --json")]
    Predict(predict::PredictArgs),
    /// Throw the die as a historical experiment threw real dice and hold it against their
    /// counts: χ², residuals, power; `--fit` calibrates one setup value to them, or several at
    /// once on a grid (`compare joint`).
    #[command(after_help = "Examples:
  dicesim compare wolf-white
  dicesim compare weldon --throws 2000 --out weldon.png --out weldon.csv
  dicesim compare weldon --throws 2000 --fit ground.friction:0.2:1.2 --json
  dicesim compare budden --calibrate-on 0.47,1.16,2.12 --out budden.png
  dicesim compare shaved-die --preset calibrated-table --cuts 0.015,0.03,0.06 --throws 100000
  dicesim compare joint --preset calibrated-table --fit ground.restitution:0.2:0.6:5 --fit ground.table_mass:250:2000:5")]
    Compare(compare::CompareArgs),
    /// Put the shards of a sweep (`batch --shard`, `basin --shard`) back together.
    #[command(after_help = "Examples:
  dicesim merge parts --out rolls.csv
  dicesim merge parts/*.part.json --out rolls.parquet --json
  dicesim merge rows-*.part.json --out map.csv --out map.png")]
    Merge(merge::MergeArgs),
    /// Write (and submit) a Slurm job array for a sweep, one task per shard, and its merge.
    #[command(after_help = "Examples:
  dicesim slurm --shards 8 --dir sweep -- batch --rolls 40000 --seed 7
  dicesim slurm --shards 64 --cpus-per-task 4 --time 1:00:00 --dir /scratch/$USER/sweep \\
                --format parquet --submit -- batch --rolls 1000000000 --seed 7")]
    Slurm(slurm::SlurmArgs),
    /// Time both engines on the same rolls and maps in this process and print the ratios.
    Bench(bench::BenchArgs),
    /// The terminal explorer: a live die, energy plots, parameters and outcomes (the default).
    #[command(after_help = "Examples:
  dicesim tui
  dicesim tui --preset slow-motion-classroom --no-color")]
    Tui(tui::TuiArgs),
    /// Print a shell completion script to standard output.
    #[command(after_help = "Examples:
  dicesim completions bash > ~/.local/share/bash-completion/completions/dicesim
  dicesim completions zsh > ~/.zfunc/_dicesim
  dicesim completions fish > ~/.config/fish/completions/dicesim.fish")]
    Completions {
        #[arg(value_enum)]
        shell: clap_complete::Shell,
    },
    /// Print a manual page (roff): the program's, or a command's with its options; or write
    /// every page into a folder.
    #[command(after_help = "Examples:
  dicesim man > dicesim.1 && man ./dicesim.1
  dicesim man batch | man -l -
  dicesim man presets save
  dicesim man --out-dir ~/.local/share/man/man1")]
    Man(man::ManArgs),
}

/// Whether colour is off: `--no-color` anywhere on the command line, or NO_COLOR set to
/// anything but the empty string (<https://no-color.org>).
pub(crate) fn color_off(no_color_flag: bool) -> bool {
    no_color_flag || std::env::var_os("NO_COLOR").is_some_and(|v| !v.is_empty())
}

/// Parses the command line and runs the command.
pub fn main() -> Result<(), CliError> {
    let flag = std::env::args_os().any(|a| a == "--no-color");
    let color = if color_off(flag) {
        clap::ColorChoice::Never
    } else {
        clap::ColorChoice::Auto
    };
    let matches = match Cli::command().color(color).try_get_matches() {
        Ok(matches) => matches,
        // --help and --version go to standard output: a write that fails there (a full disk,
        // /dev/full) is a failure like any other output's, not a success.
        Err(e) if !e.use_stderr() => {
            e.print()?;
            std::io::stdout().flush()?;
            return Ok(());
        }
        Err(e) => e.exit(),
    };
    let cli = <Cli as clap::FromArgMatches>::from_arg_matches(&matches).unwrap_or_else(|e| e.exit());
    let no_color = color_off(cli.no_color);
    match cli.command {
        Some(CliCommand::Roll(args)) => roll::run(&args),
        Some(CliCommand::Trace(args)) => trace::run(&args),
        Some(CliCommand::Animate(args)) => animate::run(&args),
        Some(CliCommand::Presets(args)) => presets::run(&args),
        Some(CliCommand::Batch(args)) => batch::run(&args),
        Some(CliCommand::Basin(args)) => basin::run(&args),
        Some(CliCommand::Predict(args)) => predict::run(&args),
        Some(CliCommand::Bench(args)) => bench::run(&args),
        Some(CliCommand::Compare(args)) => compare::run(&args),
        Some(CliCommand::Merge(args)) => merge::run(&args),
        Some(CliCommand::Slurm(args)) => {
            let sweep = parse_sweep(&args.command);
            slurm::run(&args, sweep)
        }
        Some(CliCommand::Tui(args)) => tui::run(&args, no_color),
        Some(CliCommand::Completions { shell }) => {
            // clap_complete panics on a failed write; the script is written whole here, and a
            // failure (a full disk) is reported like any output's.
            let mut script = Vec::new();
            clap_complete::generate(shell, &mut Cli::command(), "dicesim", &mut script);
            let mut out = std::io::stdout().lock();
            out.write_all(&script)?;
            out.flush()?;
            Ok(())
        }
        Some(CliCommand::Man(args)) => man::run(&args, Cli::command()),
        None => tui::run(&tui::TuiArgs::default(), no_color),
    }
}

/// The sweep of `dicesim slurm`, its command line parsed as dicesim parses its own.
pub(super) fn parse_sweep(command: &[String]) -> Result<SweepCommand, clap::Error> {
    let argv = std::iter::once("dicesim").chain(command.iter().map(String::as_str));
    Ok(match Cli::try_parse_from(argv)?.command {
        Some(CliCommand::Batch(b)) => SweepCommand::Batch(b),
        Some(CliCommand::Basin(b)) => SweepCommand::Basin(b),
        _ => SweepCommand::Other,
    })
}
