//! Headless commands: the model usable and checkable without a terminal UI.

// A command's function parses, calls the layer below and prints: a long one is work that
// belongs in a crate underneath (the threshold is in clippy.toml).
#![warn(clippy::too_many_lines)]

mod animate;
mod args;
mod basin;
mod batch;
mod bench;
mod command;
mod compare;
mod error;
mod man;
mod merge;
mod predict;
mod presets;
mod roll;
mod running;
mod slurm;
mod trace;
mod tui;

pub use command::main;
pub use error::{CliError, ErrorKind};
pub use running::interrupted_status;
