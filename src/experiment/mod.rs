//! Experiments on the model: random initial conditions, batches, basin maps, statistics.

pub mod random;
pub mod record;
pub mod stats;

pub use random::RandomRanges;
pub use record::{RollRecord, roll_record};
pub use stats::FaceTally;
