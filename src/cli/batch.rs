//! `dicesim batch`: many rolls in parallel, per-roll results and their statistics.

use super::args::{RunArgs, SetupArgs, Worded, Wording};
use super::error::CliError;
use super::running::{self, cancel_on_ctrl_c};
use crate::tables;
use clap::Args;
use dicesim_experiment::RunOptions;
use dicesim_experiment::batch_sweep::BatchSweep;
use dicesim_experiment::ics::parse_initial_conditions;
use dicesim_experiment::limits::BATCH_ROLLS;
use dicesim_experiment::shard::Shard;
use dicesim_physics::InitialCondition;
use dicesim_setup::preset::{Preset, refuse_unapplied};
use dicesim_setup::random::{check_drawn_setup, seed_given, unapplied_when_drawn};
use std::io::Write;
use std::path::PathBuf;

/// The largest `--ics` file read, bytes (about a million rows).
const MAX_ICS_BYTES: u64 = 256 * 1024 * 1024;

#[derive(Debug, Args)]
pub(crate) struct BatchArgs {
    #[command(flatten)]
    pub(crate) setup: SetupArgs,
    /// Roll N dice with initial conditions drawn from the preset's `[random]` ranges (at most
    /// 10¹¹ rolls per batch).
    #[arg(
        long,
        value_name = "N",
        required_unless_present = "ics",
        conflicts_with = "ics",
        // A batch of no rolls has no face shares to give (compare and predict refuse it too).
        value_parser = clap::value_parser!(u64).range(1..)
    )]
    pub(crate) rolls: Option<u64>,
    /// Roll the initial conditions of a CSV file: a header with `id` and any of height,
    /// velocity_x|y|z, angular_velocity_x|y|z, angular_momentum_x|y|z, yaw, pitch, roll
    /// (missing columns take the preset's initial values).
    #[arg(long, value_name = "FILE.csv")]
    pub(crate) ics: Option<PathBuf>,
    /// Seed of the random draws (default: the preset's `random.seed`); roll i's draw depends
    /// on (seed, i) alone.
    #[arg(long, value_name = "S", value_parser = dicesim_setup::random::parse_seed, conflicts_with = "ics")]
    pub(crate) seed: Option<u64>,
    #[command(flatten)]
    pub(crate) run: RunArgs<Batch>,
    /// Roll every throw twice: in setup A (as given) and in setup B, A with this value
    /// changed (a `--set` key of the die, ground, world or integrator; repeatable). Prints
    /// the table of A's face against B's and the share of throws that agree; --out writes
    /// each throw's two outcomes (.csv) or the figures (.json).
    #[arg(long, value_name = "KEY=VALUE", conflicts_with = "shard")]
    pub(crate) versus: Vec<String>,
}

/// How `batch` words its run options.
#[derive(Debug)]
pub(crate) struct Batch;

impl Worded for Batch {
    const WORDING: Wording = Wording {
        jobs: "Worker threads (default: one per core); the results do not depend on it",
        out: "Write every roll (id, initial condition, start face, face, status, steps, simulated \
              seconds) to a .csv, .json or .parquet file (Parquet: the same columns in about a \
              third of the bytes, for pandas, polars or DuckDB)",
        out_value: "FILE.csv|FILE.json|FILE.parquet",
        repeatable: false,
        force: "Replace existing output files (--out, and a shard's --part summary)",
        json: Some("Print the summary as one JSON object instead of text"),
        sharded: true,
        engine: "The engine that steps the rolls; every roll's result is bit for bit the same with \
                 either, so this changes speed only",
    };
}

pub(crate) fn run(args: &BatchArgs) -> Result<(), CliError> {
    let options = args.run.options()?;
    if !args.versus.is_empty() {
        return run_versus(args, &options);
    }
    let sharding = args.run.sharding()?;
    let shard = sharding.as_ref().map(|(s, _)| *s);
    let (preset, params, given) = check_sweep(args, shard)?;
    let output = args.run.output(&["csv", "json", "parquet"])?;
    if sharding.is_some() && output.as_ref().is_some_and(|o| o.extension() == "json") {
        return Err(CliError::Usage(
            "--shard writes its records as .csv or .parquet (a JSON file cannot be merged as it streams)"
                .to_string(),
        ));
    }
    let seed = args.seed.unwrap_or(preset.random.seed);
    let sweep = BatchSweep::new(&preset, seed, given.as_deref(), args.rolls.unwrap_or(0), shard);
    let stop = cancel_on_ctrl_c()?;
    let bar = running::progress_bar(
        sweep.rolls().len(),
        "{bar:40} {pos}/{len} rolls, {per_sec}, {eta} left",
    );
    let (batch, written) = sweep
        .roll(&params, &options, &stop, output.as_ref(), &mut |n| bar.inc(n))
        .map_err(CliError::experiment(""))?;
    bar.finish_and_clear();
    if let Some((shard, part)) = &sharding {
        let records = args.run.out_path().zip(written);
        sweep
            .part(*shard, part.path(), records, &batch)
            .write(part)
            .map_err(CliError::output(""))?;
    }
    let mut out = std::io::stdout().lock();
    if args.run.json {
        let v = sweep.report(&batch);
        writeln!(out, "{v}")?;
    } else {
        tables::batch_run(&mut out, &batch)?;
    }
    out.flush()?;
    if batch.cancelled {
        return Err(CliError::Interrupted {
            completed: batch.completed,
            requested: batch.requested,
            what: "rolls",
        });
    }
    Ok(())
}

