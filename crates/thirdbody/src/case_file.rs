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

use serde::de::{self, DeserializeSeed, MapAccess, Visitor};
use serde::{Deserialize, Deserializer};

use crate::body::layered::{Base, BaseContact, Ply, Stack};
use crate::body::solid::{SolidRheology, ViscoelasticHalfSpace};
use crate::case::{Body, Case, Elastic, GridSpec, Loading, Units};
use crate::contact::SolverParams;
use crate::error::{require_positive, Error, Result};
use crate::layer::rheology::{preset_keys, KeyKind, KeyReader, KeyValue, Preset, PRESETS};
use crate::layer::{ComplianceLaw, Integration, Layer, Rheology, Table};
use crate::shape::{HeightMap, Profile, Slider};
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

impl CaseFile {
    /// The works a solve of this case file relies on ([`Case::references`] with its
    /// `[solver] method`).
    pub fn references(&self) -> Vec<crate::provenance::Reference> {
        self.case.references(self.solver.method)
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCase {
    units: Option<RawUnits>,
    slider: Option<RawSlider>,
    substrate: Option<RawSubstrate>,
    coating: Option<RawCoating>,
    body: Option<RawBody>,
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
    Cylinder,
    Profile,
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

/// `[substrate]`: an elastic half-space (`young`, `poisson`) or, with a
/// `rheology`, a viscoelastic one (`crate::body::solid`).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSubstrate {
    rheology: Option<RawSolid>,
    young: Option<f64>,
    poisson: Option<f64>,
    glassy_modulus: Option<f64>,
    relaxed_modulus: Option<f64>,
    relaxation_time: Option<f64>,
    order: Option<f64>,
    branch_count: Option<usize>,
    glassy_compliance: Option<f64>,
    branch_compliances: Option<Vec<f64>>,
    equilibrium_modulus: Option<f64>,
    branch_moduli: Option<Vec<f64>>,
    branch_times: Option<Vec<f64>>,
}

/// `[substrate] rheology`.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(rename_all = "snake_case")]
enum RawSolid {
    Elastic,
    Zener,
    FractionalZener,
    Prony,
    RelaxationProny,
}

impl RawSolid {
    fn name(self) -> &'static str {
        match self {
            RawSolid::Elastic => "elastic",
            RawSolid::Zener => "zener",
            RawSolid::FractionalZener => "fractional_zener",
            RawSolid::Prony => "prony",
            RawSolid::RelaxationProny => "relaxation_prony",
        }
    }

    /// The keys besides `rheology` and `poisson` it takes.
    fn keys(self) -> &'static [&'static str] {
        match self {
            RawSolid::Elastic => &["young"],
            RawSolid::Zener => &["glassy_modulus", "relaxed_modulus", "relaxation_time"],
            RawSolid::FractionalZener => &[
                "glassy_modulus",
                "relaxed_modulus",
                "relaxation_time",
                "order",
                "branch_count",
            ],
            RawSolid::Prony => &["glassy_compliance", "branch_compliances", "branch_times"],
            RawSolid::RelaxationProny => &["equilibrium_modulus", "branch_moduli", "branch_times"],
        }
    }
}

impl RawSubstrate {
    /// The keys given, besides `rheology` and `poisson`.
    fn given(&self) -> Vec<&'static str> {
        [
            ("young", self.young.is_some()),
            ("glassy_modulus", self.glassy_modulus.is_some()),
            ("relaxed_modulus", self.relaxed_modulus.is_some()),
            ("relaxation_time", self.relaxation_time.is_some()),
            ("order", self.order.is_some()),
            ("branch_count", self.branch_count.is_some()),
            ("glassy_compliance", self.glassy_compliance.is_some()),
            ("branch_compliances", self.branch_compliances.is_some()),
            ("equilibrium_modulus", self.equilibrium_modulus.is_some()),
            ("branch_moduli", self.branch_moduli.is_some()),
            ("branch_times", self.branch_times.is_some()),
        ]
        .into_iter()
        .filter_map(|(k, given)| given.then_some(k))
        .collect()
    }
}

