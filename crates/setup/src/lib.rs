//! A setup of the model and how it is named, read and written: the registry of every
//! parameter (its key, unit and range), presets (named TOML files, docs/presets.md), the
//! scan keys and quantities the experiments and the explorer name, and the one way a file
//! is written (atomically, never over an existing file without `--force`).
//!
//! Below it is only the physics; everything above takes its setups from here.

pub mod chaos;
pub mod keys;
pub mod number;
pub mod output;
pub mod preset;
pub mod quantity;
pub mod random;
pub mod registry;
