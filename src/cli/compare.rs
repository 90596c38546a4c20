//! `dicesim compare`: the simulated die thrown as a historical experiment threw real ones,
//! held against its counts, and one setup value fitted to them.

use super::args::{RunArgs, SetupArgs, Worded, Wording, with_overrides};
use super::error::CliError;
use super::running;
use crate::tables;
use clap::{Args, ValueEnum};
use dicesim_experiment::compare::{
    CompareSpec, Comparison, CountsSpec, DEFAULT_CANDIDATES, FitSpec, run_comparison,
    run_counts as run_player_counts,
};
use dicesim_experiment::compare_budden::{
    BuddenSpec, DEFAULT_CALIBRATE_ON, DEFAULT_FIT, hand_throw, run_budden as roll_budden,
    unapplied as budden_unapplied, unapplied_by_comparison,
};
use dicesim_experiment::compare_joint::{
    DEFAULT_VALUES_PER_KEY, GridKey, JointSpec, run_joint as roll_joint,
};
use dicesim_experiment::compare_shaved::{
    DEFAULT_CUTS, ShavedSpec, default_throws as shaved_default_throws, run_shaved as run_shaved_die,
    setups as shaved_setups, unapplied as shaved_unapplied,
};
use dicesim_experiment::limits::EXPERIMENT_ROLLS;
use dicesim_experiment::player_counts::{CountsInput, player_die_name, preset_for_die};
use dicesim_experiment::real_data::Dataset;
use dicesim_experiment::{RunOptions, provenance};
use dicesim_figures::compare_plot::{
    budden_png, budden_record, comparison_png, comparison_record, counts_record, shaved_die_png,
    shaved_die_record,
};
use dicesim_figures::joint_plot::{joint_png, joint_record};
use dicesim_setup::output::Output;
use dicesim_setup::preset::{Preset, Store, refuse_unapplied};
use dicesim_setup::random::check_drawn_setup;

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
    /// A die shaved along its 1–6 axis, counted by how often 1 or 6 came up (Murray's group, 2001).
    ShavedDie,
    /// Budden's calibration ratios and the shaved die at 3 % together: two or more keys
    /// fitted at once on a grid (--fit once per key), their deviances summed.
    Joint,
}

impl DatasetArg {
    /// The cubic die's experiment (`None` for Budden's cuboids and the shaved die).
    fn dataset(self) -> Option<Dataset> {
        match self {
            DatasetArg::Weldon => Some(Dataset::Weldon),
            DatasetArg::WolfRed => Some(Dataset::WolfRed),
            DatasetArg::WolfWhite => Some(Dataset::WolfWhite),
            DatasetArg::Budden | DatasetArg::ShavedDie | DatasetArg::Joint => None,
        }
    }
}