/// The viscoelastic half-space of a `[substrate]` with a `rheology` other than
/// `"elastic"`; errors name the key.
fn viscoelastic_substrate(s: RawSubstrate, rheology: RawSolid) -> Result<ViscoelasticHalfSpace> {
    let name = rheology.name();
    for key in s.given() {
        unused(
            !rheology.keys().contains(&key),
            &format!("substrate.{key}"),
            &format!(
                "rheology = \"{name}\" takes {} and poisson",
                rheology.keys().join(", ")
            ),
        )?;
    }
    let needs = |v: Option<f64>, key: &str, what: &str| {
        need(
            v,
            &format!("substrate.{key}"),
            &format!("a {name} substrate needs {what}"),
        )
    };
    let needs_list = |v: Option<Vec<f64>>, key: &str, what: &str| {
        need(
            v,
            &format!("substrate.{key}"),
            &format!("a {name} substrate needs {what}"),
        )
    };
    let moduli = |s: &RawSubstrate| -> Result<(f64, f64, f64)> {
        Ok((
            needs(
                s.glassy_modulus,
                "glassy_modulus",
                "its glassy (instantaneous) Young's modulus",
            )?,
            needs(
                s.relaxed_modulus,
                "relaxed_modulus",
                "its relaxed (long-time) Young's modulus",
            )?,
            needs(
                s.relaxation_time,
                "relaxation_time",
                "its relaxation time (> 0)",
            )?,
        ))
    };
    let solid = match rheology {
        RawSolid::Elastic => unreachable!("an elastic substrate is not viscoelastic"),
        RawSolid::Zener => {
            let (glassy_modulus, relaxed_modulus, relaxation_time) = moduli(&s)?;
            SolidRheology::Zener {
                glassy_modulus,
                relaxed_modulus,
                relaxation_time,
            }
        }
        RawSolid::FractionalZener => {
            let (glassy_modulus, relaxed_modulus, relaxation_time) = moduli(&s)?;
            SolidRheology::FractionalZener {
                glassy_modulus,
                relaxed_modulus,
                relaxation_time,
                order: needs(s.order, "order", "its order (0 < order <= 1)")?,
                branch_count: s.branch_count,
            }
        }
        RawSolid::Prony => SolidRheology::Prony {
            glassy_compliance: needs(
                s.glassy_compliance,
                "glassy_compliance",
                "its glassy tensile creep compliance (>= 0)",
            )?,
            branch_compliances: needs_list(
                s.branch_compliances,
                "branch_compliances",
                "its branches' tensile creep compliances (>= 0)",
            )?,
            branch_times: needs_list(
                s.branch_times,
                "branch_times",
                "one retardation time (> 0) per branch",
            )?,
        },
        RawSolid::RelaxationProny => SolidRheology::RelaxationProny {
            equilibrium_modulus: needs(
                s.equilibrium_modulus,
                "equilibrium_modulus",
                "its equilibrium (long-time) Young's modulus (> 0)",
            )?,
            branch_moduli: needs_list(
                s.branch_moduli,
                "branch_moduli",
                "its branches' Young's moduli (>= 0)",
            )?,
            branch_times: needs_list(
                s.branch_times,
                "branch_times",
                "one relaxation time (> 0) per branch",
            )?,
        },
    };
    let body = ViscoelasticHalfSpace {
        rheology: solid,
        poisson: needs(
            s.poisson,
            "poisson",
            "its Poisson's ratio (-1 < poisson < 0.5)",
        )?,
    };
    body.validate()?;
    Ok(body)
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCoating {
    young: Option<f64>,
    poisson: Option<f64>,
    thickness: Option<f64>,
}

/// `[body]` with `[[body.layers]]`: a stack of layers on a half-space (the
/// `[substrate]`) or on a rigid base.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBody {
    base: Option<RawBase>,
    bonding: Option<RawBonding>,
    layers: Option<Vec<RawCoating>>,
}

