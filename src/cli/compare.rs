//! `dicesim compare`: the simulated die thrown as a historical experiment threw real ones,
//! held against its counts, and one setup value fitted to them.

use super::{CliError, EngineArg, SetupArgs};
use crate::experiment::RunOptions;
use crate::experiment::compare::{CompareSpec, Comparison, DEFAULT_CANDIDATES, FitSpec, run_comparison};
use crate::experiment::compare_plot::comparison_png;
use crate::experiment::compare_stats::FitMethod;
use crate::experiment::figure::setup_value;
use crate::experiment::plot::{Record, random_starts};
use crate::experiment::real_data::Dataset;
use clap::{Args, ValueEnum};
use std::io::Write;
use std::path::PathBuf;

/// The most rolls one comparison takes (throws × dice × candidates).
const MAX_ROLLS: u64 = 1_000_000_000;

/// The experiments a cubic die can be thrown against today.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum DatasetArg {
    /// Weldon's 26 306 throws of 12 dice, counted by how many showed a 5 or a 6 (1894).
    Weldon,
    /// Wolf's red die, 20 000 throws counted by face (about 1850).
    WolfRed,
    /// Wolf's white die, 20 000 throws counted by face (about 1850).
    WolfWhite,
}

impl DatasetArg {
    fn dataset(self) -> Dataset {
        match self {
            DatasetArg::Weldon => Dataset::Weldon,
            DatasetArg::WolfRed => Dataset::WolfRed,
            DatasetArg::WolfWhite => Dataset::WolfWhite,
        }
    }
}

#[derive(Debug, Args)]
pub(crate) struct CompareArgs {
    /// The experiment to throw the simulated die against.
    #[arg(value_enum)]
    pub(crate) dataset: DatasetArg,
    #[command(flatten)]
    pub(crate) setup: SetupArgs,
    /// Simulated throws by the experiment's protocol (12 dice a throw for Weldon), each die
    /// drawn from the preset's `[random]` ranges (default: as many as the experiment made).
    #[arg(long, visible_alias = "rolls", value_name = "N", value_parser = clap::value_parser!(u64).range(1..))]
    pub(crate) throws: Option<u64>,
    /// Seed of the random throws (default: the preset's `random.seed`).
    #[arg(long, value_name = "S")]
    pub(crate) seed: Option<u64>,
    /// Fit one setup value to the data: candidates evenly spaced from LO to HI, each rolled
    /// with the same throws, e.g. `ground.friction:0.2:1.2` or `die.extra_corner_mass.8:0:1`.
    #[arg(long, value_name = "KEY:LO:HI", allow_hyphen_values = true)]
    pub(crate) fit: Option<String>,
    /// Candidates of a fit (at least 20).
    #[arg(long, value_name = "N", default_value_t = DEFAULT_CANDIDATES, requires = "fit")]
    pub(crate) candidates: usize,
    /// Worker threads (default: one per core); the results do not depend on it.
    #[arg(long, value_name = "J", value_parser = clap::value_parser!(u64).range(1..))]
    pub(crate) jobs: Option<u64>,
    /// Write the comparison to a .csv, .json or .png file (repeatable: one of each, say).
    #[arg(long, value_name = "FILE.csv|FILE.json|FILE.png")]
    pub(crate) out: Vec<PathBuf>,
    /// Replace existing output files.
    #[arg(long)]
    pub(crate) force: bool,
    /// Print the result as one JSON object instead of text.
    #[arg(long)]
    pub(crate) json: bool,
    /// The engine that steps the rolls; the result is bit for bit the same with either.
    #[arg(long, value_enum, default_value_t = EngineArg::Auto)]
    pub(crate) engine: EngineArg,
}

