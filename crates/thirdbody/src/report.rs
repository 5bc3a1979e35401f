//! The report of a solve, as every front end writes it (`summary.json` of the CLI,
//! the rows of a sweep's `results.csv`, a Python dict): the scalar results of the
//! [`Summary`], the solver's report, the window, the units, the wall time the front
//! end measured and, when stresses were computed, their summary and the sections.
//! One definition, serialised with serde, so that every front end reports exactly
//! the same keys (listed in docs/outputs.md). A line contact's report has no y keys
//! (its y is the one strip's length, not a coordinate): `contact = "line"` and the
//! datum of its approach (`reference_distance`) say what it is instead.

use serde::{Serialize, Serializer};

use crate::case::{Case, Units};
use crate::grid::Geometry;
use crate::solution::{Method, Solution, Summary};
use crate::stress::{StressResults, StressSummary};

/// What `summary.json` holds.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// The scalar results (without the y keys for a line contact).
    #[serde(flatten, serialize_with = "summary_keys")]
    pub summary: Summary,
    /// `"line"` for a line contact (plane strain, loads and forces per unit
    /// length); absent for a point contact.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contact: Option<&'static str>,
    /// A line contact's datum of the approach (`loading.reference_distance`, or its
    /// default the cylinder's radius).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reference_distance: Option<f64>,
    /// Wall time of kernel set-up and solve, as the front end measured it.
    pub solve_seconds: f64,
    /// `"dimensionless"` or `"si"`.
    pub units: &'static str,
    /// The algorithm used.
    pub method: Method,
    /// Inner Krylov iterations in total.
    pub linear_iterations: usize,
    /// Windows tried.
    pub windows: usize,
    /// The final window's extent along x (cell edges).
    pub window_x_min: f64,
    /// See `window_x_min`.
    pub window_x_max: f64,
    /// The final window's extent along y (cell edges); absent for a line contact.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub window_y_min: Option<f64>,
    /// See `window_y_min`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub window_y_max: Option<f64>,
    /// Stress results, when stresses were computed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stress: Option<StressReport>,
    /// Where the result lies outside the model's assumptions (see
    /// [`model_warnings`]); absent when there is nothing to say.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
    /// The thirdbody version that computed the result.
    pub thirdbody_version: &'static str,
    /// The git commit it was built from (`null` when not built from a checkout).
    pub commit: Option<&'static str>,
    /// SHA-256 of the canonical case ([`crate::provenance::case_hash`]).
    pub case_hash: String,
}

/// Largest contact half-length, as a fraction of the slider's radius, for which the
/// half-space and paraboloid model is taken to hold (the paraboloid differs from a
/// sphere by 0.3% at 0.1 R; the half-space needs the contact small against the body).
pub const MAX_CONTACT_FRACTION: f64 = 0.1;
/// Largest approach D as a fraction of R (for Hertz, a/R = 0.1 means D/R = 0.01).
pub const MAX_APPROACH_FRACTION: f64 = 0.01;

/// Relative difference between `friction_coefficient` and
/// `dissipation_friction_coefficient` that a resolved grid always meets; a coarser
/// grid is allowed [`ENERGY_IMBALANCE_PER_CELL`] times the cell over the contact's
/// half-length along x when that is larger.
pub const MAX_ENERGY_IMBALANCE: f64 = 0.01;

/// The two friction estimates share the contact's edges, which cells resolve to
/// first order: measured on Kelvin–Voigt and Zener layers on rigid and elastic
/// bodies, creep lengths from 1/400 to 3700 cells, they agree within 0.33 h / a
/// at 128^2 (contact half-lengths a of 39 to 58 cells) and 0.6 h / a at 12^2 to
/// 32^2 (docs/validation.md).
pub const ENERGY_IMBALANCE_PER_CELL: f64 = 1.0;

/// Friction coefficients below this fraction of the contact's slope `a / R` are
/// at the rounding level of the slope's sum (a glassy body at 1e12 times its
/// creep speed gives mu = 3e-14 from a symmetric pressure): no energy balance is
/// checked there.
pub const FRICTION_NOISE: f64 = 1e-9;

