//! The contact solver (design.md §2): finds the contact area, the pressure p >= 0
//! and the approach D such that `w_body(p) + w_layer(p) + f - D = 0` where p > 0,
//! the gap is >= 0 where p = 0, and `sum(p) h^2 = Q` (paper eq. 3-4 and system 6).
//!
//! Without creep (no layer, or a linear layer at infinite velocity) the operator is
//! symmetric positive definite and [`polonsky_keer`] conjugate gradients are used;
//! otherwise the layer's creep makes it non-symmetric and the semi-smooth Newton
//! iteration of [`newton`] is used. Both stop on the relative complementarity
//! residual `||min(p, c g)|| / ||p||` (c = inverse self-compliance of a cell), which
//! is reported, and fail with the residual history when they do not converge. The
//! window is chosen automatically unless the case fixes it ([`window`]): a solution
//! whose contact reaches the window's edge is never returned.

mod newton;
mod polonsky_keer;
pub(crate) mod window;

use std::sync::Arc;

use crate::body::surface_kernel_spectrum;
use crate::case::Case;
use crate::convolution::{ConvolutionPlan, KernelSpectrum, Parallelism};
use crate::error::{Error, Result};
use crate::grid::Grid;
use crate::layer::{ComplianceLaw, LayerOperator};
use crate::operator::{ConvolutionOperator, InfluenceOperator};
use crate::solution::{Method, Solution, SolveInfo};

/// Stopping criteria and resources of a solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverParams {
    /// Relative complementarity residual at which the solve stops.
    pub tolerance: f64,
    /// Most outer iterations per window.
    pub max_iterations: usize,
    /// Threads for one solve's FFTs.
    pub parallelism: Parallelism,
    /// Most windows the automatic window may try.
    pub max_windows: usize,
}

impl Default for SolverParams {
    fn default() -> Self {
        SolverParams {
            tolerance: 1e-10,
            max_iterations: 2000,
            parallelism: Parallelism::Rayon,
            max_windows: 6,
        }
    }
}

impl SolverParams {
    /// Checks the parameters; errors name the `[solver]` field.
    pub fn validate(&self) -> Result<()> {
        if !(self.tolerance.is_finite() && self.tolerance > 0.0 && self.tolerance < 1.0) {
            return Err(Error::invalid(
                "solver.tolerance",
                self.tolerance,
                "0 < tolerance < 1",
            ));
        }
        if self.max_iterations == 0 {
            return Err(Error::invalid("solver.max_iterations", 0, "at least 1"));
        }
        Ok(())
    }
}

/// What a solve reports while it runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Progress {
    /// A new window is being solved.
    Window {
        /// 1 for the first window.
        attempt: usize,
        /// The window.
        grid: Grid,
    },
    /// An outer iteration finished.
    Iteration {
        /// Iteration number in this window.
        iteration: usize,
        /// Relative residual after it.
        residual: f64,
    },
}

/// What an inner solver returns.
#[derive(Debug, Clone)]
pub(crate) struct SolveReport {
    pub iterations: usize,
    pub linear_iterations: usize,
    pub residual: f64,
    pub approach: f64,
    pub history: Vec<f64>,
}

/// The relative complementarity residual `||min(p / P, g / W)|| / ||p / P||`, zero
/// exactly when p >= 0, g >= 0 and p g = 0. `P` is the mean contact pressure and `W`
/// the largest surface displacement `|w|`, so the measure does not depend on the cell
/// size: a residual r means gaps within about r W of zero in the contact and pressures
/// within about r P of zero outside it.
pub(crate) fn relative_complementarity_residual(p: &[f64], g: &[f64], w: &[f64]) -> f64 {
    let (mut sum, mut count) = (0.0, 0usize);
    for &pk in p {
        if pk > 0.0 {
            sum += pk;
            count += 1;
        }
    }
    let w_max = w.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if count == 0 || w_max == 0.0 {
        return f64::INFINITY;
    }
    let c = sum / count as f64 / w_max;
    let (mut num, mut den) = (0.0, 0.0);
    for (pk, gk) in p.iter().zip(g) {
        let m = pk.min(c * gk);
        num += m * m;
        den += pk * pk;
    }
    (num / den).sqrt()
}

/// Solves a case.
pub fn solve(case: &Case, params: &SolverParams) -> Result<Solution> {
    solve_observed(case, params, &mut |_| {})
}

/// Solves a case, reporting progress to `observer`.
pub fn solve_observed(
    case: &Case,
    params: &SolverParams,
    observer: &mut dyn FnMut(Progress),
) -> Result<Solution> {
    case.validate()?;
    params.validate()?;
    let fixed = case.grid.half_width.is_some();
    let mut grid = window::initial_window(case)?;
    let mut warm: Option<(Grid, Vec<f64>)> = None;
    for attempt in 1..=params.max_windows.max(1) {
        observer(Progress::Window { attempt, grid });
        let plan = ConvolutionPlan::new(grid.nx, grid.ny, params.parallelism);
        let kernel = Arc::new(surface_kernel_spectrum(&case.body, &grid, &plan)?);
        let mut solution =
            solve_on_grid(case, &grid, &plan, &kernel, warm.as_ref(), params, observer)?;
        solution.info.windows = attempt;
        let touches = grid.touches_edge(&solution.pressure);
        if fixed {
            if touches {
                let [wx, wy] = grid.half_widths();
                return Err(Error::ContactAtWindowEdge {
                    half_width_x: wx,
                    half_width_y: wy,
                });
            }
            window::check_resolution(&solution)?;
            return Ok(solution);
        }
        match window::next_window(&grid, &solution.pressure, touches) {
            None => return Ok(solution),
            Some(next) => {
                warm = Some((grid, solution.pressure));
                grid = next;
            }
        }
    }
    let [wx, wy] = grid.half_widths();
    Err(Error::ContactAtWindowEdge {
        half_width_x: wx,
        half_width_y: wy,
    })
}