#[derive(Debug, Args)]
pub(crate) struct CompareArgs {
    /// The experiment to throw the simulated die against (or --counts: a player's own).
    #[arg(value_enum, required_unless_present = "counts")]
    pub(crate) dataset: Option<DatasetArg>,
    /// Your own counts of a die's faces, held against the simulated die ("Is my die
    /// fair?"): a CSV file of `face,count` rows (`# die: d20` names the die; `#` lines are
    /// notes), or FACE=COUNT pairs, e.g. `1=12,2=9,3=11,4=8,5=10,6=10` (a value with `=` is
    /// counts, any other a file). The die is the preset's (default: the one the file names).
    #[arg(long, value_name = "FILE|FACE=COUNT,…", conflicts_with_all = ["dataset", "calibrate_on", "cuts", "no_fit"])]
    pub(crate) counts: Option<String>,
    #[command(flatten)]
    pub(crate) setup: SetupArgs,
    /// Simulated throws by the experiment's protocol (12 dice a throw for Weldon; for
    /// Budden, throws of each ratio's cuboid; for `joint`, the shaved die's throws per grid
    /// point, Budden's ratios thrown as he threw them), each die drawn from the preset's `[random]`
    /// ranges (default: as many as the experiment made, for Budden ratio by ratio); at most
    /// 10⁹ rolls in one experiment, throws × dice × candidates.
    #[arg(long, visible_alias = "rolls", value_name = "N", value_parser = clap::value_parser!(u64).range(1..))]
    pub(crate) throws: Option<u64>,
    /// Seed of the random throws (default: the preset's `random.seed`). Budden: several,
    /// e.g. `--seed 11,12,13`, throw every ratio once per seed and pool the counts.
    #[arg(long, value_name = "S[,S…]", value_delimiter = ',', value_parser = dicesim_setup::random::parse_seed)]
    pub(crate) seed: Vec<u64>,
    /// Fit one setup value to the data: candidates evenly spaced from LO to HI, each rolled
    /// with the same throws, e.g. `ground.friction:0.2:1.2` or `die.extra_corner_mass.8:0:1`
    /// (Budden fits unless --no-fit; default `ground.damping:0.009:0.016`, the range where the
    /// paper's table steps every cuboid stably). `compare joint`: once per key, two or more,
    /// each KEY:LO:HI or KEY:LO:HI:N (N values; default --candidates), on a grid.
    #[arg(long, value_name = "KEY:LO:HI", allow_hyphen_values = true)]
    pub(crate) fit: Vec<String>,
    /// Budden only: fit nothing; throw every ratio with the preset's table as it stands
    /// (the --calibrate-on ratios keep their role, for a table fitted on them elsewhere).
    #[arg(long, conflicts_with_all = ["fit", "candidates"])]
    pub(crate) no_fit: bool,
    /// Candidates of a fit (at least 20, at most 1000 candidates; default 21); for `compare
    /// joint`, the values of each key without its own N (at least 3, default 5; at most 1000
    /// grid points).
    #[arg(long, value_name = "N")]
    pub(crate) candidates: Option<usize>,
    /// Budden only: the ratios x/y the fit uses (the others are predicted with the best
    /// value, out of sample).
    #[arg(long, value_name = "R,R,…", value_delimiter = ',', default_values_t = DEFAULT_CALIBRATE_ON)]
    pub(crate) calibrate_on: Vec<f64>,
    /// Shaved die only: the cuts c, fractions of the side taken off along the 1–6 axis,
    /// each thrown with the same throws as the uncut die (more than 0, at most 0.5;
    /// default 0.015, 0.03, 0.06).
    #[arg(long, value_name = "C,C,…", value_delimiter = ',')]
    pub(crate) cuts: Vec<f64>,
    #[command(flatten)]
    pub(crate) run: RunArgs<Compare>,
}

/// How `compare` words its run options.
#[derive(Debug)]
pub(crate) struct Compare;

impl Worded for Compare {
    const WORDING: Wording = Wording {
        jobs: "Worker threads (default: one per core); the results do not depend on it",
        out: "Write the comparison to a .csv, .json or .png file (repeatable: one of each, say)",
        out_value: "FILE.csv|FILE.json|FILE.png",
        repeatable: true,
        force: "Replace existing output files",
        json: Some("Print the result as one JSON object instead of text"),
        sharded: false,
        engine: "The engine that steps the rolls; the result is bit for bit the same with either",
    };
}

