//! The report of a solve, as every front end writes it (`summary.json` of the CLI,
//! the rows of a sweep's `results.csv`, a Python dict): the scalar results of the
//! [`Summary`], the solver's report, the window, the units, the wall time the front
//! end measured and, when stresses were computed, their summary and the sections.
//! One definition, serialised with serde, so that every front end reports exactly
//! the same keys (listed in docs/outputs.md).

use serde::Serialize;

use crate::case::Units;
use crate::solution::{Method, Solution, Summary};
use crate::stress::{StressResults, StressSummary};

/// What `summary.json` holds.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// The scalar results.
    #[serde(flatten)]
    pub summary: Summary,
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
    /// The final window's extent along y (cell edges).
    pub window_y_min: f64,
    /// See `window_y_min`.
    pub window_y_max: f64,
    /// Stress results, when stresses were computed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stress: Option<StressReport>,
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
    /// The report of `solution`, solved in `units` in `solve_seconds`, with the
    /// stresses computed from it, if any.
    pub fn new(
        solution: &Solution,
        units: Units,
        solve_seconds: f64,
        stress: Option<&StressResults>,
    ) -> Self {
        let g = &solution.grid;
        let [wx, wy] = g.half_widths();
        let [cx, cy] = g.centre();
        let info = &solution.info;
        Report {
            summary: solution.summary(),
            solve_seconds,
            units: units.name(),
            method: info.method,
            linear_iterations: info.linear_iterations,
            windows: info.windows,
            window_x_min: cx - wx,
            window_x_max: cx + wx,
            window_y_min: cy - wy,
            window_y_max: cy + wy,
            stress: stress.map(StressReport::of),
        }
    }
}
