//! A slider's heights given as a numpy array instead of a file (2-D for a height
//! map, 1-D for a line contact's profile): the case's text then reads
//! `file = "<array>"` and the parser's height-map loader hands it the array, so the
//! library checks it, interpolates it and hashes it exactly as the same heights
//! read from an NPY file.

use std::path::Path;

use numpy::{PyArray2, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use thirdbody::HeightMap;
use thirdbody_engine::heightmap;

/// What `slider.file` says when the heights are an array.
pub const ARRAY_FILE: &str = "<array>";

/// Heights of shape `(ny, nx)`, row-major with rows along y, as an NPY map's.
#[derive(Debug, Clone, PartialEq)]
pub struct Heights {
    pub nx: usize,
    pub ny: usize,
    pub values: Vec<f64>,
}

impl Heights {
    /// Any array-like of numbers with two dimensions, or one (a profile, one row),
    /// converted to float64 by numpy.
    pub fn from_py(value: &Bound<'_, PyAny>) -> PyResult<Self> {
        let numpy = value.py().import("numpy")?;
        let array = numpy
            .call_method1("ascontiguousarray", (value, "float64"))
            .map_err(|e| {
                PyValueError::new_err(format!(
                    "slider.heights is not allowed: a 2-D array of numbers, or 1-D for a \
                     profile ({e})"
                ))
            })?;
        if let Ok(row) = array.extract::<PyReadonlyArray1<'_, f64>>() {
            let values: Vec<f64> = row.as_array().iter().copied().collect();
            return Ok(Heights {
                nx: values.len(),
                ny: 1,
                values,
            });
        }
        let array: PyReadonlyArray2<'_, f64> = array.extract().map_err(|_| {
            let shape = array
                .getattr("shape")
                .and_then(|s| s.repr())
                .map(|r| r.to_string())
                .unwrap_or_default();
            PyValueError::new_err(format!(
                "slider.heights of shape {shape} is not allowed: a 2-D array (ny, nx), rows \
                 along y, or a 1-D array for a profile"
            ))
        })?;
        let view = array.as_array();
        let (ny, nx) = view.dim();
        Ok(Heights {
            nx,
            ny,
            values: view.iter().copied().collect(),
        })
    }

    /// The heights as a numpy array of shape `(ny, nx)` (pickling).
    pub fn to_py<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let array = numpy::ndarray::Array2::from_shape_vec((self.ny, self.nx), self.values.clone())
            .map_err(|e| PyValueError::new_err(format!("slider.heights: {e}")))?;
        Ok(PyArray2::from_owned_array(py, array))
    }
}

/// The height map `file` with sample spacing `cell_size`: the array `heights` when
/// the file is [`ARRAY_FILE`] and the case has one, else the file read beside the
/// case (`base`), as `thirdbody solve` reads it.
pub fn load(
    heights: Option<&Heights>,
    base: &Path,
    file: &str,
    cell_size: f64,
) -> thirdbody::Result<HeightMap> {
    match heights {
        Some(h) if file == ARRAY_FILE => Ok(HeightMap {
            nx: h.nx,
            ny: h.ny,
            cell_size,
            heights: h.values.clone(),
        }),
        _ => heightmap::load(base, file, cell_size),
    }
}
