//! Rolls, traces, batches, maps and comparisons, each the same run as its command's with
//! the same checks, seeds and bits; a long one releases the GIL and answers Ctrl-C.

use crate::interrupt::run_interruptible;
use crate::setup::{Setup, value_error};
use dicesim_experiment::basin::{MAX_CELLS, unapplied_by_map};
use dicesim_experiment::batch_sweep::BatchSweep;
use dicesim_experiment::compare::{CompareSpec, Comparison, DEFAULT_CANDIDATES, FitSpec, run_comparison};
use dicesim_experiment::compare_budden::{
    BuddenComparison, BuddenSpec, DEFAULT_CALIBRATE_ON, DEFAULT_FIT, hand_throw, run_budden,
    unapplied_by_comparison,
};
use dicesim_experiment::compare_shaved::{
    DEFAULT_CUTS, ShavedComparison, ShavedSpec, default_throws as shaved_default_throws, run_shaved,
    setups as shaved_setups, unapplied as shaved_unapplied,
};
use dicesim_experiment::data_file::Column;
use dicesim_experiment::one_roll::OneRoll;
use dicesim_experiment::real_data::Dataset;
use dicesim_experiment::trace as trace_rows;
use dicesim_experiment::{Axis, Engine, MapSpec, Method, RunOptions, provenance, run_map_with};
use dicesim_physics::Roll;
use dicesim_setup::number::StepClock;
use dicesim_setup::preset::refuse_unapplied;
use dicesim_setup::random::{check_drawn_setup, seed_given, unapplied_when_drawn, unapplied_when_fixed};
use pyo3::prelude::*;
use pyo3::types::PyBytes;

/// The most rolls one batch or comparison takes from Python: past this a run is days of
/// core time, a typo more likely than a plan (the command line's `--shard` splits more).
const MAX_ROLLS: u64 = 1_000_000_000;

/// A records table as it crosses into Python: the file's bytes, its columns (name and
/// `integer`, `real` or `text`) and what the command's `--json` prints of the run.
type Records<'py> = (Bound<'py, PyBytes>, String, String);

/// Refuses the setup's changes `why_not` says the run would not apply, as the command line
/// refuses such a `--set`.
fn refuse(setup: &Setup, why_not: impl Fn(&str) -> Option<String>) -> PyResult<()> {
    refuse_unapplied(&setup.changes, why_not).map_err(value_error)
}

/// The threads and engine of a run: `jobs` 0 is one per core.
fn options(jobs: usize, engine: &str) -> PyResult<RunOptions> {
    let (cores, most) = (
        dicesim_experiment::batch::thread_count(0),
        dicesim_experiment::batch::max_jobs(),
    );
    if jobs > most {
        return Err(value_error(format!(
            "jobs={jobs}: at most {most} (4 × the {cores} cores here)"
        )));
    }
    let engine = Engine::from_name(engine).ok_or_else(|| {
        value_error(format!(
            "engine={engine:?}: expected \"auto\", \"scalar\" or \"lanes\""
        ))
    })?;
    Ok(RunOptions { jobs, engine })
}

/// Columns as the sidecar names them.
fn columns_json(columns: &[Column]) -> String {
    serde_json::to_string(columns).expect("columns always serialise")
}

/// One roll of the setup's initial condition: what `dicesim roll --json` prints, as JSON text.
#[pyfunction]
pub(crate) fn roll(py: Python<'_>, setup: &Setup) -> PyResult<String> {
    refuse(setup, |key| unapplied_when_fixed(key, "roll"))?;
    let preset = setup.preset.clone();
    let changed = !setup.changes.is_empty();
    run_interruptible(py, move |_| {
        OneRoll::run(&preset).map(|rolled| rolled.json(&preset, changed).to_string())
    })?
    .map_err(value_error)
}

