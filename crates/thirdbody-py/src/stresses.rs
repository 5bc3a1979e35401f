//! `Solution.stresses`: a section asked for from Python, refused before it starts
//! when its results cannot fit in the memory available, and computed in parts of a
//! few depths so that Ctrl-C stops it between parts. Each depth of a section is
//! computed alone by the library, so the parts give the same bits as one call.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use thirdbody::stress::request::summarise;
use thirdbody::stress::{
    Section, Side, StressField, StressRequest, StressResults, STORED_FIELD_NAMES,
};

use crate::errors::not_enough_memory;
use crate::interrupt::{in_own_pool, interruptible};

/// A part takes about this long at most (its size is doubled while it takes less
/// than a quarter of it and halved while it takes more): Ctrl-C waits no longer,
/// and a part's set-up (the kernels, the pressure's transform) is paid rarely.
const PART_SECONDS: Duration = Duration::from_millis(200);

/// Depths given as a numpy array (no copy through Python floats) or any sequence of
/// numbers.
pub fn depths_from(value: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
    if let Ok(array) = value.extract::<PyReadonlyArray1<'_, f64>>() {
        return Ok(array.as_array().to_vec());
    }
    value.extract::<Vec<f64>>().map_err(|_| {
        PyValueError::new_err(format!(
            "depths = {} is not allowed: a list or 1-D array of depths z >= 0",
            value.repr().map(|r| r.to_string()).unwrap_or_default()
        ))
    })
}

/// The section `name` of `Solution.stresses`.
pub fn section(
    name: &str,
    y: f64,
    z: f64,
    depths: Option<Vec<f64>>,
    interface: usize,
    side: &str,
) -> PyResult<Section> {
    let need_depths = |what: &str, depths: Option<Vec<f64>>| {
        depths.ok_or_else(|| {
            PyValueError::new_err(format!("section {what} needs depths (a list of z >= 0)"))
        })
    };
    Ok(match name {
        "xz" => Section::XzPlane {
            y,
            depths: need_depths("xz", depths)?,
        },
        "surface" => Section::Plane { z: 0.0 },
        "plane" => Section::Plane { z },
        "block" => Section::Block {
            depths: need_depths("block", depths)?,
        },
        "interface" => Section::Interface {
            index: interface,
            side: match side {
                "above" | "coating" => Side::Above,
                "below" | "substrate" => Side::Below,
                other => {
                    return Err(PyValueError::new_err(format!(
                        "side = {other:?} is not allowed: \"above\" or \"below\" (for a coating \
                         also \"coating\" or \"substrate\")"
                    )))
                }
            },
        },
        other => {
            return Err(PyValueError::new_err(format!(
                "section = {other:?} is not allowed: \"xz\", \"surface\", \"plane\", \"block\" or \"interface\""
            )))
        }
    })
}

fn gib(bytes: f64) -> String {
    format!("{:.1} GiB", bytes / (1u64 << 30) as f64)
}

/// `NotEnoughMemoryError` when the results of `section` named `name` on a grid of
/// `cells` (the library's estimate) would not fit in `available` bytes.
pub fn check_memory(
    py: Python<'_>,
    name: &str,
    section: &Section,
    cells: [usize; 2],
    available: Option<f64>,
) -> PyResult<()> {
    let Some(available) = available else {
        return Ok(());
    };
    let bytes = section.estimated_bytes(cells);
    if bytes <= available {
        return Ok(());
    }
    let depths = section.depth_count();
    let per_depth = bytes / depths.max(1) as f64;
    let fits = (available / per_depth).floor() as usize;
    let advice = if depths > 1 {
        format!("at most {fits} depths fit: ask for fewer, or for a few at a time")
    } else {
        "use a smaller grid".to_string()
    };
    Err(not_enough_memory(
        py,
        format!(
            "not enough memory: stresses(\"{name}\") with {depths} depth(s) needs about {} \
             ({} points of {} fields, 8 bytes each) but {} is available: {advice}",
            gib(bytes),
            section.point_count(cells),
            STORED_FIELD_NAMES.len(),
            gib(available),
        ),
    ))
}

/// `section` with the depths `range` of it (a section of several depths).
fn part(section: &Section, range: std::ops::Range<usize>) -> Section {
    match section {
        Section::XzPlane { y, depths } => Section::XzPlane {
            y: *y,
            depths: depths[range].to_vec(),
        },
        Section::Block { depths } => Section::Block {
            depths: depths[range].to_vec(),
        },
        other => other.clone(),
    }
}

