//! Python bindings of thirdbody (issue 12, first part): a [`Case`] parsed by the
//! library's own case-file parser (so the validation and its messages are the CLI's),
//! [`solve`] with the GIL released, and a [`Solution`] whose summary is the library's
//! [`thirdbody::Report`] (the keys of `summary.json`) and whose fields are numpy
//! arrays laid out as the CLI's NPY files (rows along y). The front end does no
//! physics: every number comes from the `thirdbody` crate.

use std::ffi::OsString;
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::{Duration, Instant};

use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyBytes, PyDict, PyInt};
use thirdbody::case_file::{parse_case_file, CaseFile};
use thirdbody::stress::{Section, Side, STORED_FIELD_NAMES};
use thirdbody::Progress;
use thirdbody_cli::heightmap;
use thirdbody_cli::sweep::folder::{Record, SweepFile};
use thirdbody_cli::sweep::results::results_csv;
use thirdbody_cli::sweep::run::solve_record;
use thirdbody_cli::sweep::spec::apply;
use thirdbody_cli::sweep::values::KeyValue;
use thirdbody_cli::sweep::Sweep;

/// A contact case: slider, body, layer, loading, grid and solver settings, exactly as
/// a case file gives them. Immutable: `with_` derives variants.
#[pyclass(module = "thirdbody", frozen)]
struct Case {
    file: CaseFile,
    text: String,
    /// Folder that relative height-map paths are read from.
    base: PathBuf,
}

/// Parses a case file's text as `thirdbody solve` does (height maps relative to
/// `base`). A `[sweep]` section (read by `thirdbody.sweep`, as by `thirdbody sweep`)
/// is set aside first: the case is the sweep's base case.
fn parse(text: &str, base: &Path) -> PyResult<CaseFile> {
    let without_sweep = text.parse::<toml::Table>().ok().and_then(|mut table| {
        table.remove("sweep")?;
        Some(table.to_string())
    });
    parse_case_file(
        without_sweep.as_deref().unwrap_or(text),
        &mut |file, cell_size| heightmap::load(base, file, cell_size),
    )
    .map_err(|e| PyValueError::new_err(e.to_string()))
}

/// A Python value as a TOML value; `key` names it in the error.
fn to_toml(key: &str, value: &Bound<'_, PyAny>) -> PyResult<toml::Value> {
    if let Ok(b) = value.downcast::<PyBool>() {
        return Ok(toml::Value::Boolean(b.is_true()));
    }
    if value.is_instance_of::<PyInt>() {
        if let Ok(i) = value.extract::<i64>() {
            return Ok(toml::Value::Integer(i));
        }
    }
    if let Ok(x) = value.extract::<f64>() {
        return Ok(toml::Value::Float(x));
    }
    if let Ok(s) = value.extract::<String>() {
        return Ok(toml::Value::String(s));
    }
    if let Ok(d) = value.downcast::<PyDict>() {
        let mut table = toml::Table::new();
        for (k, v) in d.iter() {
            let name: String = k.extract().map_err(|_| {
                PyValueError::new_err(format!("{key}: section keys must be strings"))
            })?;
            let dotted = if key.is_empty() {
                name.clone()
            } else {
                format!("{key}.{name}")
            };
            table.insert(name, to_toml(&dotted, &v)?);
        }
        return Ok(toml::Value::Table(table));
    }
    if let Ok(list) = value.try_iter() {
        let items: PyResult<Vec<toml::Value>> = list
            .enumerate()
            .map(|(i, v)| to_toml(&format!("{key}[{i}]"), &v?))
            .collect();
        return Ok(toml::Value::Array(items?));
    }
    Err(PyValueError::new_err(format!(
        "{key} = {} is not allowed: a number, a string, a boolean, a list or a dict",
        value.repr().map(|r| r.to_string()).unwrap_or_default()
    )))
}