/// One roll's trajectory as `dicesim trace` writes it: the column names, the steps (u64)
/// and every other column's values (f64, row by row), in native byte order.
#[pyfunction]
#[pyo3(signature = (setup, steps = None, every = 1))]
pub(crate) fn trace<'py>(
    py: Python<'py>,
    setup: &Setup,
    steps: Option<u64>,
    every: u64,
) -> PyResult<(Vec<String>, Bound<'py, PyBytes>, Bound<'py, PyBytes>)> {
    refuse(setup, |key| unapplied_when_fixed(key, "trace"))?;
    if every == 0 {
        return Err(value_error(
            "every=0: one row every K steps needs K of at least 1",
        ));
    }
    let params = setup.preset.params();
    let mut roll = Roll::new(&params, &setup.preset.initial).map_err(value_error)?;
    let clock = StepClock::new(params.integrator.dt);
    let (step_bytes, value_bytes) = run_interruptible(py, |stop| {
        let (mut step_bytes, mut value_bytes) = (Vec::new(), Vec::new());
        // A stop ends the rows early; what the caller sees is the interrupt.
        let _ = trace_rows::follow(&mut roll, steps, every, &mut |roll| {
            if stop.load(std::sync::atomic::Ordering::Relaxed) {
                return Err(());
            }
            step_bytes.extend(roll.steps().to_ne_bytes());
            value_bytes.extend(
                trace_rows::values(roll, &clock)
                    .into_iter()
                    .flat_map(f64::to_ne_bytes),
            );
            Ok(())
        });
        (step_bytes, value_bytes)
    })?;
    Ok((
        trace_rows::header_for(&params),
        PyBytes::new(py, &step_bytes),
        PyBytes::new(py, &value_bytes),
    ))
}

/// `rolls` rolls drawn from the setup's random ranges with `seed` (default: the preset's):
/// the Parquet file `dicesim batch --out FILE.parquet` writes, byte for byte, and the
/// batch's `--json` report.
#[pyfunction]
#[pyo3(signature = (setup, rolls, seed = None, jobs = 0, engine = "auto"))]
pub(crate) fn batch<'py>(
    py: Python<'py>,
    setup: &Setup,
    rolls: u64,
    seed: Option<u64>,
    jobs: usize,
    engine: &str,
) -> PyResult<Records<'py>> {
    let options = options(jobs, engine)?;
    if !(1..=MAX_ROLLS).contains(&rolls) {
        return Err(value_error(format!("rolls={rolls}: from 1 to {MAX_ROLLS}")));
    }
    let preset = &setup.preset;
    refuse(setup, |key| {
        unapplied_when_drawn(key, &preset.random, "batch").or_else(|| seed_given(key, seed.is_some()))
    })?;
    let params = preset.params();
    check_drawn_setup(&params, &preset.random, &preset.initial).map_err(value_error)?;
    let sweep = BatchSweep::new(preset, seed.unwrap_or(preset.random.seed), None, rolls, None);
    let mut bytes = Vec::new();
    let done = run_interruptible(py, |stop| {
        sweep.roll_into(&params, &options, stop, ("parquet", &mut bytes), &mut |_| {})
    })?;
    let (batch, _) = done.map_err(value_error)?;
    let columns = dicesim_experiment::ics::records_columns(sweep.spin);
    Ok((
        PyBytes::new(py, &bytes),
        columns_json(&columns),
        sweep.report(&batch).to_string(),
    ))
}

/// The ending over a grid of two setup values: the CSV `dicesim basin --out map.csv`
/// writes, and the map's provenance.
#[pyfunction]
#[pyo3(signature = (setup, x, y, res = (200, 100), method = None, jobs = 0, engine = "auto"))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn basin<'py>(
    py: Python<'py>,
    setup: &Setup,
    x: &str,
    y: &str,
    res: (usize, usize),
    method: Option<&str>,
    jobs: usize,
    engine: &str,
) -> PyResult<Records<'py>> {
    let options = options(jobs, engine)?;
    let (w, h) = res;
    if !(1..=10_000).contains(&w) || !(1..=10_000).contains(&h) || w * h > MAX_CELLS {
        return Err(value_error(format!(
            "res=({w}, {h}): from 1 to 10000 nodes each way, at most {MAX_CELLS} in all"
        )));
    }
    let x = Axis::parse(x, w).map_err(|e| value_error(format!("x: {e}")))?;
    let y = Axis::parse(y, h).map_err(|e| value_error(format!("y: {e}")))?;
    refuse(setup, |key| unapplied_by_map(key, &x, &y))?;
    if x.key.key == y.key.key {
        return Err(value_error(format!(
            "x and y both vary `{}`: a map needs two different values",
            x.key.key
        )));
    }
    // As `basin`: a 1-D scan rolls every cell, a 2-D map refines where neighbours differ.
    let method = match method {
        None if h == 1 => Method::Uniform,
        None | Some("adaptive") => Method::Adaptive,
        Some("uniform") => Method::Uniform,
        Some(other) => {
            return Err(value_error(format!(
                "method={other:?}: expected \"adaptive\" or \"uniform\""
            )));
        }
    };
    let preset = &setup.preset;
    let params = preset.params();
    let spec = MapSpec { x, y, method };
    let map = run_interruptible(py, |stop| {
        run_map_with(&params, &preset.initial, &spec, &options, stop, &mut |_| {})
    })?
    .map_err(value_error)?;
    let mut bytes = Vec::new();
    map.write_csv(&mut bytes).map_err(value_error)?;
    let report = serde_json::json!({
        "provenance": provenance::map(preset, &map),
        "method": map.method_report(),
        "complete": map.complete,
    });
    Ok((
        PyBytes::new(py, &bytes),
        columns_json(&map.csv_columns()),
        report.to_string(),
    ))
}

