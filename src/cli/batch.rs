//! `dicesim batch`: many rolls in parallel, per-roll results and their statistics.

use super::shard::{
    Hashing, ShardArgs, batch_fingerprint, batch_provenance, csv_provenance_line, write_batch_part,
};
use super::{CliError, EngineArg, SetupArgs, cancel_on_ctrl_c};
use clap::Args;
use dicesim_experiment::csv_io;
use dicesim_experiment::ending::Ending;
use dicesim_experiment::ics::{parse_initial_conditions, record_csv_row, records_csv_header};
use dicesim_experiment::parquet::RecordsWriter;
use dicesim_experiment::shard::Shard;
use dicesim_experiment::shard::Sweep;
use dicesim_experiment::versus::{NO_FACE, VersusRun, stream_versus};
use dicesim_experiment::{BatchRun, BatchSummary, RollRecord, Rolls, RunOptions, stream_batch};
use dicesim_physics::InitialCondition;
use dicesim_setup::number::fmt_num;
use dicesim_setup::output::Output;
use dicesim_setup::preset::Preset;
use dicesim_setup::random::RandomDraws;
use serde_json::json;
use std::io::Write;
use std::path::PathBuf;

/// The most rolls one batch takes. Records stream to `--out` as they complete, so memory
/// does not grow with the batch; past this a batch is years of core time, a typo more
/// likely than a plan, and a sweep that size belongs on many machines (`--shard`).
pub(crate) const MAX_ROLLS: u64 = 100_000_000_000;

/// The largest `--ics` file read, bytes (about a million rows).
const MAX_ICS_BYTES: u64 = 256 * 1024 * 1024;

#[derive(Debug, Args)]
pub(crate) struct BatchArgs {
    #[command(flatten)]
    pub(crate) setup: SetupArgs,
    /// Roll N dice with initial conditions drawn from the preset's `[random]` ranges.
    #[arg(
        long,
        value_name = "N",
        required_unless_present = "ics",
        conflicts_with = "ics"
    )]
    pub(crate) rolls: Option<u64>,
    /// Roll the initial conditions of a CSV file: a header with `id` and any of height,
    /// velocity_x|y|z, angular_velocity_x|y|z, angular_momentum_x|y|z, yaw, pitch, roll
    /// (missing columns take the preset's initial values).
    #[arg(long, value_name = "FILE.csv")]
    pub(crate) ics: Option<PathBuf>,
    /// Seed of the random draws (default: the preset's `random.seed`); roll i's draw depends
    /// on (seed, i) alone.
    #[arg(long, value_name = "S", conflicts_with = "ics")]
    pub(crate) seed: Option<u64>,
    /// Worker threads (default: one per core); the results do not depend on it.
    #[arg(long, value_name = "J", value_parser = clap::value_parser!(u64).range(1..))]
    pub(crate) jobs: Option<u64>,
    /// Write every roll (id, initial condition, start face, face, status, steps, simulated
    /// seconds) to a .csv, .json or .parquet file (Parquet: the same columns in about a
    /// third of the bytes, for pandas, polars or DuckDB).
    #[arg(long, value_name = "FILE.csv|FILE.json|FILE.parquet")]
    pub(crate) out: Option<PathBuf>,
    /// Replace existing output files (--out, and a shard's --part summary).
    #[arg(long)]
    pub(crate) force: bool,
    /// Print the summary as one JSON object instead of text.
    #[arg(long)]
    pub(crate) json: bool,
    #[command(flatten)]
    pub(crate) shard: ShardArgs,
    /// The engine that steps the rolls; every roll's result is bit for bit the same with
    /// either, so this changes speed only.
    #[arg(long, value_enum, default_value_t = EngineArg::Auto)]
    pub(crate) engine: EngineArg,
    /// Roll every throw twice: in setup A (as given) and in setup B, A with this value
    /// changed (a `--set` key of the die, ground, world or integrator; repeatable). Prints
    /// the table of A's face against B's and the share of throws that agree; --out writes
    /// each throw's two outcomes (.csv) or the figures (.json).
    #[arg(long, value_name = "KEY=VALUE", conflicts_with = "shard")]
    pub(crate) versus: Vec<String>,
}

