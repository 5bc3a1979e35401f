//! Python bindings of thirdbody (issue 12, first part): a [`Case`] parsed by the
//! library's own case-file parser (so the validation and its messages are the CLI's),
//! [`solve`] with the GIL released, and a [`Solution`] whose summary is the library's
//! [`thirdbody::Report`] (the keys of `summary.json`) and whose fields are numpy
//! arrays laid out as the CLI's NPY files (rows along y). The front end does no
//! physics: every number comes from the `thirdbody` crate.

use std::time::Instant;

use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use thirdbody::case_file::{parse_case_file, CaseFile};

/// A contact case: slider, body, layer, loading, grid and solver settings, exactly as
/// a case file gives them.
#[pyclass(module = "thirdbody", frozen)]
struct Case {
    file: CaseFile,
    text: String,
}

/// Parses a case file's text; height maps are files the CLI reads and are not yet
/// accepted from Python.
fn parse(text: &str) -> PyResult<CaseFile> {
    let mut no_maps = |path: &str, _: f64| -> thirdbody::Result<thirdbody::HeightMap> {
        Err(thirdbody::Error::invalid(
            "slider.file",
            path,
            "a height map read by the command-line program (not yet from Python)",
        ))
    };
    parse_case_file(text, &mut no_maps).map_err(|e| PyValueError::new_err(e.to_string()))
}

#[pymethods]
impl Case {
    /// A case from the text of a TOML case file (docs/case-file.md).
    #[staticmethod]
    fn from_toml(text: &str) -> PyResult<Self> {
        Ok(Case {
            file: parse(text)?,
            text: text.to_owned(),
        })
    }

    /// A case from a TOML case file on disk.
    #[staticmethod]
    fn from_file(path: std::path::PathBuf) -> PyResult<Self> {
        let text = std::fs::read_to_string(&path).map_err(|e| {
            PyValueError::new_err(format!("cannot read case file {}: {e}", path.display()))
        })?;
        Self::from_toml(&text)
    }

    /// The case file's text this case was parsed from.
    #[getter]
    fn toml(&self) -> &str {
        &self.text
    }

    /// The grid's cell counts `(nx, ny)`.
    #[getter]
    fn cells(&self) -> (usize, usize) {
        let [nx, ny] = self.file.case.grid.cells;
        (nx, ny)
    }

    fn __repr__(&self) -> String {
        let [nx, ny] = self.file.case.grid.cells;
        format!("<thirdbody.Case {nx} x {ny} cells>")
    }
}

/// The solved contact: `summary` (a dict with the keys of `summary.json`) and the
/// fields as numpy arrays of shape `(ny, nx)`.
#[pyclass(module = "thirdbody", frozen)]
struct Solution {
    solution: thirdbody::Solution,
    summary_json: String,
}

/// A field as a `(ny, nx)` array (rows along y, as the NPY files).
fn field<'py>(py: Python<'py>, values: &[f64], nx: usize, ny: usize) -> Bound<'py, PyArray2<f64>> {
    PyArray1::from_slice(py, values)
        .reshape([ny, nx])
        .expect("a field has nx * ny values")
}

#[pymethods]
impl Solution {
    /// The summary: the keys and values of `summary.json`.
    #[getter]
    fn summary<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let json = py.import("json")?;
        json.call_method1("loads", (self.summary_json.as_str(),))
    }

    /// Contact pressure.
    #[getter]
    fn pressure<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let g = &self.solution.grid;
        field(py, &self.solution.pressure, g.nx, g.ny)
    }

    /// Gap between slider and deformed surface.
    #[getter]
    fn gap<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let g = &self.solution.grid;
        field(py, &self.solution.gap, g.nx, g.ny)
    }

    /// Elastic body's surface displacement.
    #[getter]
    fn body_displacement<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let g = &self.solution.grid;
        field(py, &self.solution.body_displacement, g.nx, g.ny)
    }

    /// Layer's displacement (`None` without a layer).
    #[getter]
    fn layer_displacement<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray2<f64>>> {
        let g = &self.solution.grid;
        let values = self.solution.layer_displacement.as_ref()?;
        Some(field(py, values, g.nx, g.ny))
    }

    /// Layer's compliance `C[p]` (`None` without a layer).
    #[getter]
    fn compliance<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray2<f64>>> {
        let g = &self.solution.grid;
        let values = self.solution.compliance.as_ref()?;
        Some(field(py, values, g.nx, g.ny))
    }

    /// x of the cell centres.
    #[getter]
    fn x<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let g = &self.solution.grid;
        let xs: Vec<f64> = (0..g.nx).map(|i| g.x(i)).collect();
        PyArray1::from_vec(py, xs)
    }

    /// y of the cell centres.
    #[getter]
    fn y<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let g = &self.solution.grid;
        let ys: Vec<f64> = (0..g.ny).map(|j| g.y(j)).collect();
        PyArray1::from_vec(py, ys)
    }
}

/// Solves `case`. The computation runs without the GIL, so other Python threads
/// (and other solves) run meanwhile.
#[pyfunction]
fn solve(py: Python<'_>, case: &Case) -> PyResult<Solution> {
    let file = &case.file;
    let (solution, seconds) = py
        .allow_threads(|| {
            let start = Instant::now();
            thirdbody::solve(&file.case, &file.solver).map(|s| (s, start.elapsed().as_secs_f64()))
        })
        .map_err(|e| {
            if e.is_input() {
                PyValueError::new_err(e.to_string())
            } else {
                PyRuntimeError::new_err(e.to_string())
            }
        })?;
    let report = thirdbody::Report::new(&file.case, &solution, seconds, None);
    let summary_json = serde_json::to_string(&report)
        .map_err(|e| PyRuntimeError::new_err(format!("summary: {e}")))?;
    Ok(Solution {
        solution,
        summary_json,
    })
}

/// The works the computations rely on, as BibTeX (what `thirdbody cite` prints).
#[pyfunction]
fn cite() -> &'static str {
    thirdbody::provenance::REFERENCES
}

/// The compiled part of the `thirdbody` package.
#[pymodule]
fn _thirdbody(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Case>()?;
    m.add_class::<Solution>()?;
    m.add_function(wrap_pyfunction!(solve, m)?)?;
    m.add_function(wrap_pyfunction!(cite, m)?)?;
    m.add("__version__", thirdbody::provenance::VERSION)?;
    Ok(())
}
