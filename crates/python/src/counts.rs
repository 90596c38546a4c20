//! A player's own counts of a die's faces held against the simulated die ("Is my die
//! fair?"): `dicesim compare --counts` from Python, with the same checks, seeds and bits.

use crate::interrupt::run_interruptible;
use crate::setup::{Setup, value_error};
use dicesim_experiment::compare::{CountsSpec, DEFAULT_CANDIDATES, FitSpec, run_counts};
use dicesim_experiment::compare_budden::unapplied_by_comparison;
use dicesim_experiment::limits::EXPERIMENT_ROLLS;
use dicesim_experiment::player_counts::{CountsInput, player_die_name, preset_for_die};
use dicesim_experiment::{Engine, RunOptions, provenance};
use dicesim_setup::preset::{Store, refuse_unapplied};
use dicesim_setup::random::check_drawn_setup;
use pyo3::prelude::*;
use pyo3::types::PyBytes;

/// Adds the function to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(compare_counts, m)?)
}

/// The counts (`counts`: a file's path or `FACE=COUNT` pairs, as `--counts` takes them)
/// against the setup's die, or without a setup the shipped preset of the die the counts
/// name: the CSV and the JSON of `dicesim compare --counts … --out FILE.csv --out FILE.json`.
#[pyfunction]
#[pyo3(signature = (setup, counts, throws = None, seed = None, fit = None, candidates = None,
    jobs = 0, engine = "auto"))]
#[allow(clippy::too_many_arguments)]
fn compare_counts<'py>(
    py: Python<'py>,
    setup: Option<&Setup>,
    counts: &str,
    throws: Option<u64>,
    seed: Option<u64>,
    fit: Option<String>,
    candidates: Option<usize>,
    jobs: usize,
    engine: &str,
) -> PyResult<(Bound<'py, PyBytes>, String, String)> {
    let engine = Engine::from_name(engine).ok_or_else(|| {
        value_error(format!(
            "engine={engine:?}: expected \"auto\", \"scalar\" or \"lanes\""
        ))
    })?;
    let most = dicesim_experiment::batch::max_jobs();
    if jobs > most {
        return Err(value_error(format!(
            "jobs={jobs}: at most {most} (4 × the cores here)"
        )));
    }
    let options = RunOptions { jobs, engine };
    let input = CountsInput::read(counts).map_err(|e| value_error(format!("counts: {e}")))?;
    let (preset, changes) = match (setup, input.named_die().and_then(preset_for_die)) {
        (Some(s), _) => (s.preset.clone(), s.changes.clone()),
        (None, named) => (
            Store::from_env().load_or_default(named).map_err(value_error)?.0,
            Vec::new(),
        ),
    };
    let params = preset.params();
    let die = player_die_name(params.die.kind.name());
    let counts = input
        .for_die(&die, params.die.face_numbers())
        .map_err(|e| value_error(format!("counts: {e}")))?;
    if throws == Some(0) {
        return Err(value_error("throws=0: a comparison needs at least one throw"));
    }
    if candidates.is_some() && fit.is_none() {
        return Err(value_error(
            "candidates counts a fit's values: give fit=\"KEY:LO:HI\"",
        ));
    }
    let candidate_count = candidates.unwrap_or(DEFAULT_CANDIDATES);
    let fit_spec = fit
        .as_deref()
        .map(|f| FitSpec::parse(f, candidate_count))
        .transpose()
        .map_err(|e| value_error(format!("fit: {e}")))?;
    refuse_unapplied(&changes, |key| {
        unapplied_by_comparison(key, false, &preset.random, fit_spec.as_ref(), seed.is_some())
    })
    .map_err(value_error)?;
    check_drawn_setup(&params, &preset.random, &preset.initial).map_err(value_error)?;
    let spec = CountsSpec {
        throws: throws.unwrap_or_else(|| CountsSpec::default_throws(&counts)),
        counts,
        seed: seed.unwrap_or(preset.random.seed),
        fit: fit_spec,
    };
    spec.validate(params.die.face_numbers()).map_err(value_error)?;
    EXPERIMENT_ROLLS.check(spec.total_rolls()).map_err(value_error)?;
    let comparison = run_interruptible(py, |stop| {
        run_counts(
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
    let mut bytes = Vec::new();
    comparison.write_csv(&mut bytes).map_err(value_error)?;
    let mut result = serde_json::to_value(&comparison).map_err(value_error)?;
    result["provenance"] = provenance::counts(&preset, &spec, fit.as_deref(), candidate_count);
    let columns = serde_json::to_string(&comparison.csv_columns()).map_err(value_error)?;
    Ok((PyBytes::new(py, &bytes), columns, result.to_string()))
}
