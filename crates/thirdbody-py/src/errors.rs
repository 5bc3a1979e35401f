//! The package's own exception and warning classes, defined in Python
//! (`thirdbody/_errors.py`: `NotEnoughMemoryError` is both a `MemoryError` and a
//! `ValueError`, which a class made here could not be) and raised from here.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

fn class<'py>(py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
    py.import("thirdbody._errors")?.getattr(name)
}

/// `thirdbody.NotEnoughMemoryError(message)`: work refused before it starts.
pub fn not_enough_memory(py: Python<'_>, message: String) -> PyErr {
    match class(py, "NotEnoughMemoryError").and_then(|c| c.call1((message.clone(),))) {
        Ok(error) => PyErr::from_value(error),
        Err(_) => PyValueError::new_err(message),
    }
}

/// Each of a summary's `warnings` (results outside the model) as a Python warning of
/// category `thirdbody.ThirdbodyWarning`, shown where the caller's code called.
pub fn warn_all(py: Python<'_>, warnings: &[String]) -> PyResult<()> {
    if warnings.is_empty() {
        return Ok(());
    }
    let category = class(py, "ThirdbodyWarning")?;
    let warn = py.import("warnings")?.getattr("warn")?;
    for w in warnings {
        // No Python frame of the package's between: the default stack level points
        // at the caller's line.
        warn.call1((w.as_str(), &category))?;
    }
    Ok(())
}