/// `folder` (the working directory when `None` or empty) as an absolute path, so that
/// a case pickled to a worker started elsewhere (a Dask or Slurm worker) still finds
/// its height maps.
fn absolute_folder(folder: Option<&Path>) -> PathBuf {
    let folder = folder.filter(|f| !f.as_os_str().is_empty());
    let folder = folder.unwrap_or(Path::new("."));
    std::path::absolute(folder).unwrap_or_else(|_| folder.to_path_buf())
}

impl Case {
    fn from_text(text: String, base: PathBuf) -> PyResult<Self> {
        let file = parse(&text, &base)?;
        Ok(Case { file, text, base })
    }
}

#[pymethods]
impl Case {
    /// A case from sections given as keyword arguments or one dict, mirroring the
    /// case file: `Case(slider={"shape": "sphere", "radius": 1.0}, substrate={...},
    /// loading={...}, grid={"cells": [128, 128]})`. Validated as a case file is.
    #[new]
    #[pyo3(signature = (sections=None, **kwargs))]
    fn new(
        sections: Option<&Bound<'_, PyDict>>,
        kwargs: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let py_sections = PyDict::new(
            sections
                .map(|s| s.py())
                .or(kwargs.map(|k| k.py()))
                .ok_or_else(|| PyValueError::new_err("give the case's sections"))?,
        );
        for d in [sections, kwargs].into_iter().flatten() {
            py_sections.update(d.as_mapping())?;
        }
        let toml::Value::Table(table) = to_toml("", py_sections.as_any())? else {
            unreachable!("a dict converts to a table")
        };
        Self::from_text(table.to_string(), absolute_folder(None))
    }

    /// A case from the text of a TOML case file (docs/case-file.md); relative
    /// height-map paths are read from `base_dir` (default: the working directory).
    #[staticmethod]
    #[pyo3(signature = (text, base_dir=None))]
    fn from_toml(text: &str, base_dir: Option<PathBuf>) -> PyResult<Self> {
        Self::from_text(text.to_owned(), absolute_folder(base_dir.as_deref()))
    }

    /// A case from a TOML case file on disk (height maps read beside it).
    #[staticmethod]
    fn from_file(path: PathBuf) -> PyResult<Self> {
        let text = std::fs::read_to_string(&path).map_err(|e| {
            PyValueError::new_err(format!("cannot read case file {}: {e}", path.display()))
        })?;
        Self::from_text(text, absolute_folder(path.parent()))
    }

    /// A variant with some keys changed: dotted keys as `thirdbody sweep --vary`
    /// takes them (`"loading.velocity"`, `"layer.branch_times[0]"`), as a dict or
    /// keyword arguments with `__` for the dot (`loading__velocity=1e-2`); `None`
    /// removes a key.
    #[pyo3(signature = (changes=None, **kwargs))]
    fn with_(
        &self,
        changes: Option<&Bound<'_, PyDict>>,
        kwargs: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let mut table: toml::Table = self
            .text
            .parse()
            .map_err(|e| PyValueError::new_err(format!("{e}")))?;
        for d in [changes, kwargs].into_iter().flatten() {
            for (k, v) in d.iter() {
                let key: String = k.extract::<String>()?.replace("__", ".");
                let value = if v.is_none() {
                    KeyValue::Remove
                } else {
                    KeyValue::Set(to_toml(&key, &v)?)
                };
                apply(&mut table, &key, &value).map_err(PyValueError::new_err)?;
            }
        }
        Self::from_text(table.to_string(), self.base.clone())
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

    /// SHA-256 of the canonical case (the `case_hash` of `summary.json`).
    #[getter]
    fn case_hash(&self) -> String {
        thirdbody::provenance::case_hash(&self.file.case)
    }

    /// Pickling (process pools, Dask): the text and the height-map folder.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, (String, PathBuf))> {
        let this = slf.get();
        let rebuild = slf
            .py()
            .import("thirdbody")?
            .getattr("Case")?
            .getattr("from_toml")?;
        Ok((rebuild, (this.text.clone(), this.base.clone())))
    }

