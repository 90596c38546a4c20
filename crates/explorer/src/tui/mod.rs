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

mod chart;
mod curve;
mod dialog_keys;
mod dialogs;
mod die;
mod effects;
mod energy;
pub(crate) mod fit;
mod footer;
pub(crate) mod format;
mod header;
mod help;
mod input;
mod keys;
pub(crate) mod layout;
mod ledger;
pub(crate) mod map;
mod map_keys;
mod outcomes;
pub(crate) mod param;
mod params_panel;
mod plot;
mod popup;
mod presentation;
mod render;
mod run;
mod separation;
mod solid;
pub(crate) mod state;
pub(crate) mod theme;
mod throw_keys;
mod timeline;
mod tty;
mod twin_keys;
mod vectors;
mod versus;

pub use keys::markdown_tables;
pub use render::render;
pub use run::{ExplorerError, run};
pub use state::app::App;
pub use theme::Theme;

#[cfg(test)]
mod class_tests;
#[cfg(test)]
mod control_tests;
#[cfg(test)]
mod tests;

#[cfg(test)]
mod map_tests;

#[cfg(test)]
mod view_tests;

#[cfg(test)]
mod twin_tests;

#[cfg(test)]
mod plot_tests;

#[cfg(test)]
mod contrast_tests;

#[cfg(test)]
mod lesson_tests;

#[cfg(test)]
mod versus_tests;

#[cfg(test)]
mod teacher_tests;

#[cfg(test)]
pub(crate) mod screen_tests;
