//! Why a command failed, and what kind of failure it is: the exit status follows from it.

use dicesim_experiment as experiment;
use dicesim_experiment::merge::MergeError;
use dicesim_experiment::slurm::SlurmError;
use dicesim_physics::ParamError;
use dicesim_setup::preset::PresetError;
use std::path::PathBuf;

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
    /// The explorer could not open or stopped with an error (what it was doing, and why).
    #[error(transparent)]
    Explorer(#[from] dicesim_explorer::tui::ExplorerError),
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
            CliError::Preset(PresetError::Write { .. }) => ErrorKind::Failure,
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
