//! The explorer's state: [`app::App`] and every part it holds (the roll, the user's setup,
//! the twins, the die and map screens, the dialogs and editors, what `update` sends out),
//! with the rules that change them. It sits below the input routing, the panels and the
//! drawing: nothing here imports any of them, so each of those reads the state and none is
//! read by it.

pub(crate) mod app;
pub(crate) mod camera;
pub(crate) mod dialog;
pub(crate) mod die_screen;
pub(crate) mod editor;
pub(crate) mod lesson_run;
pub(crate) mod map_view;
pub(crate) mod messages;
pub(crate) mod projection;
pub(crate) mod roll_view;
pub(crate) mod throw;
pub(crate) mod twins;
pub(crate) mod user_setup;