/// Sentences saying where `solution` of `case` lies outside the model's
/// assumptions: a contact or an approach that is not small against the slider's
/// radius, a friction coefficient above 1 (the small-slope hysteresis friction of
/// paper eq. 12 is then meaningless), friction and dissipated power that
/// disagree by more than [`MAX_ENERGY_IMBALANCE`] (the grid does not resolve the
/// layer), a peak pressure at the contact's edge that the cells do not resolve (no
/// layer; [`EDGE_PEAK_CELLS`]), or a solve that stalled short of its tolerance and
/// returned its best iterate ([`crate::contact::STALLED_BUT_SOLVED`]).
pub fn model_warnings(case: &Case, solution: &Solution) -> Vec<String> {
    let s = solution.summary();
    let r = case.slider.equivalent_radius();
    let mut out = Vec::new();
    let half_length = [
        s.contact_x_min.abs(),
        s.contact_x_max.abs(),
        s.contact_y_min.abs(),
        s.contact_y_max.abs(),
    ]
    .into_iter()
    .filter(|v| v.is_finite())
    .fold(0.0f64, f64::max);
    if half_length > MAX_CONTACT_FRACTION * r {
        out.push(format!(
            "the contact reaches {:.3e} R from the initial contact point (more than \
             {MAX_CONTACT_FRACTION} R): the half-space and paraboloid model assumes a \
             contact small against the slider",
            half_length / r
        ));
    }
    if s.penetration > MAX_APPROACH_FRACTION * r {
        out.push(format!(
            "the approach D is {:.3e} R (more than {MAX_APPROACH_FRACTION} R): the model \
             assumes small deformations",
            s.penetration / r
        ));
    }
    if s.friction_coefficient.abs() > 1.0 {
        out.push(format!(
            "mu = {:.3e} exceeds 1: the hysteresis friction of paper eq. 12 assumes small \
             slopes, which such a contact does not have",
            s.friction_coefficient
        ));
    }
    if let Some(message) = energy_balance_warning(case, &s) {
        out.push(message);
    }
    if let Some(message) = edge_peak_warning(case, solution) {
        out.push(message);
    }
    let info = &solution.info;
    if info.residual > info.tolerance {
        out.push(format!(
            "the solver stopped at a residual of {:.1e}, above the tolerance {:.1e}: the \
             iteration cycled between contact sets that differ at the contact's edge (a \
             feature narrower than a cell there, e.g. a glassy leading edge), so the \
             discrete problem has no closer solution on this grid; the result is its \
             best iterate (another cell count may reach the tolerance)",
            info.residual, info.tolerance
        ));
    }
    out
}

/// The energy-balance check of steady sliding: `mu Q V` must equal the power
/// dissipated in the layer. Only where the layer creeps (a finite speed): at
/// infinite speed nothing dissipates and mu is zero up to rounding. Both estimates
/// resolve the contact's edges to first order in the cell, so the allowed
/// difference is the larger of [`MAX_ENERGY_IMBALANCE`] and
/// [`ENERGY_IMBALANCE_PER_CELL`] `h / a`, a the contact's half-length along x.
/// Cells from the pressure's maximum within which an unloaded cell means the peak is
/// not resolved.
pub const EDGE_PEAK_CELLS: usize = 3;

/// The sentence for a pressure whose maximum lies within [`EDGE_PEAK_CELLS`] of an
/// unloaded cell, on a body without a layer: a concentration at the contact's edge
/// narrower than the grid resolves (under a coating far stiffer and thinner than
/// the contact, or behind the glassy leading edge of a viscoelastic body), whose
/// value then follows the cell size. A layer places its contacts' edges inside
/// their cells and its leading-edge jumps are resolved that way, and where its flow
/// creeps less than a cell the pressure's rise behind the leading edge is modelled
/// inside the entry cell ([`crate::layer::Rise`]), so it is left out.
fn edge_peak_warning(case: &Case, solution: &Solution) -> Option<String> {
    if case.layer.is_some() {
        return None;
    }
    let grid = &solution.grid;
    let (nx, ny) = (grid.nx(), grid.ny());
    // The pressure at the cells' centres (behind a modelled rise, a share of the
    // centre value).
    let p = solution.centre_pressure();
    let peak = (0..p.len()).max_by(|&a, &b| p[a].total_cmp(&p[b]))?;
    if p[peak] <= 0.0 {
        return None;
    }
    let (i, j) = (peak % nx, peak / nx);
    let r = EDGE_PEAK_CELLS;
    let rows = j.saturating_sub(r)..(j + r + 1).min(ny);
    let unloaded = rows
        .flat_map(|l| (i.saturating_sub(r)..(i + r + 1).min(nx)).map(move |k| (k, l)))
        .any(|(k, l)| p[l * nx + k] <= 0.0);
    let at = if grid.is_line() {
        format!("x = {:.4e}", grid.x(i))
    } else {
        format!("x = {:.4e}, y = {:.4e}", grid.x(i), grid.y(j))
    };
    unloaded.then(|| {
        format!(
            "the pressure peaks within {r} cells of the contact's edge ({at}): the \
             peak is narrower than the cells resolve (e.g. an edge concentration under a \
             stiff thin coating, a glassy leading edge, or a contact spot a few cells \
             wide), so max_pressure follows the cell \
             size; refine the grid to converge it (the load, the contact's extent and the \
             friction converge sooner)"
        )
    })
}

