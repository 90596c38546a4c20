//! `dicesim batch`: many rolls in parallel, per-roll results and their statistics.

use super::shard::{ShardArgs, batch_fingerprint, write_batch_part};
use super::{CliError, SetupArgs};
use crate::experiment::ics::{parse_initial_conditions, write_records_csv};
use crate::experiment::parquet::RecordsWriter;
use crate::experiment::shard::Sweep;
use crate::experiment::{Batch, BatchSummary, RollRecord, Rolls, run_batch};
use crate::output::Output;
use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use serde_json::json;
use std::io::{IsTerminal, Write};
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// The most rolls one batch takes: their records stay in memory (~1.5 GB at the limit).
pub(crate) const MAX_ROLLS: u64 = 10_000_000;

/// The largest `--ics` file read, bytes (about a million rows).
const MAX_ICS_BYTES: u64 = 256 * 1024 * 1024;

/// Exit status of a second Ctrl-C, which cannot wait for the error to reach `main`: as a
/// shell reports a SIGINT (128 + 2), the status `main` gives an interrupted batch.
const INTERRUPTED_AT_ONCE: i32 = 130;

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
    /// Replace an existing --out file.
    #[arg(long, requires = "out")]
    pub(crate) force: bool,
    /// Print the summary as one JSON object instead of text.
    #[arg(long)]
    pub(crate) json: bool,
    #[command(flatten)]
    pub(crate) shard: ShardArgs,
}

pub(crate) fn run(args: &BatchArgs) -> Result<(), CliError> {
    let jobs = super::checked_jobs(args.jobs)?;
    let sharding = args.shard.resolve(args.out.as_deref())?;
    // A shard keeps only its own rolls' records.
    let kept = args.rolls.map(|n| {
        sharding
            .as_ref()
            .map_or(n, |(s, _)| s.range(n).end - s.range(n).start)
    });
    if let Some(n) = kept
        && n > MAX_ROLLS
    {
        return Err(CliError::Usage(format!(
            "--rolls {n}: at most {MAX_ROLLS} per batch (every roll's record is kept for the summary and --out, \
             about {} bytes each); split it with --shard K/N",
            size_of::<RollRecord>()
        )));
    }
    let preset = args.setup.resolve()?;
    let params = preset.params();
    params.validate()?;
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
    let given = match &args.ics {
        Some(path) => {
            let text =
                crate::preset::read_regular_file(path, MAX_ICS_BYTES).map_err(|message| CliError::Read {
                    flag: "--ics",
                    path: path.clone(),
                    source: std::io::Error::other(message),
                })?;
            let ics = parse_initial_conditions(&text, &preset.initial, params.inertia())
                .map_err(CliError::experiment(&format!("--ics {}: ", path.display())))?;
            Some(ics)
        }
        None => None,
    };
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

    let stop = Arc::new(AtomicBool::new(false));
    let handler_stop = stop.clone();
    // The first Ctrl-C finishes the running chunk and keeps everything done; a second one
    // quits at once.
    ctrlc::set_handler(move || {
        if handler_stop.swap(true, Ordering::SeqCst) {
            std::process::exit(INTERRUPTED_AT_ONCE);
        }
    })
    .map_err(|e| CliError::Io(std::io::Error::other(format!("cannot catch Ctrl-C: {e}"))))?;

    let bar = if std::io::stderr().is_terminal() {
        ProgressBar::new(rolls.len())
    } else {
        ProgressBar::with_draw_target(Some(rolls.len()), ProgressDrawTarget::hidden())
    };
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} rolls, {per_sec}, {eta} left")
            .expect("the progress template is valid"),
    );
    let batch = run_batch(&params, &rolls, jobs, &stop, &mut |done: &[RollRecord]| {
        bar.set_position(done.len() as u64)
    })
    .map_err(CliError::experiment(""))?;
    bar.finish_and_clear();

    let summary = batch.summary();
    if let Some(output) = &output {
        output
            .write(|w| write_records(w, output.extension(), &batch, &summary, seed, given.is_some()))
            .map_err(CliError::output(""))?;
    }
    if let Some((shard, part)) = &sharding {
        let sweep = Sweep::Batch {
            preset: preset.name.clone(),
            fingerprint: batch_fingerprint(&preset, given.as_deref()),
            seed: given.is_none().then_some(seed),
            rolls: total,
        };
        write_batch_part(part, sweep, *shard, range, args.out.as_deref(), &batch)?;
    }
    let mut out = std::io::stdout().lock();
    if args.json {
        let v = json!({
            "preset": preset.name,
            "seed": if given.is_some() { None } else { Some(seed) },
            "requested": batch.requested,
            "completed": batch.records.len(),
            "interrupted": batch.cancelled,
            "jobs": batch.jobs,
            "summary": summary,
        });
        writeln!(out, "{v}")?;
    } else {
        print_summary(&mut out, &batch, &summary)?;
    }
    out.flush()?;
    if batch.cancelled {
        return Err(CliError::Interrupted {
            completed: batch.records.len(),
            requested: batch.requested,
        });
    }
    Ok(())
}

/// The per-roll file, as CSV or JSON by `extension`.
fn write_records(
    w: &mut (dyn Write + Send),
    extension: &str,
    batch: &Batch,
    summary: &BatchSummary,
    seed: u64,
    given: bool,
) -> std::io::Result<()> {
    match extension {
        "csv" => write_records_csv(&mut *w, &batch.records)?,
        "json" => {
            let v = json!({
                "seed": if given { None } else { Some(seed) },
                "requested": batch.requested,
                "interrupted": batch.cancelled,
                "summary": summary,
                "rolls": batch.records,
            });
            serde_json::to_writer(&mut *w, &v)?;
            writeln!(w)?;
        }
        _ => {
            let mut parquet = RecordsWriter::new(w).map_err(std::io::Error::other)?;
            for r in &batch.records {
                parquet.write(r).map_err(std::io::Error::other)?;
            }
            parquet.finish().map_err(std::io::Error::other)?;
        }
    }
    Ok(())
}

fn print_summary(out: &mut impl Write, batch: &Batch, s: &BatchSummary) -> std::io::Result<()> {
    writeln!(
        out,
        "{} rolls on {} thread{}",
        s.rolls,
        batch.jobs,
        if batch.jobs == 1 { "" } else { "s" }
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
    writeln!(out, "face   count   share")?;
    for f in 0..6 {
        writeln!(
            out,
            "{:>4} {:>7}  {:>5.1}%",
            f + 1,
            s.faces.counts[f],
            100.0 * s.face_shares[f]
        )?;
    }
    match (s.chi_square, s.p_value) {
        (Some(chi2), Some(p)) => writeln!(out, "χ² against a fair die  {chi2:.3} (5 dof), p = {p:.4}")?,
        _ => writeln!(out, "χ² against a fair die  n/a (no faces)")?,
    }
    let [same, adjacent, opposite] = s.start_face_shares.map(|x| 100.0 * x);
    writeln!(
        out,
        "from the start face    same {same:.1}%, adjacent {adjacent:.1}%, opposite {opposite:.1}%"
    )?;
    let st = &s.status;
    writeln!(
        out,
        "status                 settled {}, settled without a face {}, did not settle {}, unstable {}",
        st.settled, st.settled_without_face, st.timeout, st.unstable
    )?;
    Ok(())
}
