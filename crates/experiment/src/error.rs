//! Why an experiment could not run, and a CSV writer's error as the I/O error it wraps.

use dicesim_physics::ParamError;

/// A CSV writer's error as the I/O error it wraps, so a closed pipe stays a closed pipe
/// (`csv` turns every error into `ErrorKind::Other`). Records of a fixed width serialise
/// nothing else.
pub fn csv_io(e: csv::Error) -> std::io::Error {
    match e.into_kind() {
        csv::ErrorKind::Io(e) => e,
        other => std::io::Error::other(format!("CSV: {other:?}")),
    }
}

/// Why an experiment could not run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    /// A value outside its allowed range.
    #[error("{0}")]
    OutOfRange(#[from] ParamError),
    /// A scan key that names no numeric setup value.
    #[error("{0}")]
    UnknownKey(#[from] dicesim_setup::keys::UnknownKey),
    /// A malformed map axis (`KEY:MIN:MAX`).
    #[error("`{spec}`: {message}")]
    Axis { spec: String, message: String },
    /// A node of a map whose setup is refused (a body that cannot exist, a start inside the
    /// table): the node's values, then the setup's own refusal.
    #[error("the node {node}: {error}")]
    Node { node: String, error: Box<ParamError> },
    /// A malformed row of an initial-condition file (1-based line).
    #[error("line {line}: {message}")]
    Ics { line: usize, message: String },
    /// A shard that cannot be rolled on its own.
    #[error("cannot shard {0}")]
    Shard(String),
    /// The worker threads could not be started.
    #[error("cannot start worker threads: {0}")]
    Threads(String),
    /// An image could not be drawn or written.
    #[error("cannot draw the map: {0}")]
    Plot(String),
    /// The sink of a streamed batch refused its records (e.g. the disk is full).
    #[error("cannot write the rolls: {0}")]
    Records(String),
    /// An animation that cannot be made as asked.
    #[error("cannot make the animation: {0}")]
    Animation(String),
    /// A roll's trace or plot could not be written.
    #[error("cannot export the roll: {0}")]
    Export(String),
    /// A file could not be written (or its path was refused).
    #[error("{0}")]
    Output(#[from] dicesim_setup::output::OutputError),
    /// The cancel flag stopped the work.
    #[error("cancelled")]
    Cancelled,
    /// A comparison with real dice that cannot be rolled as asked.
    #[error("{0}")]
    Compare(String),
    /// A predictability experiment that cannot be rolled as asked.
    #[error("{0}")]
    Predict(String),
    /// A size past its limit ([`crate::limits`]), refused before any work.
    #[error("{0}")]
    Limit(String),
}
