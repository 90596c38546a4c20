//! What every test of the explorer starts from (`fixtures`), and the checks of every
//! screen at once: each drawn at every size and snapshot, no word cut, every cell readable
//! in every theme, the lesson's steps as a class sees them.

pub(crate) mod fixtures;

mod contrast_tests;
mod dice_tests;
mod lesson_tests;
pub(crate) mod screen_tests;