    fn __repr__(&self) -> String {
        let [nx, ny] = self.file.case.grid.cells;
        format!(
            "<thirdbody.Case {nx} x {ny} cells, hash {}>",
            &self.case_hash()[..12]
        )
    }
}

/// The solved contact: `summary` (a dict with the keys of `summary.json`) and the
/// fields as numpy arrays of shape `(ny, nx)`.
#[pyclass(module = "thirdbody", frozen)]
struct Solution {
    /// The library's solution; its pressure and grid serve later stress requests.
    solution: thirdbody::Solution,
    /// The fields as numpy arrays, made once when the solve ends and shared
    /// (read-only) by every access.
    arrays: Fields,
    summary_json: String,
    /// The case file's text (the Dataset's `case` attribute).
    case_text: String,
    units: thirdbody::Units,
    /// The case's `[stress]` section, computed with the solve as the CLI does.
    stress_results: Option<thirdbody::stress::StressResults>,
}

/// A solution's fields as read-only numpy arrays.
struct Fields {
    pressure: Py<PyArray2<f64>>,
    gap: Py<PyArray2<f64>>,
    body_displacement: Py<PyArray2<f64>>,
    layer_displacement: Option<Py<PyArray2<f64>>>,
    compliance: Option<Py<PyArray2<f64>>>,
    x: Py<PyArray1<f64>>,
    y: Py<PyArray1<f64>>,
}

/// A read-only numpy array that owns `values` (no copy), of shape `shape`.
fn read_only<'py, D: numpy::ndarray::Dimension>(
    py: Python<'py>,
    values: Vec<f64>,
    shape: impl numpy::ndarray::IntoDimension<Dim = D>,
) -> PyResult<Py<numpy::PyArray<f64, D>>> {
    let array = numpy::ndarray::Array::from_shape_vec(shape, values)
        .map_err(|e| PyRuntimeError::new_err(format!("a field's shape: {e}")))?;
    let array = numpy::PyArray::from_owned_array(py, array);
    // Shared by every access: nobody may change the solution under another reader.
    array.getattr("flags")?.setattr("writeable", false)?;
    Ok(array.unbind())
}

/// The fields of a Dataset: name, unit in SI, long name.
const DATASET_FIELDS: [(&str, &str, &str); 5] = [
    ("pressure", "Pa", "contact pressure"),
    ("gap", "m", "gap between slider and deformed surface"),
    (
        "body_displacement",
        "m",
        "elastic body's surface displacement",
    ),
    ("layer_displacement", "m", "third-body layer's displacement"),
    ("compliance", "m/Pa", "third-body layer's compliance C[p]"),
];

/// A section's coordinates and fields as a dict (see `Solution.stresses`).
fn section_dict<'py>(
    py: Python<'py>,
    field: &thirdbody::stress::StressField,
) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    out.set_item("x", PyArray1::from_slice(py, &field.xs))?;
    out.set_item("y", PyArray1::from_slice(py, &field.ys))?;
    out.set_item("z", PyArray1::from_slice(py, &field.zs))?;
    let shape = [field.zs.len(), field.ys.len(), field.xs.len()];
    for (name, values) in STORED_FIELD_NAMES.iter().zip(field.stored_fields()) {
        let array = PyArray1::from_vec(py, values)
            .reshape(shape)
            .expect("a section's field has one value per point");
        out.set_item(*name, array)?;
    }
    Ok(out)
}

