//! The `dicesim` binary as a user runs it, and the checks of the repository as a whole (its
//! docs' links, its packaging, the layers of its crates, no import cycles in any crate): one
//! test binary, so a change relinks one program, not one a file.
//!
//! The tests of a library alone live with their crate (`crates/*/tests/`).

mod animate;
mod batches_and_maps;
mod commands;
mod common;
mod compare;
mod docs;
mod evidence;
mod fair_die;
mod import_cycles;
mod inputs;
mod layers;
mod lesson;
mod limits;
mod loaded_dice;
mod man;
mod merge_checks;
mod merge_fuzz;
mod one_validation;
mod outputs;
mod package;
mod polyhedral_dice;
mod presets;
mod provenance;
mod round_three;
mod shards;
mod signals;
mod slurm_checks;
mod smaller_items;
mod start_checks;
mod terminal;
mod trace_impacts;
mod unapplied_sets;
mod versus;