pub(crate) fn run(args: &CompareArgs) -> Result<(), CliError> {
    let options = args.run.options()?;
    let Some(dataset_arg) = args.dataset else {
        return run_counts(args, &options);
    };
    let preset = args.setup.resolve()?;
    refuse_unapplied_sets(args, dataset_arg, &preset)?;
    if dataset_arg == DatasetArg::Joint {
        return run_joint(args, &options, &preset);
    }
    let params = preset.params();
    // The same up-front check as `batch`: the body, and no drawn throw inside the table.
    check_drawn_setup(&params, &preset.random, &preset.initial)?;
    let candidates = args.candidates.unwrap_or(DEFAULT_CANDIDATES);
    if dataset_arg == DatasetArg::ShavedDie {
        return run_shaved(args, &options, &preset);
    }
    let one_fit = one_fit(args)?;
    if !args.cuts.is_empty() {
        return Err(CliError::Usage(
            "--cuts chooses the shaved die's cuts: it is for `compare shaved-die` only".to_string(),
        ));
    }
    let Some(dataset) = dataset_arg.dataset() else {
        return run_budden(args, &options, &preset, candidates, one_fit);
    };
    let seed = cubic_die_seed(args, &preset)?;
    let spec = CompareSpec {
        dataset,
        throws: args.throws.unwrap_or_else(|| dataset.data().total()),
        seed,
        fit: one_fit
            .map(|f| FitSpec::parse(f, candidates))
            .transpose()
            .map_err(CliError::experiment("--fit "))?,
    };
    spec.validate().map_err(CliError::experiment(""))?;
    let total = spec.total_rolls();
    let outputs = prepare(args, total)?;
    let comparison = running::run_with_progress(total, PROGRESS, |stop, done| {
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
    let provenance = provenance::comparison(&preset, &spec, one_fit, candidates);
    let png = || {
        let record = comparison_record(&comparison, &preset, &spec, one_fit, &provenance);
        comparison_png(&comparison, &record).map_err(CliError::experiment(""))
    };
    let fit = spec.fit.as_ref().map(|f| f.candidates);
    write_comparison(
        args,
        &outputs,
        &comparison,
        &preset,
        &provenance,
        &png,
        (spec.throws, fit),
        Counted::Throws,
    )
}

/// What a comparison counts as it goes: a historical experiment its throws, a player's die
/// its rolls.
#[derive(Clone, Copy)]
enum Counted {
    Throws,
    Rolls,
}

/// Writes a finished (or cancelled) comparison: its `--out` files, its JSON or its table;
/// then, if it was cancelled, says how far it got of `throws` a candidate times the candidates
/// a fit has (`None`: no fit).
#[allow(clippy::too_many_arguments)]
fn write_comparison(
    args: &CompareArgs,
    outputs: &[Output],
    comparison: &Comparison,
    preset: &Preset,
    provenance: &serde_json::Value,
    png: &dyn Fn() -> Result<Vec<u8>, CliError>,
    (throws, fit): (u64, Option<usize>),
    counted: Counted,
) -> Result<(), CliError> {
    running::write_results(
        outputs,
        args.run.json,
        running::Results {
            value: comparison,
            provenance,
            columns: &comparison.csv_columns(),
            csv: &|w| comparison.write_csv(w),
            png,
            table: &|out| tables::comparison(out, comparison, &preset.name),
        },
    )?;
    if comparison.cancelled {
        let done: u64 = comparison.candidates.iter().map(|c| c.throws + c.uncounted).sum();
        return Err(CliError::Interrupted {
            completed: done,
            requested: throws * fit.map_or(1, |c| c as u64),
            what: match (counted, fit.is_some()) {
                (Counted::Throws, true) => "throws (whole candidates only)",
                (Counted::Throws, false) => "throws",
                (Counted::Rolls, true) => "rolls (whole candidates only)",
                (Counted::Rolls, false) => "rolls",
            },
        });
    }
    Ok(())
}

/// The one key `--fit` names, if any: a fit of several keys at once is `compare joint`'s.
fn one_fit(args: &CompareArgs) -> Result<Option<&str>, CliError> {
    match args.fit.as_slice() {
        [] => Ok(None),
        [one] => Ok(Some(one.as_str())),
        several => Err(CliError::Usage(format!(
            "--fit is given {} times: this comparison fits one key; a fit of several keys at once is \
             `compare joint`'s (Budden's calibration ratios and the shaved die at 3 % together)",
            several.len()
        ))),
    }
}

/// The seed of a cubic die's comparison, refusing the options that are Budden's alone and
/// `--candidates` without a fit (a cubic die fits only when told to).
fn cubic_die_seed(args: &CompareArgs, preset: &Preset) -> Result<u64, CliError> {
    if args.candidates.is_some() && args.fit.is_empty() {
        return Err(CliError::Usage(
            "--candidates counts a fit's values: give --fit KEY:LO:HI".to_string(),
        ));
    }
    if args.calibrate_on != DEFAULT_CALIBRATE_ON {
        return Err(CliError::Usage(
            "--calibrate-on chooses Budden's ratios: it is for `compare budden` only".to_string(),
        ));
    }
    if args.no_fit {
        return Err(CliError::Usage(
            "--no-fit is for `compare budden` (which fits unless told not to); the other experiments fit only with --fit"
                .to_string(),
        ));
    }
    match args.seed.as_slice() {
        [] => Ok(preset.random.seed),
        [one] => Ok(*one),
        _ => Err(CliError::Usage(
            "--seed: several seeds are pooled for `compare budden` only; give one".to_string(),
        )),
    }
}

/// Refuses a `--set` the comparison would not apply, before any roll: a start value the
/// throws draw, a seed `--seed` replaces, the value `--fit` sets, and for Budden the die the
/// cuboids replace ([`budden_unapplied`]).
fn refuse_unapplied_sets(args: &CompareArgs, dataset: DatasetArg, preset: &Preset) -> Result<(), CliError> {
    if dataset == DatasetArg::Joint {
        let fitted: Vec<GridKey> = args
            .fit
            .iter()
            .filter_map(|f| GridKey::parse(f, DEFAULT_VALUES_PER_KEY).ok())
            .collect();
        refuse_unapplied(&args.setup.set, |key| {
            budden_unapplied(key)
                .or_else(|| shaved_unapplied(key))
                .or_else(|| dicesim_setup::random::seed_given(key, !args.seed.is_empty()))
                .or_else(|| {
                    fitted
                        .iter()
                        .find(|k| k.key.overlaps(key))
                        .map(|k| format!("--fit sets `{}` at every grid point", k.key.key))
                })
        })?;
        return Ok(());
    }
    if dataset == DatasetArg::ShavedDie {
        refuse_unapplied(&args.setup.set, |key| {
            shaved_unapplied(key).or_else(|| dicesim_setup::random::seed_given(key, !args.seed.is_empty()))
        })?;
        return Ok(());
    }
    refuse_unapplied_by_comparison(args, dataset == DatasetArg::Budden, preset)
}

/// Refuses a `--set` a comparison of counts by face (a historical experiment's or a
/// player's; `budden`: Budden's cuboids) would not apply: a start value the throws draw, a
/// seed `--seed` replaces, the value `--fit` sets, and for Budden the die the cuboids replace.
fn refuse_unapplied_by_comparison(args: &CompareArgs, budden: bool, preset: &Preset) -> Result<(), CliError> {
    let ranges = if budden {
        hand_throw(&preset.random)
    } else {
        preset.random
    };
    let fit = args
        .fit
        .first()
        .map(String::as_str)
        .or((budden && !args.no_fit).then_some(DEFAULT_FIT))
        .and_then(|f| FitSpec::parse(f, DEFAULT_CANDIDATES).ok());
    refuse_unapplied(&args.setup.set, |key| {
        unapplied_by_comparison(key, budden, &ranges, fit.as_ref(), !args.seed.is_empty())
    })?;
    Ok(())
}

/// How a comparison's progress bar reads.
const PROGRESS: &str = "{bar:40} {pos}/{len} rolls, {per_sec}, {eta} left";

/// Before any roll, as both kinds of comparison check it: the size within bounds and every
/// `--out` file writable.
fn prepare(args: &CompareArgs, total: u64) -> Result<Vec<Output>, CliError> {
    EXPERIMENT_ROLLS.check(total).map_err(CliError::experiment(""))?;
    args.run.outputs(&["csv", "json", "png"])
}

/// `dicesim compare shaved-die`: every throw with the uncut die and each cut one, the
/// paired bias per cut against the experiment's. Refuses the options of a fit and of
/// Budden's ratios, which it has none of.
fn run_shaved(args: &CompareArgs, options: &RunOptions, preset: &Preset) -> Result<(), CliError> {
    let refuse = |option: &str| {
        Err(CliError::Usage(format!(
            "{option} is not for `compare shaved-die`: it fits nothing and throws one die, cut by each of --cuts"
        )))
    };
    if !args.fit.is_empty() {
        return refuse("--fit");
    }
    if args.candidates.is_some() {
        return refuse("--candidates");
    }
    if args.no_fit {
        return refuse("--no-fit");
    }
    if args.calibrate_on != DEFAULT_CALIBRATE_ON {
        return refuse("--calibrate-on");
    }
    let seed = match args.seed.as_slice() {
        [] => preset.random.seed,
        [one] => *one,
        _ => {
            return Err(CliError::Usage(
                "--seed: several seeds are pooled for `compare budden` only; give one".to_string(),
            ));
        }
    };
    let spec = ShavedSpec {
        cuts: if args.cuts.is_empty() {
            DEFAULT_CUTS.to_vec()
        } else {
            args.cuts.clone()
        },
        throws: args.throws.unwrap_or_else(shaved_default_throws),
        seed,
    };
    let params = preset.params();
    // Every setup checked (the body cuttable, every cut within range and room) before any roll.
    shaved_setups(&params, &preset.initial, &spec).map_err(CliError::experiment(""))?;
    let total = spec.total_rolls();
    EXPERIMENT_ROLLS.check(total).map_err(CliError::experiment(""))?;
    let outputs = args.run.outputs(&["csv", "json", "png"])?;
    let comparison = running::run_with_progress(total, PROGRESS, |stop, done| {
        run_shaved_die(&params, &preset.initial, &spec, options, stop, &mut |p| {
            done(p.done)
        })
    })?;
    let provenance = provenance::shaved_die(preset, &spec);
    let png = || {
        let record = shaved_die_record(&comparison, preset, &spec, &provenance);
        shaved_die_png(&comparison, &record).map_err(CliError::experiment(""))
    };
    running::write_results(
        &outputs,
        args.run.json,
        running::Results {
            value: &comparison,
            provenance: &provenance,
            columns: &comparison.csv_columns(),
            csv: &|w| comparison.write_csv(w),
            png: &png,
            table: &|out| tables::shaved_die(out, &comparison, &preset.name),
        },
    )?;
    if comparison.cancelled {
        let done = comparison
            .cuts
            .first()
            .map_or(0, |c| c.simulated.throws + c.simulated.uncounted);
        return Err(CliError::Interrupted {
            completed: done,
            requested: spec.throws,
            what: "throws",
        });
    }
    Ok(())
}

/// `dicesim compare budden`: the fit on the calibration ratios, then every ratio predicted.
fn run_budden(
    args: &CompareArgs,
    options: &RunOptions,
    preset: &Preset,
    candidates: usize,
    one_fit: Option<&str>,
) -> Result<(), CliError> {
    let params = preset.params();
    let fit_text = (!args.no_fit).then(|| one_fit.unwrap_or(DEFAULT_FIT));
    let spec = BuddenSpec {
        throws: args.throws,
        seeds: if args.seed.is_empty() {
            vec![preset.random.seed]
        } else {
            args.seed.clone()
        },
        fit: fit_text
            .map(|f| FitSpec::parse(f, candidates))
            .transpose()
            .map_err(CliError::experiment("--fit "))?,
        calibrate_on: args.calibrate_on.clone(),
    };
    spec.validate().map_err(CliError::experiment(""))?;
    let total = spec.total_rolls();
    let outputs = prepare(args, total)?;
    let comparison = running::run_with_progress(total, PROGRESS, |stop, done| {
        roll_budden(
            &params,
            &preset.random,
            &preset.initial,
            &spec,
            options,
            stop,
            &mut |p| done(p.done),
        )
    })?;
    // The throw as rolled: the preset's ranges from a uniformly random orientation.
    let provenance = provenance::budden(preset, &spec, fit_text);
    let png = || {
        let record = budden_record(&comparison, preset, &spec, fit_text, &provenance);
        budden_png(&comparison, &record).map_err(CliError::experiment(""))
    };
    running::write_results(
        &outputs,
        args.run.json,
        running::Results {
            value: &comparison,
            provenance: &provenance,
            columns: &comparison.csv_columns(),
            csv: &|w| comparison.write_csv(w),
            png: &png,
            table: &|out| tables::budden(out, &comparison, &preset.name),
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

/// `dicesim compare joint`: two or more keys fitted at once on a grid, each point throwing
/// Budden's calibration ratios and the shaved die at 3 %, their deviances summed. Refuses
/// the options it has no use for. It skips `run`'s check of the preset alone, which may lack
/// a value the grid sets (a table top's stiffness given, its mass fitted): every grid
/// point's bodies are checked before the first roll.
fn run_joint(args: &CompareArgs, options: &RunOptions, preset: &Preset) -> Result<(), CliError> {
    let refuse = |option: &str, why: &str| {
        Err(CliError::Usage(format!(
            "{option} is not for `compare joint`: {why}"
        )))
    };
    if args.no_fit {
        return refuse("--no-fit", "it is a fit of two or more keys (--fit once per key)");
    }
    if !args.cuts.is_empty() {
        return refuse(
            "--cuts",
            "it throws the shaved die at the one cut the experiment measured, 3 %",
        );
    }
    let seed = match args.seed.as_slice() {
        [] => preset.random.seed,
        [one] => *one,
        _ => {
            return refuse(
                "several seeds",
                "both experiments are thrown with one seed; give one",
            );
        }
    };
    let per_key = args.candidates.unwrap_or(DEFAULT_VALUES_PER_KEY);
    let keys = args
        .fit
        .iter()
        .map(|f| GridKey::parse(f, per_key))
        .collect::<Result<Vec<_>, _>>()
        .map_err(CliError::experiment(""))?;
    let spec = JointSpec {
        keys,
        seed,
        shaved_throws: args.throws.unwrap_or_else(shaved_default_throws),
        calibrate_on: args.calibrate_on.clone(),
    };
    spec.validate().map_err(CliError::experiment(""))?;
    let total = spec.total_rolls();
    let outputs = prepare(args, total)?;
    let params = preset.params();
    let comparison = running::run_with_progress(total, PROGRESS, |stop, done| {
        roll_joint(
            &params,
            &preset.random,
            &preset.initial,
            &spec,
            options,
            stop,
            &mut |p| done(p.done),
        )
    })?;
    let provenance = provenance::joint(preset, &spec);
    let png = || {
        let record = joint_record(&comparison, preset, &spec, &provenance);
        joint_png(&comparison, &record).map_err(CliError::experiment(""))
    };
    running::write_results(
        &outputs,
        args.run.json,
        running::Results {
            value: &comparison,
            provenance: &provenance,
            columns: &comparison.csv_columns(),
            csv: &|w| comparison.write_csv(w),
            png: &png,
            table: &|out| tables::joint(out, &comparison, &preset.name),
        },
    )?;
    if comparison.cancelled {
        return Err(CliError::Interrupted {
            completed: comparison.points.len() as u64,
            requested: spec.points().len() as u64,
            what: "grid points (whole points only)",
        });
    }
    Ok(())
}

/// `dicesim compare --counts`: a player's counts of one die against the simulated die
/// (fair, or with the flaw the preset and `--set` give it), and with `--fit`, the flaw's
/// size fitted to them.
fn run_counts(args: &CompareArgs, options: &RunOptions) -> Result<(), CliError> {
    let text = args
        .counts
        .as_deref()
        .expect("clap asks for a dataset or --counts");
    let input = CountsInput::read(text).map_err(CliError::experiment("--counts: "))?;
    // The die the counts name chooses the preset when none is given.
    let preset = match (&args.setup.preset, input.named_die().and_then(preset_for_die)) {
        (None, Some(name)) => {
            let (preset, _) = Store::from_env().load_or_default(Some(name))?;
            with_overrides(&preset, "--set", &args.setup.set)?
        }
        _ => args.setup.resolve()?,
    };
    let params = preset.params();
    let die = player_die_name(params.die.kind.name());
    let counts = input
        .for_die(&die, params.die.face_numbers())
        .map_err(CliError::experiment("--counts: "))?;
    refuse_unapplied_by_comparison(args, false, &preset)?;
    check_drawn_setup(&params, &preset.random, &preset.initial)?;
    let one_fit = one_fit(args)?;
    let candidates = args.candidates.unwrap_or(DEFAULT_CANDIDATES);
    let seed = cubic_die_seed(args, &preset)?;
    let spec = CountsSpec {
        throws: args.throws.unwrap_or_else(|| CountsSpec::default_throws(&counts)),
        counts,
        seed,
        fit: one_fit
            .map(|f| FitSpec::parse(f, candidates))
            .transpose()
            .map_err(CliError::experiment("--fit "))?,
    };
    spec.validate(params.die.face_numbers())
        .map_err(CliError::experiment(""))?;
    let total = spec.total_rolls();
    let outputs = prepare(args, total)?;
    let comparison = running::run_with_progress(total, PROGRESS, |stop, done| {
        run_player_counts(
            &params,
            &preset.random,
            &preset.initial,
            &spec,
            options,
            stop,
            &mut |p| done(p.done),
        )
    })?;
    let provenance = provenance::counts(&preset, &spec, one_fit, candidates);
    let png = || {
        let record = counts_record(&comparison, &preset, &spec, one_fit, &provenance);
        comparison_png(&comparison, &record).map_err(CliError::experiment(""))
    };
    let fit = spec.fit.as_ref().map(|f| f.candidates);
    write_comparison(
        args,
        &outputs,
        &comparison,
        &preset,
        &provenance,
        &png,
        (spec.throws, fit),
        Counted::Rolls,
    )
}