impl Solution {
    /// The field `name` of [`DATASET_FIELDS`] (None when the case has no layer).
    fn named_field<'py>(
        &self,
        py: Python<'py>,
        name: &str,
    ) -> PyResult<Option<Bound<'py, PyArray2<f64>>>> {
        let a = &self.arrays;
        let array = match name {
            "pressure" => Some(&a.pressure),
            "gap" => Some(&a.gap),
            "body_displacement" => Some(&a.body_displacement),
            "layer_displacement" => a.layer_displacement.as_ref(),
            "compliance" => a.compliance.as_ref(),
            other => return Err(PyValueError::new_err(format!("no field {other}"))),
        };
        Ok(array.map(|a| a.bind(py).clone()))
    }
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
        self.arrays.pressure.bind(py).clone()
    }

    /// Gap between slider and deformed surface.
    #[getter]
    fn gap<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.arrays.gap.bind(py).clone()
    }

    /// Elastic body's surface displacement.
    #[getter]
    fn body_displacement<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.arrays.body_displacement.bind(py).clone()
    }

    /// Layer's displacement (`None` without a layer).
    #[getter]
    fn layer_displacement<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray2<f64>>> {
        Some(self.arrays.layer_displacement.as_ref()?.bind(py).clone())
    }

    /// Layer's compliance `C[p]` (`None` without a layer).
    #[getter]
    fn compliance<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray2<f64>>> {
        Some(self.arrays.compliance.as_ref()?.bind(py).clone())
    }

    /// x of the cell centres.
    #[getter]
    fn x<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.arrays.x.bind(py).clone()
    }

    /// Subsurface stresses on one section, as the CLI writes them: a dict of the
    /// coordinates `x`, `y`, `z` (1-D) and the eleven fields `sigma_x, sigma_y,
    /// sigma_z, tau_xy, tau_xz, tau_yz, s1, s2, s3, tau1, von_mises`, each of shape
    /// `(len(z), len(y), len(x))`, tension positive. `section` is `"xz"` (the plane
    /// `y`, at `depths`), `"surface"`, `"plane"` (depth `z`), `"block"` (every cell
    /// centre at `depths`) or `"interface"` (a coated body's interface, `side` =
    /// `"coating"` or `"substrate"`). Runs without the GIL.
    #[pyo3(signature = (section, *, y=0.0, z=0.0, depths=None, side="coating"))]
    fn stresses<'py>(
        &self,
        py: Python<'py>,
        section: &str,
        y: f64,
        z: f64,
        depths: Option<Vec<f64>>,
        side: &str,
    ) -> PyResult<Bound<'py, PyDict>> {
        let need_depths = |what: &str| {
            depths.clone().ok_or_else(|| {
                PyValueError::new_err(format!("section {what} needs depths (a list of z >= 0)"))
            })
        };
        let section = match section {
            "xz" => Section::XzPlane {
                y,
                depths: need_depths("xz")?,
            },
            "surface" => Section::Plane { z: 0.0 },
            "plane" => Section::Plane { z },
            "block" => Section::Block {
                depths: need_depths("block")?,
            },
            "interface" => Section::Interface {
                side: match side {
                    "coating" => Side::Coating,
                    "substrate" => Side::Substrate,
                    other => {
                        return Err(PyValueError::new_err(format!(
                            "side = {other:?} is not allowed: \"coating\" or \"substrate\""
                        )))
                    }
                },
            },
            other => {
                return Err(PyValueError::new_err(format!(
                    "section = {other:?} is not allowed: \"xz\", \"surface\", \"plane\", \"block\" or \"interface\""
                )))
            }
        };
        let field = py
            .allow_threads(|| in_own_pool(None, || self.solution.stresses(&section)))?
            .map_err(to_py_error)?;
        section_dict(py, &field)
    }

    /// The stresses of the case's `[stress]` section, computed with the solve as
    /// `thirdbody solve` computes them: a dict from each section's name (`"xz"`,
    /// `"surface"`, `"interface_coating"`, ... as in the CLI's file names) to a dict
    /// as `stresses` returns. Their scalars are `summary["stress"]`. Raises
    /// `ValueError` when the case has no `[stress]` section or was solved with
    /// `stresses=False`.
    fn case_stresses<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let results = self.stress_results.as_ref().ok_or_else(|| {
            PyValueError::new_err(
                "no stresses: the case has no [stress] section (docs/case-file.md) or was \
                 solved with stresses=False",
            )
        })?;
        let out = PyDict::new(py);
        for (named, field) in &results.sections {
            out.set_item(named.name(), section_dict(py, field)?)?;
        }
        Ok(out)
    }

    /// The solution as an `xarray.Dataset` (xarray is an optional dependency):
    /// variables `pressure`, `gap`, `body_displacement` and, with a layer,
    /// `layer_displacement` and `compliance` on dims `(y, x)`; coordinates in the
    /// case's units (the `units` attribute of each is `"1"` for a dimensionless case);
    /// attributes: the case file's text (`case`), its hash, the thirdbody version and
    /// commit, and every scalar of the summary (NetCDF-ready).
    fn to_xarray<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let xarray = py.import("xarray").map_err(|_| {
            pyo3::exceptions::PyImportError::new_err(
                "Solution.to_xarray needs xarray: pip install xarray",
            )
        })?;
        let si = self.units == thirdbody::Units::Si;
        let unit = |u: &'static str| if si { u } else { "1" };
        let variables = PyDict::new(py);
        for (name, si_unit, long_name) in DATASET_FIELDS {
            let values = self.named_field(py, name)?;
            let Some(values) = values else { continue };
            let attrs = PyDict::new(py);
            attrs.set_item("units", unit(si_unit))?;
            attrs.set_item("long_name", long_name)?;
            variables.set_item(name, (("y", "x"), values, attrs))?;
        }
        let coords = PyDict::new(py);
        for (name, values, long_name) in [
            (
                "x",
                self.x(py),
                "sliding direction (the slider moves in +x)",
            ),
            ("y", self.y(py), "across the sliding direction"),
        ] {
            let attrs = PyDict::new(py);
            attrs.set_item("units", unit("m"))?;
            attrs.set_item("long_name", long_name)?;
            coords.set_item(name, ((name,), values, attrs))?;
        }
        let attrs = PyDict::new(py);
        let summary = self.summary(py)?;
        let summary = summary.downcast::<PyDict>()?;
        for (k, v) in summary.iter() {
            // NetCDF attributes are numbers and strings: booleans become 0/1, and
            // nulls and nested values are left out (they stay in `summary`).
            if v.is_instance_of::<PyBool>() {
                attrs.set_item(k, i64::from(v.is_truthy()?))?;
            } else if v.is_instance_of::<PyInt>()
                || v.extract::<f64>().is_ok()
                || v.extract::<String>().is_ok()
            {
                attrs.set_item(k, v)?;
            }
        }
        attrs.set_item("case", &self.case_text)?;
        let kwargs = PyDict::new(py);
        kwargs.set_item("data_vars", variables)?;
        kwargs.set_item("coords", coords)?;
        kwargs.set_item("attrs", attrs)?;
        xarray.call_method("Dataset", (), Some(&kwargs))
    }

    /// y of the cell centres.
    #[getter]
    fn y<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.arrays.y.bind(py).clone()
    }
}

