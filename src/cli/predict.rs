//! `dicesim predict`: how precisely a throw must be known to predict its face.

use super::args::{RunArgs, SetupArgs, Worded, Wording};
use super::error::CliError;
use super::running;
use crate::tables;
use clap::Args;
use dicesim_experiment::predict::{PredictSpec, default_epsilons, run_prediction};
use dicesim_experiment::provenance;
use dicesim_experiment::{RandomRanges, ScanKey};
use dicesim_figures::figure::setup_value;
use dicesim_figures::plot::{Record, random_starts};
use dicesim_figures::predict_plot::prediction_png;
use dicesim_setup::preset::refuse_unapplied;
use dicesim_setup::random::{seed_given, unapplied_when_drawn};

#[derive(Debug, Args)]
pub(crate) struct PredictArgs {
    #[command(flatten)]
    pub(crate) setup: SetupArgs,
    /// Random starts per curve, drawn from the preset's `[random]` ranges; each is rolled
    /// beside one twin per ε (at most 10⁹ rolls in one experiment, starts × (1 + ε count) ×
    /// values).
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
    #[arg(long, value_name = "S", value_parser = dicesim_setup::random::parse_seed)]
    pub(crate) seed: Option<u64>,
    #[command(flatten)]
    pub(crate) run: RunArgs<Predict>,
}

/// How `predict` words its run options.
#[derive(Debug)]
pub(crate) struct Predict;

impl Worded for Predict {
    const WORDING: Wording = Wording {
        jobs: "Worker threads (default: one per core); the results do not depend on it",
        out: "Write the curves to a .csv, .json or .png file (repeatable: one of each, say)",
        out_value: "FILE.csv|FILE.json|FILE.png",
        repeatable: true,
        force: "Replace existing output files",
        json: Some("Print the result as one JSON object instead of text"),
        sharded: false,
        engine: "The engine that steps the rolls; the result is bit for bit the same with either",
    };
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

/// A --set the throws or the --vary values replace is refused, not dropped.
fn refuse_unapplied_sets(
    args: &PredictArgs,
    ranges: &RandomRanges,
    vary: Option<&(ScanKey, Vec<f64>)>,
) -> Result<(), CliError> {
    refuse_unapplied(&args.setup.set, |key| {
        unapplied_when_drawn(key, ranges, "predict")
            .or_else(|| seed_given(key, args.seed.is_some()))
            .or_else(|| {
                vary.filter(|(k, _)| k.overlaps(key))
                    .map(|(k, _)| format!("--vary {} sets it on every curve", k.key))
            })
    })?;
    Ok(())
}

pub(crate) fn run(args: &PredictArgs) -> Result<(), CliError> {
    let options = args.run.options()?;
    let preset = args.setup.resolve()?;
    let vary = args.vary.as_deref().map(parse_vary).transpose()?;
    refuse_unapplied_sets(args, &preset.random, vary.as_ref())?;
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
        sweep: vary,
    };
    spec.validate().map_err(CliError::experiment(""))?;
    let curves = spec.sweep.as_ref().map_or(1, |(_, v)| v.len() as u64);
    let total = args
        .rolls
        .saturating_mul(1 + spec.epsilons.len() as u64)
        .saturating_mul(curves);
    dicesim_experiment::limits::EXPERIMENT_ROLLS
        .check(total)
        .map_err(CliError::experiment(""))?;
    let outputs = args.run.outputs(&["csv", "json", "png"])?;
    let prediction =
        running::run_with_progress(total, "{bar:40} {pos}/{len} rolls, {elapsed}", |stop, done| {
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

    let provenance = provenance::prediction(&preset, &spec, args.vary.as_deref());
    let png = || {
        // The swept value is the legend's: the caption never states the preset's one.
        let varied: Vec<&str> = spec.sweep.iter().map(|(k, _)| k.key.as_str()).collect();
        let record = Record::of_experiment(
            "predictability of a throw",
            experiment_line(&preset.name, &preset.random, &spec, args.vary.as_deref()),
            &params,
            &varied,
            &provenance,
        );
        prediction_png(&prediction, &record).map_err(CliError::experiment(""))
    };
    running::write_results(
        &outputs,
        args.run.json,
        running::Results {
            value: &prediction,
            provenance: &provenance,
            columns: &prediction.csv_columns(),
            csv: &|w| prediction.write_csv(w),
            png: &png,
            table: &|out| tables::prediction(out, &prediction),
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
        random_starts(
            r,
            spec.seed,
            &spec.sweep.iter().map(|(k, _)| k.key.as_str()).collect::<Vec<_>>()
        ),
        epsilons.join(", "),
    )
}
