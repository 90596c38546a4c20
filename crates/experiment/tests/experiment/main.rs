//! The experiment layer's integration tests: the shipped presets roll as described, real
//! dice bodies alike in both engine widths, two setups over the same throws, and the
//! literature's predictability statements.

mod predictability;
mod real_dice;
mod shipped_presets;
mod versus;
