//! `dicesim.Setup`: a preset with the changes made to it, read and changed by the registry's
//! keys exactly as `--set` changes it (the same names, units, ranges and messages).

use dicesim_setup::keys::ScanKey;
use dicesim_setup::output::{Output, OutputError};
use dicesim_setup::preset::{Preset, SHIPPED, Store};
use dicesim_setup::registry::{self, Shape, Value};
use pyo3::exceptions::{PyFileExistsError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The message the command line prints for `error`, as a Python `ValueError`.
pub(crate) fn value_error(error: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(error.to_string())
}

#[pyclass(module = "dicesim._native", from_py_object)]
#[derive(Clone)]
pub(crate) struct Setup {
    /// The preset with every change applied.
    pub(crate) preset: Preset,
    /// The changes in order, as `--set KEY=VALUE` would give them: what a run refuses to
    /// drop, as the command line refuses a `--set` it would not apply.
    pub(crate) changes: Vec<String>,
}

#[pymethods]
impl Setup {
    /// A preset by name (the user's folder, then the shipped set) or path; `None`: `paper`.
    #[new]
    #[pyo3(signature = (preset = None))]
    fn new(preset: Option<&str>) -> PyResult<Self> {
        let (preset, _) = Store::from_env().load_or_default(preset).map_err(value_error)?;
        Ok(Setup {
            preset,
            changes: Vec::new(),
        })
    }

    /// A setup from a preset file's text (`origin` names it in errors).
    #[staticmethod]
    #[pyo3(signature = (text, origin = "<string>"))]
    fn from_toml(text: &str, origin: &str) -> PyResult<Self> {
        let preset = Preset::from_toml_str(text, origin).map_err(value_error)?;
        Ok(Setup {
            preset,
            changes: Vec::new(),
        })
    }

    #[getter]
    fn name(&self) -> &str {
        &self.preset.name
    }

    #[getter]
    fn description(&self) -> &str {
        &self.preset.description
    }

    /// The numbers a roll of the setup's die can show, in the order a batch's face counts
    /// and shares list them ([`Die::face_numbers`](dicesim_physics::Die::face_numbers)).
    #[getter]
    fn face_numbers(&self) -> Vec<u32> {
        // Widened: a list of bytes would reach Python as `bytes`, not as a list of numbers.
        self.preset
            .params()
            .die
            .face_numbers()
            .iter()
            .map(|&n| u32::from(n))
            .collect()
    }

    /// The changes made since the preset was loaded, as `KEY=VALUE`.
    #[getter]
    fn changes(&self) -> Vec<String> {
        self.changes.clone()
    }

    /// Applies `KEY=VALUE` (`value` in `--set`'s TOML form) as `--set` does: on any error
    /// nothing changes and the error is the command line's.
    fn set_text(&mut self, key: &str, value: &str) -> PyResult<()> {
        let change = format!("{key}={value}");
        self.preset = self
            .preset
            .with_overrides(std::slice::from_ref(&change))
            .map_err(value_error)?;
        self.changes.push(change);
        Ok(())
    }

    /// The value of a key as the setup stores it: a number, a list, a name, a seed, a flag
    /// or `None` (an optional value not given); a vector's component by its own key
    /// (`initial.velocity.y`).
    fn get<'py>(&self, py: Python<'py>, key: &str) -> PyResult<Bound<'py, PyAny>> {
        let values = self.preset.values();
        if let Some(spec) = registry::find(key) {
            return python_value(py, (spec.read)(&values));
        }
        let scan = ScanKey::named(key).map_err(|_| unknown_key(key))?;
        Ok(scan
            .get(&values.params, &values.initial)
            .into_pyobject(py)?
            .into_any())
    }

    /// Every key, in the order a preset file lists them.
    #[staticmethod]
    fn keys() -> Vec<&'static str> {
        registry::ALL.iter().map(|s| s.key()).collect()
    }

    /// A key's row: its unit, allowed range, default and meaning.
    #[staticmethod]
    fn describe<'py>(py: Python<'py>, key: &str) -> PyResult<Bound<'py, PyDict>> {
        let spec = registry::find(key)
            .or_else(|| ScanKey::named(key).ok().map(|k| k.spec))
            .ok_or_else(|| unknown_key(key))?;
        let row = PyDict::new(py);
        row.set_item("key", spec.key())?;
        row.set_item("unit", spec.limits.unit)?;
        row.set_item("meaning", spec.comment)?;
        match spec.shape {
            Shape::Number(_)
            | Shape::Optional { .. }
            | Shape::Vector { .. }
            | Shape::Range(_)
            | Shape::PerCorner(_)
            | Shape::List { .. } => {
                row.set_item("min", spec.limits.min)?;
                row.set_item("max", spec.limits.max)?;
            }
            Shape::Choice { names, .. } => row.set_item("choices", names.to_vec())?,
            Shape::Seed(_) | Shape::Flag(_) => {}
        }
        row.set_item("default", python_value(py, spec.default_value())?)?;
        Ok(row)
    }

    /// The setup as a preset file (TOML), every value with its comment.
    fn to_toml(&self) -> String {
        self.preset.to_toml()
    }

    /// Writes the setup as a preset file at `path` (`.toml`): whole or not at all, and an
    /// existing file only with `force`.
    #[pyo3(signature = (path, force = false))]
    fn save(&self, path: std::path::PathBuf, force: bool) -> PyResult<()> {
        let output = Output::check(&path, &["toml"], force).map_err(|e| match e {
            OutputError::Exists { .. } => PyFileExistsError::new_err(e.to_string()),
            e => value_error(e),
        })?;
        let text = self.preset.to_toml();
        output
            .write_table(None, |w| w.write_all(text.as_bytes()))
            .map_err(value_error)
    }

    /// An independent copy, with the changes it was made with.
    fn copy(&self) -> Setup {
        self.clone()
    }

    fn __repr__(&self) -> String {
        match self.changes.as_slice() {
            [] => format!("Setup({:?})", self.preset.name),
            changes => format!("Setup({:?}, changes={changes:?})", self.preset.name),
        }
    }
}

