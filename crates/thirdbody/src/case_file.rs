//! Case files: the TOML text that describes one contact problem (slider, body,
//! layer, loading, grid and solver settings), parsed into a [`Case`] and
//! [`SolverParams`] and then checked by [`Case::validate`]. The schema and every
//! key's range are documented in `docs/case-file.md`; the physics of each section
//! is in paper eq. 1-2 and 9-12 (layer, bodies, friction).
//!
//! Every section denies unknown keys. A key that the chosen options do not use
//! (`delta` with `law = "linear"`, `radius_x` with a sphere, ...) is an
//! [`Error::UnusedField`]; a key the options need is an [`Error::MissingField`];
//! syntax and type errors are [`Error::Parse`] with one line `line L: ...`. The
//! library never touches the filesystem: a height map is loaded by a callback that
//! the caller supplies.

use serde::Deserialize;

use crate::case::{Body, Case, Elastic, GridSpec, Loading, Units};
use crate::contact::SolverParams;
use crate::error::{Error, Result};
use crate::layer::{
    ComplianceLaw, Integration, Layer, RelaxationBranch, RetardationBranch, Rheology, Table,
};
use crate::shape::{HeightMap, Slider};
use crate::stress::{SectionKind, StressRequest};

/// A parsed and validated case file.
#[derive(Debug, Clone, PartialEq)]
pub struct CaseFile {
    /// The contact problem.
    pub case: Case,
    /// Solver settings (`[solver]`, defaults otherwise).
    pub solver: SolverParams,
    /// Stresses to compute after the solve (`[stress]`; `None` without that section).
    pub stress: Option<StressRequest>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCase {
    units: Option<RawUnits>,
    slider: Option<RawSlider>,
    substrate: Option<RawElastic>,
    coating: Option<RawCoating>,
    layer: Option<RawLayer>,
    loading: Option<RawLoading>,
    grid: Option<RawGrid>,
    solver: Option<RawSolver>,
    stress: Option<RawStress>,
}

#[derive(Debug, Deserialize)]
#[serde(rename_all = "snake_case")]
enum RawUnits {
    Dimensionless,
    Si,
}

#[derive(Debug, Deserialize)]
#[serde(rename_all = "snake_case")]
enum RawShape {
    Sphere,
    Ellipsoid,
    HeightMap,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSlider {
    shape: Option<RawShape>,
    radius: Option<f64>,
    radius_x: Option<f64>,
    radius_y: Option<f64>,
    file: Option<String>,
    cell_size: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawElastic {
    young: Option<f64>,
    poisson: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCoating {
    young: Option<f64>,
    poisson: Option<f64>,
    thickness: Option<f64>,
}

#[derive(Debug, Default, Clone, Copy, Deserialize)]
#[serde(rename_all = "snake_case")]
enum RawRheology {
    #[default]
    Maxwell,
    KelvinVoigt,
    Zener,
    Burgers,
    Prony,
    RelaxationProny,
    FractionalZener,
}

#[derive(Debug, Default, Deserialize)]
#[serde(rename_all = "snake_case")]
enum RawLaw {
    #[default]
    Linear,
    Sigmoid,
    Table,
}

#[derive(Debug, Default, Deserialize)]
#[serde(rename_all = "snake_case")]
enum RawIntegration {
    #[default]
    Exact,
    Secant,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLayer {
    #[serde(default)]
    rheology: RawRheology,
    compliance: Option<f64>,
    relaxation_time: Option<f64>,
    glassy_compliance: Option<f64>,
    retardation_time: Option<f64>,
    branch_compliances: Option<Vec<f64>>,
    branch_times: Option<Vec<f64>>,
    viscosity: Option<f64>,
    equilibrium_stiffness: Option<f64>,
    branch_stiffnesses: Option<Vec<f64>>,
    order: Option<f64>,
    branch_count: Option<usize>,
    #[serde(default)]
    law: RawLaw,
    delta: Option<f64>,
    p0: Option<f64>,
    pressures: Option<Vec<f64>>,
    compliances: Option<Vec<f64>>,
    #[serde(default)]
    integration: RawIntegration,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLoading {
    normal_load: Option<f64>,
    velocity: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawGrid {
    #[serde(default, deserialize_with = "exactly_two")]
    cells: Option<[usize; 2]>,
    #[serde(default, deserialize_with = "exactly_two")]
    half_width: Option<[f64; 2]>,
    #[serde(default, deserialize_with = "exactly_two")]
    centre: Option<[f64; 2]>,
}

/// A pair `[x, y]` written as an array of exactly two numbers (a fixed-size array
/// alone would silently drop a third element: `cells = [128, 128, 128]`).
fn exactly_two<'de, D, T>(d: D) -> std::result::Result<Option<[T; 2]>, D::Error>
where
    D: serde::Deserializer<'de>,
    T: Deserialize<'de> + Copy,
{
    let values: Vec<T> = Vec::deserialize(d)?;
    match values[..] {
        [x, y] => Ok(Some([x, y])),
        _ => Err(serde::de::Error::custom(format!(
            "{} values given: give exactly two, [x, y]",
            values.len()
        ))),
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSolver {
    tolerance: Option<f64>,
    max_iterations: Option<usize>,
    max_windows: Option<usize>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawStress {
    sections: Option<Vec<String>>,
    y: Option<f64>,
    max_depth: Option<f64>,
    depth_points: Option<usize>,
    planes: Option<Vec<f64>>,
}

/// Parses and validates a case file.
///
/// `load_height_map(file, cell_size)` is called for `shape = "height_map"` with the
/// `slider.file` string as written and `slider.cell_size`; it returns the map (its
/// heights are checked afterwards by [`Case::validate`]).
///
/// # Examples
/// ```
/// use thirdbody::case_file::parse_case_file;
/// let text = r#"
/// [slider]
/// shape = "sphere"
/// radius = 1.0
/// [substrate]
/// young = 1.0
/// poisson = 0.3
/// [loading]
/// normal_load = 5e-6
/// [grid]
/// cells = [64, 64]
/// "#;
/// let file = parse_case_file(text, &mut |_, _| unreachable!()).unwrap();
/// assert!(file.case.layer.is_none());
/// ```
pub fn parse_case_file(
    text: &str,
    load_height_map: &mut dyn FnMut(&str, f64) -> Result<HeightMap>,
) -> Result<CaseFile> {
    let raw: RawCase = toml::from_str(text).map_err(|e| toml_error(text, &e))?;
    let slider = section(raw.slider, "slider", "shape = \"sphere\" and radius (> 0)")?;
    let substrate = section(
        raw.substrate,
        "substrate",
        "young (> 0) and poisson (-1 < poisson < 0.5)",
    )?;
    let loading = section(raw.loading, "loading", "normal_load (> 0)")?;
    let grid = section(raw.grid, "grid", "cells = [nx, ny], each >= 8")?;

    let substrate = elastic(substrate.young, substrate.poisson, "substrate")?;
    let body = match raw.coating {
        None => Body::Homogeneous(substrate),
        Some(c) => Body::Coated {
            coating: elastic(c.young, c.poisson, "coating")?,
            thickness: need(
                c.thickness,
                "coating.thickness",
                "a [coating] needs its thickness (> 0)",
            )?,
            substrate,
        },
    };
    let layer = raw.layer.map(layer).transpose()?;
    let loading = Loading {
        normal_load: need(
            loading.normal_load,
            "loading.normal_load",
            "the normal load Q (> 0) is always needed",
        )?,
        velocity: loading.velocity,
    };
    let grid = GridSpec {
        cells: need(
            grid.cells,
            "grid.cells",
            "give cells = [nx, ny] with nx, ny >= 8",
        )?,
        half_width: grid.half_width,
        centre: grid.centre,
    };
    let solver = solver_params(raw.solver)?;
    let units = match raw.units {
        None | Some(RawUnits::Dimensionless) => Units::Dimensionless,
        Some(RawUnits::Si) => Units::Si,
    };
    // The slider last: loading a height map may read a file, so do it only for an
    // otherwise well-formed case.
    let slider = slider_shape(slider, load_height_map)?;
    let case = Case {
        slider,
        body,
        layer,
        loading,
        grid,
        units,
    };
    case.validate()?;
    let stress = raw.stress.map(stress_request).transpose()?;
    if let Some(request) = &stress {
        request.validate(&case.body)?;
    }
    Ok(CaseFile {
        case,
        solver,
        stress,
    })
}

/// One line `line L: message` (plus the section the line is in) from a TOML error.
fn toml_error(text: &str, e: &toml::de::Error) -> Error {
    let message = e.message().trim().replace('\n', " ");
    let Some(span) = e.span() else {
        return Error::Parse(message);
    };
    let start = span.start.min(text.len());
    let line = text[..start].matches('\n').count() + 1;
    let line_start = text[..start].rfind('\n').map_or(0, |k| k + 1);
    let current = text[line_start..].lines().next().unwrap_or("").trim_start();
    // Where the error is: the key on its line, in the last table header above it.
    if current.starts_with('[') {
        return Error::Parse(format!("line {line}: {message}"));
    }
    let table = text[..line_start]
        .lines()
        .rev()
        .map(str::trim)
        .find(|l| l.starts_with('['))
        .and_then(|l| l.split(']').next())
        .map(|l| l.trim_start_matches('[').trim());
    let key = current
        .split_once('=')
        .map(|(k, _)| k.trim())
        .filter(|k| !k.is_empty());
    let place = match (table, key) {
        (Some(t), Some(k)) => format!(" ({t}.{k})"),
        (Some(t), None) => format!(" (in [{t}])"),
        (None, Some(k)) => format!(" ({k})"),
        (None, None) => String::new(),
    };
    Error::Parse(format!("line {line}{place}: {message}"))
}

fn section<T>(value: Option<T>, name: &str, needs: &str) -> Result<T> {
    value.ok_or_else(|| Error::MissingField {
        field: format!("[{name}]"),
        why: format!("every case needs a [{name}] section with {needs}"),
    })
}

fn need<T>(value: Option<T>, field: &str, why: &str) -> Result<T> {
    value.ok_or_else(|| Error::MissingField {
        field: field.to_string(),
        why: why.to_string(),
    })
}

fn unused(present: bool, field: &str, why: &str) -> Result<()> {
    if present {
        Err(Error::UnusedField {
            field: field.to_string(),
            why: why.to_string(),
        })
    } else {
        Ok(())
    }
}

fn elastic(young: Option<f64>, poisson: Option<f64>, section: &str) -> Result<Elastic> {
    Ok(Elastic {
        young: need(
            young,
            &format!("{section}.young"),
            "Young's modulus (> 0) is needed",
        )?,
        poisson: need(
            poisson,
            &format!("{section}.poisson"),
            "Poisson's ratio (-1 < poisson < 0.5) is needed",
        )?,
    })
}

fn slider_shape(
    s: RawSlider,
    load_height_map: &mut dyn FnMut(&str, f64) -> Result<HeightMap>,
) -> Result<Slider> {
    let shape = need(
        s.shape,
        "slider.shape",
        "choose \"sphere\", \"ellipsoid\" or \"height_map\"",
    )?;
    match shape {
        RawShape::Sphere => {
            let why = "a sphere has only a radius";
            unused(s.radius_x.is_some(), "slider.radius_x", why)?;
            unused(s.radius_y.is_some(), "slider.radius_y", why)?;
            unused(s.file.is_some(), "slider.file", why)?;
            unused(s.cell_size.is_some(), "slider.cell_size", why)?;
            Ok(Slider::Sphere {
                radius: need(s.radius, "slider.radius", "a sphere needs its radius (> 0)")?,
            })
        }
        RawShape::Ellipsoid => {
            let why = "an ellipsoid has radius_x and radius_y";
            unused(s.radius.is_some(), "slider.radius", why)?;
            unused(s.file.is_some(), "slider.file", why)?;
            unused(s.cell_size.is_some(), "slider.cell_size", why)?;
            Ok(Slider::Ellipsoid {
                radius_x: need(
                    s.radius_x,
                    "slider.radius_x",
                    "an ellipsoid needs radius_x (> 0)",
                )?,
                radius_y: need(
                    s.radius_y,
                    "slider.radius_y",
                    "an ellipsoid needs radius_y (> 0)",
                )?,
            })
        }
        RawShape::HeightMap => {
            let why = "a height map is given by file and cell_size";
            unused(s.radius.is_some(), "slider.radius", why)?;
            unused(s.radius_x.is_some(), "slider.radius_x", why)?;
            unused(s.radius_y.is_some(), "slider.radius_y", why)?;
            let file = need(
                s.file,
                "slider.file",
                "a height map needs its file (CSV or NPY)",
            )?;
            let cell_size = need(
                s.cell_size,
                "slider.cell_size",
                "a height map needs the spacing of its samples (> 0)",
            )?;
            Ok(Slider::HeightMap(load_height_map(&file, cell_size)?))
        }
    }
}

fn layer(l: RawLayer) -> Result<Layer> {
    let law = match l.law {
        RawLaw::Linear => {
            let why = "only law = \"sigmoid\" uses delta and p0, only law = \"table\" uses \
                       pressures and compliances";
            unused(l.delta.is_some(), "layer.delta", why)?;
            unused(l.p0.is_some(), "layer.p0", why)?;
            unused(l.pressures.is_some(), "layer.pressures", why)?;
            unused(l.compliances.is_some(), "layer.compliances", why)?;
            ComplianceLaw::Linear
        }
        RawLaw::Sigmoid => {
            let why = "only law = \"table\" uses pressures and compliances";
            unused(l.pressures.is_some(), "layer.pressures", why)?;
            unused(l.compliances.is_some(), "layer.compliances", why)?;
            let delta = need(
                l.delta,
                "layer.delta",
                "law = \"sigmoid\" needs delta (0 <= delta <= 1)",
            )?;
            let p0 = need(l.p0, "layer.p0", "law = \"sigmoid\" needs p0 (> 0)")?;
            ComplianceLaw::Sigmoid { delta, p0 }
        }
        RawLaw::Table => {
            if matches!(l.rheology, RawRheology::Maxwell | RawRheology::KelvinVoigt) {
                unused(
                    l.compliance.is_some(),
                    "layer.compliance",
                    "law = \"table\" takes its compliances from the table",
                )?;
            }
            let why = "only law = \"sigmoid\" uses delta and p0";
            unused(l.delta.is_some(), "layer.delta", why)?;
            unused(l.p0.is_some(), "layer.p0", why)?;
            let pressures = need(
                l.pressures.clone(),
                "layer.pressures",
                "law = \"table\" needs pressures (starting at 0, increasing)",
            )?;
            let compliances = need(
                l.compliances.clone(),
                "layer.compliances",
                "law = \"table\" needs one compliance (>= 0) per pressure",
            )?;
            ComplianceLaw::Table(Table::new(pressures, compliances)?)
        }
    };
    let table_compliance = match &law {
        ComplianceLaw::Table(t) => Some(t.compliances()[0]),
        _ => None,
    };
    let rheology = rheology(&l, table_compliance)?;
    let integration = match l.integration {
        RawIntegration::Exact => Integration::Exact,
        RawIntegration::Secant => Integration::Secant,
    };
    Ok(Layer {
        rheology,
        law,
        integration,
    })
}

/// The keys a rheology preset takes, in case-file order.
fn rheology_keys(r: RawRheology) -> (&'static str, &'static [&'static str]) {
    match r {
        RawRheology::Maxwell => ("maxwell", &["compliance", "relaxation_time"]),
        RawRheology::KelvinVoigt => ("kelvin_voigt", &["compliance", "retardation_time"]),
        RawRheology::Zener => (
            "zener",
            &["glassy_compliance", "compliance", "retardation_time"],
        ),
        RawRheology::Burgers => (
            "burgers",
            &[
                "glassy_compliance",
                "relaxation_time",
                "compliance",
                "retardation_time",
            ],
        ),
        RawRheology::Prony => (
            "prony",
            &[
                "glassy_compliance",
                "branch_compliances",
                "branch_times",
                "viscosity",
            ],
        ),
        RawRheology::RelaxationProny => (
            "relaxation_prony",
            &[
                "equilibrium_stiffness",
                "branch_stiffnesses",
                "branch_times",
            ],
        ),
        RawRheology::FractionalZener => (
            "fractional_zener",
            &[
                "glassy_compliance",
                "compliance",
                "retardation_time",
                "order",
                "branch_count",
            ],
        ),
    }
}

/// Default number of branches of a fractional Zener layer.
const FRACTIONAL_BRANCHES: usize = 24;

fn rheology(l: &RawLayer, table_compliance: Option<f64>) -> Result<Rheology> {
    let (name, keys) = rheology_keys(l.rheology);
    let present = [
        ("compliance", l.compliance.is_some()),
        ("relaxation_time", l.relaxation_time.is_some()),
        ("glassy_compliance", l.glassy_compliance.is_some()),
        ("retardation_time", l.retardation_time.is_some()),
        ("branch_compliances", l.branch_compliances.is_some()),
        ("branch_times", l.branch_times.is_some()),
        ("viscosity", l.viscosity.is_some()),
        ("equilibrium_stiffness", l.equilibrium_stiffness.is_some()),
        ("branch_stiffnesses", l.branch_stiffnesses.is_some()),
        ("order", l.order.is_some()),
        ("branch_count", l.branch_count.is_some()),
    ];
    for (key, given) in present {
        let why = format!("rheology = \"{name}\" takes only {}", keys.join(", "));
        unused(given && !keys.contains(&key), &format!("layer.{key}"), &why)?;
    }
    // Maxwell and Kelvin–Voigt layers with a table law take their one compliance
    // from the table, as the paper's layer always has.
    let main_compliance = |what: &str| -> Result<f64> {
        match table_compliance {
            Some(c0) if matches!(l.rheology, RawRheology::Maxwell | RawRheology::KelvinVoigt) => {
                unused(
                    l.compliance.is_some(),
                    "layer.compliance",
                    "law = \"table\" takes its compliances from the table",
                )?;
                Ok(c0)
            }
            _ => need(
                l.compliance,
                "layer.compliance",
                &format!("a {name} layer needs {what} (> 0)"),
            ),
        }
    };
    let time = |value: Option<f64>, key: &str, what: &str| {
        need(
            value,
            &format!("layer.{key}"),
            &format!("a {name} layer needs {what} (> 0)"),
        )
    };
    let glassy = || {
        need(
            l.glassy_compliance,
            "layer.glassy_compliance",
            &format!("a {name} layer needs its glassy (instantaneous) compliance C_g"),
        )
    };
    Ok(match l.rheology {
        RawRheology::Maxwell => Rheology::Maxwell {
            compliance: main_compliance("its compliance C0")?,
            relaxation_time: need(
                l.relaxation_time,
                "layer.relaxation_time",
                "a [layer] needs its relaxation time T (> 0)",
            )?,
        },
        RawRheology::KelvinVoigt => Rheology::KelvinVoigt {
            compliance: main_compliance("its compliance C1")?,
            retardation_time: time(
                l.retardation_time,
                "retardation_time",
                "its retardation time",
            )?,
        },
        RawRheology::Zener => Rheology::Zener {
            glassy_compliance: glassy()?,
            compliance: main_compliance("the compliance C1 of its Kelvin–Voigt branch")?,
            retardation_time: time(
                l.retardation_time,
                "retardation_time",
                "its retardation time",
            )?,
        },
        RawRheology::Burgers => Rheology::Burgers {
            glassy_compliance: glassy()?,
            relaxation_time: time(
                l.relaxation_time,
                "relaxation_time",
                "the relaxation time T of its Maxwell element",
            )?,
            compliance: main_compliance("the compliance C1 of its Kelvin–Voigt branch")?,
            retardation_time: time(
                l.retardation_time,
                "retardation_time",
                "its retardation time",
            )?,
        },
        RawRheology::Prony => {
            let compliances = need(
                l.branch_compliances.clone(),
                "layer.branch_compliances",
                "a prony layer needs the compliances of its Kelvin–Voigt branches (a list)",
            )?;
            let times = branch_times(l, compliances.len(), "branch_compliances")?;
            Rheology::Prony {
                glassy_compliance: glassy()?,
                branches: compliances
                    .into_iter()
                    .zip(times)
                    .map(|(compliance, time)| RetardationBranch { compliance, time })
                    .collect(),
                viscosity: l.viscosity,
            }
        }
        RawRheology::RelaxationProny => {
            let stiffnesses = need(
                l.branch_stiffnesses.clone(),
                "layer.branch_stiffnesses",
                "a relaxation_prony layer needs the stiffnesses of its Maxwell branches (a list)",
            )?;
            let times = branch_times(l, stiffnesses.len(), "branch_stiffnesses")?;
            Rheology::RelaxationProny {
                equilibrium_stiffness: need(
                    l.equilibrium_stiffness,
                    "layer.equilibrium_stiffness",
                    "a relaxation_prony layer needs its equilibrium stiffness K_inf (>= 0; 0 \
                     for a layer that flows)",
                )?,
                branches: stiffnesses
                    .into_iter()
                    .zip(times)
                    .map(|(stiffness, time)| RelaxationBranch { stiffness, time })
                    .collect(),
            }
        }
        RawRheology::FractionalZener => Rheology::FractionalZener {
            glassy_compliance: glassy()?,
            compliance: main_compliance("the compliance C1 of its retarded part")?,
            retardation_time: time(
                l.retardation_time,
                "retardation_time",
                "its retardation time",
            )?,
            order: need(
                l.order,
                "layer.order",
                "a fractional_zener layer needs its order alpha (0 < alpha <= 1)",
            )?,
            branch_count: l.branch_count.unwrap_or(FRACTIONAL_BRANCHES),
        },
    })
}

/// `branch_times`, one per entry of the list `key`.
fn branch_times(l: &RawLayer, n: usize, key: &str) -> Result<Vec<f64>> {
    let times = need(
        l.branch_times.clone(),
        "layer.branch_times",
        &format!("one time (> 0) per entry of layer.{key}"),
    )?;
    if times.len() != n {
        return Err(Error::invalid(
            "layer.branch_times",
            format!("{} times for {n} branches", times.len()),
            &format!("one time per entry of layer.{key}"),
        ));
    }
    Ok(times)
}

fn stress_request(raw: RawStress) -> Result<StressRequest> {
    let defaults = StressRequest::default();
    let sections = raw
        .sections
        .map(|names| {
            names
                .iter()
                .map(|n| {
                    SectionKind::from_name(n).ok_or_else(|| {
                        Error::invalid(
                            "stress.sections",
                            format!("\"{n}\""),
                            "\"xz\", \"surface\", \"interface\" or \"block\"",
                        )
                    })
                })
                .collect::<Result<Vec<_>>>()
        })
        .transpose()?;
    Ok(StressRequest {
        sections,
        y: raw.y.unwrap_or(defaults.y),
        max_depth: raw.max_depth,
        depth_points: raw.depth_points.unwrap_or(defaults.depth_points),
        planes: raw.planes.unwrap_or_default(),
    })
}

fn solver_params(raw: Option<RawSolver>) -> Result<SolverParams> {
    let mut params = SolverParams::default();
    let Some(raw) = raw else {
        return Ok(params);
    };
    if let Some(t) = raw.tolerance {
        if !(t.is_finite() && t > 0.0 && t < 1.0) {
            return Err(Error::invalid("solver.tolerance", t, "0 < tolerance < 1"));
        }
        params.tolerance = t;
    }
    if let Some(n) = raw.max_iterations {
        if n == 0 {
            return Err(Error::invalid(
                "solver.max_iterations",
                n,
                "at least 1 iteration",
            ));
        }
        params.max_iterations = n;
    }
    if let Some(n) = raw.max_windows {
        if n == 0 {
            return Err(Error::invalid("solver.max_windows", n, "at least 1 window"));
        }
        params.max_windows = n;
    }
    Ok(params)
}

#[cfg(test)]
#[path = "case_file_tests.rs"]
mod tests;
