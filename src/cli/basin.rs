//! `dicesim basin`: the outcome over a grid of two setup values, as CSV or an image.

use super::shard::{
    Hashing, ShardArgs, csv_provenance_line, map_fingerprint, map_provenance, new_part, write_part,
};
use super::{CliError, EngineArg, SetupArgs, cancel_on_ctrl_c};
use clap::{Args, ValueEnum};
use dicesim_experiment::shard::Sweep;
use dicesim_experiment::{Axis, BasinMap, FaceTally, Layer, MapSpec, Method, RunOptions, run_map_rows};
use dicesim_figures::plot::write_image;
use dicesim_physics::Params;
use dicesim_setup::output::Output;
use dicesim_setup::preset::Preset;
use std::io::Write;
use std::path::PathBuf;

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
    /// Grid nodes along x and y, both ends of each range included; `Wx1` is a 1-D scan.
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
    /// Worker threads (default: one per core); the map does not depend on it.
    #[arg(long, value_name = "J", value_parser = clap::value_parser!(u64).range(1..))]
    pub(crate) jobs: Option<u64>,
    /// Write the map to a .csv, .png or .svg file.
    #[arg(long, value_name = "map.csv|map.png|map.svg")]
    pub(crate) out: Option<PathBuf>,
    /// Replace existing output files (--out, and a shard's --part summary).
    #[arg(long)]
    pub(crate) force: bool,
    #[command(flatten)]
    pub(crate) shard: ShardArgs,
    /// The engine that steps the rolls; the map is bit for bit the same with either.
    #[arg(long, value_enum, default_value_t = EngineArg::Auto)]
    pub(crate) engine: EngineArg,
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

/// Everything about a map's sweep that can be checked before any work: its size, setup,
/// axes and every node's start. `slurm` runs the same checks before it writes a script.
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
    if w * h > MAX_CELLS {
        // The map, the copy shown while refining, and the image or CSV drawn from it.
        let needed = 2 * w * h * size_of::<Option<dicesim_experiment::Cell>>();
        return Err(CliError::Usage(format!(
            "--res {w}x{h}: {} cells would need about {} of memory; at most {MAX_CELLS} cells (e.g. 2048x2048)",
            w * h,
            dicesim_setup::number::human_bytes(needed as u64)
        )));
    }
    let preset = args.setup.resolve()?;
    let params = preset.params();
    let x = Axis::parse(&args.x, w).map_err(CliError::experiment("--x "))?;
    let y = Axis::parse(&args.y, h).map_err(CliError::experiment("--y "))?;
    check_nodes_clear_of_table(&params, &preset.initial, &x, &y)?;
    Ok((preset, params, x, y))
}

/// The check `roll` makes of its one start, made of every node before any is rolled: the
/// first node whose start puts a corner into the table is the error, with its axis values.
fn check_nodes_clear_of_table(
    params: &Params,
    base: &dicesim_physics::InitialCondition,
    x: &Axis,
    y: &Axis,
) -> Result<(), CliError> {
    for j in 0..y.cells {
        for i in 0..x.cells {
            let (p, ic) = dicesim_experiment::basin::node_setup(params, base, x, y, i, j);
            if let Err(e) = ic.check_clear_of_table(&p) {
                return Err(CliError::Usage(format!(
                    "the node {} = {}, {} = {}: {e}",
                    x.key.key,
                    x.value(i),
                    y.key.key,
                    y.value(j)
                )));
            }
        }
    }
    Ok(())
}

/// The most cells a map takes (e.g. 2048×2048): the map and its partial copy stay in memory.
pub(crate) const MAX_CELLS: usize = 2048 * 2048;