#[derive(Debug, Deserialize)]
#[serde(rename_all = "snake_case")]
enum RawBase {
    HalfSpace,
    Rigid,
}

#[derive(Debug, Deserialize)]
#[serde(rename_all = "snake_case")]
enum RawBonding {
    Bonded,
    Frictionless,
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

/// `[layer]`: the law's keys, the rheology's name, and the keys of the rheology
/// presets ([`PRESETS`]), each read as the preset declares it. Unknown keys are
/// errors at their line, as `deny_unknown_fields` gives them elsewhere.
#[derive(Debug, Default)]
struct RawLayer {
    rheology: Option<&'static Preset>,
    law: RawLaw,
    delta: Option<f64>,
    p0: Option<f64>,
    pressures: Option<Vec<f64>>,
    compliances: Option<Vec<f64>>,
    integration: RawIntegration,
    /// The rheology keys given, in file order.
    rheology_keys: Vec<(&'static str, KeyValue)>,
}

/// The keys of `[layer]` that are not a rheology preset's.
const LAW_KEYS: [&str; 6] = [
    "law",
    "delta",
    "p0",
    "pressures",
    "compliances",
    "integration",
];

/// A key of `[layer]`.
enum LayerKey {
    Rheology,
    Law,
    Delta,
    P0,
    Pressures,
    Compliances,
    Integration,
    Preset(&'static str, KeyKind),
}

/// Reads a `[layer]` key; an unknown one is an error at its line.
struct LayerKeySeed;

impl<'de> DeserializeSeed<'de> for LayerKeySeed {
    type Value = LayerKey;
    fn deserialize<D: Deserializer<'de>>(self, d: D) -> std::result::Result<LayerKey, D::Error> {
        d.deserialize_identifier(self)
    }
}

impl Visitor<'_> for LayerKeySeed {
    type Value = LayerKey;
    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a [layer] key")
    }
    fn visit_str<E: de::Error>(self, key: &str) -> std::result::Result<LayerKey, E> {
        Ok(match key {
            "rheology" => LayerKey::Rheology,
            "law" => LayerKey::Law,
            "delta" => LayerKey::Delta,
            "p0" => LayerKey::P0,
            "pressures" => LayerKey::Pressures,
            "compliances" => LayerKey::Compliances,
            "integration" => LayerKey::Integration,
            _ => {
                let all = preset_keys();
                let Some(&(key, kind)) = all.iter().find(|(k, _)| *k == key) else {
                    let names = std::iter::once("rheology")
                        .chain(all.iter().map(|(k, _)| *k))
                        .chain(LAW_KEYS);
                    return Err(E::custom(format!(
                        "unknown field `{key}`, expected {}",
                        one_of(names)
                    )));
                };
                LayerKey::Preset(key, kind)
            }
        })
    }
}

/// serde's wording of a list of allowed names: "one of `a`, `b`, `c`".
fn one_of<'a>(names: impl Iterator<Item = &'a str>) -> String {
    let quoted: Vec<String> = names.map(|n| format!("`{n}`")).collect();
    format!("one of {}", quoted.join(", "))
}

/// Reads `rheology = "<name>"`; a name no preset has is an error at its line.
struct PresetSeed;

impl<'de> DeserializeSeed<'de> for PresetSeed {
    type Value = &'static Preset;
    fn deserialize<D: Deserializer<'de>>(
        self,
        d: D,
    ) -> std::result::Result<&'static Preset, D::Error> {
        d.deserialize_str(self)
    }
}

impl Visitor<'_> for PresetSeed {
    type Value = &'static Preset;
    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("the name of a rheology preset")
    }
    fn visit_str<E: de::Error>(self, name: &str) -> std::result::Result<&'static Preset, E> {
        Preset::named(name).ok_or_else(|| {
            E::custom(format!(
                "unknown variant `{name}`, expected {}",
                one_of(PRESETS.iter().map(|p| p.name))
            ))
        })
    }
}