/// Runs `work` on a rayon pool made for this call (`threads` threads; by default
/// as many as rayon's global pool would have, so results equal the CLI's). Never
/// rayon's global pool: a process forked after that pool started (a
/// `ProcessPoolExecutor`'s worker on Linux) inherits it without its threads, and its
/// first parallel loop would wait forever. A pool costs tens of microseconds.
fn in_own_pool<R: Send>(threads: Option<usize>, work: impl FnOnce() -> R + Send) -> PyResult<R> {
    let mut builder = rayon::ThreadPoolBuilder::new();
    if let Some(n) = threads {
        builder = builder.num_threads(n);
    }
    let pool = builder
        .build()
        .map_err(|e| PyRuntimeError::new_err(format!("cannot start the solver's threads: {e}")))?;
    Ok(pool.install(work))
}

/// How often a running solve looks at the caller's signals (Ctrl-C) and hands
/// progress to the caller's callback.
const POLL: Duration = Duration::from_millis(50);

/// A progress event as the dict given to `solve`'s `progress` callback.
fn progress_dict<'py>(
    py: Python<'py>,
    progress: &Progress,
    window: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    match *progress {
        Progress::Window { attempt, grid } => {
            d.set_item("event", "window")?;
            d.set_item("window", attempt)?;
            d.set_item("cells", (grid.nx, grid.ny))?;
            let [wx, wy] = grid.half_widths();
            d.set_item("half_width", (wx, wy))?;
        }
        Progress::Iteration {
            iteration,
            residual,
        } => {
            d.set_item("event", "iteration")?;
            d.set_item("window", window)?;
            d.set_item("iteration", iteration)?;
            d.set_item("residual", residual)?;
        }
    }
    Ok(d)
}