/// Appends `more` (the next depths of the same section) to `field`.
fn append(field: &mut StressField, more: StressField) {
    field.zs.extend(more.zs);
    for (c, m) in field.components.iter_mut().zip(more.components) {
        c.extend(m);
    }
}

/// The stresses of `section` under `solution`'s pressure, in parts of a few depths
/// (at least 2: one depth alone is computed with parallel transforms, which may
/// round differently), looking at `stop` between parts: `None` once it is set.
fn in_parts(
    solution: &thirdbody::Solution,
    section: &Section,
    stop: &AtomicBool,
) -> Option<thirdbody::Result<StressField>> {
    let total = section.depth_count();
    if total <= 2 {
        return Some(solution.stresses(section));
    }
    if let Err(e) = section.validate(&solution.body) {
        return Some(Err(e));
    }
    let mut size = 2 * rayon::current_num_threads().max(1);
    let mut done = 0;
    let mut field: Option<StressField> = None;
    while done < total {
        if stop.load(Ordering::Relaxed) {
            return None;
        }
        let mut end = (done + size).min(total);
        if total - end == 1 {
            end = total;
        }
        let start = Instant::now();
        let more = match solution.stresses(&part(section, done..end)) {
            Ok(more) => more,
            Err(e) => return Some(Err(e)),
        };
        let took = start.elapsed();
        match field.as_mut() {
            Some(f) => append(f, more),
            None => field = Some(more),
        }
        done = end;
        if took < PART_SECONDS / 4 {
            size *= 2;
        } else if took > PART_SECONDS {
            size = (size / 2).max(2);
        }
    }
    field.map(Ok)
}

/// The stresses and summary `request` asks for under `solution`: the sections and
/// summary of [`StressRequest::compute`], each section computed in parts looking at
/// `stop` between them (`None` once it is set).
pub fn request_in_parts(
    solution: &thirdbody::Solution,
    request: &StressRequest,
    stop: &AtomicBool,
) -> Option<thirdbody::Result<StressResults>> {
    let named = match request.sections(&solution.body, &solution.grid, &solution.mean_pressure()) {
        Ok(named) => named,
        Err(e) => return Some(Err(e)),
    };
    let mut sections = Vec::with_capacity(named.len());
    for n in named {
        match in_parts(solution, &n.section, stop)? {
            Ok(field) => sections.push((n, field)),
            Err(e) => return Some(Err(e)),
        }
    }
    let summary = summarise(&sections, &solution.body);
    Some(Ok(StressResults { sections, summary }))
}

/// Computes `section` without the GIL; Ctrl-C stops it between parts and raises
/// `KeyboardInterrupt`.
pub fn compute(
    py: Python<'_>,
    solution: &thirdbody::Solution,
    section: &Section,
) -> PyResult<thirdbody::Result<StressField>> {
    let outcome = interruptible(
        py,
        |stop, _events: std::sync::mpsc::Sender<()>| {
            in_own_pool(None, || in_parts(solution, section, stop))
        },
        |_, _| Ok(()),
    )??;
    // Without a caller's exception the parts ran to the end.
    Ok(outcome.expect("stopped only by the caller's exception"))
}

/// A section's coordinates and fields as a dict (see `Solution.stresses`); the six
/// components move into numpy without a copy, so the results take the eleven fields
/// the library's estimate counts.
pub fn section_dict(py: Python<'_>, field: StressField) -> PyResult<Bound<'_, PyDict>> {
    let out = PyDict::new(py);
    out.set_item("x", PyArray1::from_slice(py, &field.xs))?;
    out.set_item("y", PyArray1::from_slice(py, &field.ys))?;
    out.set_item("z", PyArray1::from_slice(py, &field.zs))?;
    let shape = [field.zs.len(), field.ys.len(), field.xs.len()];
    let [s1, s2, s3] = field.principal();
    let derived = [s1, s2, s3, field.tau1(), field.von_mises()];
    let values = field.components.into_iter().chain(derived);
    for (name, values) in STORED_FIELD_NAMES.iter().zip(values) {
        let array = PyArray1::from_vec(py, values)
            .reshape(shape)
            .expect("a section's field has one value per point");
        out.set_item(*name, array)?;
    }
    Ok(out)
}