/// Solves a case on a given grid with a prepared kernel spectrum (no window
/// adaptation): the building block for sweeps that share a grid and body.
pub fn solve_on_grid(
    case: &Case,
    grid: &Grid,
    plan: &Arc<ConvolutionPlan>,
    kernel: &Arc<KernelSpectrum>,
    warm: Option<&(Grid, Vec<f64>)>,
    params: &SolverParams,
    observer: &mut dyn FnMut(Progress),
) -> Result<Solution> {
    let n = grid.len();
    let mut f = vec![0.0; n];
    let mut slope = vec![0.0; n];
    case.slider.sample(grid, &mut f, &mut slope)?;
    let mut op = ConvolutionOperator::new(plan.convolver(), Arc::clone(kernel));
    let velocity = case.velocity();
    let layer = case
        .layer
        .as_ref()
        .map(|l| LayerOperator::new(l.clone(), grid.nx, grid.ny, grid.cell, velocity));
    let load = case.loading.normal_load;
    let area = grid.cell_area();
    let estimate = window::ContactEstimate::of(case);

    // Symmetric when nothing creeps and the layer, if any, is linear.
    let winkler = match &layer {
        None => Some(0.0),
        Some(l) if l.creep_per_cell() == 0.0 && matches!(l.layer().law, ComplianceLaw::Linear) => {
            Some(l.layer().compliance)
        }
        _ => None,
    };
    let mut p = match warm {
        Some((old, old_p)) => window::interpolate(old, old_p, grid),
        None => Vec::new(),
    };
    let (method, report) = match (winkler, &layer) {
        (Some(c_w), _) => {
            if p.iter().all(|&v| v <= 0.0) {
                p = window::hertz_like_guess(grid, &f, &estimate);
            }
            let r = polonsky_keer::polonsky_keer(
                &mut op, c_w, &f, load, area, &mut p, params, observer,
            )?;
            (Method::PolonskyKeer, r)
        }
        (None, Some(layer_op)) => {
            if p.iter().all(|&v| v <= 0.0) {
                p = window::rigid_base_guess(grid, &f, layer_op, &estimate, load);
            }
            let r = newton::semismooth_newton(
                &mut op, layer_op, &f, load, area, &mut p, params, observer,
            )?;
            (Method::SemismoothNewton, r)
        }
        (None, None) => unreachable!("no layer always has the symmetric path"),
    };
    assemble(
        case,
        grid,
        &mut op,
        layer.as_ref(),
        f,
        slope,
        p,
        method,
        report,
    )
}

/// Clips round-off negatives, restores the load exactly and computes every field.
#[allow(clippy::too_many_arguments)]
fn assemble(
    case: &Case,
    grid: &Grid,
    op: &mut dyn InfluenceOperator,
    layer: Option<&LayerOperator>,
    f: Vec<f64>,
    slope: Vec<f64>,
    mut p: Vec<f64>,
    method: Method,
    report: SolveReport,
) -> Result<Solution> {
    let n = grid.len();
    let load = case.loading.normal_load;
    p.iter_mut().for_each(|v| *v = v.max(0.0));
    let sum: f64 = p.iter().sum();
    let scale = load / (sum * grid.cell_area());
    p.iter_mut().for_each(|v| *v *= scale);
    let mut wb = vec![0.0; n];
    op.apply(&p, &mut wb);
    let (wl, compliance) = match layer {
        Some(l) => {
            let mut wl = vec![0.0; n];
            l.maxwell_row_sweep(&p, &mut wl);
            let c: Vec<f64> = p.iter().map(|&v| l.layer().law_at(v).compliance).collect();
            (Some(wl), Some(c))
        }
        None => (None, None),
    };
    let gap: Vec<f64> = (0..n)
        .map(|k| wb[k] + wl.as_ref().map_or(0.0, |w| w[k]) + f[k] - report.approach)
        .collect();
    if !p.iter().chain(&gap).all(|v| v.is_finite()) {
        return Err(Error::NoConvergence {
            iterations: report.iterations,
            residual: f64::NAN,
            tolerance: 0.0,
            history: report.history,
            hint: "the solution is not finite; check the case's scales".into(),
        });
    }
    Ok(Solution {
        grid: *grid,
        pressure: p,
        body_displacement: wb,
        layer_displacement: wl,
        compliance,
        gap,
        shape: f,
        shape_slope: slope,
        approach: report.approach,
        normal_load: load,
        info: SolveInfo {
            method,
            iterations: report.iterations,
            linear_iterations: report.linear_iterations,
            residual: report.residual,
            windows: 1,
            history: report.history,
        },
    })
}