pub(crate) fn run(args: &BatchArgs) -> Result<(), CliError> {
    let jobs = super::checked_jobs(args.jobs)?;
    if !args.versus.is_empty() {
        return run_versus(args, jobs);
    }
    let sharding = args.shard.resolve(args.out.as_deref(), args.force)?;
    let (preset, params, given) = check_sweep(args, sharding.as_ref().map(|(s, _)| *s))?;
    let output = args
        .out
        .as_deref()
        .map(|p| Output::check(p, &["csv", "json", "parquet"], args.force))
        .transpose()
        .map_err(CliError::output("--out "))?;
    if sharding.is_some() && output.as_ref().is_some_and(|o| o.extension() == "json") {
        return Err(CliError::Usage(
            "--shard writes its records as .csv or .parquet (a JSON file cannot be merged as it streams)"
                .to_string(),
        ));
    }
    let seed = args.seed.unwrap_or(preset.random.seed);
    let total = given
        .as_ref()
        .map_or(args.rolls.unwrap_or(0), |ics| ics.len() as u64);
    let range = sharding
        .as_ref()
        .map_or(0..total, |(shard, _)| shard.range(total));
    let rolls = match &given {
        Some(ics) => Rolls::Given(&ics[range.start as usize..range.end as usize]),
        None => Rolls::Random {
            ranges: &preset.random,
            base: &preset.initial,
            seed,
            first: range.start,
            count: range.end - range.start,
        },
    };

    let stop = cancel_on_ctrl_c()?;
    let options = RunOptions {
        jobs,
        engine: args.engine.engine(),
    };
    let bar = super::progress_bar(rolls.len(), "{bar:40} {pos}/{len} rolls, {per_sec}, {eta} left");
    let seed_field = given.is_none().then_some(seed);
    let fingerprint = batch_fingerprint(&preset, given.as_deref());
    let provenance = batch_provenance(
        &preset,
        seed_field,
        total,
        given.is_some().then_some(fingerprint.as_str()),
    );
    let mut written = None;
    let mut run = None;
    // The sink's own I/O error, kept whole (the engine only carries its words).
    let write_error = std::cell::RefCell::new(None);
    let roll = |sink: &mut dyn FnMut(&[RollRecord]) -> std::io::Result<()>| {
        stream_batch(&params, &rolls, &options, &stop, &mut |chunk: &[RollRecord]| {
            bar.inc(chunk.len() as u64);
            sink(chunk).map_err(|e| {
                let words = e.to_string();
                *write_error.borrow_mut() = Some(e);
                words
            })
        })
    };
    // Records go to the file as they arrive, so memory stays flat in the number of rolls;
    // the file appears under its name only once it is whole (or an interrupted prefix).
    match &output {
        Some(output) => output
            .write(|w| {
                let mut hashing = Hashing::new(w);
                let mut records = RecordsFile::start(
                    &mut hashing,
                    output.extension(),
                    &provenance,
                    seed_field,
                    rolls.len(),
                )?;
                let done = roll(&mut |chunk| records.write(chunk));
                let batch = done.map_err(|e| match write_error.borrow_mut().take() {
                    Some(io) => io,
                    None => std::io::Error::other(e.to_string()),
                })?;
                records.finish(&batch)?;
                written = Some(hashing.seal());
                run = Some(batch);
                Ok(())
            })
            .map_err(CliError::output(""))?,
        None => run = Some(roll(&mut |_| Ok(())).map_err(CliError::experiment(""))?),
    }
    let batch = run.expect("the batch ran");
    bar.finish_and_clear();
    let summary = &batch.summary;
    if let Some((shard, part)) = &sharding {
        let sweep = Sweep::Batch {
            preset: preset.name.clone(),
            fingerprint,
            seed: seed_field,
            rolls: total,
        };
        let mut setup = preset.clone();
        setup.random.seed = seed;
        let records = args.out.as_deref().zip(written);
        write_batch_part(part, sweep, *shard, range, records, &setup, &batch)?;
    }
    let mut out = std::io::stdout().lock();
    if args.json {
        let v = json!({
            "preset": preset.name,
            "seed": seed_field,
            "requested": batch.requested,
            "completed": batch.completed,
            "interrupted": batch.cancelled,
            "jobs": batch.jobs,
            "engine": batch.engine,
            "summary": summary,
        });
        writeln!(out, "{v}")?;
    } else {
        print_summary(&mut out, &batch, summary)?;
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
    if let Some(n) = kept
        && n > MAX_ROLLS
    {
        return Err(CliError::Usage(format!(
            "--rolls {n}: at most {MAX_ROLLS} per batch; split a sweep this large over machines with --shard K/N"
        )));
    }
    let preset = args.setup.resolve()?;
    let params = preset.params();
    params.validate()?;
    if args.ics.is_none() {
        preset.random.check_clear_of_table(&params, &preset.initial)?;
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

/// The per-roll file as the records arrive: CSV, JSON or Parquet by extension. JSON puts
/// the rolls first and what is known only at the end (interrupted, summary) after them.
enum RecordsFile<'w> {
    Csv(csv::Writer<&'w mut (dyn Write + Send)>),
    Json {
        w: &'w mut (dyn Write + Send),
        first: bool,
    },
    Parquet(RecordsWriter<&'w mut (dyn Write + Send)>),
}

impl<'w> RecordsFile<'w> {
    /// Starts the file with its provenance: a leading `#` comment line in CSV (which
    /// `--ics` and `merge` read past), a field in JSON, key-value metadata in Parquet.
    fn start(
        w: &'w mut (dyn Write + Send),
        extension: &str,
        provenance: &serde_json::Value,
        seed: Option<u64>,
        requested: u64,
    ) -> std::io::Result<Self> {
        Ok(match extension {
            "csv" => {
                writeln!(w, "{}", csv_provenance_line(provenance))?;
                let mut csv = csv::Writer::from_writer(w);
                csv.write_record(records_csv_header()).map_err(csv_io)?;
                RecordsFile::Csv(csv)
            }
            "json" => {
                write!(
                    w,
                    "{{\"provenance\":{provenance},\"seed\":{},\"requested\":{requested},\"rolls\":[",
                    json!(seed)
                )?;
                RecordsFile::Json { w, first: true }
            }
            _ => RecordsFile::Parquet(
                RecordsWriter::new(w, &provenance.to_string()).map_err(std::io::Error::other)?,
            ),
        })
    }

    fn write(&mut self, records: &[RollRecord]) -> std::io::Result<()> {
        match self {
            RecordsFile::Csv(csv) => {
                for r in records {
                    csv.write_record(record_csv_row(r)).map_err(csv_io)?;
                }
            }
            RecordsFile::Json { w, first } => {
                for r in records {
                    if !std::mem::take(first) {
                        w.write_all(b",")?;
                    }
                    serde_json::to_writer(&mut **w, r)?;
                }
            }
            RecordsFile::Parquet(parquet) => {
                for r in records {
                    parquet.write(r).map_err(std::io::Error::other)?;
                }
            }
        }
        Ok(())
    }

    fn finish(self, batch: &BatchRun) -> std::io::Result<()> {
        match self {
            RecordsFile::Csv(mut csv) => csv.flush(),
            RecordsFile::Json { w, .. } => writeln!(
                w,
                "],\"interrupted\":{},\"summary\":{}}}",
                batch.cancelled,
                json!(batch.summary)
            ),
            RecordsFile::Parquet(parquet) => parquet.finish().map(drop).map_err(std::io::Error::other),
        }
    }
}

fn print_summary(out: &mut impl Write, batch: &BatchRun, s: &BatchSummary) -> std::io::Result<()> {
    writeln!(
        out,
        "{} rolls on {} thread{}, {} engine",
        s.rolls,
        batch.jobs,
        if batch.jobs == 1 { "" } else { "s" },
        batch.engine.name()
    )?;
    print_counts(out, s)?;
    writeln!(
        out,
        "speed                  {:.0} rolls/s, {:.1} M steps/s ({} steps in {:.2} s)",
        s.rolls_per_s,
        s.steps_per_s / 1e6,
        s.steps,
        s.elapsed_s
    )?;
    Ok(())
}

/// The summary's lines that depend on the rolls alone (not on threads or time), as `batch`
/// and `merge` print them.
pub(super) fn print_counts(out: &mut impl Write, s: &BatchSummary) -> std::io::Result<()> {
    writeln!(out, "face   count   share   95% interval")?;
    for f in 0..6 {
        let [low, high] = s.face_intervals[f].map(|x| 100.0 * x);
        writeln!(
            out,
            "{:>4} {:>7}  {:>5.1}%  {low:>5.1}–{high:.1}%",
            f + 1,
            s.faces.counts[f],
            100.0 * s.face_shares[f]
        )?;
    }
    match (s.chi_square, s.p_value) {
        // p as the explorer prints it (three significant digits, 6.02e-28 rather than 0.0000).
        (Some(chi2), Some(p)) => writeln!(
            out,
            "χ² against a fair die  {chi2:.3} (5 dof), p = {}",
            fmt_num(p)
        )?,
        _ => writeln!(out, "χ² against a fair die  n/a (no faces)")?,
    }
    match s.rolls_to_detect {
        Some(n) => writeln!(
            out,
            "bias detectable in     {n} rolls (χ² at 5 %, 80 % power, for the bias measured here)"
        )?,
        None if s.chi_square.is_some() => {
            writeln!(out, "bias detectable in     — (no bias measured beyond chance)")?
        }
        None => {}
    }
    let [same, adjacent, opposite] = s.start_face_shares.map(|x| 100.0 * x);
    writeln!(
        out,
        "from the start face    same {same:.1}%, adjacent {adjacent:.1}%, opposite {opposite:.1}%"
    )?;
    let st = &s.status;
    writeln!(
        out,
        "status                 settled {}, {} {}, {} {}, {} {}",
        st.settled,
        Ending::WithoutFace.name(),
        st.settled_without_face,
        Ending::DidNotSettle.name(),
        st.timeout,
        Ending::Unstable.name(),
        st.unstable
    )?;
    Ok(())
}

/// `batch --versus`: the same throws in setup A (as given) and in B (with the `--versus`
/// values), A's ending against B's.
fn run_versus(args: &BatchArgs, jobs: usize) -> Result<(), CliError> {
    let (preset, params, given) = check_sweep(args, None)?;
    let twin = preset.with_overrides(&args.versus)?;
    // The throws are A's: a value of the throw itself would make the throws differ.
    if twin.initial != preset.initial || twin.random != preset.random {
        return Err(CliError::Usage(format!(
            "--versus {}: the throws are shared, so --versus changes the setup (die.*, ground.*, \
             world.*, integrator.*), not the throw (initial.*, random.*)",
            args.versus.join(" ")
        )));
    }
    let params_b = twin.params();
    params_b.validate()?;
    let output = args
        .out
        .as_deref()
        .map(|p| Output::check(p, &["csv", "json"], args.force))
        .transpose()
        .map_err(CliError::output("--out "))?;
    let seed = args.seed.unwrap_or(preset.random.seed);
    let rolls = match &given {
        Some(ics) => Rolls::Given(ics),
        None => Rolls::Random {
            ranges: &preset.random,
            base: &preset.initial,
            seed,
            first: 0,
            count: args.rolls.unwrap_or(0),
        },
    };
    let seed_field = given.is_none().then_some(seed);
    let fingerprint = batch_fingerprint(&preset, given.as_deref());
    let mut provenance = batch_provenance(
        &preset,
        seed_field,
        rolls.len(),
        given.is_some().then_some(fingerprint.as_str()),
    );
    provenance["versus"] = json!(args.versus);
    let options = RunOptions {
        jobs,
        engine: args.engine.engine(),
    };
    let stop = cancel_on_ctrl_c()?;
    let bar = super::progress_bar(
        rolls.len(),
        "{bar:40} {pos}/{len} throws ×2, {per_sec}, {eta} left",
    );
    let write_error = std::cell::RefCell::new(None);
    let roll = |sink: &mut dyn FnMut(&[RollRecord]) -> std::io::Result<()>| {
        stream_versus(
            &params,
            &params_b,
            &rolls,
            &options,
            &stop,
            &mut |chunk: &[RollRecord]| {
                bar.inc(chunk.len() as u64 / 2);
                sink(chunk).map_err(|e| {
                    let words = e.to_string();
                    *write_error.borrow_mut() = Some(e);
                    words
                })
            },
        )
    };
    let figures = |run: &VersusRun| {
        json!({
            "preset": preset.name,
            "versus": args.versus,
            "seed": seed_field,
            "requested": run.requested,
            "completed": run.completed,
            "interrupted": run.cancelled,
            "jobs": run.jobs,
            "engine": run.engine,
        })
    };
    let run = match &output {
        Some(output) if output.extension() == "csv" => {
            let mut run = None;
            output
                .write(|w| {
                    writeln!(w, "{}", csv_provenance_line(&provenance))?;
                    let mut csv = csv::Writer::from_writer(w);
                    csv.write_record(versus_csv_header()).map_err(csv_io)?;
                    let done = roll(&mut |chunk| {
                        for pair in chunk.chunks_exact(2) {
                            csv.write_record(versus_csv_row(&pair[0], &pair[1]))
                                .map_err(csv_io)?;
                        }
                        Ok(())
                    });
                    let done = done.map_err(|e| match write_error.borrow_mut().take() {
                        Some(io) => io,
                        None => std::io::Error::other(e.to_string()),
                    })?;
                    csv.flush()?;
                    run = Some(done);
                    Ok(())
                })
                .map_err(CliError::output(""))?;
            run.expect("the throws were rolled")
        }
        _ => roll(&mut |_| Ok(())).map_err(CliError::experiment(""))?,
    };
    bar.finish_and_clear();
    let mut v = figures(&run);
    let summary = json!(run.table.summary());
    for (key, value) in summary.as_object().expect("a struct") {
        v[key] = value.clone();
    }
    if let Some(output) = output.as_ref().filter(|o| o.extension() == "json") {
        v["provenance"] = provenance.clone();
        output
            .write_bytes(format!("{v}\n").as_bytes())
            .map_err(CliError::output(""))?;
    }
    let mut out = std::io::stdout().lock();
    if args.json {
        writeln!(out, "{v}")?;
    } else {
        print_versus(&mut out, &run, &preset.name, &args.versus)?;
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

/// The per-throw CSV of `--versus`: the throw (id, initial condition, start face) and each
/// setup's ending, A's columns `a_…`, B's `b_…`.
fn versus_csv_header() -> Vec<String> {
    let header = records_csv_header();
    let (throw, ending) = header.split_at(header.len() - VERSUS_ENDING_COLUMNS);
    let mut h: Vec<String> = throw.iter().map(|c| c.to_string()).collect();
    for side in ["a", "b"] {
        h.extend(ending.iter().map(|c| format!("{side}_{c}")));
    }
    h
}

/// Columns of a roll's record that are its ending: face, status, steps, time_s.
const VERSUS_ENDING_COLUMNS: usize = 4;

fn versus_csv_row(a: &RollRecord, b: &RollRecord) -> Vec<String> {
    let mut row = record_csv_row(a);
    let b = record_csv_row(b);
    row.extend_from_slice(&b[b.len() - VERSUS_ENDING_COLUMNS..]);
    row
}

/// The table and the share that agree, as text.
fn print_versus(
    out: &mut impl Write,
    run: &VersusRun,
    preset: &str,
    versus: &[String],
) -> std::io::Result<()> {
    let t = &run.table;
    writeln!(
        out,
        "{} throws in A ({preset} as given) and B (A with {}), {} thread{}, {} engine",
        t.throws(),
        versus.join(" "),
        run.jobs,
        if run.jobs == 1 { "" } else { "s" },
        run.engine.name()
    )?;
    writeln!(out, "A \\ B     1      2      3      4      5      6  none")?;
    for (a, row) in t.counts.iter().enumerate() {
        let name = if a == NO_FACE {
            "none".to_string()
        } else {
            (a + 1).to_string()
        };
        write!(out, "{name:>5}")?;
        for count in row {
            write!(out, " {count:>6}")?;
        }
        writeln!(out)?;
    }
    match t.agreement() {
        Some((share, [low, high])) => writeln!(
            out,
            "agreement  {:.1}% ({} of {}), 95% interval {:.1}–{:.1}%",
            100.0 * share,
            t.agreeing(),
            t.faced(),
            100.0 * low,
            100.0 * high
        )?,
        None => writeln!(out, "agreement  none: no throw ended on a face in both setups")?,
    }
    writeln!(
        out,
        "           over the throws ending on a face in both; {} ended on no face in A or B (\"none\")",
        t.throws() - t.faced()
    )?;
    Ok(())
}