/// `ValueError` with the CLI's message when a solve of `file` (and its `[stress]`
/// section) would not fit in the memory available now.
fn fits_in_memory(file: &CaseFile) -> PyResult<()> {
    thirdbody_cli::memory::check(
        &file.case,
        file.stress.as_ref(),
        1,
        thirdbody_cli::memory::available_bytes(),
    )
    .map_err(PyValueError::new_err)
}

/// A library error as the Python exception: bad input is a `ValueError` with the
/// CLI's message, anything else a `RuntimeError`.
fn to_py_error(e: thirdbody::Error) -> PyErr {
    if e.is_input() {
        PyValueError::new_err(e.to_string())
    } else {
        PyRuntimeError::new_err(e.to_string())
    }
}

/// Solves `case`. The computation runs without the GIL on a thread of its own while
/// the calling thread waits: every 50 ms (and at each event) it gives the events to
/// `progress` (a callable taking one dict: `event` = `"window"` with `window`,
/// `cells`, `half_width`, or `"iteration"` with `window`, `iteration`, `residual`)
/// and looks at Ctrl-C, which stops the solve and raises `KeyboardInterrupt`. An
/// exception from `progress` also stops the solve and is raised. With `stresses`
/// (the default) the case's `[stress]` section, if any, is computed as `thirdbody
/// solve` computes it (`summary["stress"]`, `Solution.case_stresses()`).
#[pyfunction]
#[pyo3(signature = (case, progress=None, *, stresses=true))]
fn solve(
    py: Python<'_>,
    case: &Case,
    progress: Option<PyObject>,
    stresses: bool,
) -> PyResult<Solution> {
    let file = &case.file;
    fits_in_memory(file)?;
    let stop = AtomicBool::new(false);
    let (events, received) = mpsc::channel::<Progress>();
    let mut caller_error: Option<PyErr> = None;
    let mut window = 0;
    let (stop, caller_error_slot, progress) = (&stop, &mut caller_error, &progress);
    let request = file.stress.as_ref().filter(|_| stresses);
    let outcome = py.allow_threads(move || {
        std::thread::scope(|scope| {
            let worker = scope.spawn(move || {
                in_own_pool(None, || {
                    let start = Instant::now();
                    let mut kernels = thirdbody::KernelCache::new();
                    let mut observer = |p: Progress| {
                        let _ = events.send(p);
                        if stop.load(Ordering::Relaxed) {
                            ControlFlow::Break(())
                        } else {
                            ControlFlow::Continue(())
                        }
                    };
                    let solution = thirdbody::solve_with(
                        &file.case,
                        &file.solver,
                        &mut kernels,
                        &mut observer,
                    )?;
                    let seconds = start.elapsed().as_secs_f64();
                    let stresses = request.map(|r| solution.stress_results(r)).transpose()?;
                    Ok((solution, seconds, stresses))
                })
            });
            let mut pending = Vec::new();
            loop {
                let finished = match received.recv_timeout(POLL) {
                    Ok(p) => {
                        pending.push(p);
                        pending.extend(received.try_iter());
                        false
                    }
                    Err(RecvTimeoutError::Timeout) => false,
                    Err(RecvTimeoutError::Disconnected) => true,
                };
                if caller_error_slot.is_none() {
                    let checked = Python::with_gil(|py| -> PyResult<()> {
                        py.check_signals()?;
                        for p in pending.drain(..) {
                            if let Progress::Window { attempt, .. } = p {
                                window = attempt;
                            }
                            if let Some(callback) = progress {
                                callback.call1(py, (progress_dict(py, &p, window)?,))?;
                            }
                        }
                        Ok(())
                    });
                    if let Err(e) = checked {
                        *caller_error_slot = Some(e);
                        stop.store(true, Ordering::Relaxed);
                    }
                }
                pending.clear();
                if finished {
                    break;
                }
            }
            worker.join()
        })
    });
    if let Some(e) = caller_error {
        return Err(e);
    }
    let (mut solution, seconds, stress_results) = outcome
        .map_err(|_| PyRuntimeError::new_err("the solver panicked (a bug, please report it)"))??
        .map_err(to_py_error)?;
    let report = thirdbody::Report::new(&file.case, &solution, seconds, stress_results.as_ref());
    let summary_json = serde_json::to_string(&report)
        .map_err(|e| PyRuntimeError::new_err(format!("summary: {e}")))?;
    let g = solution.grid;
    let shape = (g.ny, g.nx);
    // The fields move into numpy without a copy; the pressure stays for stresses.
    let arrays = Fields {
        pressure: read_only(py, solution.pressure.clone(), shape)?,
        gap: read_only(py, std::mem::take(&mut solution.gap), shape)?,
        body_displacement: read_only(py, std::mem::take(&mut solution.body_displacement), shape)?,
        layer_displacement: solution
            .layer_displacement
            .take()
            .map(|v| read_only(py, v, shape))
            .transpose()?,
        compliance: solution
            .compliance
            .take()
            .map(|v| read_only(py, v, shape))
            .transpose()?,
        x: read_only(py, (0..g.nx).map(|i| g.x(i)).collect(), g.nx)?,
        y: read_only(py, (0..g.ny).map(|j| g.y(j)).collect(), g.ny)?,
    };
    Ok(Solution {
        solution,
        arrays,
        summary_json,
        case_text: case.text.clone(),
        units: file.case.units,
        stress_results,
    })
}

