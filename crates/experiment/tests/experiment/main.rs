//! The experiment layer's integration tests: the shipped presets roll as described, real
//! dice bodies alike in both engine widths, two setups over the same throws, the
//! literature's predictability statements, and a provenance that rebuilds its setup.

mod fair_die;
mod predictability;
mod provenance;
mod real_dice;
mod shipped_presets;
mod versus;
