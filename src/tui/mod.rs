//! The terminal explorer: [`App`] state, pure [`update`] and [`render`], and [`run`], the
//! event loop that owns the terminal.

pub mod app;
pub mod camera;
mod dialogs;
mod help;
mod ledger;
pub mod map;
pub mod param;
pub mod render;
mod run;
pub mod theme;
mod twin;
mod vectors;

pub use app::{App, Msg, update};
pub use render::render;
pub use run::run;
pub use theme::Theme;

#[cfg(test)]
mod class_tests;
#[cfg(test)]
mod tests;

#[cfg(test)]
mod map_tests;
