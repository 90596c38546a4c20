//! The terminal explorer: [`App`] state, pure `update` and
//! [`render()`], and [`run()`], the event loop that owns the terminal.
//!
//! Its folders build on each other in one direction, each importing only those before it:
//!
//! - `vocabulary/`: what every other part names: the one key table (`key_table`), the
//!   parameter rows (`param`), numbers as text (`format`), text fitted to a width (`fit`),
//!   the themes, the die's solid, and where each part of the main screen goes (`layout`);
//! - `state/`: `App` and every part it holds, and the rules that change them;
//! - `input/`: `update`, which turns a key, a click or a snapshot into changes of the state
//!   and effects, with the keys of the modes the key table alone does not settle (the map
//!   screen's, the dialogs', the twins', throw mode's);
//! - `panels/`: one module a panel, each drawing one part of a screen from the state through
//!   one entry point, `render(app, area, frame)`;
//! - `render/`: the table of which panel takes which place and when (`places`), and the
//!   render that follows it (`screen`);
//! - `event_loop/`: the loop that owns the terminal (`run`), the effects `update` asks for
//!   (`effects`) and the terminal's input decoder (`tty`).
//!
//! Tests sit with what they test: a panel's in `panels/NAME/NAME_tests.rs`, the keys' in
//! `input/`, whole frames in `render/`; `tests/` holds the fixtures they start from and the
//! checks of every screen at once. No function here is longer than 100 lines (clippy's
//! `too_many_lines`, set in the crate's `clippy.toml`).

#![warn(clippy::too_many_lines)]

pub(crate) mod event_loop;
pub(crate) mod input;
pub(crate) mod panels;
pub(crate) mod render;
pub(crate) mod state;
pub(crate) mod vocabulary;

pub use event_loop::run::{ExplorerError, run};
pub use render::export::{TERMINAL_COLUMNS, TERMINAL_ROWS, write_presentation};
pub use render::screen::render;
pub use state::app::App;
pub use vocabulary::key_table::markdown_tables;
pub use vocabulary::theme::Theme;

#[cfg(test)]
pub(crate) mod tests;
