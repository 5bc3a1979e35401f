//! Python bindings of thirdbody: a [`Case`] parsed by the library's own case-file
//! parser (so the validation and its messages are the CLI's), [`solve`] and a
//! [`Solver`] with the GIL released, and a [`Solution`] whose summary is the library's
//! [`thirdbody::Report`] (the keys of `summary.json`) and whose fields are numpy
//! arrays laid out as the CLI's NPY files (rows along y). The front end does no
//! physics: every number comes from the `thirdbody` crate.

mod errors;
mod heights;
mod interrupt;
mod stresses;

use std::ffi::OsString;
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::sync::atomic::Ordering;
use std::sync::{Arc, Mutex};
use std::time::Instant;

use numpy::{PyArray1, PyArray2, PyArrayDyn};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyBytes, PyDict, PyFloat, PyInt, PyTuple};
use thirdbody::case_file::{parse_case_file, CaseFile};
use thirdbody::{KernelCache, Progress};

use errors::{not_enough_memory, warn_all};
use heights::{Heights, ARRAY_FILE};
use interrupt::{in_own_pool, interruptible};
use thirdbody_engine::heightmap;
use thirdbody_engine::sweep::folder::{Record, SweepFile};
use thirdbody_engine::sweep::record::solve_record;
use thirdbody_engine::sweep::results::results_csv;
use thirdbody_engine::sweep::spec::apply;
use thirdbody_engine::sweep::values::KeyValue;
use thirdbody_engine::sweep::Sweep;

/// A contact case: slider, body, layer, loading, grid and solver settings, exactly as
/// a case file gives them. Immutable: `with_` derives variants.
#[pyclass(module = "thirdbody", frozen)]
struct Case {
    file: CaseFile,
    text: String,
    /// Folder that relative height-map paths are read from.
    base: PathBuf,
    /// The slider's heights when given as an array (`slider.file = "<array>"`).
    heights: Option<Arc<Heights>>,
}

/// Parses a case file's text as `thirdbody solve` does (height maps relative to
/// `base`, or the array `heights`). A `[sweep]` section (read by `thirdbody.sweep`,
/// as by `thirdbody sweep`) is set aside first: the case is the sweep's base case.
fn parse(text: &str, base: &Path, heights: Option<&Heights>) -> PyResult<CaseFile> {
    let without_sweep = text.parse::<toml::Table>().ok().and_then(|mut table| {
        table.remove("sweep")?;
        Some(table.to_string())
    });
    parse_case_file(
        without_sweep.as_deref().unwrap_or(text),
        &mut |file, cell_size| heights::load(heights, base, file, cell_size),
    )
    .map_err(|e| PyValueError::new_err(e.to_string()))
}

/// `slider` (a section's dict) without its `heights`, which are returned, and with
/// `file = "<array>"` in their place.
fn take_heights<'py>(
    slider: &Bound<'py, PyDict>,
) -> PyResult<(Bound<'py, PyDict>, Option<Heights>)> {
    let Some(value) = slider.get_item("heights")? else {
        return Ok((slider.clone(), None));
    };
    if slider.contains("file")? {
        return Err(PyValueError::new_err(
            "slider.heights and slider.file are not allowed together: the heights as an \
             array or a file of them",
        ));
    }
    let rest = slider.copy()?;
    rest.del_item("heights")?;
    rest.set_item("file", ARRAY_FILE)?;
    Ok((rest, Some(Heights::from_py(&value)?)))
}

