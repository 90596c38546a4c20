//! `dicesim predict`: how precisely a throw must be known to predict its face.

use super::{CliError, EngineArg, SetupArgs};
use clap::Args;
use dicesim_experiment::predict::{PredictSpec, Prediction, default_epsilons, run_prediction};
use dicesim_experiment::{RandomRanges, RunOptions, ScanKey};
use dicesim_figures::figure::setup_value;
use dicesim_figures::plot::{Record, random_starts};
use dicesim_figures::predict_plot::prediction_png;
use std::io::Write;
use std::path::PathBuf;

/// The most rolls one experiment takes (starts × (1 + ε count) × values).
const MAX_ROLLS: u64 = 1_000_000_000;

#[derive(Debug, Args)]
pub(crate) struct PredictArgs {
    #[command(flatten)]
    pub(crate) setup: SetupArgs,
    /// Random starts per curve, drawn from the preset's `[random]` ranges; each is rolled
    /// beside one twin per ε.
    #[arg(long, value_name = "N", default_value_t = 1000)]
    pub(crate) rolls: u64,
    /// The relative perturbations ε of the twins, increasing, comma-separated (default one
    /// per decade from 1e-15 to 1e-1).
    #[arg(
        long,
        value_name = "E1,E2,…",
        value_delimiter = ',',
        allow_hyphen_values = true
    )]
    pub(crate) epsilon: Vec<f64>,
    /// One curve per value of one setup key, e.g. `initial.height=2,5,15` or
    /// `ground.damping=0.001,0.005,0.02` (the height is the random starts' height).
    #[arg(long, value_name = "KEY=V1,V2,…")]
    pub(crate) vary: Option<String>,
    /// Seed of the random starts (default: the preset's `random.seed`).
    #[arg(long, value_name = "S")]
    pub(crate) seed: Option<u64>,
    /// Worker threads (default: one per core); the results do not depend on it.
    #[arg(long, value_name = "J", value_parser = clap::value_parser!(u64).range(1..))]
    pub(crate) jobs: Option<u64>,
    /// Write the curves to a .csv, .json or .png file (repeatable: one of each, say).
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

/// `KEY=V1,V2,…` as the key and its values.
fn parse_vary(text: &str) -> Result<(ScanKey, Vec<f64>), CliError> {
    let (key, values) = text
        .split_once('=')
        .ok_or_else(|| CliError::Usage(format!("--vary `{text}`: expected KEY=V1,V2,…")))?;
    let key = ScanKey::parse(key.trim()).map_err(|e| CliError::experiment("--vary ")(e.into()))?;
    let values = values
        .split(',')
        .map(|v| {
            v.trim()
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| CliError::Usage(format!("--vary `{text}`: `{v}` is not a number")))
        })
        .collect::<Result<Vec<f64>, CliError>>()?;
    Ok((key, values))
}