/// A batch's setup as checked: the preset, its parameters and the given starts if any.
pub(crate) type CheckedSweep = (
    Preset,
    dicesim_physics::Params,
    Option<Vec<(u64, InitialCondition)>>,
);

/// Everything about a batch's sweep that can be checked before any work, as a shard of it
/// (`shard`) would check it: the roll count, the setup, the random ranges' starts or every
/// row of `--ics`. `slurm` runs the same checks before it writes a script.
pub(crate) fn check_sweep(args: &BatchArgs, shard: Option<Shard>) -> Result<CheckedSweep, CliError> {
    // A shard keeps only its own rolls' records.
    let kept = args
        .rolls
        .map(|n| shard.map_or(n, |s| s.range(n).end - s.range(n).start));
    if let Some(n) = kept {
        BATCH_ROLLS.check(n).map_err(CliError::experiment(""))?;
    }
    let preset = args.setup.resolve()?;
    // A --set the starts replace is refused, not dropped.
    refuse_unapplied(&args.setup.set, |key| match &args.ics {
        None => unapplied_when_drawn(key, &preset.random, "batch")
            .or_else(|| seed_given(key, args.seed.is_some())),
        Some(_) => key
            .starts_with("random.")
            .then(|| "`batch --ics` rolls the file's starts; it draws no random throws".to_string()),
    })?;
    let params = preset.params();
    match &args.ics {
        None => check_drawn_setup(&params, &preset.random, &preset.initial)?,
        Some(_) => params.validate()?,
    }
    let given = match &args.ics {
        Some(path) => {
            let text = dicesim_setup::preset::read_regular_file(path, MAX_ICS_BYTES).map_err(|message| {
                CliError::Read {
                    flag: "--ics",
                    path: path.clone(),
                    source: std::io::Error::other(message),
                }
            })?;
            let ics = parse_initial_conditions(&text, &preset.initial, params.inertia())
                .map_err(CliError::experiment(&format!("--ics {}: ", path.display())))?;
            // The check `roll` makes of its one start, made of every row before any roll.
            for (id, ic) in &ics {
                ic.check_clear_of_table(&params).map_err(|e| {
                    CliError::Usage(format!(
                        "--ics {}: id {id}: {}",
                        path.display(),
                        e.to_string().replace("initial.", "")
                    ))
                })?;
            }
            Some(ics)
        }
        None => None,
    };
    Ok((preset, params, given))
}

/// `batch --versus`: the same throws in setup A (as given) and in B (with the `--versus`
/// values), A's ending against B's.
fn run_versus(args: &BatchArgs, options: &RunOptions) -> Result<(), CliError> {
    let (preset, params, given) = check_sweep(args, None)?;
    let twin = super::args::with_overrides(&preset, "--versus", &args.versus)?;
    // The throws are A's: a value of the throw itself would make the throws differ.
    if twin.initial != preset.initial || twin.random != preset.random {
        return Err(CliError::Usage(format!(
            "--versus {}: the throws are shared, so --versus changes the setup (die.*, ground.*, \
             world.*, integrator.*), not the throw (initial.*, random.*)",
            args.versus.join(" ")
        )));
    }
    let params_b = twin.params();
    if params_b == params {
        return Err(CliError::Usage(format!(
            "--versus {}: B is A itself (the setup already has these values), so every throw would \
             agree; give a value that differs from A's",
            args.versus.join(" ")
        )));
    }
    // B's body and its draws get A's check: a --versus body that cannot exist, or whose
    // drawn starts put a corner into the table, is refused in the words roll would use.
    if given.is_none() {
        check_drawn_setup(&params_b, &twin.random, &twin.initial)?;
    } else {
        params_b.validate()?;
    }
    let output = args.run.output(&["csv", "json"])?;
    let seed = args.seed.unwrap_or(preset.random.seed);
    let sweep =
        BatchSweep::new(&preset, seed, given.as_deref(), args.rolls.unwrap_or(0), None).against(&args.versus);
    let stop = cancel_on_ctrl_c()?;
    let bar = running::progress_bar(
        sweep.rolls().len(),
        "{bar:40} {pos}/{len} throws ×2, {per_sec}, {eta} left",
    );
    let csv = output.as_ref().filter(|o| o.extension() == "csv");
    let run = sweep
        .roll_versus((&params, &params_b), options, &stop, csv, &mut |n| bar.inc(n))
        .map_err(CliError::experiment(""))?;
    bar.finish_and_clear();
    let v = sweep.versus_report(&run);
    if let Some(output) = output.as_ref().filter(|o| o.extension() == "json") {
        output
            .write_bytes(format!("{v}\n").as_bytes())
            .map_err(CliError::output(""))?;
    }
    let mut out = std::io::stdout().lock();
    if args.run.json {
        writeln!(out, "{v}")?;
    } else {
        tables::versus(&mut out, &run, &preset.name, &args.versus)?;
    }
    out.flush()?;
    if run.cancelled {
        return Err(CliError::Interrupted {
            completed: run.completed,
            requested: run.requested,
            what: "throws",
        });
    }
    Ok(())
}
