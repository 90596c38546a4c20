//! `dicesim basin`: the outcome over a grid of two setup values, as CSV or an image.

use super::args::{RunArgs, SetupArgs, Worded, Wording};
use super::error::CliError;
use super::running::{self, cancel_on_ctrl_c};
use crate::tables;
use clap::{Args, ValueEnum};
use dicesim_experiment::basin::unapplied_by_map;
use dicesim_experiment::hashing::Written;
use dicesim_experiment::limits::MAP_CELLS;
use dicesim_experiment::provenance;
use dicesim_experiment::shard::{Part, Sweep};
use dicesim_experiment::{Axis, BasinMap, Layer, MapSpec, Method, run_map_rows};
use dicesim_figures::plot::write_image;
use dicesim_physics::Params;
use dicesim_setup::output::Output;
use dicesim_setup::preset::{Preset, refuse_unapplied};
use std::io::Write;

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum LayerArg {
    /// The face up at the end.
    Face,
    /// Simulated seconds until the roll ended.
    SettleTime,
}

#[derive(Debug, Args)]
pub(crate) struct BasinArgs {
    #[command(flatten)]
    pub(crate) setup: SetupArgs,
    /// The horizontal axis: any numeric preset key, vector components included, with its
    /// range, e.g. `initial.angular_velocity.x:-60:60`.
    #[arg(long = "x", value_name = "KEY:MIN:MAX", allow_hyphen_values = true)]
    pub(crate) x: String,
    /// The vertical axis, as --x (with `--res Wx1`, one scan at the middle of its range).
    #[arg(long = "y", value_name = "KEY:MIN:MAX", allow_hyphen_values = true)]
    pub(crate) y: String,
    /// Grid nodes along x and y, both ends of each range included; `Wx1` is a 1-D scan (at
    /// most 4194304 cells (2048x2048) in all).
    #[arg(long, value_name = "WxH", default_value = "200x100", value_parser = parse_resolution)]
    pub(crate) res: (usize, usize),
    /// What each cell shows.
    #[arg(long, value_enum, default_value_t = LayerArg::Face)]
    pub(crate) layer: LayerArg,
    /// Roll a coarse grid, then only where neighbouring cells differ (default for 2-D face
    /// maps; may miss islands smaller than the coarse spacing).
    #[arg(long, conflicts_with = "uniform")]
    pub(crate) adaptive: bool,
    /// Roll every cell (default for the settle-time layer and 1-D scans).
    #[arg(long)]
    pub(crate) uniform: bool,
    #[command(flatten)]
    pub(crate) run: RunArgs<Basin>,
}

/// How `basin` words its run options.
#[derive(Debug)]
pub(crate) struct Basin;

impl Worded for Basin {
    const WORDING: Wording = Wording {
        jobs: "Worker threads (default: one per core); the map does not depend on it",
        out: "Write the map to a .csv, .png or .svg file (repeatable: one of each, say)",
        out_value: "map.csv|map.png|map.svg",
        repeatable: true,
        force: "Replace existing output files (--out, and a shard's --part summary)",
        json: None,
        sharded: true,
        engine: "The engine that steps the rolls; the map is bit for bit the same with either",
    };
}

fn parse_resolution(s: &str) -> Result<(usize, usize), String> {
    let bad = || format!("`{s}`: expected WxH with whole numbers from 1 to 10000, e.g. 200x100");
    let (w, h) = s.split_once(['x', 'X', '×']).ok_or_else(bad)?;
    let w: usize = w.trim().parse().map_err(|_| bad())?;
    let h: usize = h.trim().parse().map_err(|_| bad())?;
    if !(1..=10_000).contains(&w) || !(1..=10_000).contains(&h) {
        return Err(bad());
    }
    Ok((w, h))
}

/// Everything about a map's sweep that can be checked before any work: its size, setup and
/// axes. Every node's setup is checked by the map itself before its first roll (the same
/// check `roll` makes, `check_nodes`); `slurm` runs that too before it writes a script.
///
/// `sharded`: the map is rolled in shards (`--shard`, or `slurm`'s array tasks).
pub(crate) fn check_sweep(args: &BasinArgs, sharded: bool) -> Result<(Preset, Params, Axis, Axis), CliError> {
    if sharded && args.adaptive {
        return Err(CliError::Usage(
            "--shard rolls every cell of its rows: adaptive refinement compares cells across shards"
                .to_string(),
        ));
    }
    let (w, h) = args.res;
    let cells = (w as u64).saturating_mul(h as u64);
    if cells > MAP_CELLS.max {
        // The map, the copy shown while refining, and the image or CSV drawn from it.
        let needed = cells.saturating_mul(2 * size_of::<Option<dicesim_experiment::Cell>>() as u64);
        let needed = dicesim_setup::number::human_bytes(needed);
        let what = format!("--res {w}x{h}: {cells} cells would need about {needed} of memory");
        return Err(CliError::experiment("")(MAP_CELLS.refuse(what)));
    }
    let preset = args.setup.resolve()?;
    let params = preset.params();
    let x = Axis::parse(&args.x, w).map_err(CliError::experiment("--x "))?;
    let y = Axis::parse(&args.y, h).map_err(CliError::experiment("--y "))?;
    // A --set the map's axes replace, or that it never reads, is refused, not dropped.
    refuse_unapplied(&args.setup.set, |key| unapplied_by_map(key, &x, &y))?;
    if x.key.spec.key() == y.key.spec.key() && x.key.component == y.key.component {
        // The y value would overwrite the x value in every cell: a map of nothing.
        return Err(CliError::Usage(format!(
            "--x and --y both vary `{}`: a map needs two different values",
            x.key.key
        )));
    }
    Ok((preset, params, x, y))
}