pub(crate) fn run(args: &BasinArgs) -> Result<(), CliError> {
    let jobs = super::checked_jobs(args.jobs)?;
    let (w, h) = args.res;
    let (preset, params, x, y) = check_sweep(args, args.shard.shard.is_some())?;
    let layer = match args.layer {
        LayerArg::Face => Layer::Face,
        LayerArg::SettleTime => Layer::SettleTime,
    };
    // Filled cells copy a corner's settle time, which says little about the cells between,
    // and a 1-D scan is plotted as settle time: these roll every cell unless asked otherwise.
    let sharding = args.shard.resolve(args.out.as_deref(), args.force)?;
    let method = match (args.adaptive, args.uniform) {
        _ if sharding.is_some() => Method::Uniform,
        (true, _) => Method::Adaptive,
        (_, true) => Method::Uniform,
        _ if layer == Layer::SettleTime || h == 1 => Method::Uniform,
        _ => Method::Adaptive,
    };
    let output = args
        .out
        .as_deref()
        .map(|p| Output::check(p, &["csv", "png", "svg"], args.force))
        .transpose()
        .map_err(CliError::output("--out "))?;
    if sharding.is_some() && output.as_ref().is_some_and(|o| o.extension() != "csv") {
        return Err(CliError::Usage(
            "--shard writes its rows as .csv; `dicesim merge` draws the image of the whole map".to_string(),
        ));
    }
    let rows = sharding
        .as_ref()
        .map_or(0..h as u64, |(shard, _)| shard.range(h as u64));

    let total = (w * (rows.end - rows.start) as usize) as u64;
    let bar = super::progress_bar(total, "{bar:40} {pos}/{len} cells rolled, {elapsed}");
    let options = RunOptions {
        jobs,
        engine: args.engine.engine(),
    };
    let stop = cancel_on_ctrl_c()?;
    let start = std::time::Instant::now();
    let spec = MapSpec { x, y, method };
    let engine = format!("{} engine", options.engine.resolve().name());
    let map = run_map_rows(
        &params,
        &preset.initial,
        &spec,
        rows.start as usize..rows.end as usize,
        &options,
        &stop,
        &mut |m: &BasinMap| bar.set_position(m.sampled as u64),
    )
    .map_err(CliError::experiment(""))?;
    bar.finish_and_clear();
    let elapsed = start.elapsed().as_secs_f64();
    let faces: FaceTally = map
        .cells
        .iter()
        .flatten()
        .filter_map(|c| c.outcome.face)
        .collect();

    let mut written = None;
    let provenance = map_provenance(&preset, &map);
    if let Some(output) = &output {
        match output.extension() {
            "csv" => output
                .write(|w| {
                    let mut hashing = Hashing::new(w);
                    writeln!(hashing, "{}", csv_provenance_line(&provenance))?;
                    map.write_csv(&mut hashing)?;
                    written = Some(hashing.seal());
                    Ok(())
                })
                .map_err(CliError::output(""))?,
            _ => write_image(
                &map,
                layer,
                (&preset.name, &params, &preset.initial),
                &provenance,
                output,
            )
            .map_err(|e| match e {
                dicesim_experiment::Error::Output(e) => CliError::output("")(e),
                e => CliError::experiment(&format!("{}: ", output.path().display()))(e),
            })?,
        }
    }
    if let Some((shard, part)) = &sharding {
        let sweep = Sweep::Map {
            preset: preset.name.clone(),
            fingerprint: map_fingerprint(&preset),
            x: args.x.clone(),
            y: args.y.clone(),
            width: w,
            height: h,
            layer: layer.name().to_string(),
        };
        let records = args.out.as_deref().zip(written);
        let mut summary = new_part(sweep, *shard, rows.clone(), part.path(), records, &preset);
        summary.complete = map.complete;
        summary.map_faces = Some(faces);
        summary.elapsed_s = elapsed;
        summary.jobs = jobs;
        write_part(part, &summary)?;
    }
    let mut out = std::io::stdout().lock();
    print_map_summary(&mut out, &map, layer, &faces)?;
    if let Some((shard, _)) = &sharding {
        writeln!(
            out,
            "shard               {shard}: rows {} to {}",
            rows.start,
            rows.end.saturating_sub(1)
        )?;
    }
    writeln!(
        out,
        "time                {elapsed:.2} s on {jobs} thread{}, {engine}",
        if jobs == 1 { "" } else { "s" },
    )?;
    if let Some(path) = &args.out {
        writeln!(out, "wrote               {}", path.display())?;
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

/// What `basin` and `merge` print about a map: its grid, method, axes and the face shares
/// over its known cells.
pub(super) fn print_map_summary(
    out: &mut impl Write,
    map: &BasinMap,
    layer: Layer,
    faces: &FaceTally,
) -> std::io::Result<()> {
    let (x, y) = (&map.x, &map.y);
    let (w, h) = (map.width(), map.height());
    writeln!(out, "{w}×{h} {} map, {}", layer.name(), map.method_report())?;
    writeln!(out, "x  {} from {} to {}", x.key.label(), x.min, x.max)?;
    if h == 1 {
        writeln!(out, "y  {} = {}", y.key.label(), y.value(0))?;
    } else {
        writeln!(out, "y  {} from {} to {}", y.key.label(), y.min, y.max)?;
    }
    let shares: Vec<String> = (1..=6)
        .map(|f| format!("{f}: {:.1}%", 100.0 * faces.share(f)))
        .collect();
    writeln!(out, "faces over the map  {}", shares.join(", "))?;
    let unsettled = map.cells.iter().flatten().count() as u64 - faces.total();
    if unsettled > 0 {
        writeln!(out, "cells without a face {unsettled}")?;
    }
    Ok(())
}
