//! dicesim from Python: the extension module `dicesim._native`, which the `dicesim` package
//! (python/dicesim/) wraps with docstrings, numpy arrays and pyarrow tables.
//!
//! The module only translates: every setup, run and record is the layers' own (setup,
//! experiment), so a Python caller gets the CLI's keys, errors, seeds and bits. Records cross
//! into Python once, as the bytes of the file the CLI would write.

mod counts;
mod interrupt;
mod runs;
mod setup;

use pyo3::prelude::*;

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<setup::Setup>()?;
    m.add_function(wrap_pyfunction!(setup::preset_names, m)?)?;
    m.add_function(wrap_pyfunction!(runs::roll, m)?)?;
    m.add_function(wrap_pyfunction!(runs::trace, m)?)?;
    m.add_function(wrap_pyfunction!(runs::batch, m)?)?;
    m.add_function(wrap_pyfunction!(runs::basin, m)?)?;
    m.add_function(wrap_pyfunction!(runs::compare, m)?)?;
    counts::register(m)?;
    m.add("VERSION", dicesim_experiment::VERSION_LINE)?;
    m.add("PROGRAM", dicesim_experiment::PROGRAM)?;
    Ok(())
}
