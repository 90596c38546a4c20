//! The terminal explorer: [`App`] state, pure [`update`](input::update) and [`render()`],
//! and [`run()`], the event loop that owns the terminal.
//!
//! Its modules build on each other in one direction, each importing only those before it:
//! the vocabulary (the key table `keys`, `param`, `format`, `fit`, `theme`, `layout`,
//! `solid`); the `state` (`App` and every part it holds, and the rules that change them);
//! the input routing that `update` runs (`input`, with the map screen's, the dialogs', the
//! twins' and throw mode's keys); the panels, each drawing one part of the screen from the
//! state; then
//! `render`, which lays the panels out, and the event loop (`run`, `effects`, `tty`).

#![warn(clippy::too_many_lines)]

pub(crate) mod event_loop;
pub(crate) mod input;
pub(crate) mod panels;
pub(crate) mod render;
pub(crate) mod state;
pub(crate) mod vocabulary;

pub use event_loop::run::{ExplorerError, run};
pub use render::screen::render;
pub use state::app::App;
pub use vocabulary::key_table::markdown_tables;
pub use vocabulary::theme::Theme;

#[cfg(test)]
pub(crate) mod tests;
