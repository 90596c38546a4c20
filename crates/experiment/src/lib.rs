//! Experiments on the model: random initial conditions, batches, basin maps, statistics,
//! comparisons with real dice; and what makes a sweep of them reproducible anywhere: the
//! provenance and fingerprints its files carry, its shards and their part summaries, their
//! merge and re-verification, and the Slurm job array that runs them.
//!
//! Everything here takes [`Params`](dicesim_physics::Params) and
//! [`InitialCondition`](dicesim_physics::InitialCondition) values as arguments; resolving a
//! preset is the caller's job.

pub mod basin;
pub mod batch;
pub mod batch_sweep;
pub mod bench;
pub mod compare;
pub mod compare_budden;
pub mod compare_stats;
pub mod ending;
pub(crate) mod engine;
pub mod hashing;
pub mod ics;
pub mod merge;
pub mod parquet;
pub mod predict;
pub mod provenance;
pub mod real_data;
pub mod record;
pub mod shard;
pub mod slurm;
pub(crate) mod stats;
pub(crate) mod summary;
pub mod tables;
pub mod tally;
pub mod trace;
pub mod versus;

/// The program and its version, as every output records it.
pub const PROGRAM: &str = concat!("dicesim ", env!("CARGO_PKG_VERSION"));

pub use basin::run_map_rows;
pub use basin::{Axis, BasinMap, Cell, Layer, MapSpec, Method, UNIFORM_SWITCH_SHARE, run_map, run_map_with};
pub use batch::{Batch, BatchRun, Rolls, RunOptions, run_batch, stream_batch};
pub use dicesim_physics::RandomRanges;
pub use dicesim_setup::keys::ScanKey;
pub use engine::Engine;
pub use record::{RollRecord, roll_record};
pub use stats::FaceTally;
pub use summary::BatchSummary;

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
}