/// A Python value as a TOML value; `key` names it in the error.
fn to_toml(key: &str, value: &Bound<'_, PyAny>) -> PyResult<toml::Value> {
    if let Ok(b) = value.downcast::<PyBool>() {
        return Ok(toml::Value::Boolean(b.is_true()));
    }
    if is_numpy_bool(value) {
        return Ok(toml::Value::Boolean(value.is_truthy()?));
    }
    // Any integer: Python's, numpy's (`np.int64`, a 0-d integer array), anything with
    // `__index__`; never a float, which has none.
    if value.is_instance_of::<PyInt>() || !value.is_instance_of::<PyFloat>() {
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

/// Whether `value` is a numpy boolean (`np.True_`, which is no Python `bool`).
fn is_numpy_bool(value: &Bound<'_, PyAny>) -> bool {
    let kind = value.get_type();
    let module = kind.module().map(|m| m.to_string()).unwrap_or_default();
    let name = kind.name().map(|n| n.to_string()).unwrap_or_default();
    module == "numpy" && (name == "bool_" || name == "bool")
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
        Self::with_heights(text, base, None)
    }

    fn with_heights(text: String, base: PathBuf, heights: Option<Arc<Heights>>) -> PyResult<Self> {
        let file = parse(&text, &base, heights.as_deref())?;
        Ok(Case {
            file,
            text,
            base,
            heights,
        })
    }
}

#[pymethods]
impl Case {
    /// A case from sections given as keyword arguments or one dict, mirroring the
    /// case file: `Case(slider={"shape": "sphere", "radius": 1.0}, substrate={...},
    /// loading={...}, grid={"cells": [128, 128]})`. Validated as a case file is. A
    /// height map may be given as an array instead of a file: `slider={"shape":
    /// "height_map", "heights": array, "cell_size": h}` (shape `(ny, nx)`, rows along
    /// y, as an NPY map).
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
        let mut heights = None;
        if let Some(slider) = py_sections.get_item("slider")? {
            if let Ok(slider) = slider.downcast::<PyDict>() {
                let (rest, taken) = take_heights(slider)?;
                py_sections.set_item("slider", rest)?;
                heights = taken.map(Arc::new);
            }
        }
        let toml::Value::Table(table) = to_toml("", py_sections.as_any())? else {
            unreachable!("a dict converts to a table")
        };
        Self::with_heights(table.to_string(), absolute_folder(None), heights)
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
    /// removes a key. `"slider.heights"` takes an array of heights (see `Case`).
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
        let mut heights = self.heights.clone();
        for d in [changes, kwargs].into_iter().flatten() {
            for (k, v) in d.iter() {
                let key: String = k.extract::<String>()?.replace("__", ".");
                if key == "slider.heights" {
                    heights = Some(Arc::new(Heights::from_py(&v)?));
                    let file = KeyValue::Set(toml::Value::String(ARRAY_FILE.into()));
                    apply(&mut table, "slider.file", &file).map_err(PyValueError::new_err)?;
                    continue;
                }
                let mut v = v;
                if key == "slider" {
                    // A whole slider section, perhaps with its heights.
                    if let Ok(slider) = v.downcast::<PyDict>() {
                        let (rest, taken) = take_heights(slider)?;
                        heights = taken.map(Arc::new).or(heights);
                        v = rest.into_any();
                    }
                }
                let value = if v.is_none() {
                    KeyValue::Remove
                } else {
                    KeyValue::Set(to_toml(&key, &v)?)
                };
                apply(&mut table, &key, &value).map_err(PyValueError::new_err)?;
            }
        }
        Self::with_heights(table.to_string(), self.base.clone(), heights)
    }

    /// The case file's text this case was parsed from (`slider.file = "<array>"`
    /// for heights given as an array).
    #[getter]
    fn toml(&self) -> &str {
        &self.text
    }

    /// The grid's cell counts, as the fields' shape: `(nx, ny)`, or `(nx,)` for a
    /// line contact.
    #[getter]
    fn cells<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        let [nx, ny] = self.file.case.grid.cells;
        if self.file.case.slider.is_line() {
            PyTuple::new(py, [nx])
        } else {
            PyTuple::new(py, [nx, ny])
        }
    }

    /// SHA-256 of the canonical case (the `case_hash` of `summary.json`).
    #[getter]
    fn case_hash(&self) -> String {
        thirdbody::provenance::case_hash(&self.file.case)
    }

    /// Pickling (process pools, Dask): the text, the height-map folder and the
    /// heights given as an array, if any.
    #[allow(clippy::type_complexity)]
    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(
        Bound<'py, PyAny>,
        (String, PathBuf, Option<Bound<'py, PyArray2<f64>>>),
    )> {
        let this = slf.get();
        let py = slf.py();
        let rebuild = py
            .import("thirdbody")?
            .getattr("Case")?
            .getattr("_rebuild")?;
        let heights = this.heights.as_ref().map(|h| h.to_py(py)).transpose()?;
        Ok((rebuild, (this.text.clone(), this.base.clone(), heights)))
    }

    /// The case `__reduce__` describes.
    #[staticmethod]
    fn _rebuild(text: String, base: PathBuf, heights: Option<&Bound<'_, PyAny>>) -> PyResult<Self> {
        let heights = heights.map(Heights::from_py).transpose()?.map(Arc::new);
        Self::with_heights(text, base, heights)
    }

    fn __repr__(&self) -> String {
        let [nx, ny] = self.file.case.grid.cells;
        let cells = if self.file.case.slider.is_line() {
            format!("line contact, {nx}")
        } else {
            format!("{nx} x {ny}")
        };
        format!(
            "<thirdbody.Case {cells} cells, hash {}>",
            &self.case_hash()[..12]
        )
    }
}

