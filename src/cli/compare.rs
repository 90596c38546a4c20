//! `dicesim compare`: the simulated die thrown as a historical experiment threw real ones,
//! held against its counts, and one setup value fitted to them.

use super::{CliError, EngineArg, SetupArgs};
use clap::{Args, ValueEnum};
use dicesim_experiment::RunOptions;
use dicesim_experiment::compare::{CompareSpec, Comparison, DEFAULT_CANDIDATES, FitSpec, run_comparison};
use dicesim_experiment::compare_budden::{
    BuddenComparison, BuddenSpec, DEFAULT_CALIBRATE_ON, DEFAULT_FIT, RatioRole, hand_throw,
    run_budden as roll_budden,
};
use dicesim_experiment::compare_stats::{FitInterval, FitMethod};
use dicesim_experiment::real_data::Dataset;
use dicesim_figures::compare_plot::{budden_png, comparison_png};
use dicesim_figures::figure::setup_value;
use dicesim_figures::plot::{Record, random_starts};
use dicesim_setup::random::RandomDraws;
use std::io::Write;
use std::path::PathBuf;

/// The most rolls one comparison takes (throws × dice × candidates).
const MAX_ROLLS: u64 = 1_000_000_000;

/// The experiments the simulated die can be thrown against.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum DatasetArg {
    /// Weldon's 26 306 throws of 12 dice, counted by how many showed a 5 or a 6 (1894).
    Weldon,
    /// Wolf's red die, 20 000 throws counted by face (about 1850).
    WolfRed,
    /// Wolf's white die, 20 000 throws counted by face (about 1850).
    WolfWhite,
    /// Budden's steel cuboids, 15 ratios x/y, counted by square-face landings (1980).
    Budden,
}

