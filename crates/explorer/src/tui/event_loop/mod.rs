//! The event loop: the terminal, the worker, the effects `update` asks for.

pub(crate) mod effects;
pub(crate) mod run;
pub(crate) mod tty;

#[cfg(test)]
mod effects_tests;
