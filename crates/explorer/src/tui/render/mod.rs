//! Drawing a frame: which panel takes which place (`places`), and the render that follows it.

pub(crate) mod export;
pub(crate) mod places;
pub(crate) mod screen;

#[cfg(test)]
mod render_tests;
