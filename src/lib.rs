pub mod cli;
pub mod experiment;
pub(crate) mod fault;
pub mod output;
pub mod physics;
pub mod preset;
pub mod tui;
pub mod worker;