fn energy_balance_warning(case: &Case, s: &Summary) -> Option<String> {
    let speed = case.loading.velocity.unwrap_or(f64::INFINITY);
    let body_creeps = !case.body.model().kernel_is_even(speed);
    if (case.layer.is_none() && !body_creeps) || !speed.is_finite() {
        return None;
    }
    let (mu, dissipated) = (s.friction_coefficient, s.dissipation_friction_coefficient);
    let scale = mu.abs().max(dissipated.abs());
    // The slope's mu sums p x / R over a pressure symmetric to its rounding: below
    // 1e-9 of the contact's slope (a / R) both estimates are noise, not friction.
    let half_length = 0.5 * (s.contact_x_max - s.contact_x_min);
    let slope = half_length / case.slider.equivalent_radius();
    if scale == 0.0 || scale < FRICTION_NOISE * slope {
        return None;
    }
    let imbalance = (dissipated - mu).abs() / scale;
    let cells = half_length / s.cell_size;
    let allowed = MAX_ENERGY_IMBALANCE.max(ENERGY_IMBALANCE_PER_CELL / cells);
    (imbalance > allowed).then(|| {
        format!(
            "the energy balance is off by {:.1} %: mu = {mu:.4e} from the slider's slope, \
             {dissipated:.4e} from the power dissipated in the layer and the body, where a grid \
             resolving the contact ({cells:.0} cells over its half-length along x here) \
             keeps them within {:.1} %; refine the grid (more cells, or a window closer \
             to the contact) and compare",
            100.0 * imbalance,
            100.0 * allowed
        )
    })
}

/// A line contact's summary keys: those of [`Summary`] without its y keys.
#[derive(Serialize)]
struct LineSummary {
    normal_load: f64,
    penetration: f64,
    max_pressure: f64,
    max_pressure_x: f64,
    contact_area: f64,
    contact_x_min: f64,
    contact_x_max: f64,
    moment: f64,
    friction_coefficient: f64,
    tangential_force: f64,
    dissipation_friction_coefficient: f64,
    iterations: usize,
    residual: f64,
    nx: usize,
    cell_size: f64,
}

/// Serialises `s` whole for a point contact and without its y keys for a line
/// contact (whose grid alone has one row: a point grid has at least
/// [`crate::grid::MIN_CELLS`] rows).
fn summary_keys<S: Serializer>(s: &Summary, serializer: S) -> Result<S::Ok, S::Error> {
    if s.ny != 1 {
        return s.serialize(serializer);
    }
    LineSummary {
        normal_load: s.normal_load,
        penetration: s.penetration,
        max_pressure: s.max_pressure,
        max_pressure_x: s.max_pressure_x,
        contact_area: s.contact_area,
        contact_x_min: s.contact_x_min,
        contact_x_max: s.contact_x_max,
        moment: s.moment,
        friction_coefficient: s.friction_coefficient,
        tangential_force: s.tangential_force,
        dissipation_friction_coefficient: s.dissipation_friction_coefficient,
        iterations: s.iterations,
        residual: s.residual,
        nx: s.nx,
        cell_size: s.cell_size,
    }
    .serialize(serializer)
}

/// The `stress` object of a report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StressReport {
    /// The scalar stress results.
    #[serde(flatten)]
    pub summary: StressSummary,
    /// Each section computed.
    pub sections: Vec<SectionReport>,
}

/// One computed section in a report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SectionReport {
    /// Its name (`xz`, `surface`, `interface_coating`, ...), as in the file names.
    pub name: String,
    /// Points along x, y and z.
    pub points: [usize; 3],
    /// Its depths.
    pub depths: Vec<f64>,
    /// y of an XZ plane (a section with one row).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub y: Option<f64>,
}

impl Units {
    /// The name a report gives the units.
    pub fn name(self) -> &'static str {
        match self {
            Units::Dimensionless => "dimensionless",
            Units::Si => "si",
        }
    }
}

impl StressReport {
    /// The report of computed stresses.
    pub fn of(results: &StressResults) -> Self {
        StressReport {
            summary: results.summary.clone(),
            sections: results
                .sections
                .iter()
                .map(|(named, f)| SectionReport {
                    name: named.name(),
                    points: [f.xs.len(), f.ys.len(), f.zs.len()],
                    depths: f.zs.clone(),
                    y: match f.ys[..] {
                        [y] => Some(y),
                        _ => None,
                    },
                })
                .collect(),
        }
    }
}