/// The cases of a sweep (the CLI's `thirdbody sweep` product, ids and labels) and
/// the assembly of its `results.csv`; `thirdbody.sweep` runs the cases.
#[pyclass(module = "thirdbody", frozen)]
struct SweepPlan {
    sweep: Sweep,
    file: SweepFile,
    base: PathBuf,
}

/// One `--vary` argument from a Python key and value: a string is the CLI's value
/// syntax (`"1e-3..1e-1:10"`, `"linear,table"`); a list or tuple gives the values
/// (`None` removes the key).
fn vary_argument(key: &str, value: &Bound<'_, PyAny>) -> PyResult<String> {
    if let Ok(text) = value.extract::<String>() {
        return Ok(format!("{key}={text}"));
    }
    if value.downcast::<PyDict>().is_err() {
        if let Ok(items) = value.try_iter() {
            let mut written = Vec::new();
            for (i, item) in items.enumerate() {
                let item = item?;
                if item.is_none() {
                    written.push("none".to_string());
                } else {
                    written.push(to_toml(&format!("{key}[{i}]"), &item)?.to_string());
                }
            }
            return Ok(format!("{key}={}", written.join(",")));
        }
    }
    Err(PyValueError::new_err(format!(
        "vary[{key:?}] is not allowed: a list of values or a string in the syntax of \
         thirdbody sweep --vary (e.g. \"1e-3..1e-1:10\")"
    )))
}

