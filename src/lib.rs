//! The `dicesim` command line: argument parsing and printing over the layers below.

// A command's function parses, calls the layer below and prints: a long one is work that
// belongs in a crate underneath (the threshold is in clippy.toml).
#![warn(clippy::too_many_lines)]

pub mod cli;
pub mod tables;