/// The solved contact: `summary` (a dict with the keys of `summary.json`) and the
/// fields as numpy arrays of shape `(ny, nx)`, or `(nx,)` for a line contact.
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

/// A solution's fields as read-only numpy arrays: of shape `(ny, nx)` for a point
/// contact, `(nx,)` for a line contact (which has no `y`).
struct Fields {
    pressure: Py<PyArrayDyn<f64>>,
    gap: Py<PyArrayDyn<f64>>,
    body_displacement: Py<PyArrayDyn<f64>>,
    layer_displacement: Option<Py<PyArrayDyn<f64>>>,
    compliance: Option<Py<PyArrayDyn<f64>>>,
    x: Py<PyArray1<f64>>,
    y: Option<Py<PyArray1<f64>>>,
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

impl Solution {
    /// The field `name` of [`DATASET_FIELDS`] (None when the case has no layer).
    fn named_field<'py>(
        &self,
        py: Python<'py>,
        name: &str,
    ) -> PyResult<Option<Bound<'py, PyArrayDyn<f64>>>> {
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
    fn pressure<'py>(&self, py: Python<'py>) -> Bound<'py, PyArrayDyn<f64>> {
        self.arrays.pressure.bind(py).clone()
    }

    /// Gap between slider and deformed surface.
    #[getter]
    fn gap<'py>(&self, py: Python<'py>) -> Bound<'py, PyArrayDyn<f64>> {
        self.arrays.gap.bind(py).clone()
    }

    /// Elastic body's surface displacement.
    #[getter]
    fn body_displacement<'py>(&self, py: Python<'py>) -> Bound<'py, PyArrayDyn<f64>> {
        self.arrays.body_displacement.bind(py).clone()
    }

    /// Layer's displacement (`None` without a layer).
    #[getter]
    fn layer_displacement<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArrayDyn<f64>>> {
        Some(self.arrays.layer_displacement.as_ref()?.bind(py).clone())
    }

    /// Layer's compliance `C[p]` (`None` without a layer).
    #[getter]
    fn compliance<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArrayDyn<f64>>> {
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
    /// centre at `depths`) or `"interface"` (interface number `interface` of a
    /// layered body, 0 under the top layer, on `side` = `"above"` or `"below"`; for
    /// a coating also `"coating"` or `"substrate"`); `depths` a list or 1-D array. Refused with
    /// `NotEnoughMemoryError` before it starts when the results (11 fields of 8 bytes
    /// per point) would not fit in the memory available. Runs without the GIL, a few
    /// depths at a time: Ctrl-C stops it and raises `KeyboardInterrupt`.
    #[pyo3(signature = (section, *, y=0.0, z=0.0, depths=None, interface=0, side="above"))]
    // Each Python keyword argument is one parameter.
    #[allow(clippy::too_many_arguments)]
    fn stresses<'py>(
        &self,
        py: Python<'py>,
        section: &str,
        y: f64,
        z: f64,
        depths: Option<&Bound<'py, PyAny>>,
        interface: usize,
        side: &str,
    ) -> PyResult<Bound<'py, PyDict>> {
        let name = section;
        if self.solution.grid.is_line() && y != 0.0 {
            return Err(PyValueError::new_err(format!(
                "y = {y} is not allowed: a line contact (plane strain) has no y; its \
                 sections are at y = 0"
            )));
        }
        let depths = depths.map(stresses::depths_from).transpose()?;
        let section = stresses::section(name, y, z, depths, interface, side)?;
        let g = self.solution.grid;
        stresses::check_memory(
            py,
            name,
            &section,
            [g.nx(), g.ny()],
            thirdbody_engine::memory::available_bytes(),
        )?;
        let field = stresses::compute(py, &self.solution, &section)?.map_err(to_py_error)?;
        stresses::section_dict(py, field)
    }

    /// The stresses of the case's `[stress]` section, computed with the solve as
    /// `thirdbody solve` computes them: a dict from each section's name (`"xz"`,
    /// `"surface"`, `"interface_0_above"`, ... as in the CLI's file names) to a dict
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
            out.set_item(named.name(), stresses::section_dict(py, field.clone())?)?;
        }
        Ok(out)
    }

    /// The solution as an `xarray.Dataset` (xarray is an optional dependency):
    /// variables `pressure`, `gap`, `body_displacement` and, with a layer,
    /// `layer_displacement` and `compliance` on dims `(y, x)`, or `(x,)` for a line
    /// contact (whose summary has no y keys); coordinates in the
    /// case's units (the `units` attribute of each is `"1"` for a dimensionless case);
    /// attributes: the case file's text (`case`), its hash, the thirdbody version and
    /// commit, every scalar of the summary and its `warnings`, if any, as one string
    /// of a line each (NetCDF-ready).
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
            if self.arrays.y.is_some() {
                variables.set_item(name, (("y", "x"), values, attrs))?;
            } else {
                variables.set_item(name, (("x",), values, attrs))?;
            }
        }
        let coords = PyDict::new(py);
        let axes = [
            Some((
                "x",
                self.x(py),
                "sliding direction (the slider moves in +x)",
            )),
            self.y(py).map(|y| ("y", y, "across the sliding direction")),
        ];
        for (name, values, long_name) in axes.into_iter().flatten() {
            let attrs = PyDict::new(py);
            attrs.set_item("units", unit("m"))?;
            attrs.set_item("long_name", long_name)?;
            coords.set_item(name, ((name,), values, attrs))?;
        }
        let attrs = PyDict::new(py);
        let summary = self.summary(py)?;
        let summary = summary.downcast::<PyDict>()?;
        for (k, v) in summary.iter() {
            // NetCDF attributes are numbers and strings: booleans become 0/1, the
            // warnings one string, and nulls and nested values are left out (they
            // stay in `summary`).
            if v.is_instance_of::<PyBool>() {
                attrs.set_item(k, i64::from(v.is_truthy()?))?;
            } else if k.extract::<String>()? == "warnings" {
                // A list of sentences: one string, a sentence per line.
                let lines: Vec<String> = v.extract()?;
                attrs.set_item(k, lines.join("\n"))?;
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

    /// y of the cell centres (`None` for a line contact, which has no y).
    #[getter]
    fn y<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        Some(self.arrays.y.as_ref()?.bind(py).clone())
    }

    /// Whether this is a line contact (plane strain: fields of shape `(nx,)`, loads
    /// and forces per unit length).
    #[getter]
    fn is_line(&self) -> bool {
        self.solution.grid.is_line()
    }
}

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
            // The fields' shape: one axis for a line contact.
            let [wx, wy] = grid.half_widths();
            if grid.is_line() {
                d.set_item("cells", (grid.nx(),))?;
                d.set_item("half_width", (wx,))?;
            } else {
                d.set_item("cells", (grid.nx(), grid.ny()))?;
                d.set_item("half_width", (wx, wy))?;
            }
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

