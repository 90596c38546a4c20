//! Headless commands: the model usable and checkable without a terminal UI.

mod animate;
mod args;
mod basin;
mod batch;
mod bench;
mod compare;
mod merge;
mod predict;
mod presets;
mod roll;
mod slurm;
mod trace;
mod tui;

use clap::{CommandFactory, Parser, Subcommand};
use dicesim_experiment as experiment;
use dicesim_experiment::merge::MergeError;
use dicesim_experiment::slurm::SlurmError;
use dicesim_physics::ParamError;
use dicesim_setup::preset::PresetError;
use signal_hook::consts::{SIGHUP, SIGINT, SIGQUIT, SIGTERM};
use std::io::Write as _;
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// The progress bar of a long command: drawn on stderr while it is a terminal, hidden
/// otherwise (a pipe or a log file gets no bar codes), in `template`'s words.
pub(crate) fn progress_bar(total: u64, template: &str) -> indicatif::ProgressBar {
    use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
    use std::io::IsTerminal;
    let bar = if std::io::stderr().is_terminal() {
        ProgressBar::new(total)
    } else {
        ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::hidden())
    };
    bar.set_style(ProgressStyle::with_template(template).expect("the progress template is valid"));
    bar
}

/// Exit status of a second Ctrl-C, which cannot wait for the error to reach `main`: as a
/// shell reports a SIGINT (128 + 2), the status `main` gives an interrupted command.
const INTERRUPTED_AT_ONCE: i32 = 130;

/// The signals that ask a command to stop: Ctrl-C, `kill`, a closed terminal, Ctrl-\\ (and
/// Slurm's time limit, which sends SIGTERM).
const STOP_SIGNALS: [i32; 4] = [SIGINT, SIGTERM, SIGHUP, SIGQUIT];

/// Runs a long experiment as every such command does: a progress bar over its `total` rolls
/// (`template` in indicatif's words), Ctrl-C asking it to stop, its error worded like the
/// others'. `run` gets the stop flag and reports how many rolls are done.
pub(crate) fn run_with_progress<T>(
    total: u64,
    template: &str,
    run: impl FnOnce(&AtomicBool, &mut dyn FnMut(u64)) -> Result<T, experiment::Error>,
) -> Result<T, CliError> {
    let bar = progress_bar(total, template);
    let stop = cancel_on_ctrl_c()?;
    let result = run(&stop, &mut |done| bar.set_position(done)).map_err(CliError::experiment(""))?;
    bar.finish_and_clear();
    Ok(result)
}

/// A long experiment's result, written the one way every such command writes it.
pub(crate) struct Results<'a, T: serde::Serialize> {
    pub(crate) value: &'a T,
    /// What defines the experiment: the CSV's first line, the JSON's `provenance`.
    pub(crate) provenance: &'a serde_json::Value,
    /// The CSV's rows after its provenance line.
    pub(crate) csv: &'a dyn Fn(&mut (dyn std::io::Write + Send)) -> std::io::Result<()>,
    pub(crate) png: &'a dyn Fn() -> Result<Vec<u8>, CliError>,
    /// The table printed when `--json` is not given.
    pub(crate) table: &'a dyn Fn(&mut dyn std::io::Write) -> std::io::Result<()>,
}

/// Writes each `--out` file by its extension (CSV, JSON with the provenance, else PNG), then
/// prints the table and the files written, or the JSON alone with `--json`.
pub(crate) fn write_results<T: serde::Serialize>(
    outputs: &[dicesim_setup::output::Output],
    json: bool,
    r: Results<'_, T>,
) -> Result<(), CliError> {
    for output in outputs {
        match output.extension() {
            "csv" => output.write(|w| {
                writeln!(w, "{}", experiment::provenance::csv_line(r.provenance))?;
                (r.csv)(w)
            }),
            "json" => output.write(|w| {
                let mut v = serde_json::to_value(r.value)?;
                v["provenance"] = r.provenance.clone();
                serde_json::to_writer_pretty(&mut *w, &v)?;
                writeln!(w)
            }),
            _ => output.write_bytes(&(r.png)()?),
        }
        .map_err(CliError::output(""))?;
    }
    let mut out = std::io::stdout().lock();
    if json {
        serde_json::to_writer_pretty(&mut out, r.value).map_err(std::io::Error::from)?;
        writeln!(out)?;
    } else {
        (r.table)(&mut out)?;
        for output in outputs {
            writeln!(out, "wrote {}", output.path().display())?;
        }
    }
    out.flush()?;
    Ok(())
}

/// A flag the first stop signal sets (the running rolls notice it within a few thousand
/// steps and the command keeps what is complete); a second signal stops at once, after
/// removing the temporary file being written and saying so.
pub(crate) fn cancel_on_ctrl_c() -> Result<Arc<AtomicBool>, CliError> {
    let stop = Arc::new(AtomicBool::new(false));
    on_stop_signals(Some(stop.clone()))?;
    Ok(stop)
}

