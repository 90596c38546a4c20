//! Figures of the experiments: basin maps, energy and predictability plots, comparisons
//! with real dice (PNG and SVG), and animated GIFs of a roll.
//!
//! Figures read experiment results; nothing below this crate draws.

pub mod animation;
pub mod compare_plot;
pub mod energy_plot;
pub mod export;
pub mod figure;
pub mod joint_plot;
pub mod plane;
pub mod plot;
pub mod predict_plot;
