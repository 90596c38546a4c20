//! `dicesim merge`: the shards of a sweep put back together (the checks and the merge are
//! the experiment crate's [`Parts`]); this draws a map's images and prints the summary.

use super::error::CliError;
use super::running;
use crate::tables;
use clap::Args;
use dicesim_experiment::merge::{BatchMerge, MapMerge, Parts};
use dicesim_figures::plot::image_file_bytes;
use dicesim_setup::output::{Output, Staged, commit};
use std::io::Write;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub(crate) struct MergeArgs {
    /// The part summaries (`*.part.json`) that `batch --shard` or `basin --shard` wrote, or
    /// folders holding them; in any order.
    #[arg(required = true, value_name = "PARTS")]
    pub(crate) parts: Vec<PathBuf>,
    /// Write the merged result: a batch's .csv or .parquet; a map's .csv, .png or .svg
    /// (repeatable).
    /// Without it, only the summary is printed.
    #[arg(long, value_name = "FILE")]
    pub(crate) out: Vec<PathBuf>,
    /// Replace existing --out files.
    #[arg(long, requires = "out")]
    pub(crate) force: bool,
    /// Print the summary as one JSON object instead of text.
    #[arg(long)]
    pub(crate) json: bool,
    /// Roll N records chosen at random again and refuse the merge unless each ends bit for
    /// bit as recorded (the other checks catch damage and mix-ups; only rolling again
    /// catches records that are consistent but not what the setup rolls).
    #[arg(long, value_name = "N", default_value_t = 0)]
    pub(crate) verify: u64,
    /// Merge parts that builds of different commits (of this version) rolled: refused
    /// without it, since another build may roll differently; the merged files name every
    /// build, and --verify rolls records again with this one.
    #[arg(long)]
    pub(crate) accept_mixed_builds: bool,
}

pub(crate) fn run(args: &MergeArgs) -> Result<(), CliError> {
    // A merge keeps nothing partial: a signal removes the file being written and exits.
    running::stop_at_once_on_signals()?;
    // Existing files are refused before any work, unless replacing them was asked for.
    let outputs = super::args::checked_outputs(&args.out, &["csv", "parquet", "png", "svg"], args.force)?;
    let parts = Parts::read(&args.parts, &outputs, args.accept_mixed_builds)?;
    if !parts.is_map() {
        let merged = parts.merge_batch(&outputs, args.verify)?;
        return print_batch(args, &merged);
    }
    if args.json {
        return Err(CliError::Parts(
            "--json: a map's summary is text (its cells are the --out .csv)".to_string(),
        ));
    }
    let (merged, csv) = parts.merge_map(&outputs, args.verify)?;
    // The images with the CSV: all of them written, or none.
    let mut staged: Vec<Staged> = csv.into_iter().collect();
    for image in outputs.iter().filter(|o| o.extension() != "csv") {
        staged.push(draw(&merged, image)?);
    }
    commit(staged).map_err(CliError::output(""))?;
    print_map(args, &merged)
}

/// Draws a merged map's image, as `basin` draws a map rolled on one machine, staged to be
/// committed with the merge's other files.
fn draw(merged: &MapMerge, image: &Output) -> Result<Staged, CliError> {
    let preset = &merged.preset;
    let setup = (preset.name.as_str(), &preset.params(), &preset.initial);
    let bytes = image_file_bytes(&merged.map, merged.layer, setup, &merged.provenance, image)
        .map_err(CliError::experiment(&format!("{}: ", image.path().display())))?;
    let mut staged = image.stage(None).map_err(CliError::output(""))?;
    staged
        .write_all(&bytes)
        .map_err(|e| CliError::output("")(image.failed(&e)))?;
    Ok(staged)
}

fn print_batch(args: &MergeArgs, m: &BatchMerge) -> Result<(), CliError> {
    let mut stdout = std::io::stdout().lock();
    if args.json {
        writeln!(stdout, "{}", m.report())?;
    } else {
        tables::merged_batch(&mut stdout, m, &args.out)?;
    }
    Ok(())
}

fn print_map(args: &MergeArgs, m: &MapMerge) -> Result<(), CliError> {
    tables::merged_map(&mut std::io::stdout().lock(), m, &args.out)?;
    Ok(())
}
