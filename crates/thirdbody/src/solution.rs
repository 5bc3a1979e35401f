//! A solved contact and the quantities users read off it: contact area and
//! extents, maximum pressure, the moment `M = sum(x p) h^2` and the hysteresis
//! friction coefficient `mu = sum(p df/dx) h^2 / Q` (the general form of paper
//! eq. 12; for the paraboloid sphere it equals `M / (R Q)`), and the tangential
//! force `Q_T = mu Q` that opposes the sliding. `mu > 0` when the pressure is
//! shifted to the leading edge (+x).

use serde::Serialize;

use std::borrow::Cow;

use crate::case::Body;
use crate::grid::Grid;
use crate::layer::{cell_mean_pressure, ContactEdge};

/// Which algorithm produced a solution.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Method {
    /// Polonsky–Keer conjugate gradients (symmetric operator: no creep).
    PolonskyKeer,
    /// Semi-smooth Newton on the complementarity conditions with GMRES.
    SemismoothNewton,
    /// Dense direct solve of the paper's system (6) with an active-set loop.
    DenseReference,
}

/// How the solve went.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SolveInfo {
    /// Algorithm that converged (Newton also when it took over from conjugate
    /// gradients that did not).
    pub method: Method,
    /// Outer iterations (CG steps or Newton steps; both summed when Newton took
    /// over) of the final window.
    pub iterations: usize,
    /// Inner Krylov iterations in total (0 for CG).
    pub linear_iterations: usize,
    /// Products of the body's influence operator (DC-FFT convolutions) on the final
    /// window, the solve's unit of cost.
    pub operator_products: usize,
    /// Final relative complementarity residual (see the contact module).
    pub residual: f64,
    /// The residual the solve was asked for (`solver.tolerance`). `residual` is above
    /// it only when the iteration stalled after reaching
    /// [`crate::contact::STALLED_BUT_SOLVED`]; the report then warns.
    pub tolerance: f64,
    /// Windows tried (the automatic window may enlarge or refit).
    pub windows: usize,
    /// Residual after each outer iteration of the final window.
    pub history: Vec<f64>,
}

/// A converged contact.
#[derive(Debug, Clone)]
pub struct Solution {
    /// The window and cells.
    pub grid: Grid,
    /// The body it was solved on (its stresses are computed on it).
    pub body: Body,
    /// Contact pressure per cell, >= 0: at the cell's centre.
    pub pressure: Vec<f64>,
    /// The contacts' leading edges the layer located inside their cells (empty for
    /// most layers): there a cell's mean pressure, which the load, the friction and
    /// the stresses integrate, differs from its centre value
    /// ([`Solution::mean_pressure`]).
    pub contact_edges: Vec<ContactEdge>,
    /// Normal displacement of the elastic body's surface.
    pub body_displacement: Vec<f64>,
    /// Normal displacement of the layer `w3` (`None` without a layer).
    pub layer_displacement: Option<Vec<f64>>,
    /// Layer compliance `C[p]` per cell (paper Fig. 3b; `None` without a layer).
    pub compliance: Option<Vec<f64>>,
    /// Gap between slider and deformed surface: `w_body + w_layer + f - D`
    /// (zero in contact to solver precision, >= 0 outside).
    pub gap: Vec<f64>,
    /// Slider shape f at cell centres.
    pub shape: Vec<f64>,
    /// Slope df/dx at cell centres.
    pub shape_slope: Vec<f64>,
    /// The power dissipated in the layer and in the body divided by the sliding
    /// speed (0 for an elastic body without a layer, or at infinite speed): by
    /// energy balance, the tangential force.
    pub dissipated_force: f64,
    /// Approach (penetration) D of the slider.
    pub approach: f64,
    /// Normal load Q.
    pub normal_load: f64,
    /// Solver report.
    pub info: SolveInfo,
}

