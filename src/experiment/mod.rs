//! Experiments on the model: random initial conditions, batches, basin maps, statistics.

pub mod random;
pub mod stats;

pub use random::RandomRanges;
pub use stats::FaceTally;