impl From<LayerArg> for Layer {
    fn from(layer: LayerArg) -> Layer {
        match layer {
            LayerArg::Face => Layer::Face,
            LayerArg::SettleTime => Layer::SettleTime,
        }
    }
}

impl BasinArgs {
    /// How the cells are found: a shard rolls every cell of its rows (refinement compares
    /// cells across shards); filled cells copy a corner's settle time, which says little
    /// about the cells between, and a 1-D scan is plotted as settle time: these roll every
    /// cell unless asked otherwise.
    fn method(&self, sharded: bool) -> Method {
        match (self.adaptive, self.uniform) {
            _ if sharded => Method::Uniform,
            (true, _) => Method::Adaptive,
            (_, true) => Method::Uniform,
            _ if Layer::from(self.layer) == Layer::SettleTime || self.res.1 == 1 => Method::Uniform,
            _ => Method::Adaptive,
        }
    }
}

pub(crate) fn run(args: &BasinArgs) -> Result<(), CliError> {
    let options = args.run.options()?;
    let (w, h) = args.res;
    let (preset, params, x, y) = check_sweep(args, args.run.shard.shard.is_some())?;
    let layer = Layer::from(args.layer);
    let sharding = args.run.sharding()?;
    let method = args.method(sharding.is_some());
    let outputs = args.run.outputs(&["csv", "png", "svg"])?;
    if sharding.is_some() && (outputs.len() > 1 || outputs.iter().any(|o| o.extension() != "csv")) {
        return Err(CliError::Usage(
            "--shard writes its rows as one .csv; `dicesim merge` draws the image of the whole map"
                .to_string(),
        ));
    }
    let shard = sharding
        .as_ref()
        .map(|(shard, _)| (*shard, shard.range(h as u64)));
    let rows = shard.as_ref().map_or(0..h as u64, |(_, rows)| rows.clone());
    let total = (w * (rows.end - rows.start) as usize) as u64;
    let bar = running::progress_bar(total, "{bar:40} {pos}/{len} cells rolled, {elapsed}");
    let stop = cancel_on_ctrl_c()?;
    let start = std::time::Instant::now();
    let map = run_map_rows(
        &params,
        &preset.initial,
        &MapSpec { x, y, method },
        rows.start as usize..rows.end as usize,
        &options,
        &stop,
        &mut |m: &BasinMap| bar.set_position(m.sampled as u64),
    )
    .map_err(CliError::experiment(""))?;
    bar.finish_and_clear();
    let elapsed = start.elapsed().as_secs_f64();
    // Each file in the order given; a shard's one CSV is the part's record.
    let mut written = None;
    for output in &outputs {
        written = write_map(&map, layer, &preset, output)?.or(written);
    }
    if let (Some((_, part)), Some(shard)) = (&sharding, shard.clone()) {
        let sweep = Sweep::map(&preset, (args.x.as_str(), args.y.as_str()), args.res, layer);
        let records = args.run.out_path().zip(written);
        let ran = (elapsed, options.jobs);
        Part::of_map(sweep, shard, part.path(), records, &preset, &map, ran)
            .write(part)
            .map_err(CliError::output(""))?;
    }
    let mut out = std::io::stdout().lock();
    let known = map.cells.iter().flatten().count() as u64;
    tables::map_summary(&mut out, &map, layer, &map.face_tally(), known)?;
    if let Some((shard, rows)) = &shard {
        writeln!(
            out,
            "shard               {shard}: rows {} to {}",
            rows.start,
            rows.end.saturating_sub(1)
        )?;
    }
    let jobs = options.jobs;
    writeln!(
        out,
        "time                {elapsed:.2} s on {jobs} thread{}, {} engine",
        if jobs == 1 { "" } else { "s" },
        options.engine.resolve().name()
    )?;
    for output in &outputs {
        writeln!(out, "wrote               {}", output.path().display())?;
    }
    out.flush()?;
    if !map.complete {
        // A cancelled uniform map keeps an exact prefix of its cells in row order (what a
        // longer run agrees with); an adaptive one its last whole refinement level.
        return Err(CliError::Interrupted {
            completed: map.cells.iter().flatten().count() as u64,
            requested: total,
            what: "cells",
        });
    }
    Ok(())
}

/// Writes the map to `output`: its CSV (returning the file's size and hash, which a
/// shard's part records), or its image.
fn write_map(
    map: &BasinMap,
    layer: Layer,
    preset: &Preset,
    output: &Output,
) -> Result<Option<Written>, CliError> {
    let provenance = provenance::map(preset, map);
    if output.extension() == "csv" {
        return Ok(Some(
            map.write_csv_file(&provenance, output)
                .map_err(CliError::output(""))?,
        ));
    }
    let setup = (preset.name.as_str(), &preset.params(), &preset.initial);
    write_image(map, layer, setup, &provenance, output)
        .map_err(CliError::experiment(&format!("{}: ", output.path().display())))?;
    Ok(None)
}