impl<'de> Deserialize<'de> for RawLayer {
    fn deserialize<D: Deserializer<'de>>(d: D) -> std::result::Result<RawLayer, D::Error> {
        d.deserialize_map(RawLayerVisitor)
    }
}

struct RawLayerVisitor;

impl<'de> Visitor<'de> for RawLayerVisitor {
    type Value = RawLayer;
    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("the [layer] table")
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> std::result::Result<RawLayer, A::Error> {
        let mut l = RawLayer::default();
        while let Some(key) = map.next_key_seed(LayerKeySeed)? {
            match key {
                LayerKey::Rheology => l.rheology = Some(map.next_value_seed(PresetSeed)?),
                LayerKey::Law => l.law = map.next_value()?,
                LayerKey::Delta => l.delta = Some(map.next_value()?),
                LayerKey::P0 => l.p0 = Some(map.next_value()?),
                LayerKey::Pressures => l.pressures = Some(map.next_value()?),
                LayerKey::Compliances => l.compliances = Some(map.next_value()?),
                LayerKey::Integration => l.integration = map.next_value()?,
                LayerKey::Preset(key, kind) => {
                    let value = match kind {
                        KeyKind::Number => KeyValue::Number(map.next_value()?),
                        KeyKind::Numbers => KeyValue::Numbers(map.next_value()?),
                        KeyKind::Count => KeyValue::Count(map.next_value()?),
                    };
                    l.rheology_keys.push((key, value));
                }
            }
        }
        Ok(l)
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLoading {
    normal_load: Option<f64>,
    velocity: Option<f64>,
    reference_distance: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawGrid {
    cells: Option<Axes<usize>>,
    half_width: Option<Axes<f64>>,
    centre: Option<Axes<f64>>,
}

/// A grid key as written: one number (a line contact's x), or an array (`[x, y]`
/// for a point contact, `[x]` for a line contact).
#[derive(Debug, Deserialize)]
#[serde(untagged)]
enum Axes<T> {
    One(T),
    Many(Vec<T>),
}

impl<T: Copy + std::fmt::Display> Axes<T> {
    /// The value of `key` for a point contact (`[x, y]`) or a line contact (`x` or
    /// `[x]`, returned as `[x, fill]`); any other form is an error naming the key.
    fn for_geometry(&self, key: &str, line: bool, fill: T) -> Result<[T; 2]> {
        match (self, line) {
            (Axes::Many(v), false) if v.len() == 2 => Ok([v[0], v[1]]),
            (Axes::One(x), true) => Ok([*x, fill]),
            (Axes::Many(v), true) if v.len() == 1 => Ok([v[0], fill]),
            (written, true) => Err(Error::invalid(
                key,
                written.describe(),
                "one value along x for a line contact (slider.shape = \"cylinder\"), e.g. \
                 cells = 1024",
            )),
            (written, false) => Err(Error::invalid(
                key,
                written.describe(),
                "exactly two values [x, y] for a point contact (one value is a line \
                 contact's, slider.shape = \"cylinder\")",
            )),
        }
    }

    fn describe(&self) -> String {
        match self {
            Axes::One(x) => x.to_string(),
            Axes::Many(v) => format!(
                "[{}]",
                v.iter()
                    .map(ToString::to_string)
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        }
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
    let body = body(raw.substrate, raw.coating, raw.body)?;
    let loading = section(raw.loading, "loading", "normal_load (> 0)")?;
    let grid = section(raw.grid, "grid", "cells = [nx, ny], each >= 8")?;
    let layer = raw.layer.map(layer).transpose()?;
    let line = matches!(slider.shape, Some(RawShape::Cylinder | RawShape::Profile));
    if !line {
        unused(
            loading.reference_distance.is_some(),
            "loading.reference_distance",
            "it is a line contact's datum (slider.shape = \"cylinder\" or \"profile\")",
        )?;
    }
    let loading = Loading {
        normal_load: need(
            loading.normal_load,
            "loading.normal_load",
            "the normal load Q (> 0) is always needed (per unit length for a line contact)",
        )?,
        velocity: loading.velocity,
        reference_distance: loading.reference_distance,
    };
    let cells = need(
        grid.cells,
        "grid.cells",
        if line {
            "give cells = N with N >= 8 (a line contact)"
        } else {
            "give cells = [nx, ny] with nx, ny >= 8"
        },
    )?;
    let grid = GridSpec {
        cells: cells.for_geometry("grid.cells", line, 1)?,
        half_width: grid
            .half_width
            .map(|w| w.for_geometry("grid.half_width", line, 0.0))
            .transpose()?,
        centre: grid
            .centre
            .map(|c| c.for_geometry("grid.centre", line, 0.0))
            .transpose()?,
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

/// The body from `[substrate]`, `[coating]` (one layer on the substrate) or `[body]`
/// with `[[body.layers]]` (docs/case-file.md, "The body").
fn body(
    substrate: Option<RawSubstrate>,
    coating: Option<RawCoating>,
    raw: Option<RawBody>,
) -> Result<Body> {
    let rheology = substrate.as_ref().and_then(|s| s.rheology);
    if let Some(r) = rheology.filter(|r| *r != RawSolid::Elastic) {
        let why = "layers on a viscoelastic substrate are not supported: its kernel is \
                   that of a homogeneous half-space";
        unused(coating.is_some(), "coating", why)?;
        unused(raw.is_some(), "body", why)?;
        let s = substrate.expect("a rheology comes with its [substrate]");
        return Ok(Body::Viscoelastic(viscoelastic_substrate(s, r)?));
    }
    let rigid = matches!(
        raw.as_ref().and_then(|b| b.base.as_ref()),
        Some(RawBase::Rigid)
    );
    let substrate = if rigid {
        unused(
            substrate.is_some(),
            "substrate",
            "a rigid base (body.base = \"rigid\") has no substrate material",
        )?;
        None
    } else {
        let s = section(
            substrate,
            "substrate",
            "young (> 0) and poisson (-1 < poisson < 0.5)",
        )?;
        for key in s.given() {
            unused(
                key != "young",
                &format!("substrate.{key}"),
                "an elastic substrate takes young and poisson; name a rheology \
                 (substrate.rheology = \"zener\", ...) for a viscoelastic one",
            )?;
        }
        let m = elastic(s.young, s.poisson, "substrate")?;
        m.validate("substrate")?;
        Some(m)
    };
    // Each layer checked under the name it was written with (`coating.thickness`,
    // `body.layers[2].young`).
    let ply = |c: RawCoating, name: &str| -> Result<Ply> {
        let ply = Ply {
            material: elastic(c.young, c.poisson, name)?,
            thickness: need(
                c.thickness,
                &format!("{name}.thickness"),
                "every layer needs its thickness (> 0)",
            )?,
        };
        ply.material.validate(name)?;
        require_positive(&format!("{name}.thickness"), ply.thickness)?;
        Ok(ply)
    };
    let Some(raw) = raw else {
        let substrate = substrate.expect("a half-space base");
        return Ok(match coating {
            None => Body::Homogeneous(substrate),
            Some(c) => Body::Layered(Stack {
                layers: vec![ply(c, "coating")?],
                base: Base::HalfSpace(substrate),
            }),
        });
    };
    unused(
        coating.is_some(),
        "coating",
        "a [coating] is one layer of [[body.layers]]: give either, not both",
    )?;
    let base =
        match (substrate, raw.bonding) {
            (Some(m), None) => Base::HalfSpace(m),
            (Some(_), Some(_)) => return Err(Error::UnusedField {
                field: "body.bonding".into(),
                why: "the bonding names how layers rest on a rigid base (body.base = \"rigid\"); \
                      on the [substrate] half-space they are bonded"
                    .into(),
            }),
            (None, bonding) => Base::Rigid(
                match need(
                    bonding,
                    "body.bonding",
                    "a rigid base needs its bonding: \"bonded\" or \"frictionless\"",
                )? {
                    RawBonding::Bonded => BaseContact::Bonded,
                    RawBonding::Frictionless => BaseContact::Frictionless,
                },
            ),
        };
    let layers = raw
        .layers
        .unwrap_or_default()
        .into_iter()
        .enumerate()
        .map(|(i, c)| ply(c, &format!("body.layers[{i}]")))
        .collect::<Result<Vec<_>>>()?;
    if layers.is_empty() {
        return Err(Error::MissingField {
            field: "body.layers".into(),
            why: "a [body] needs at least one [[body.layers]] entry (young, poisson, thickness), \
                  listed from the surface down"
                .into(),
        });
    }
    Ok(Body::Layered(Stack { layers, base }))
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
        s.shape.as_ref(),
        "slider.shape",
        "choose \"sphere\", \"ellipsoid\", \"height_map\", \"cylinder\" or \"profile\"",
    )?;
    // A shape of one radius (sphere, cylinder) and one sampled from a file (height
    // map, profile): the keys each may have.
    let radius = |s: &RawSlider, what: &str| -> Result<f64> {
        let why = format!("a {what} has only a radius");
        unused(s.radius_x.is_some(), "slider.radius_x", &why)?;
        unused(s.radius_y.is_some(), "slider.radius_y", &why)?;
        unused(s.file.is_some(), "slider.file", &why)?;
        unused(s.cell_size.is_some(), "slider.cell_size", &why)?;
        need(
            s.radius,
            "slider.radius",
            &format!("a {what} needs its radius (> 0)"),
        )
    };
    let mut sampled = |s: RawSlider, what: &str, file_is: &str| -> Result<HeightMap> {
        let why = format!("a {what} is given by file and cell_size");
        unused(s.radius.is_some(), "slider.radius", &why)?;
        unused(s.radius_x.is_some(), "slider.radius_x", &why)?;
        unused(s.radius_y.is_some(), "slider.radius_y", &why)?;
        let file = need(
            s.file,
            "slider.file",
            &format!("a {what} needs its file ({file_is})"),
        )?;
        let cell_size = need(
            s.cell_size,
            "slider.cell_size",
            &format!("a {what} needs the spacing of its samples (> 0)"),
        )?;
        load_height_map(&file, cell_size)
    };
    match shape {
        RawShape::Profile => Ok(Slider::Profile(Profile::from_map(sampled(
            s,
            "profile",
            "CSV or NPY, one row of heights",
        )?)?)),
        RawShape::HeightMap => Ok(Slider::HeightMap(sampled(s, "height map", "CSV or NPY")?)),
        RawShape::Cylinder => Ok(Slider::Cylinder {
            radius: radius(&s, "cylinder")?,
        }),
        RawShape::Sphere => Ok(Slider::Sphere {
            radius: radius(&s, "sphere")?,
        }),
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
    }
}

fn layer(l: RawLayer) -> Result<Layer> {
    let preset = l.rheology.unwrap_or_else(Preset::default_preset);
    let given = |key: &str| l.rheology_keys.iter().any(|(k, _)| *k == key);
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
            if preset.compliance_from_table {
                unused(
                    given("compliance"),
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
        ComplianceLaw::Linear | ComplianceLaw::Sigmoid { .. } => None,
    };
    // The rheology's keys: those another preset takes are unused here.
    let why = format!(
        "rheology = \"{}\" takes only {}",
        preset.name,
        preset.key_names().join(", ")
    );
    for (key, _) in preset_keys() {
        unused(
            given(key) && !preset.takes(key),
            &format!("layer.{key}"),
            &why,
        )?;
    }
    // Presets with one compliance (the paper's Maxwell layer, Kelvin–Voigt) take it
    // from a table law.
    let table_compliance = table_compliance.filter(|_| preset.compliance_from_table);
    let rheology: Rheology = (preset.parse)(&KeyReader::new(
        preset.name,
        &l.rheology_keys,
        table_compliance,
    ))?;
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
