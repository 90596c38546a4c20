//! The terminal explorer: [`App`] state, pure [`update`] and [`render`], and [`run`], the
//! event loop that owns the terminal.

pub(crate) mod app;
pub(crate) mod camera;
mod curve;
mod dialog;
mod dialogs;
mod die;
mod editor;
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
mod map_view;
mod outcomes;
pub(crate) mod param;
mod params_panel;
mod plot;
mod presentation;
pub mod render;
mod roll_view;
pub(crate) mod run;
mod setup;
pub(crate) mod theme;
mod timeline;
mod tty;
mod twin;
mod twin_view;
mod vectors;
mod versus;

pub use app::{App, Effect, Msg};
pub use input::update;
pub use render::render;
pub use run::run;
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
pub(crate) mod screen_tests;