pub(crate) fn run(args: &CompareArgs) -> Result<(), CliError> {
    let jobs = super::checked_jobs(args.jobs)?;
    let preset = args.setup.resolve()?;
    let params = preset.params();
    params.validate()?;
    // The same up-front start check as `batch`: no drawn throw may start inside the table.
    preset.random.check_clear_of_table(&params, &preset.initial)?;
    let dataset = args.dataset.dataset();
    let spec = CompareSpec {
        dataset,
        throws: args.throws.unwrap_or_else(|| dataset.data().total()),
        seed: args.seed.unwrap_or(preset.random.seed),
        fit: args
            .fit
            .as_deref()
            .map(|f| FitSpec::parse(f, args.candidates))
            .transpose()
            .map_err(CliError::experiment("--fit "))?,
    };
    spec.validate().map_err(CliError::experiment(""))?;
    let total = spec.total_rolls();
    if total > MAX_ROLLS {
        return Err(CliError::Usage(format!(
            "{total} rolls: at most {MAX_ROLLS} in one comparison (fewer --throws or --candidates)"
        )));
    }
    let outputs = super::checked_outputs(&args.out, &["csv", "json", "png"], args.force)?;

    let options = RunOptions {
        jobs,
        engine: args.engine.engine(),
    };
    let comparison = super::run_with_progress(
        total,
        "{bar:40} {pos}/{len} rolls, {per_sec}, {eta} left",
        |stop, done| {
            run_comparison(
                &params,
                &preset.random,
                &preset.initial,
                &spec,
                &options,
                stop,
                &mut |p| done(p.done),
            )
        },
    )?;

    // What defines the comparison, in every file it writes (never threads or time).
    let mut values = preset.as_written();
    values.random.seed = spec.seed;
    let provenance = serde_json::json!({
        "program": crate::experiment::PROGRAM,
        "preset": values,
        "dataset": dataset.name(),
        "seed": spec.seed,
        "throws": spec.throws,
        "fit": args.fit,
        "candidates": args.fit.as_ref().map(|_| args.candidates),
    });
    for output in &outputs {
        match output.extension() {
            "csv" => output.write(|w| {
                writeln!(w, "{}", super::shard::csv_provenance_line(&provenance))?;
                comparison.write_csv(w)
            }),
            "json" => output.write(|w| {
                let mut v = serde_json::to_value(&comparison)?;
                v["provenance"] = provenance.clone();
                serde_json::to_writer_pretty(&mut *w, &v)?;
                writeln!(w)
            }),
            _ => {
                let title = format!("{} against real dice", preset.name);
                // The caption names the setup whose throws are drawn: a fit's shown value.
                let (mut shown, mut initial) = (params, preset.initial);
                if let (Some(fit), Some(value)) = (&spec.fit, comparison.shown().and_then(|c| c.value)) {
                    fit.key.set(&mut shown, &mut initial, value);
                }
                // The throws are drawn from the random ranges: those define the figure.
                let fit = match (
                    &args.fit,
                    comparison.shown().and_then(|c| c.value),
                    &comparison.key,
                ) {
                    (Some(f), Some(v), Some(k)) => format!(
                        "; --fit {f} over {} candidates, drawn at the best, {k} = {}",
                        args.candidates,
                        setup_value(v)
                    ),
                    _ => String::new(),
                };
                let experiment = format!(
                    "{}: {} throws as {} threw them, each die {}{fit}",
                    preset.name,
                    spec.throws,
                    dataset.name(),
                    random_starts(&preset.random, spec.seed),
                );
                let record = Record::of_experiment(&title, experiment, &shown, &provenance);
                let png = comparison_png(&comparison, &record).map_err(CliError::experiment(""))?;
                output.write_bytes(&png)
            }
        }
        .map_err(CliError::output(""))?;
    }
    let mut out = std::io::stdout().lock();
    if args.json {
        serde_json::to_writer_pretty(&mut out, &comparison).map_err(std::io::Error::from)?;
        writeln!(out)?;
    } else {
        print_comparison(&mut out, &comparison, &preset.name)?;
        for path in &args.out {
            writeln!(out, "wrote {}", path.display())?;
        }
    }
    out.flush()?;
    if comparison.cancelled {
        let candidates = spec.fit.as_ref().map_or(1, |f| f.candidates as u64);
        let done: u64 = comparison.candidates.iter().map(|c| c.throws + c.uncounted).sum();
        return Err(CliError::Interrupted {
            completed: done,
            requested: spec.throws * candidates,
            what: if spec.fit.is_some() {
                "throws (whole candidates only)"
            } else {
                "throws"
            },
        });
    }
    Ok(())
}

/// A p-value as a person reads it: four decimals, or scientific notation when tiny.
fn p_text(p: f64) -> String {
    if p >= 1e-4 {
        format!("{p:.4}")
    } else {
        format!("{p:.2e}")
    }
}

