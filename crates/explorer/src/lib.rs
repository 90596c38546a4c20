//! The explorer: a simulation worker thread and the terminal UI that shows it.
//!
//! The UI never steps the physics: the worker does, and the UI draws its snapshots.

pub(crate) mod fault;
pub mod lesson;
pub mod tui;
pub mod worker;