/// A registry value as Python holds it: a float, a list of floats, a str, an int, a bool, or
/// None for an optional value not given.
fn python_value(py: Python<'_>, value: Value) -> PyResult<Bound<'_, PyAny>> {
    Ok(match value {
        Value::Number(x) => x.into_pyobject(py)?.into_any(),
        Value::Vector(v) => v.to_vec().into_pyobject(py)?.into_any(),
        Value::Range(r) => r.to_vec().into_pyobject(py)?.into_any(),
        Value::Name(n) => n.into_pyobject(py)?.into_any(),
        Value::Seed(s) => s.into_pyobject(py)?.into_any(),
        Value::Flag(b) => pyo3::types::PyBool::new(py, b).to_owned().into_any(),
        Value::PerCorner(v) => v.to_vec().into_pyobject(py)?.into_any(),
        Value::List(list) if list.width() > 1 => list
            .items()
            .map(<[f64]>::to_vec)
            .collect::<Vec<_>>()
            .into_pyobject(py)?
            .into_any(),
        Value::List(list) => list.values().to_vec().into_pyobject(py)?.into_any(),
        Value::Absent => py.None().into_bound(py),
    })
}

/// The error for a key no row or component has, listing them as the command line does.
fn unknown_key(key: &str) -> PyErr {
    let known = registry::ALL
        .iter()
        .map(|s| s.key())
        .collect::<Vec<_>>()
        .join(", ");
    value_error(format!("unknown key `{key}`; known keys: {known}"))
}

/// The names of the shipped presets.
#[pyfunction]
pub(crate) fn preset_names() -> Vec<&'static str> {
    SHIPPED.iter().map(|(name, _)| *name).collect()
}