/// `NotEnoughMemoryError` (a `ValueError`) with the CLI's message when a solve of
/// `file` (and its `[stress]` section) would not fit in the memory available now.
fn fits_in_memory(py: Python<'_>, file: &CaseFile) -> PyResult<()> {
    thirdbody_engine::memory::check(
        &file.case,
        file.stress.as_ref(),
        1,
        thirdbody_engine::memory::available_bytes(),
    )
    .map_err(|message| not_enough_memory(py, message))
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

/// Solves `case` with the kernels of `kernels` (building and keeping those it
/// lacks). The computation runs without the GIL on a thread of its own while the
/// calling thread waits: every 50 ms (and at each event) it gives the events to
/// `progress` and looks at Ctrl-C, which stops the solve and raises
/// `KeyboardInterrupt`. An exception from `progress` also stops the solve and is
/// raised; the case's `[stress]` section, computed a few depths at a time, stops as
/// well. The summary's warnings are given to `warnings.warn`.
fn solve_in(
    py: Python<'_>,
    case: &Case,
    progress: Option<PyObject>,
    stresses: bool,
    kernels: &Mutex<KernelCache>,
) -> PyResult<Solution> {
    let file = &case.file;
    if stresses {
        thirdbody_engine::geometry::check(&file.case, file.stress.as_ref())
            .map_err(PyValueError::new_err)?;
    }
    fits_in_memory(py, file)?;
    let request = file.stress.as_ref().filter(|_| stresses);
    let mut window = 0;
    let outcome = interruptible(
        py,
        |stop, events| {
            in_own_pool(None, || {
                // Taken on the solve's own thread: waiting for a solve of another
                // thread to give it back, this thread still answers Ctrl-C.
                let mut kernels = kernels.lock().unwrap_or_else(|e| e.into_inner());
                let start = Instant::now();
                let mut observer = |p: Progress| {
                    let _ = events.send(p);
                    if stop.load(Ordering::Relaxed) {
                        ControlFlow::Break(())
                    } else {
                        ControlFlow::Continue(())
                    }
                };
                let solution =
                    thirdbody::solve_with(&file.case, &file.solver, &mut kernels, &mut observer)?;
                let seconds = start.elapsed().as_secs_f64();
                // Stopped (Ctrl-C) in the stresses: no stresses, and the caller's
                // KeyboardInterrupt is raised instead of this result.
                let stresses = request
                    .and_then(|r| stresses::request_in_parts(&solution, r, stop))
                    .transpose()?;
                Ok((solution, seconds, stresses))
            })
        },
        |py, batch: Vec<Progress>| {
            for p in batch {
                if let Progress::Window { attempt, .. } = p {
                    window = attempt;
                }
                if let Some(callback) = &progress {
                    callback.call1(py, (progress_dict(py, &p, window)?,))?;
                }
            }
            Ok(())
        },
    )?;
    let (mut solution, seconds, stress_results) = outcome?.map_err(to_py_error)?;
    let report = thirdbody::Report::new(&file.case, &solution, seconds, stress_results.as_ref());
    let summary_json = serde_json::to_string(&report)
        .map_err(|e| PyRuntimeError::new_err(format!("summary: {e}")))?;
    let g = solution.grid;
    let shape = if g.is_line() {
        numpy::ndarray::IxDyn(&[g.nx()])
    } else {
        numpy::ndarray::IxDyn(&[g.ny(), g.nx()])
    };
    // The fields move into numpy without a copy; the pressure stays for stresses.
    let arrays = Fields {
        // Each cell's mean pressure (the centre value but where a contact's edge
        // cuts the cell), as the command line writes it.
        pressure: read_only(py, solution.mean_pressure().into_owned(), shape.clone())?,
        gap: read_only(py, std::mem::take(&mut solution.gap), shape.clone())?,
        body_displacement: read_only(
            py,
            std::mem::take(&mut solution.body_displacement),
            shape.clone(),
        )?,
        layer_displacement: solution
            .layer_displacement
            .take()
            .map(|v| read_only(py, v, shape.clone()))
            .transpose()?,
        compliance: solution
            .compliance
            .take()
            .map(|v| read_only(py, v, shape))
            .transpose()?,
        x: read_only(py, (0..g.nx()).map(|i| g.x(i)).collect(), g.nx())?,
        y: (!g.is_line())
            .then(|| read_only(py, (0..g.ny()).map(|j| g.y(j)).collect(), g.ny()))
            .transpose()?,
    };
    warn_all(py, &report.warnings)?;
    Ok(Solution {
        solution,
        arrays,
        summary_json,
        case_text: case.text.clone(),
        units: file.case.units,
        stress_results,
    })
}

/// Solves `case` with kernels built for this call (a `Solver` keeps them between
/// calls). The computation runs without the GIL on a thread of its own while the
/// calling thread waits: every 50 ms (and at each event) it gives the events to
/// `progress` (a callable taking one dict: `event` = `"window"` with `window`,
/// `cells`, `half_width`, or `"iteration"` with `window`, `iteration`, `residual`)
/// and looks at Ctrl-C, which stops the solve and raises `KeyboardInterrupt`. An
/// exception from `progress` also stops the solve and is raised. With `stresses`
/// (the default) the case's `[stress]` section, if any, is computed as `thirdbody
/// solve` computes it (`summary["stress"]`, `Solution.case_stresses()`). Each of the
/// summary's `warnings` is also given to `warnings.warn` as a `ThirdbodyWarning`.
#[pyfunction]
#[pyo3(signature = (case, progress=None, *, stresses=true))]
fn solve(
    py: Python<'_>,
    case: &Case,
    progress: Option<PyObject>,
    stresses: bool,
) -> PyResult<Solution> {
    solve_in(
        py,
        case,
        progress,
        stresses,
        &Mutex::new(KernelCache::new()),
    )
}

/// A solver that keeps what is costly to build between solves: the DC-FFT plans and
/// the surface kernels (a coated body's costs 0.1 to 6 s at 256²), one per body,
/// grid size and cell size, up to `capacity` of them (and 256 MiB). Solves of cases
/// that differ in load, velocity or layer reuse them; a case whose automatic window
/// comes out different (another load may choose another cell size) builds its own.
/// One solve at a time: a second thread's call waits for the first (give each
/// thread its own `Solver`).
#[pyclass(module = "thirdbody", frozen)]
struct Solver {
    kernels: Mutex<KernelCache>,
}

impl Solver {
    /// Runs `f` on the cache, waited for without the GIL (a solve in another thread
    /// may hold it, and that solve needs the GIL to finish).
    fn with_kernels<R: Send>(
        &self,
        py: Python<'_>,
        f: impl FnOnce(&mut KernelCache) -> R + Send,
    ) -> R {
        py.allow_threads(|| {
            // A solve that panicked left nothing half-written in the cache: entries
            // are added whole.
            let mut kernels = self.kernels.lock().unwrap_or_else(|e| e.into_inner());
            f(&mut kernels)
        })
    }
}

#[pymethods]
impl Solver {
    /// A solver with an empty cache keeping up to `capacity` kernels (0 keeps none).
    #[new]
    #[pyo3(signature = (capacity=8))]
    fn new(capacity: usize) -> Self {
        Solver {
            kernels: Mutex::new(KernelCache::with_capacity(capacity)),
        }
    }

    /// Solves `case` as `thirdbody.solve` does, with this solver's kernels.
    #[pyo3(signature = (case, progress=None, *, stresses=true))]
    fn solve(
        &self,
        py: Python<'_>,
        case: &Case,
        progress: Option<PyObject>,
        stresses: bool,
    ) -> PyResult<Solution> {
        solve_in(py, case, progress, stresses, &self.kernels)
    }

    /// Surface kernels built since the solver was made (each one not held when a
    /// solve asked for it).
    #[getter]
    fn kernels_built(&self, py: Python<'_>) -> usize {
        self.with_kernels(py, |k| k.spectra_built())
    }

    /// Surface kernels handed out again without building them.
    #[getter]
    fn kernels_reused(&self, py: Python<'_>) -> usize {
        self.with_kernels(py, |k| k.spectra_reused())
    }

    /// Surface kernels held now.
    #[getter]
    fn kernels_held(&self, py: Python<'_>) -> usize {
        self.with_kernels(py, |k| k.len())
    }

    /// Drops every kernel and plan held.
    fn clear(&self, py: Python<'_>) {
        self.with_kernels(py, |k| k.clear())
    }

    /// Solves one sweep case as `thirdbody sweep` does (sequential FFTs; a failure is
    /// a `failed` record), with this solver's kernels, and returns its record as JSON.
    /// Runs without the GIL.
    fn _solve_record(
        &self,
        py: Python<'_>,
        text: String,
        base: PathBuf,
        id: String,
        index: usize,
        labels: Vec<String>,
    ) -> PyResult<String> {
        // One thread per case: the executor runs the cases side by side.
        let record = self.with_kernels(py, |kernels| {
            in_own_pool(Some(1), || {
                solve_record(
                    id,
                    index,
                    labels,
                    || parse_case_file(&text, &mut |file, cell| heightmap::load(&base, file, cell)),
                    kernels,
                )
            })
        })?;
        serde_json::to_string(&record).map_err(|e| PyRuntimeError::new_err(format!("record: {e}")))
    }

    fn __repr__(&self, py: Python<'_>) -> String {
        let (held, built) = self.with_kernels(py, |k| (k.len(), k.spectra_built()));
        format!("<thirdbody.Solver holding {held} kernel(s), {built} built>")
    }
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
        if case.heights.is_some() {
            return Err(PyValueError::new_err(
                "slider.heights given as an array cannot be swept (the sweep's cases are \
                 case files): save them with numpy.save and give slider.file",
            ));
        }
        let sweep = Sweep::new(&case.text, &case.base, &arguments)
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        // Each case checked alone: the executor's workers may be other machines.
        sweep
            .check_memory(|_| true, 1, thirdbody_engine::memory::available_bytes())
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
    m.add_class::<Solver>()?;
    m.add_function(wrap_pyfunction!(_command_line, m)?)?;
    m.add("__version__", thirdbody::provenance::VERSION)?;
    Ok(())
}
