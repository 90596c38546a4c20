//! The setup layer's integration tests: presets loaded, refused and saved; random draws and
//! the chaos twin's ε; every registry quantity worked out by hand; the registry's ranges and
//! verdicts across the whole allowed range.

mod chaos_twin;
mod extreme_parameters;
mod presets;
mod quantities;
mod random_draws;
mod verdicts;