/// For a command that has no use for a partial result (`merge`): any stop signal removes the
/// temporary file being written, says that nothing was written and exits.
pub(crate) fn stop_at_once_on_signals() -> Result<(), CliError> {
    on_stop_signals(None)
}

fn on_stop_signals(graceful: Option<Arc<AtomicBool>>) -> Result<(), CliError> {
    let mut signals = signal_hook::iterator::Signals::new(STOP_SIGNALS)
        .map_err(|e| CliError::Io(std::io::Error::other(format!("cannot catch signals: {e}"))))?;
    std::thread::spawn(move || {
        for signal in signals.forever() {
            if let Some(stop) = &graceful
                && !stop.swap(true, Ordering::SeqCst)
            {
                continue;
            }
            let removed = dicesim_setup::output::remove_pending();
            let what = if removed > 0 {
                "the file being written was removed, nothing was written"
            } else {
                "nothing was written"
            };
            let why = if graceful.is_some() {
                "stopped again"
            } else {
                "stopped"
            };
            let _ = writeln!(std::io::stderr(), "dicesim: {why} by signal {signal}: {what}");
            std::process::exit(if signal == SIGINT {
                INTERRUPTED_AT_ONCE
            } else {
                128 + signal
            });
        }
    });
    Ok(())
}

/// A die rolling on a table as a rigid body (Chin & Li, 2019).
#[derive(Debug, Parser)]
#[command(
    name = "dicesim",
    version,
    about,
    long_about = None,
    after_help = "Examples:
  dicesim                                   the explorer on the paper's setup
  dicesim roll --set ground.friction=0.3    one roll on a slipperier table
  dicesim batch --rolls 10000               face statistics of random rolls
  dicesim presets list                      the shipped presets and yours

Exit status: 0 success, 1 a failure while running, 2 bad input (nothing was run or written),
130 interrupted (what was done is kept), 128 + N stopped by signal N, 101 an internal error."
)]
pub(crate) struct Cli {
    #[command(subcommand)]
    pub(crate) command: Option<Command>,
    /// Never colour the output (the explorer carries meaning by bold and reverse); the
    /// NO_COLOR environment variable does the same.
    #[arg(long, global = true)]
    pub(crate) no_color: bool,
}

#[derive(Debug, Subcommand)]
pub(crate) enum Command {
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
    /// Write a roll (or a roll and its chaos twin) as an animated GIF or PNG for a slide.
    #[command(after_help = "Examples:
  dicesim animate --out roll.gif
  dicesim animate --preset gentle-drop --fps 30 --size 800x600 --out drop.png
  dicesim animate --twin 1e-6 --out twins.gif --force")]
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
    /// counts: χ², residuals, power; `--fit` calibrates one setup value to them.
    #[command(after_help = "Examples:
  dicesim compare wolf-white
  dicesim compare weldon --throws 2000 --out weldon.png --out weldon.csv
  dicesim compare weldon --throws 2000 --fit ground.friction:0.2:1.2 --json
  dicesim compare budden --calibrate-on 0.47,1.16,2.12 --out budden.png")]
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
    /// Print the manual page (roff) to standard output.
    #[command(after_help = "Examples:
  dicesim man > dicesim.1 && man ./dicesim.1")]
    Man,
}

