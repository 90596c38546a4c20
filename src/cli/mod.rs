//! Headless commands: the model usable and checkable without a terminal UI.

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