/// The scalar results of a solution, in the case's units.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// Q.
    pub normal_load: f64,
    /// D.
    pub penetration: f64,
    /// Largest pressure: at the cells' centres, and between each leading edge
    /// located inside a cell and that cell's centre.
    pub max_pressure: f64,
    /// x of the largest pressure.
    pub max_pressure_x: f64,
    /// y of the largest pressure.
    pub max_pressure_y: f64,
    /// Number of loaded cells times the cell area.
    pub contact_area: f64,
    /// Smallest x covered by a loaded cell (cell edge; a line contact's edge is
    /// located inside the cell from the pressure's square-root fall).
    pub contact_x_min: f64,
    /// Largest x covered by a loaded cell (cell edge; a line contact's located
    /// inside the cell).
    pub contact_x_max: f64,
    /// Smallest y covered by a loaded cell (cell edge).
    pub contact_y_min: f64,
    /// Largest y covered by a loaded cell (cell edge).
    pub contact_y_max: f64,
    /// `M = sum(x p) h^2` about the slider's lowest point (paper eq. 12).
    pub moment: f64,
    /// `mu = sum(p df/dx) h^2 / Q`.
    pub friction_coefficient: f64,
    /// `Q_T = mu Q`, the force that opposes the sliding.
    pub tangential_force: f64,
    /// `mu` from energy balance: the power dissipated in the layer and the body
    /// over `Q V` (an independent check of `friction_coefficient`; 0 for an elastic
    /// body without a layer).
    pub dissipation_friction_coefficient: f64,
    /// Outer iterations.
    pub iterations: usize,
    /// Final relative residual.
    pub residual: f64,
    /// Cells along x.
    pub nx: usize,
    /// Cells along y.
    pub ny: usize,
    /// Cell side h.
    pub cell_size: f64,
}

impl Summary {
    /// Whether every number is finite (a result with an overflowed friction sum or
    /// moment must not be reported).
    pub fn is_finite(&self) -> bool {
        self.first_non_finite().is_none()
    }

    /// The name of the first number that is not finite, if any.
    pub fn first_non_finite(&self) -> Option<&'static str> {
        [
            ("normal_load", self.normal_load),
            ("penetration", self.penetration),
            ("max_pressure", self.max_pressure),
            ("max_pressure_x", self.max_pressure_x),
            ("max_pressure_y", self.max_pressure_y),
            ("contact_area", self.contact_area),
            ("contact_x_min", self.contact_x_min),
            ("contact_x_max", self.contact_x_max),
            ("contact_y_min", self.contact_y_min),
            ("contact_y_max", self.contact_y_max),
            ("moment", self.moment),
            ("friction_coefficient", self.friction_coefficient),
            ("tangential_force", self.tangential_force),
            (
                "dissipation_friction_coefficient",
                self.dissipation_friction_coefficient,
            ),
            ("residual", self.residual),
            ("cell_size", self.cell_size),
        ]
        .into_iter()
        .find(|(_, v)| !v.is_finite())
        .map(|(name, _)| name)
    }
}

/// The edges of a line contact's loaded span located inside the cells: where the
/// square of the pressure, linear in the distance to an edge where the pressure
/// goes as its square root (an elastic or viscoelastic body's edge; Johnson, Contact
/// Mechanics, eq. 4.45), extrapolated from the two outermost loaded cells, vanishes;
/// kept between the outermost loaded cell's centre and the next cell's, and at the
/// cell face when the pressure does not rise inward.
fn line_contact_edges(g: &Grid, p: &[f64]) -> [f64; 2] {
    let first = p.iter().position(|&v| v > 0.0).unwrap_or(0);
    let last = p.iter().rposition(|&v| v > 0.0).unwrap_or(0);
    let h = g.cell;
    // The distance beyond the outermost centre (outer pressure `a`, next inward `b`).
    let beyond = |a: f64, b: f64| {
        let (qa, qb) = (a * a, b * b);
        if qb > qa {
            (h * qa / (qb - qa)).min(h)
        } else {
            0.5 * h
        }
    };
    if last < first + 1 {
        return [g.x(first) - 0.5 * h, g.x(last) + 0.5 * h];
    }
    [
        g.x(first) - beyond(p[first], p[first + 1]),
        g.x(last) + beyond(p[last], p[last - 1]),
    ]
}