#[pymethods]
impl SweepPlan {
    /// The product of `vary` (key -> values) over `case`, every case checked.
    #[new]
    fn new(case: &Case, vary: &Bound<'_, PyDict>) -> PyResult<Self> {
        let mut arguments = Vec::new();
        for (k, v) in vary.iter() {
            let key: String = k.extract()?;
            arguments.push(vary_argument(&key, &v)?);
        }
        let sweep = Sweep::new(&case.text, &case.base, &arguments)
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        // Each case checked alone: the executor's workers may be other machines.
        sweep
            .check_memory(|_| true, 1, thirdbody_cli::memory::available_bytes())
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        let file = SweepFile::of(&sweep);
        Ok(SweepPlan {
            sweep,
            file,
            base: case.base.clone(),
        })
    }

    fn __len__(&self) -> usize {
        self.sweep.len()
    }

    /// The varied keys, in order.
    #[getter]
    fn axes(&self) -> Vec<String> {
        self.sweep.axes().iter().map(|a| a.name.clone()).collect()
    }

    /// The arguments of `_solve_record` for case `index`: its case text, the
    /// height-map folder, its id, index and labels.
    fn job(&self, index: usize) -> PyResult<(String, PathBuf, String, usize, Vec<String>)> {
        if index >= self.sweep.len() {
            return Err(PyValueError::new_err(format!(
                "case {index} is not in a sweep of {} cases",
                self.sweep.len()
            )));
        }
        Ok((
            self.sweep.case_text(index),
            self.base.clone(),
            self.sweep.id(index).to_string(),
            index,
            self.sweep.labels(index),
        ))
    }

    /// The text of `results.csv` from the records (JSON, as `_solve_record` returns).
    fn results_csv<'py>(
        &self,
        py: Python<'py>,
        records: Vec<String>,
    ) -> PyResult<Bound<'py, PyBytes>> {
        let records: Vec<Record> = records
            .iter()
            .map(|r| serde_json::from_str(r))
            .collect::<Result<_, _>>()
            .map_err(|e| PyRuntimeError::new_err(format!("a sweep record: {e}")))?;
        let bytes = results_csv(&self.file, &records)
            .map_err(|e| PyRuntimeError::new_err(format!("results.csv: {e:#}")))?;
        Ok(PyBytes::new(py, &bytes))
    }
}

/// Solves one sweep case as `thirdbody sweep` does (sequential FFTs; a failure is a
/// `failed` record) and returns its record as JSON. Runs without the GIL.
#[pyfunction]
fn _solve_record(
    py: Python<'_>,
    text: String,
    base: PathBuf,
    id: String,
    index: usize,
    labels: Vec<String>,
) -> PyResult<String> {
    // One thread per case: the executor runs the cases side by side.
    let record = py.allow_threads(|| {
        in_own_pool(Some(1), || {
            solve_record(
                id,
                index,
                labels,
                || parse_case_file(&text, &mut |file, cell| heightmap::load(&base, file, cell)),
                &mut thirdbody::KernelCache::new(),
            )
        })
    })?;
    serde_json::to_string(&record).map_err(|e| PyRuntimeError::new_err(format!("record: {e}")))
}

/// Runs the `thirdbody` command line with `args` (program name first) and returns
/// its exit code: the package's `thirdbody` script.
#[pyfunction]
fn _command_line(py: Python<'_>, args: Vec<OsString>) -> u8 {
    py.allow_threads(|| thirdbody_cli::app::run_command_line(args))
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
    m.add_class::<SweepPlan>()?;
    m.add_function(wrap_pyfunction!(_solve_record, m)?)?;
    m.add_function(wrap_pyfunction!(_command_line, m)?)?;
    m.add("__version__", thirdbody::provenance::VERSION)?;
    Ok(())
}