pub(crate) fn run(args: &PredictArgs) -> Result<(), CliError> {
    let jobs = super::checked_jobs(args.jobs)?;
    let preset = args.setup.resolve()?;
    let params = preset.params();
    params.validate()?;
    let spec = PredictSpec {
        epsilons: if args.epsilon.is_empty() {
            default_epsilons()
        } else {
            args.epsilon.clone()
        },
        count: args.rolls,
        seed: args.seed.unwrap_or(preset.random.seed),
        sweep: args.vary.as_deref().map(parse_vary).transpose()?,
    };
    spec.validate().map_err(CliError::experiment(""))?;
    let curves = spec.sweep.as_ref().map_or(1, |(_, v)| v.len() as u64);
    let total = args
        .rolls
        .saturating_mul(1 + spec.epsilons.len() as u64)
        .saturating_mul(curves);
    if total > MAX_ROLLS {
        return Err(CliError::Usage(format!(
            "{total} rolls: at most {MAX_ROLLS} in one experiment (fewer --rolls, ε or values)"
        )));
    }
    let outputs = super::checked_outputs(&args.out, &["csv", "json", "png"], args.force)?;

    let options = RunOptions {
        jobs,
        engine: args.engine.engine(),
    };
    let prediction =
        super::run_with_progress(total, "{bar:40} {pos}/{len} rolls, {elapsed}", |stop, done| {
            run_prediction(
                &params,
                &preset.random,
                &preset.initial,
                &spec,
                &options,
                stop,
                &mut |p| done(p.done),
            )
        })?;

    // What defines the experiment, in every file it writes (never threads or time).
    let mut values = preset.as_written();
    values.random.seed = spec.seed;
    let provenance = serde_json::json!({
        "program": dicesim_experiment::PROGRAM,
        "preset": values,
        "seed": spec.seed,
        "rolls": args.rolls,
        "epsilons": spec.epsilons,
        "vary": args.vary,
    });
    let png = || {
        let record = Record::of_experiment(
            "predictability of a throw",
            experiment_line(&preset.name, &preset.random, &spec, args.vary.as_deref()),
            &params,
            &provenance,
        );
        prediction_png(&prediction, &record).map_err(CliError::experiment(""))
    };
    super::write_results(
        &outputs,
        args.json,
        super::Results {
            value: &prediction,
            provenance: &provenance,
            csv: &|w| prediction.write_csv(w),
            png: &png,
            table: &|out| print_prediction(out, &prediction),
        },
    )?;
    if prediction.cancelled {
        let done: u64 = prediction.curves.iter().map(|c| c.starts).sum();
        return Err(CliError::Interrupted {
            completed: done,
            requested: args.rolls * curves,
            what: "starts (each with its twins)",
        });
    }
    Ok(())
}

/// The table: one column of P(same face) per curve, then chance, ε½ and the start face.
fn print_prediction(out: &mut dyn Write, p: &Prediction) -> std::io::Result<()> {
    let name = |v: Option<f64>| match (&p.key, v) {
        (Some(k), Some(v)) => format!("{k} = {v}"),
        _ => "this setup".to_string(),
    };
    writeln!(
        out,
        "{} random starts per curve, each beside its ε-twin (height, velocity and spin × (1 + ε)), seed {}",
        p.count, p.seed
    )?;
    for c in &p.curves {
        writeln!(out, "\n{} ({} starts)", name(c.value), c.starts)?;
        writeln!(out, "     ε      P(same face)   95% interval")?;
        for pt in &c.points {
            writeln!(
                out,
                "{:>8}   {:>8.3}      {:.3}–{:.3}",
                // ε as given (1.5e-3, never rounded to 2e-3): the twins were rolled at it.
                format!("{:e}", pt.epsilon),
                pt.same_share,
                pt.interval[0],
                pt.interval[1]
            )?;
        }
        writeln!(
            out,
            "chance Σpᶠ²  {:.3}; halfway {:.3}; ε½ {}",
            c.chance,
            c.half,
            c.threshold.map_or("n/a (no faces)".to_string(), |t| t.text())
        )?;
        writeln!(
            out,
            "start face kept  {:.1}% ({:.1}–{:.1}%)",
            100.0 * c.start_face_share,
            100.0 * c.start_face_interval[0],
            100.0 * c.start_face_interval[1]
        )?;
    }
    Ok(())
}

/// What defines a prediction, as its image's caption says it: the starts drawn from the
/// preset's random ranges with the seed, the perturbation sizes and the varied value.
fn experiment_line(name: &str, r: &RandomRanges, spec: &PredictSpec, vary: Option<&str>) -> String {
    let epsilons: Vec<String> = spec.epsilons.iter().map(|&e| setup_value(e)).collect();
    let vary = vary
        .map(|v| format!("; one curve per value of --vary {v}"))
        .unwrap_or_default();
    format!(
        "{name}: {} starts {}, for each curve; each beside its twin at ε {}{vary}",
        spec.count,
        random_starts(r, spec.seed),
        epsilons.join(", "),
    )
}