fn print_comparison(out: &mut impl Write, c: &Comparison, preset: &str) -> std::io::Result<()> {
    writeln!(out, "{} ({})", c.dataset.name(), c.data.source)?;
    let fair = &c.data_against_fair;
    writeln!(
        out,
        "the real dice against a fair die: χ² {:.2} on {} dof, p = {}",
        fair.chi_square,
        fair.dof,
        p_text(fair.p_value)
    )?;
    if let (Some(fit), Some(key)) = (&c.fit, &c.key) {
        writeln!(
            out,
            "\nfit of {key}: {} candidates, each with the same {} throws (seed {})",
            c.candidates.len(),
            c.throws,
            c.seed
        )?;
        writeln!(
            out,
            "{:>12}  {:>10}  {:>8}  {:>4}  {:>9}",
            key.rsplit('.').next().unwrap_or(key),
            "deviance",
            "χ²",
            "dof",
            "p"
        )?;
        for k in &c.candidates {
            let (Some(value), Some(deviance)) = (k.value, k.deviance) else {
                continue;
            };
            let (chi2, dof, p) =
                k.test
                    .as_ref()
                    .map_or(("n/a".to_string(), String::new(), String::new()), |t| {
                        (
                            format!("{:.2}", t.chi_square),
                            t.dof.to_string(),
                            p_text(t.p_value),
                        )
                    });
            let mark = if Some(k) == c.shown() {
                " ← nearest the best"
            } else {
                ""
            };
            writeln!(
                out,
                "{value:>12.6}  {deviance:>10.2}  {chi2:>8}  {dof:>4}  {p:>9}{mark}"
            )?;
        }
        let side = |v: f64, open: bool, words: &str| {
            if open {
                format!("{words} {v}")
            } else {
                format!("{v:.6}")
            }
        };
        let how = match fit.method {
            FitMethod::Parabola => "on the least-squares parabola through the candidates' deviances",
            FitMethod::Candidates => "the best candidate; the deviances follow no upward parabola",
        };
        writeln!(
            out,
            "best {key} = {:.6} (deviance {:.2}, {how}); 95 % interval {} to {} (deviance within 3.84 of the best)",
            fit.best,
            fit.best_deviance,
            side(fit.low, fit.low_open, "the range's low end,"),
            side(fit.high, fit.high_open, "the range's high end,"),
        )?;
    }
    let Some(shown) = c.shown() else {
        return writeln!(out, "no simulated throws completed");
    };
    let value = match (&c.key, shown.value) {
        (Some(k), Some(v)) => format!(", {k} = {v}"),
        _ => String::new(),
    };
    writeln!(
        out,
        "\n{} real throws against {} simulated ({preset}{value}, seed {}); {} simulated throws not counted (a die ended without a face)",
        c.data.total(),
        shown.throws,
        c.seed,
        shown.uncounted
    )?;
    let rows = c.rows(shown);
    let Some(test) = &shown.test else {
        return writeln!(out, "too few simulated throws to test");
    };
    writeln!(
        out,
        "{:>10}  {:>7}  {:>6}  {:>13}  {:>9}  {:>6}  {:>13}  {:>8}",
        "category", "real", "share", "95% interval", "simulated", "share", "95% interval", "residual"
    )?;
    let pc = |x: f64| 100.0 * x;
    let interval = |i: [f64; 2]| format!("{:.2}–{:.2}%", pc(i[0]), pc(i[1]));
    for r in &rows {
        writeln!(
            out,
            "{:>10}  {:>7}  {:>5.2}%  {:>13}  {:>9}  {:>5.2}%  {:>13}  {:>+8.2}",
            r.category,
            r.data_count,
            pc(r.data_share),
            interval(r.data_interval),
            r.simulated_count,
            pc(r.simulated_share),
            interval(r.simulated_interval),
            r.residual
        )?;
    }
    writeln!(
        out,
        "χ² of the real against the simulated counts: {:.2} on {} dof, p = {}",
        test.chi_square,
        test.dof,
        p_text(test.p_value)
    )?;
    writeln!(
        out,
        "power of this comparison: {:.0}% for the difference measured (test at 5 %)",
        100.0 * test.power
    )?;
    match test.throws_to_detect {
        Some(n) => writeln!(
            out,
            "real throws that tell this model from the real die: {n} (80 % power, 5 %)"
        ),
        None => writeln!(
            out,
            "real throws that tell this model from the real die: — (no difference measured beyond chance)"
        ),
    }
}