/// The setup thrown as a historical experiment threw real dice: the CSV and the JSON of
/// `dicesim compare DATASET --out FILE.csv --out FILE.json`.
#[pyfunction]
#[pyo3(signature = (setup, dataset, throws = None, seeds = Vec::new(), fit = None, no_fit = false,
    candidates = None, calibrate_on = None, jobs = 0, engine = "auto", cuts = None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn compare<'py>(
    py: Python<'py>,
    setup: &Setup,
    dataset: &str,
    throws: Option<u64>,
    seeds: Vec<u64>,
    fit: Option<String>,
    no_fit: bool,
    candidates: Option<usize>,
    calibrate_on: Option<Vec<f64>>,
    jobs: usize,
    engine: &str,
    cuts: Option<Vec<f64>>,
) -> PyResult<Records<'py>> {
    let options = options(jobs, engine)?;
    if dataset == "shaved-die" {
        let shaved = Shaved {
            throws,
            seeds,
            fit,
            no_fit,
            candidates,
            calibrate_on,
            cuts,
        };
        return compare_shaved(py, setup, &shaved, &options);
    }
    if cuts.is_some() {
        return Err(value_error(
            "cuts chooses the shaved die's cuts: it is for \"shaved-die\" only",
        ));
    }
    let cubic = match dataset {
        "weldon" => Some(Dataset::Weldon),
        "wolf-red" => Some(Dataset::WolfRed),
        "wolf-white" => Some(Dataset::WolfWhite),
        "budden" => None,
        other => {
            return Err(value_error(format!(
                "dataset={other:?}: expected \"weldon\", \"wolf-red\", \"wolf-white\", \"budden\" or \"shaved-die\""
            )));
        }
    };
    if throws == Some(0) {
        return Err(value_error("throws=0: a comparison needs at least one throw"));
    }
    if no_fit && (fit.is_some() || candidates.is_some()) {
        return Err(value_error(
            "no_fit=True fits nothing: give no fit or candidates with it",
        ));
    }
    let preset = &setup.preset;
    let params = preset.params();
    let candidate_count = candidates.unwrap_or(DEFAULT_CANDIDATES);
    let fit_text = match cubic {
        Some(_) => fit.clone(),
        None => (!no_fit).then(|| fit.clone().unwrap_or_else(|| DEFAULT_FIT.to_string())),
    };
    let fit_spec = fit_text
        .as_deref()
        .map(|f| FitSpec::parse(f, candidate_count))
        .transpose()
        .map_err(|e| value_error(format!("fit: {e}")))?;
    let ranges = if cubic.is_none() {
        hand_throw(&preset.random)
    } else {
        preset.random
    };
    refuse(setup, |key| {
        unapplied_by_comparison(
            key,
            cubic.is_none(),
            &ranges,
            fit_spec.as_ref(),
            !seeds.is_empty(),
        )
    })?;
    check_drawn_setup(&params, &preset.random, &preset.initial).map_err(value_error)?;
    let seeds = if seeds.is_empty() {
        vec![preset.random.seed]
    } else {
        seeds
    };
    let (bytes, columns, result) = match cubic {
        Some(dataset) => {
            if calibrate_on.is_some() {
                return Err(value_error(
                    "calibrate_on chooses Budden's ratios: it is for \"budden\" only",
                ));
            }
            if no_fit {
                return Err(value_error(
                    "no_fit is for \"budden\" (which fits unless told not to)",
                ));
            }
            if candidates.is_some() && fit.is_none() {
                return Err(value_error(
                    "candidates counts a fit's values: give fit=\"KEY:LO:HI\"",
                ));
            }
            let [seed] = seeds[..] else {
                return Err(value_error(
                    "seeds: several seeds are pooled for \"budden\" only; give one",
                ));
            };
            let spec = CompareSpec {
                dataset,
                throws: throws.unwrap_or_else(|| dataset.data().total()),
                seed,
                fit: fit_spec,
            };
            spec.validate().map_err(value_error)?;
            check_size(spec.total_rolls())?;
            let c = run_interruptible(py, |stop| {
                run_comparison(
                    &params,
                    &preset.random,
                    &preset.initial,
                    &spec,
                    &options,
                    stop,
                    &mut |_| {},
                )
            })?
            .map_err(value_error)?;
            let provenance = provenance::comparison(preset, &spec, fit_text.as_deref(), candidate_count);
            crossing(&c, Comparison::write_csv, c.csv_columns(), provenance)?
        }
        None => {
            let spec = BuddenSpec {
                throws,
                seeds,
                fit: fit_spec,
                calibrate_on: calibrate_on.unwrap_or_else(|| DEFAULT_CALIBRATE_ON.to_vec()),
            };
            spec.validate().map_err(value_error)?;
            check_size(spec.total_rolls())?;
            let c = run_interruptible(py, |stop| {
                run_budden(
                    &params,
                    &preset.random,
                    &preset.initial,
                    &spec,
                    &options,
                    stop,
                    &mut |_| {},
                )
            })?
            .map_err(value_error)?;
            let provenance = provenance::budden(preset, &spec, fit_text.as_deref());
            crossing(&c, BuddenComparison::write_csv, c.csv_columns(), provenance)?
        }
    };
    Ok((
        PyBytes::new(py, &bytes),
        columns_json(&columns),
        result.to_string(),
    ))
}

