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
pub mod columns;
pub mod compare;
pub mod compare_budden;
pub mod compare_joint;
pub mod compare_shaved;
pub mod compare_stats;
pub mod data_file;
pub mod ending;
pub(crate) mod engine;
mod error;
pub mod hashing;
pub mod ics;
pub mod limits;
pub mod merge;
pub mod one_roll;
pub mod parquet;
pub mod player_counts;
pub mod predict;
pub mod provenance;
pub mod real_data;
pub mod record;
pub mod shard;
pub mod slurm;
pub(crate) mod stats;
pub(crate) mod summary;
pub mod tally;
pub mod trace;
pub mod versus;

pub use basin::run_map_rows;
pub use basin::{Axis, BasinMap, Cell, Layer, MapSpec, Method, UNIFORM_SWITCH_SHARE, run_map, run_map_with};
pub use batch::{Batch, BatchRun, Rolls, RunOptions, run_batch, stream_batch};
pub use dicesim_physics::RandomRanges;
pub use dicesim_setup::keys::ScanKey;
pub use engine::Engine;
pub use error::{Error, csv_io};
pub use provenance::{BUILD, COMMIT, PROGRAM, VERSION_LINE};
pub use record::{RollRecord, roll_record};
pub use stats::FaceTally;
pub use summary::BatchSummary;
