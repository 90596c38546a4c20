//! The `dicesim` command line: argument parsing and printing over the layers below.

// A command's function parses, calls the layer below and prints: a long one is work that
// belongs in a crate underneath (the threshold is in clippy.toml).
#![warn(clippy::too_many_lines)]

pub mod cli;
pub mod tables;

// tables.rs came from the experiment crate as it was: its `crate::` paths name that crate's
// modules until the next commit names them itself.
use dicesim_experiment::{basin, compare, compare_budden, compare_stats, ending, predict, versus};
mod stats {
    pub use dicesim_experiment::FaceTally;
}
mod summary {
    pub use dicesim_experiment::BatchSummary;
}