/// The arguments of a shaved-die comparison, and those of the others it refuses.
struct Shaved {
    throws: Option<u64>,
    seeds: Vec<u64>,
    fit: Option<String>,
    no_fit: bool,
    candidates: Option<usize>,
    calibrate_on: Option<Vec<f64>>,
    cuts: Option<Vec<f64>>,
}

/// `dicesim compare shaved-die`: every throw with the uncut die and each cut one, with the
/// command's refusals.
fn compare_shaved<'py>(
    py: Python<'py>,
    setup: &Setup,
    args: &Shaved,
    options: &RunOptions,
) -> PyResult<Records<'py>> {
    let not_here = |what: &str| {
        Err(value_error(format!(
            "{what} is not for \"shaved-die\": it fits nothing and throws one die, cut by each of cuts"
        )))
    };
    if args.fit.is_some() || args.candidates.is_some() {
        return not_here("fit");
    }
    if args.no_fit {
        return not_here("no_fit");
    }
    if args.calibrate_on.is_some() {
        return not_here("calibrate_on");
    }
    if args.throws == Some(0) {
        return Err(value_error("throws=0: a comparison needs at least one throw"));
    }
    refuse(setup, |key| {
        shaved_unapplied(key).or_else(|| seed_given(key, !args.seeds.is_empty()))
    })?;
    let preset = &setup.preset;
    let seed = match args.seeds[..] {
        [] => preset.random.seed,
        [one] => one,
        _ => {
            return Err(value_error(
                "seeds: several seeds are pooled for \"budden\" only; give one",
            ));
        }
    };
    let spec = ShavedSpec {
        cuts: args.cuts.clone().unwrap_or_else(|| DEFAULT_CUTS.to_vec()),
        throws: args.throws.unwrap_or_else(shaved_default_throws),
        seed,
    };
    let params = preset.params();
    shaved_setups(&params, &preset.initial, &spec).map_err(value_error)?;
    check_size(spec.total_rolls())?;
    let c = run_interruptible(py, |stop| {
        run_shaved(&params, &preset.initial, &spec, options, stop, &mut |_| {})
    })?
    .map_err(value_error)?;
    let (bytes, columns, result) = crossing(
        &c,
        ShavedComparison::write_csv,
        c.csv_columns(),
        provenance::shaved_die(preset, &spec),
    )?;
    Ok((
        PyBytes::new(py, &bytes),
        columns_json(&columns),
        result.to_string(),
    ))
}

/// A comparison as it crosses into Python: the CSV `compare --out FILE.csv` writes, its
/// columns, and the JSON of `--out FILE.json` with `provenance` in it.
fn crossing<C: serde::Serialize>(
    comparison: &C,
    write_csv: fn(&C, &mut dyn std::io::Write) -> std::io::Result<()>,
    columns: Vec<Column>,
    provenance: serde_json::Value,
) -> PyResult<(Vec<u8>, Vec<Column>, serde_json::Value)> {
    let mut bytes = Vec::new();
    write_csv(comparison, &mut bytes).map_err(value_error)?;
    let mut result = serde_json::to_value(comparison).map_err(value_error)?;
    result["provenance"] = provenance;
    Ok((bytes, columns, result))
}

/// Refuses a comparison past [`MAX_ROLLS`].
fn check_size(total: u64) -> PyResult<()> {
    if total > MAX_ROLLS {
        return Err(value_error(format!(
            "{total} rolls: at most {MAX_ROLLS} in one comparison (fewer throws or candidates)"
        )));
    }
    Ok(())
}