impl DatasetArg {
    /// The cubic die's experiment (`None` for Budden's cuboids).
    fn dataset(self) -> Option<Dataset> {
        match self {
            DatasetArg::Weldon => Some(Dataset::Weldon),
            DatasetArg::WolfRed => Some(Dataset::WolfRed),
            DatasetArg::WolfWhite => Some(Dataset::WolfWhite),
            DatasetArg::Budden => None,
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
    /// Simulated throws by the experiment's protocol (12 dice a throw for Weldon; for
    /// Budden, throws of each ratio's cuboid), each die drawn from the preset's `[random]`
    /// ranges (default: as many as the experiment made, for Budden ratio by ratio).
    #[arg(long, visible_alias = "rolls", value_name = "N", value_parser = clap::value_parser!(u64).range(1..))]
    pub(crate) throws: Option<u64>,
    /// Seed of the random throws (default: the preset's `random.seed`).
    #[arg(long, value_name = "S")]
    pub(crate) seed: Option<u64>,
    /// Fit one setup value to the data: candidates evenly spaced from LO to HI, each rolled
    /// with the same throws, e.g. `ground.friction:0.2:1.2` or `die.extra_corner_mass.8:0:1`
    /// (Budden always fits; default `ground.damping:0:0.05`).
    #[arg(long, value_name = "KEY:LO:HI", allow_hyphen_values = true)]
    pub(crate) fit: Option<String>,
    /// Candidates of a fit (at least 20; default 21).
    #[arg(long, value_name = "N")]
    pub(crate) candidates: Option<usize>,
    /// Budden only: the ratios x/y the fit uses (the others are predicted with the best
    /// value, out of sample).
    #[arg(long, value_name = "R,R,…", value_delimiter = ',', default_values_t = DEFAULT_CALIBRATE_ON)]
    pub(crate) calibrate_on: Vec<f64>,
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
    let candidates = args.candidates.unwrap_or(DEFAULT_CANDIDATES);
    let Some(dataset) = args.dataset.dataset() else {
        return run_budden(args, jobs, &preset, candidates);
    };
    if args.calibrate_on != DEFAULT_CALIBRATE_ON {
        return Err(CliError::Usage(
            "--calibrate-on chooses Budden's ratios: it is for `compare budden` only".to_string(),
        ));
    }
    if args.candidates.is_some() && args.fit.is_none() {
        return Err(CliError::Usage(
            "--candidates counts a fit's values: give --fit KEY:LO:HI".to_string(),
        ));
    }
    let spec = CompareSpec {
        dataset,
        throws: args.throws.unwrap_or_else(|| dataset.data().total()),
        seed: args.seed.unwrap_or(preset.random.seed),
        fit: args
            .fit
            .as_deref()
            .map(|f| FitSpec::parse(f, candidates))
            .transpose()
            .map_err(CliError::experiment("--fit "))?,
    };
    spec.validate().map_err(CliError::experiment(""))?;
    let total = spec.total_rolls();
    let (outputs, options) = prepare(args, jobs, total)?;
    let comparison = super::run_with_progress(total, PROGRESS, |stop, done| {
        run_comparison(
            &params,
            &preset.random,
            &preset.initial,
            &spec,
            &options,
            stop,
            &mut |p| done(p.done),
        )
    })?;

    // What defines the comparison, in every file it writes (never threads or time).
    let mut values = preset.as_written();
    values.random.seed = spec.seed;
    let provenance = serde_json::json!({
        "program": dicesim_experiment::PROGRAM,
        "preset": values,
        "dataset": dataset.name(),
        "seed": spec.seed,
        "throws": spec.throws,
        "fit": args.fit,
        "candidates": args.fit.as_ref().map(|_| candidates),
    });
    let png = || {
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
                candidates,
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
        comparison_png(&comparison, &record).map_err(CliError::experiment(""))
    };
    super::write_results(
        &outputs,
        args.json,
        super::Results {
            value: &comparison,
            provenance: &provenance,
            csv: &|w| comparison.write_csv(w),
            png: &png,
            table: &|out| print_comparison(out, &comparison, &preset.name),
        },
    )?;
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

fn print_comparison(out: &mut dyn Write, c: &Comparison, preset: &str) -> std::io::Result<()> {
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
        print_fit_line(out, key, fit)?;
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

/// How a comparison's progress bar reads.
const PROGRESS: &str = "{bar:40} {pos}/{len} rolls, {per_sec}, {eta} left";

/// Before any roll, as both kinds of comparison check it: the size within bounds and every
/// `--out` file writable; then how the rolls are run.
fn prepare(
    args: &CompareArgs,
    jobs: usize,
    total: u64,
) -> Result<(Vec<dicesim_setup::output::Output>, RunOptions), CliError> {
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
    Ok((outputs, options))
}

/// `dicesim compare budden`: the fit on the calibration ratios, then every ratio predicted.
fn run_budden(
    args: &CompareArgs,
    jobs: usize,
    preset: &dicesim_setup::preset::Preset,
    candidates: usize,
) -> Result<(), CliError> {
    let params = preset.params();
    let fit_text = args.fit.as_deref().unwrap_or(DEFAULT_FIT);
    let spec = BuddenSpec {
        throws: args.throws,
        seed: args.seed.unwrap_or(preset.random.seed),
        fit: FitSpec::parse(fit_text, candidates).map_err(CliError::experiment("--fit "))?,
        calibrate_on: args.calibrate_on.clone(),
    };
    spec.validate().map_err(CliError::experiment(""))?;
    let total = spec.total_rolls();
    let (outputs, options) = prepare(args, jobs, total)?;
    let comparison = super::run_with_progress(total, PROGRESS, |stop, done| {
        roll_budden(
            &params,
            &preset.random,
            &preset.initial,
            &spec,
            &options,
            stop,
            &mut |p| done(p.done),
        )
    })?;
    // The throw as rolled: the preset's ranges from a uniformly random orientation.
    let mut values = preset.as_written();
    values.random = hand_throw(&values.random);
    values.random.seed = spec.seed;
    let provenance = serde_json::json!({
        "program": dicesim_experiment::PROGRAM,
        "preset": values,
        "dataset": "budden",
        "seed": spec.seed,
        "throws": spec.throws,
        "fit": fit_text,
        "candidates": candidates,
        "calibrate_on": spec.calibrate_on,
    });
    let png = || {
        let record = budden_record(&comparison, preset, &spec, fit_text, &provenance);
        budden_png(&comparison, &record).map_err(CliError::experiment(""))
    };
    super::write_results(
        &outputs,
        args.json,
        super::Results {
            value: &comparison,
            provenance: &provenance,
            csv: &|w| comparison.write_csv(w),
            png: &png,
            table: &|out| print_budden(out, &comparison, &preset.name),
        },
    )?;
    if comparison.cancelled {
        let done: u64 = comparison
            .candidates
            .iter()
            .flat_map(|c| &c.ratios)
            .chain(comparison.ratios.iter().map(|r| &r.simulated))
            .map(|t| t.throws + t.uncounted)
            .sum();
        return Err(CliError::Interrupted {
            completed: done,
            requested: total,
            what: "throws (whole ratios of whole candidates only)",
        });
    }
    Ok(())
}

/// The PNG's caption: the throw, the fit, and the table and body assumptions.
fn budden_record(
    c: &BuddenComparison,
    preset: &dicesim_setup::preset::Preset,
    spec: &BuddenSpec,
    fit_text: &str,
    provenance: &serde_json::Value,
) -> Record {
    let n = setup_value;
    let throws = spec
        .throws
        .map_or("Budden's own throws per ratio".to_string(), |t| {
            format!("{t} throws per ratio")
        });
    let best = c.fit.as_ref().map_or(String::new(), |f| {
        format!(", drawn at the best, {} = {}", c.key, n(f.best))
    });
    // The table and world as the throws were drawn: with the fitted value at its best.
    let (mut p, mut initial) = (preset.params(), preset.initial);
    if let Some(f) = &c.fit {
        spec.fit.key.set(&mut p, &mut initial, f.best);
    }
    let caption = vec![
        format!(
            "{}: {throws}, each {}; --fit {fit_text} over {} candidates on ratios {}{best}",
            preset.name,
            random_starts(&hand_throw(&preset.random), spec.seed),
            spec.fit.candidates,
            spec.calibrate_on
                .iter()
                .map(|r| n(*r))
                .collect::<Vec<_>>()
                .join(", "),
        ),
        format!(
            "{}; table k {} dyn/cm, γ {} s/cm, μ {}; g {} cm/s², Δt {} s (every value in the file's dicesim-provenance text)",
            c.assumptions[..2].join("; "),
            n(p.ground.stiffness),
            n(p.ground.damping),
            n(p.ground.friction),
            n(p.world.gravity),
            n(p.integrator.dt),
        ),
    ];
    Record {
        text: vec![
            ("Title".to_string(), format!("{}: Budden's cuboids", preset.name)),
            ("Description".to_string(), caption.join("\n")),
            ("Software".to_string(), dicesim_experiment::PROGRAM.to_string()),
        ],
        caption,
    }
    .with_provenance(provenance)
}

/// A fit's best value and its 95 % interval (an end that reached the range's edge said so).
fn print_fit_line(out: &mut dyn Write, key: &str, fit: &FitInterval) -> std::io::Result<()> {
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
    )
}

fn print_budden(out: &mut dyn Write, c: &BuddenComparison, preset: &str) -> std::io::Result<()> {
    writeln!(out, "budden ({})", c.source)?;
    for a in &c.assumptions {
        writeln!(out, "assumed: {a}")?;
    }
    let ratios = |rs: &[f64]| {
        rs.iter()
            .map(|r| format!("{r:.2}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    writeln!(
        out,
        "\nfit of {} on ratios {}: {} candidates, each with the same throws (seed {})",
        c.key,
        ratios(&c.calibrate_on),
        c.candidates.len(),
        c.seed
    )?;
    let short = c.key.rsplit('.').next().unwrap_or(&c.key);
    writeln!(out, "{short:>12}  {:>10}  square share by ratio", "deviance")?;
    for k in &c.candidates {
        let shares: Vec<String> = k
            .ratios
            .iter()
            .map(|t| format!("{:.2}: {:.3}", t.ratio, t.square as f64 / t.throws.max(1) as f64))
            .collect();
        writeln!(
            out,
            "{:>12.6}  {:>10.2}  {}",
            k.value,
            k.deviance,
            shares.join("  ")
        )?;
    }
    let Some(fit) = &c.fit else {
        return writeln!(out, "no fit: too few candidates completed");
    };
    print_fit_line(out, &c.key, fit)?;
    writeln!(
        out,
        "\nevery ratio thrown with {} = {:.6} ({preset}, seed {}): Budden's share of square-face landings beside the simulation's",
        c.key, fit.best, c.seed
    )?;
    writeln!(
        out,
        "{:>5}  {:>9}  {:>6}  {:>6}  {:>11}  {:>6}  {:>6}  {:>11}  {:>6}  within 2σ",
        "x/y", "role", "real n", "share", "95% interval", "sim n", "share", "95% interval", "z (σ)"
    )?;
    let interval = |i: [f64; 2]| format!("{:.3}–{:.3}", i[0], i[1]);
    for r in &c.ratios {
        let s = &r.shares;
        writeln!(
            out,
            "{:>5.2}  {:>9}  {:>6}  {:>6.3}  {:>11}  {:>6}  {:>6.3}  {:>11}  {:>+6.2}  {}",
            r.ratio,
            match r.role {
                RatioRole::Calibrate => "calibrate",
                RatioRole::Predict => "predict",
            },
            r.data_throws,
            s.data_share,
            interval(s.data_interval),
            r.simulated.throws,
            s.simulated_share,
            interval(s.simulated_interval),
            s.z,
            if s.within_two_sigma() { "yes" } else { "no" }
        )?;
    }
    let uncounted: u64 = c.ratios.iter().map(|r| r.simulated.uncounted).sum();
    writeln!(
        out,
        "{uncounted} simulated throws not counted (the cuboid ended without a face)"
    )?;
    for (words, summary) in [
        ("calibration ratios (in sample)", &c.calibrated),
        ("predicted ratios (out of sample)", &c.predicted),
        ("all ratios", &c.all),
    ] {
        if let Some(s) = summary {
            writeln!(
                out,
                "{words}: {} of {} within 2σ; χ² {:.2} on {} dof, p = {}",
                s.within_two_sigma,
                s.shares,
                s.chi_square,
                s.shares,
                p_text(s.p_value)
            )?;
        }
    }
    Ok(())
}