impl Solution {
    /// The pressure each cell carries on average: [`Solution::pressure`] but at the
    /// contacts' entry cells ([`crate::layer::ContactEdge`]).
    pub fn mean_pressure(&self) -> Cow<'_, [f64]> {
        if self.contact_edges.is_empty() {
            Cow::Borrowed(&self.pressure)
        } else {
            let mut mean = vec![0.0; self.pressure.len()];
            cell_mean_pressure(&self.contact_edges, &self.pressure, &mut mean);
            Cow::Owned(mean)
        }
    }

    /// The pressure at each cell's centre: [`Solution::pressure`] but behind the
    /// leading edges where the pressure rises over part of the cell, where it is
    /// [`crate::layer::ContactEdge::centre_share`] of the centre value.
    pub fn centre_pressure(&self) -> Cow<'_, [f64]> {
        if self.contact_edges.iter().all(|e| e.rise.is_none()) {
            Cow::Borrowed(&self.pressure)
        } else {
            let mut centre = self.pressure.clone();
            for e in &self.contact_edges {
                centre[e.cell] *= e.centre_share();
            }
            Cow::Owned(centre)
        }
    }

    /// The scalar results.
    pub fn summary(&self) -> Summary {
        let g = &self.grid;
        let area = g.cell_measure();
        let mean = self.mean_pressure();
        let centre = self.centre_pressure();
        let (mut pmax, mut kmax) = (0.0, 0);
        let (mut xmin, mut xmax, mut ymin, mut ymax) = (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        );
        let (mut count, mut moment, mut traction) = (0usize, 0.0, 0.0);
        for j in 0..g.ny {
            for i in 0..g.nx {
                let k = g.index(i, j);
                if centre[k] > pmax {
                    pmax = centre[k];
                    kmax = k;
                }
                // A cell carries load where its mean is positive: a contact's edge
                // located inside it can leave its centre value at 0 (the edge
                // between the centre and the loaded face) while the part beyond
                // the edge is loaded.
                if self.pressure[k] > 0.0 || mean[k] > 0.0 {
                    count += 1;
                    let (x, y) = (g.x(i), g.y(j));
                    xmin = xmin.min(x - 0.5 * g.cell);
                    xmax = xmax.max(x + 0.5 * g.cell);
                    ymin = ymin.min(y - 0.5 * g.cell);
                    ymax = ymax.max(y + 0.5 * g.cell);
                    moment += x * mean[k] * area;
                    traction += self.shape_slope[k] * mean[k] * area;
                }
            }
        }
        if g.is_line() && count > 0 {
            [xmin, xmax] = line_contact_edges(g, &mean);
        }
        let (mut pmax_x, mut pmax_y) = (g.x(kmax % g.nx), g.y(kmax / g.nx));
        // Where the pressure jumps at a leading edge, or rises within the entry
        // cell, its peak lies between the edge and the cell's centre.
        for e in self.contact_edges.iter().filter(|e| e.is_leading()) {
            let (peak, s) = e.peak_behind(&self.pressure);
            if peak > pmax {
                pmax = peak;
                pmax_x = g.x(e.cell % g.nx) + (e.theta - s) * g.cell;
                pmax_y = g.y(e.cell / g.nx);
            }
        }
        let mu = traction / self.normal_load;
        Summary {
            normal_load: self.normal_load,
            penetration: self.approach,
            max_pressure: pmax,
            max_pressure_x: pmax_x,
            max_pressure_y: pmax_y,
            contact_area: count as f64 * area,
            contact_x_min: xmin,
            contact_x_max: xmax,
            contact_y_min: ymin,
            contact_y_max: ymax,
            moment,
            friction_coefficient: mu,
            tangential_force: mu * self.normal_load,
            dissipation_friction_coefficient: self.dissipated_force / self.normal_load,
            iterations: self.info.iterations,
            residual: self.info.residual,
            nx: g.nx,
            ny: g.ny,
            cell_size: g.cell,
        }
    }
}