/// Why a command failed. [`CliError::kind`] sorts it for the exit status.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// A preset, an override or a preset name is wrong.
    #[error(transparent)]
    Preset(#[from] PresetError),
    /// A preset of that name exists and `--force` was not given.
    #[error("{0} (--force replaces it)")]
    Exists(#[source] PresetError),
    /// A setup value outside its range.
    #[error(transparent)]
    Param(#[from] ParamError),
    /// An experiment refused its input (an axis, an initial-condition file) or could not run.
    #[error("{context}{source}")]
    Experiment {
        /// What the error is about, e.g. `--x ` (empty when the message says it).
        context: String,
        #[source]
        source: experiment::Error,
    },
    /// An argument that clap's parser cannot judge (a file's extension, the need for a
    /// terminal).
    #[error("{0}")]
    Usage(String),
    /// The parts given to `merge` are not the shards of one sweep, or one of them is not
    /// what its shard wrote (the message names the file and the problem).
    #[error("{0}")]
    Parts(String),
    /// A sweep's own step failed while running: a part summary or a merged file not
    /// written, `sbatch` missing or refusing the job.
    #[error("{0}")]
    Sweep(String),
    /// A named input file could not be read.
    #[error("{flag} {}: {source}", path.display())]
    Read {
        flag: &'static str,
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// An output file could not be written.
    #[error("{}: {source}", path.display())]
    Write {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// Standard output (or another stream) failed; a closed pipe is not a failure.
    #[error(transparent)]
    Io(#[from] std::io::Error),
    /// An output file refused before any work (it exists, its folder is missing), or a
    /// write that failed and left nothing behind.
    #[error("{context}{source}")]
    Output {
        /// The option the path came from, e.g. `--out ` (empty when the message says it).
        context: String,
        #[source]
        source: dicesim_setup::output::OutputError,
    },
    /// The explorer stopped with an error (its report, with the chain of causes).
    #[error("{0:#}")]
    Explorer(color_eyre::Report),
    /// Ctrl-C stopped a command that keeps nothing of a partial result (an animation).
    #[error("interrupted: {0}")]
    Stopped(String),
    /// Ctrl-C stopped a batch or a map; what was completed was reported and kept.
    #[error("interrupted: kept the {completed} of {requested} {what} completed")]
    Interrupted {
        completed: u64,
        requested: u64,
        /// What was counted: `rolls`, `cells`.
        what: &'static str,
    },
}

/// What kind of failure an error is: the exit status follows from it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ErrorKind {
    /// Bad input: nothing was run or written.
    Input,
    /// Something failed while running.
    Failure,
    /// The reader of standard output went away (`dicesim trace | head`): not an error.
    BrokenPipe,
    /// Interrupted by the user.
    Interrupted,
}

impl CliError {
    pub fn kind(&self) -> ErrorKind {
        match self {
            CliError::Preset(_)
            | CliError::Exists(_)
            | CliError::Param(_)
            | CliError::Usage(_)
            | CliError::Parts(_) => ErrorKind::Input,
            CliError::Read { .. } => ErrorKind::Input,
            CliError::Experiment { source, .. } => match source {
                experiment::Error::Threads(_)
                | experiment::Error::Plot(_)
                | experiment::Error::Export(_)
                | experiment::Error::Animation(_) => ErrorKind::Failure,
                _ => ErrorKind::Input,
            },
            CliError::Io(e) | CliError::Write { source: e, .. }
                if e.kind() == std::io::ErrorKind::BrokenPipe =>
            {
                ErrorKind::BrokenPipe
            }
            CliError::Output { source, .. } if source.is_refusal() => ErrorKind::Input,
            CliError::Io(_)
            | CliError::Write { .. }
            | CliError::Output { .. }
            | CliError::Explorer(_)
            | CliError::Sweep(_) => ErrorKind::Failure,
            CliError::Interrupted { .. } | CliError::Stopped(_) => ErrorKind::Interrupted,
        }
    }

    /// An output path's error, prefixed with the option it came from (`"--out "`, or `""`).
    pub(crate) fn output(context: &str) -> impl FnOnce(dicesim_setup::output::OutputError) -> CliError + '_ {
        move |source| CliError::Output {
            context: context.to_string(),
            source,
        }
    }

    /// An experiment's error, prefixed with what it is about (`"--x "`, or `""`); a file it
    /// could not write is an output's error, which names the file itself.
    pub(crate) fn experiment(context: &str) -> impl FnOnce(experiment::Error) -> CliError + '_ {
        move |source| match source {
            experiment::Error::Output(e) => CliError::output("")(e),
            source => CliError::Experiment {
                context: context.to_string(),
                source,
            },
        }
    }
}

impl From<MergeError> for CliError {
    fn from(e: MergeError) -> CliError {
        match e {
            MergeError::Parts(m) => CliError::Parts(m),
            MergeError::Failed(m) => CliError::Sweep(m),
            MergeError::Param(e) => CliError::Param(e),
            MergeError::Output { context, source } => CliError::output(context)(source),
            MergeError::Io(e) => CliError::Io(e),
        }
    }
}

impl From<SlurmError> for CliError {
    fn from(e: SlurmError) -> CliError {
        match e {
            SlurmError::Refused(m) => CliError::Usage(m),
            SlurmError::Failed(m) => CliError::Sweep(m),
            SlurmError::Output(e) => CliError::output("")(e),
            SlurmError::Io(e) => CliError::Io(e),
        }
    }
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
    let matches = Cli::command().color(color).get_matches();
    let cli = <Cli as clap::FromArgMatches>::from_arg_matches(&matches).unwrap_or_else(|e| e.exit());
    let no_color = color_off(cli.no_color);
    match cli.command {
        Some(Command::Roll(args)) => roll::run(&args),
        Some(Command::Trace(args)) => trace::run(&args),
        Some(Command::Animate(args)) => animate::run(&args),
        Some(Command::Presets(args)) => presets::run(&args),
        Some(Command::Batch(args)) => batch::run(&args),
        Some(Command::Basin(args)) => basin::run(&args),
        Some(Command::Predict(args)) => predict::run(&args),
        Some(Command::Bench(args)) => bench::run(&args),
        Some(Command::Compare(args)) => compare::run(&args),
        Some(Command::Merge(args)) => merge::run(&args),
        Some(Command::Slurm(args)) => slurm::run(&args),
        Some(Command::Tui(args)) => tui::run(&args, no_color),
        Some(Command::Completions { shell }) => {
            let mut out = std::io::stdout().lock();
            clap_complete::generate(shell, &mut Cli::command(), "dicesim", &mut out);
            Ok(())
        }
        Some(Command::Man) => {
            clap_mangen::Man::new(Cli::command()).render(&mut std::io::stdout().lock())?;
            Ok(())
        }
        None => tui::run(&tui::TuiArgs::default(), no_color),
    }
}
