//! The `dicesim` command line: argument parsing and printing over the layers below.

pub mod cli;
pub mod tables;