impl Report {
    /// The report of `solution` of `case`, solved in `solve_seconds`, with the
    /// stresses computed from it, if any.
    pub fn new(
        case: &Case,
        solution: &Solution,
        solve_seconds: f64,
        stress: Option<&StressResults>,
    ) -> Self {
        let g = &solution.grid;
        let [wx, wy] = g.half_widths();
        let [cx, cy] = g.centre();
        let info = &solution.info;
        let (contact, reference_distance, y_window) = match g.geometry() {
            Geometry::Point => (None, None, Some((cy - wy, cy + wy))),
            Geometry::Line { datum } => (Some("line"), Some(datum), None),
        };
        Report {
            summary: solution.summary(),
            contact,
            reference_distance,
            solve_seconds,
            units: case.units.name(),
            method: info.method,
            linear_iterations: info.linear_iterations,
            windows: info.windows,
            window_x_min: cx - wx,
            window_x_max: cx + wx,
            window_y_min: y_window.map(|w| w.0),
            window_y_max: y_window.map(|w| w.1),
            stress: stress.map(StressReport::of),
            warnings: model_warnings(case, solution),
            thirdbody_version: crate::provenance::VERSION,
            commit: crate::provenance::commit(),
            case_hash: crate::provenance::case_hash(case),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn report_keys(text: &str) -> serde_json::Map<String, serde_json::Value> {
        let file = crate::case_file::parse_case_file(text, &mut |_, _| unreachable!()).unwrap();
        let solution = crate::solve(&file.case, &file.solver).unwrap();
        let report = Report::new(&file.case, &solution, 0.0, None);
        match serde_json::to_value(report).unwrap() {
            serde_json::Value::Object(m) => m,
            other => panic!("{other}"),
        }
    }

    const Y_KEYS: [&str; 6] = [
        "max_pressure_y",
        "contact_y_min",
        "contact_y_max",
        "ny",
        "window_y_min",
        "window_y_max",
    ];

    #[test]
    fn the_energy_balance_warns_when_the_two_estimates_disagree_beyond_the_grid() {
        // A solved Maxwell layer (the estimates agree to 1e-3), then its dissipation
        // moved: beyond the larger of 1 % and h / a it is named, within it not.
        let file = crate::case_file::parse_case_file(
            "[slider]\nshape = \"sphere\"\nradius = 1.0\n[substrate]\nyoung = 1.0\n\
             poisson = 0.3\n[layer]\ncompliance = 0.02\nrelaxation_time = 1.0\n\
             [loading]\nnormal_load = 5e-6\nvelocity = 1e-2\n[grid]\ncells = [32, 32]\n",
            &mut |_, _| unreachable!(),
        )
        .unwrap();
        let solution = crate::solve(&file.case, &file.solver).unwrap();
        let mut s = solution.summary();
        assert!(energy_balance_warning(&file.case, &s).is_none());
        let half_length = 0.5 * (s.contact_x_max - s.contact_x_min);
        let allowed =
            MAX_ENERGY_IMBALANCE.max(ENERGY_IMBALANCE_PER_CELL * s.cell_size / half_length);
        let mu = s.friction_coefficient;
        s.dissipation_friction_coefficient = mu * (1.0 + 0.9 * allowed);
        assert!(energy_balance_warning(&file.case, &s).is_none());
        s.dissipation_friction_coefficient = mu * (1.0 + 1.5 * allowed);
        let warning = energy_balance_warning(&file.case, &s).unwrap();
        assert!(warning.contains("energy balance is off"), "{warning}");
    }

    #[test]
    fn a_line_contact_reports_no_y_but_its_geometry_and_a_point_contact_all_keys() {
        let line = report_keys(
            "[slider]\nshape = \"cylinder\"\nradius = 1.0\n[substrate]\nyoung = 1.0\n\
             poisson = 0.3\n[loading]\nnormal_load = 1e-3\nreference_distance = 2.0\n\
             [grid]\ncells = 64\n",
        );
        for key in Y_KEYS {
            assert!(!line.contains_key(key), "{key}");
        }
        assert_eq!(line["contact"], "line");
        assert_eq!(line["reference_distance"], 2.0);
        for key in [
            "normal_load",
            "max_pressure_x",
            "contact_x_min",
            "nx",
            "case_hash",
        ] {
            assert!(line.contains_key(key), "{key}");
        }
        let point = report_keys(crate::test_cases::HERTZ);
        for key in Y_KEYS {
            assert!(point.contains_key(key), "{key}");
        }
        assert!(!point.contains_key("contact") && !point.contains_key("reference_distance"));
    }
}
