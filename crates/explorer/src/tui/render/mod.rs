//! Drawing a frame: which screen and which panels, placed where.

pub(crate) mod screen;
