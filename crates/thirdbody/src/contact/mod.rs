//! The contact solver (docs/architecture.md (numerics)): finds the contact area, the pressure p >= 0
//! and the approach D such that `w_body(p) + w_layer(p) + f - D = 0` where p > 0,
//! the gap is >= 0 where p = 0, and `sum(p) h^2 = Q` (paper eq. 3-4 and system 6).
//!
//! The solvers take a [`ContactProblem`] (the assembly stage, [`crate::problem`]).
//! When the problem is symmetric positive definite (no layer, or a layer that says
//! `w3 = c p`, [`crate::layer::LayerResponse::winkler_compliance`]) Polonsky–Keer
//! conjugate gradients are used; otherwise (a creeping or nonlinear layer makes it
//! non-symmetric) the semi-smooth Newton iteration with GMRES. Both stop on the relative complementarity
//! residual `||min(p, c g)|| / ||p||` (c = inverse self-compliance of a cell), which
//! is reported, and fail with the residual history when they do not converge. The
//! window is chosen automatically unless the case fixes it (module `window`): a solution
//! whose contact reaches the window's edge is never returned.

mod newton;
pub use newton::STALLED_BUT_SOLVED;
mod polonsky_keer;
pub(crate) mod window;

use std::ops::ControlFlow;

use crate::body::EdgeProfile;
use crate::case::{Case, GridSpec};
use crate::convolution::Parallelism;
use crate::error::{Error, Result};
use crate::grid::Grid;
use crate::kernel_cache::KernelCache;
use crate::layer::{load_weights, ContactEdge, NoLayer};
use crate::operator::{OnCellMeans, Unchecked};
use crate::passes::{add_in_order, Passes};
use crate::problem::ContactProblem;
use crate::report::MAX_CONTACT_FRACTION;
use crate::solution::{Method, Solution, SolveInfo};
use crate::units::Scales;

/// The smallest residual tolerance accepted: the relative complementarity residual
/// of a converged solve sits at the rounding level of its sums, about 1e-15 to
/// 1e-14 (measured on the bundled examples), so a smaller one cannot be reached.
pub const MIN_TOLERANCE: f64 = 1e-14;
/// Newton steps over which the residual must fall by [`STAGNATION_FACTOR`], or the
/// solve is stopped as stagnating (a converging Newton iteration needs tens of steps
/// in all).
pub(crate) const NEWTON_STAGNATION_WINDOW: usize = 50;
/// The same for conjugate-gradient steps, which are cheap and whose complementarity
/// residual can plateau for a few hundred steps while the contact set settles (a
/// stiff coating, E1/E2 = 90 on h1 = 0.002: 382 steps, a plateau of ~200).
pub(crate) const CG_STAGNATION_WINDOW: usize = 500;
/// See [`NEWTON_STAGNATION_WINDOW`].
const STAGNATION_FACTOR: f64 = 0.5;

/// What an overflowing solve says.
const OVERFLOW: &str = "the solver's numbers are not finite (they overflow or underflow): \
     the case's values are out of double precision's range together, or the contact is \
     not small against the slider; check slider.radius, the moduli, \
     loading.normal_load and the layer's compliance";

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
    /// The algorithm to use; `None` (the default) picks conjugate gradients for a
    /// symmetric problem and semi-smooth Newton otherwise. Newton can be forced on
    /// any problem (a second method to compare with); conjugate gradients only on a
    /// symmetric one.
    pub method: Option<Method>,
}

impl Default for SolverParams {
    fn default() -> Self {
        SolverParams {
            tolerance: 1e-10,
            max_iterations: 2000,
            parallelism: Parallelism::Rayon,
            max_windows: 6,
            method: None,
        }
    }
}

impl SolverParams {
    /// Checks the parameters; errors name the `[solver]` field.
    pub fn validate(&self) -> Result<()> {
        if !(self.tolerance.is_finite() && self.tolerance >= MIN_TOLERANCE && self.tolerance < 1.0)
        {
            return Err(Error::invalid(
                "solver.tolerance",
                self.tolerance,
                &format!(
                    "{MIN_TOLERANCE:e} <= tolerance < 1 (a relative residual below \
                     {MIN_TOLERANCE:e} is under double precision's rounding)"
                ),
            ));
        }
        if self.max_iterations == 0 {
            return Err(Error::invalid("solver.max_iterations", 0, "at least 1"));
        }
        if self.method == Some(Method::DenseReference) {
            return Err(Error::invalid(
                "solver.method",
                "dense_reference",
                "conjugate gradients or semi-smooth Newton (the dense reference is \
                 thirdbody_reference::solve_dense, a test crate)",
            ));
        }
        Ok(())
    }
}

/// What a solve reports while it runs. The observer answers with
/// [`ControlFlow::Break`] to stop the solve, which then returns
/// [`Error::Interrupted`] (a front end's Ctrl-C).
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
        /// Iteration number in this window (counting on through the solves again
        /// with the contacts' edges located, as the summary's `iterations` does).
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
pub(crate) fn relative_complementarity_residual(
    passes: &Passes,
    p: &[f64],
    g: &[f64],
    w: &[f64],
) -> f64 {
    let n = p.len();
    let parts = passes.partials(n, |a, b| {
        let mut part = [0.0, 0.0, 0.0];
        for k in a..b {
            if p[k] > 0.0 {
                part[0] += p[k];
                part[1] += 1.0;
            }
            part[2] = part[2].max(w[k].abs());
        }
        part
    });
    let [sum, count, _] = add_in_order(&parts);
    let w_max = parts.iter().fold(0.0f64, |m, part| m.max(part[2]));
    if count == 0.0 || w_max == 0.0 {
        return f64::INFINITY;
    }
    let c = sum / count / w_max;
    let [num, den] = passes.sum(n, |a, b| {
        let mut part = [0.0, 0.0];
        for k in a..b {
            let m = p[k].min(c * g[k]);
            part[0] += m * m;
            part[1] += p[k] * p[k];
        }
        part
    });
    (num / den).sqrt()
}

/// The error of a case whose discrete model has no unique solution (a folding layer,
/// `diagnosis` says why and what to change): an input error, since no solver
/// setting helps.
pub(crate) fn no_unique_solution(iteration: usize, residual: f64, diagnosis: String) -> Error {
    Error::OutsideModel {
        why: format!(
            "{diagnosis} (the solver stopped at residual {residual:.3e} after {iteration} \
             iterations)"
        ),
    }
}

/// Records the residual history, reports each iteration to the observer and decides
/// when to stop: the one place every iterative solver stops the same way.
pub(crate) struct Monitor<'a> {
    tolerance: f64,
    stagnation_window: usize,
    observer: &'a mut dyn FnMut(Progress) -> ControlFlow<()>,
    history: Vec<f64>,
    /// The observer asked the solve to stop.
    interrupted: bool,
}

impl<'a> Monitor<'a> {
    /// A monitor that calls a solve stagnated when `stagnation_window` iterations
    /// gain less than [`STAGNATION_FACTOR`].
    pub(crate) fn new(
        params: &SolverParams,
        stagnation_window: usize,
        observer: &'a mut dyn FnMut(Progress) -> ControlFlow<()>,
    ) -> Self {
        Monitor {
            tolerance: params.tolerance,
            stagnation_window,
            observer,
            history: Vec::new(),
            interrupted: false,
        }
    }

    /// Records the residual after `iteration`; true when it meets the tolerance.
    pub(crate) fn converged(&mut self, iteration: usize, residual: f64) -> bool {
        self.history.push(residual);
        let flow = (self.observer)(Progress::Iteration {
            iteration,
            residual,
        });
        self.interrupted |= flow.is_break();
        residual <= self.tolerance && !self.interrupted
    }

    /// The error that stops the solve short of the tolerance, if it should stop: the
    /// observer's request ([`Error::Interrupted`]), a residual that is not finite (at once; the case's values overflow), or one that
    /// has stopped falling ([`Monitor::stagnated`]; `diagnosis` is the model's own
    /// explanation, if any).
    pub(crate) fn stop(
        &mut self,
        iteration: usize,
        residual: f64,
        diagnosis: impl FnOnce() -> Option<String>,
    ) -> Option<Error> {
        if self.interrupted {
            return Some(Error::Interrupted);
        }
        if !self.last_residual().is_finite() {
            return Some(Error::OutOfRange {
                why: OVERFLOW.into(),
            });
        }
        if !self.stagnated() {
            return None;
        }
        if let Some(d) = diagnosis() {
            return Some(no_unique_solution(iteration, residual, d));
        }
        let hint = self.stagnation_hint();
        Some(Error::NoConvergence {
            iterations: iteration,
            residual,
            tolerance: self.tolerance,
            history: std::mem::take(&mut self.history),
            hint,
        })
    }

    /// The error of an iteration that can no longer move: its damped steps, however
    /// short, no longer lower its merit, so the next step would be the same.
    pub(crate) fn stuck(&mut self, iteration: usize, residual: f64, steps: usize) -> Error {
        Error::NoConvergence {
            iterations: iteration,
            residual,
            tolerance: self.tolerance,
            history: std::mem::take(&mut self.history),
            hint: format!(
                "the iteration is stuck: the last {steps} steps, shortened to a millionth, \
                 did not lower its merit, so more iterations would not help: the discrete \
                 problem is too ill-conditioned at these parameters (e.g. moduli or \
                 compliances many orders of magnitude apart); check the case's scales or \
                 try another cell count"
            ),
        }
    }

    /// Whether the residual has stopped falling: its best over the last
    /// `stagnation_window` iterations is not below [`STAGNATION_FACTOR`] times its
    /// best before them. A converging CG or Newton iteration gains far more than
    /// that; a stagnating one would otherwise run to `max_iterations`.
    pub(crate) fn stagnated(&self) -> bool {
        let (n, window) = (self.history.len(), self.stagnation_window);
        if n <= window {
            return false;
        }
        let best = |h: &[f64]| h.iter().copied().fold(f64::INFINITY, f64::min);
        let (before, recent) = self.history.split_at(n - window);
        let progressing = best(recent) < STAGNATION_FACTOR * best(before);
        !progressing
    }

    /// The message of a stagnated solve that the model cannot explain.
    pub(crate) fn stagnation_hint(&self) -> String {
        let (n, window) = (self.history.len(), self.stagnation_window);
        let from = self.history[n - 1 - window];
        let to = self.last_residual();
        format!(
            "the residual stopped falling (from {from:.3e} to {to:.3e} over the last \
             {window} iterations), so more iterations would not help: the discrete problem \
             is too ill-conditioned at these parameters (e.g. moduli or compliances many \
             orders of magnitude apart), or the iteration finds no way down from its start \
             on this grid; check the case's scales, try another cell count or use a coarser \
             tolerance"
        )
    }

    /// The last residual recorded (infinite before any).
    pub(crate) fn last_residual(&self) -> f64 {
        self.history.last().copied().unwrap_or(f64::INFINITY)
    }

    /// The report of a converged solve.
    pub(crate) fn report(
        self,
        iterations: usize,
        linear_iterations: usize,
        approach: f64,
    ) -> SolveReport {
        SolveReport {
            iterations,
            linear_iterations,
            residual: self.last_residual(),
            approach,
            history: self.history,
        }
    }

    /// The error of a solve that stopped at `residual` after `iterations`.
    pub(crate) fn failure(self, iterations: usize, residual: f64, hint: String) -> Error {
        Error::NoConvergence {
            iterations,
            residual,
            tolerance: self.tolerance,
            history: self.history,
            hint,
        }
    }
}

/// Solves a case with a kernel cache of its own.
pub fn solve(case: &Case, params: &SolverParams) -> Result<Solution> {
    solve_with(case, params, &mut KernelCache::new(), &mut |_| {
        ControlFlow::Continue(())
    })
}

/// Solves a case with a kernel cache of its own, reporting progress to `observer`.
pub fn solve_observed(
    case: &Case,
    params: &SolverParams,
    observer: &mut dyn FnMut(Progress) -> ControlFlow<()>,
) -> Result<Solution> {
    solve_with(case, params, &mut KernelCache::new(), observer)
}

/// Solves a case, taking plans and kernel spectra from the caller's `kernels` (and
/// keeping new ones there), reporting progress to `observer`. The window is the
/// case's fixed one, or chosen automatically and enlarged or refitted until the
/// contact fits (docs/architecture.md (numerics)). The solve runs in the paper's variables
/// (R = E2 = T = 1, rounded to powers of two); the solution, the errors and the windows reported to
/// `observer` are in the case's units.
pub fn solve_with(
    case: &Case,
    params: &SolverParams,
    kernels: &mut KernelCache,
    observer: &mut dyn FnMut(Progress) -> ControlFlow<()>,
) -> Result<Solution> {
    case.validate()?;
    params.validate()?;
    let scales = Scales::of(case);
    let scaled = scales.scaled_case(case)?;
    let mut observe_in_case_units = |progress: Progress| {
        observer(match progress {
            Progress::Window { attempt, grid } => Progress::Window {
                attempt,
                grid: scales.unscaled_grid(&grid),
            },
            other => other,
        })
    };
    let solution = solve_on_windows(
        &scaled,
        params,
        kernels,
        &mut observe_in_case_units,
        Settle::Edges,
    )
    .map_err(|e| scales.unscaled_error(outside_the_model(&scaled, e)))?;
    let solution = scales.unscaled_solution(solution, case.body.clone(), case.loading.normal_load);
    if let Some(name) = solution.summary().first_non_finite() {
        // Finite in the solver's units, so the case's units are what overflow: a
        // moment of 1e98 N times 1e300 m.
        return Err(Error::OutOfRange {
            why: format!(
                "the result {name} is beyond double precision's range in the case's units; \
                 write the case in units nearer its own sizes (the paper's R = E2 = T = 1 \
                 always fit)"
            ),
        });
    }
    if case.grid.half_width.is_some() {
        window::check_resolution(&solution)?;
    }
    Ok(solution)
}

/// A solve that failed to converge on a case whose estimated contact (Hertz or
/// Winkler) is larger than the model allows (the report's [`MAX_CONTACT_FRACTION`] of R, which a
/// solution beyond carries as a warning) fails because of that: say so, as an input
/// error naming the keys, rather than blame the iterations. Other errors are
/// returned as they are.
fn outside_the_model(case: &Case, e: Error) -> Error {
    // The load's own contact (Hertz or Winkler), not the creep length, which a
    // folding layer can make long inside the model.
    let extent = window::ContactEstimate::of(case).symmetric_radius;
    beyond_the_model_limit(
        case,
        extent,
        "is estimated to reach",
        "there",
        "lower loading.normal_load or layer.compliance, or raise the moduli or the \
         slider's radius",
        e,
    )
}

/// A solve that did not converge on a window whose warm start (the previous window's
/// or the scout's solution) already reached beyond [`MAX_CONTACT_FRACTION`] R from
/// the initial contact point: the model's limit is the cause, not the iterations.
/// The creep of a slow layer or body spreads a contact far beyond the load's own
/// estimate, which [`outside_the_model`] checks (the paper's layer at V = 1e-6 under
/// a sphere or a cylinder: 0.5 R and more). Other errors are returned as they are.
fn beyond_the_model(case: &Case, warm: Option<&(Grid, Vec<f64>)>, e: Error) -> Error {
    let Some((grid, p)) = warm else {
        return e;
    };
    let Some([i0, i1, j0, j1]) = window::loaded_box(grid, p) else {
        return e;
    };
    let y = |j: usize| if grid.is_line() { 0.0 } else { grid.y(j) };
    // As the report measures it: from the origin, against the equivalent radius.
    let reach = [grid.x(i0), grid.x(i1), y(j0), y(j1)]
        .into_iter()
        .fold(0.0f64, |m, v| m.max(v.abs()));
    beyond_the_model_limit(
        case,
        reach,
        "reached",
        "on the next window, after a coarser or smaller one",
        "lower loading.normal_load or layer.compliance, raise the moduli, the slider's \
         radius or loading.velocity",
        e,
    )
}

/// The "outside the model" error of a solve that did not converge (`e`) while its
/// contact `extent` (from the initial contact point) exceeds [`MAX_CONTACT_FRACTION`]
/// of the slider's radius; `e` itself otherwise (a NaN extent or radius included).
fn beyond_the_model_limit(
    case: &Case,
    extent: f64,
    measured: &str,
    whence: &str,
    remedy: &str,
    e: Error,
) -> Error {
    let Error::NoConvergence {
        iterations,
        residual,
        ..
    } = e
    else {
        return e;
    };
    let r = case.slider.equivalent_radius();
    if extent.is_nan() || r.is_nan() || extent <= MAX_CONTACT_FRACTION * r {
        return e;
    }
    Error::OutsideModel {
        why: format!(
            "its contact {measured} {:.3e} slider radii (the half-space and paraboloid \
             model holds while it stays below {MAX_CONTACT_FRACTION} R), and the solver did \
             not converge {whence} (residual {residual:.3e} after {iterations} \
             iterations); {remedy}",
            extent / r
        ),
    }
}

/// Whether a solve places the contacts' leading edges inside their cells until they
/// stay put ([`crate::layer::LayerResponse::relocated`]: several warm-started Newton
/// solves), or stops at its first converged solution (a scout's, or a window's that
/// may still be replaced). A scout's solution serves only for its window and
/// pressure, so it also skips the dissipated power ([`Dissipation`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Settle {
    Edges,
    FirstSolution,
}

/// [`solve_with`] in the solver's units: the windows of a case, from the first (its
/// fixed one or the estimate's) to the one that holds the contact. An automatic
/// window's edges are settled only once it holds the contact: each relocation is a
/// Newton solve, and a window that is replaced would spend them for nothing (a
/// Prony layer's first window took 77 Newton steps settled, 35 not).
fn solve_on_windows(
    case: &Case,
    params: &SolverParams,
    kernels: &mut KernelCache,
    observer: &mut dyn FnMut(Progress) -> ControlFlow<()>,
    settle: Settle,
) -> Result<Solution> {
    let fixed = case.grid.half_width.is_some();
    let mut grid = window::initial_window(case)?;
    let mut warm: Option<(Grid, Vec<f64>)> = None;
    if !fixed && !case.body.model().kernel_is_even(case.velocity()) {
        // A creeping body's contact is narrower than the relaxed estimate and
        // shifted forward, by amounts no closed form gives: a solve on a coarse
        // grid finds it, the first window fits it, and its pressure starts Newton.
        if let Some((window, coarse)) = scout(case, &grid, params, kernels) {
            grid = window;
            warm = Some(coarse);
        }
    }
    for attempt in 1..=params.max_windows.max(1) {
        if observer(Progress::Window { attempt, grid }).is_break() {
            return Err(Error::Interrupted);
        }
        let mut problem = case.assemble(&grid, kernels, params.parallelism)?;
        if fixed && window::lowest_point_on_edge(&grid, &problem.shape) {
            // The contact holds the slider's lowest point (where it first touches):
            // on the window's edge, the contact reaches it whatever the solve does.
            let [wx, wy] = grid.half_widths();
            return Err(Error::ContactAtWindowEdge {
                half_width_x: wx,
                half_width_y: wy,
            });
        }
        let mut first = match solve_unsettled(&mut problem, warm.as_ref(), params, observer) {
            // Newton from a cold start or a coarser window's pressure may stall where
            // it converges from the same window's solution at fewer cells; a failure
            // the model's limits explain is reported as it is.
            Err(e @ Error::NoConvergence { .. })
                if matches!(
                    outside_the_model(case, beyond_the_model(case, warm.as_ref(), e.clone())),
                    Error::NoConvergence { .. }
                ) =>
            {
                match coarse_start(case, &grid, params, kernels) {
                    Some(start) => solve_unsettled(&mut problem, Some(&start), params, observer),
                    None => Err(e),
                }
            }
            other => other,
        }
        .map_err(|e| beyond_the_model(case, warm.as_ref(), e))?;
        let newton = first.method == Method::SemismoothNewton;
        let loaded = |p: &[f64]| -> Vec<f64> { p.iter().map(|&v| v.max(0.0)).collect() };
        let mut contact = loaded(&first.pressure);
        let mut next = (!fixed)
            .then(|| window::next_window(&grid, &contact, grid.touches_edge(&contact)))
            .flatten();
        if newton && settle == Settle::Edges && next.is_none() {
            // A window that holds the contact (or a fixed one): its edges settle.
            first.report = settle_edges(
                &mut problem,
                &mut first.pressure,
                first.report,
                params,
                observer,
            )
            .map_err(|e| beyond_the_model(case, warm.as_ref(), e))?;
            contact = loaded(&first.pressure);
            if !fixed {
                next = window::next_window(&grid, &contact, grid.touches_edge(&contact));
            }
        }
        if fixed && grid.touches_edge(&contact) {
            let [wx, wy] = grid.half_widths();
            return Err(Error::ContactAtWindowEdge {
                half_width_x: wx,
                half_width_y: wy,
            });
        }
        match next {
            None => {
                let dissipation = match settle {
                    Settle::Edges => Dissipation::Computed,
                    Settle::FirstSolution => Dissipation::Skipped,
                };
                let mut solution = finish(
                    &mut problem,
                    first.pressure,
                    first.method,
                    first.report,
                    params.tolerance,
                    dissipation,
                )
                .map_err(|e| beyond_the_model(case, warm.as_ref(), e))?;
                solution.info.windows = attempt;
                return Ok(solution);
            }
            Some(next) => {
                warm = Some((grid, contact));
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

/// Grids with fewer cells across are not scouted (their own solve is as cheap).
const MIN_SCOUTED_CELLS: usize = 32;

/// How many times coarser the scout's grid is than the grid it places: half the
/// cells across for a point contact, a quarter for a line contact (whose solves are
/// cheap), each scout itself scouted the same way down to [`MIN_SCOUTED_CELLS`].
/// The warm start is then interpolated from a grid only that much coarser, and it
/// decides whether Newton converges at a nearly glassy leading edge. Scouted from 51
/// cells across (the former rule: 48 cells across whatever the grid), Zener bodies
/// at E_g/E_0 = 1e5, V tau / a0 = 1e-5 and at 1e6, 1e-6 and 1e-5 (creep over 109
/// and 1,090 cells of a 256^2 grid) failed with "did not converge" after about 95 s:
/// Newton's first step from that start raised the residual from about 1e-3 to
/// 0.1-0.35. Scouted from 128^2 they solve in 4.2, 4.5 and 13 s; from a third of
/// the cells in 19-31 s, from a quarter one of them failed. Easy cases cost what
/// they did under the former rule once the scouts skip the dissipated power (a
/// Zener body at E_g/E_0 = 10 near its friction peak on 256^2: 0.40 s against 0.43
/// s, summary included; 0.52 s with the dissipation); glassy ones are faster
/// (E_g/E_0 = 1000, V tau / a0 = 1e-4 on 512^2: 7.4 s against 53-67 s). A line
/// contact on 4096 cells warm-started from 48 cells stalled Newton.
const fn scout_factor(line: bool) -> usize {
    if line {
        4
    } else {
        2
    }
}

/// The window of a case's cells fitted to its contact as located by a solve of the
/// same case on a coarser grid ([`scout_factor`] times fewer cells across, itself
/// scouted the same way, with the automatic window), with that solve's window and
/// pressure; `None` when the grid is too small to scout or the coarse solve fails
/// (the caller then starts from the estimated window).
fn scout(
    case: &Case,
    first: &Grid,
    params: &SolverParams,
    kernels: &mut KernelCache,
) -> Option<(Grid, (Grid, Vec<f64>))> {
    if cells_across(first) < MIN_SCOUTED_CELLS {
        return None;
    }
    let factor = scout_factor(first.is_line());
    let mut grid = case.grid;
    grid.cells = [first.nx / factor, (first.ny / factor).max(1)];
    let solution = first_solution_on(case, grid, params, kernels)?;
    let window = window::fit_to_contact(first.nx, first.ny, &solution.grid, &solution.pressure)?;
    Some((window, (solution.grid, solution.pressure)))
}

/// The pressure of `window` solved with half the cells across (a fixed window,
/// itself started the same way where its solve fails), to start again a solve of
/// `window` that did not converge; `None` when the grid is too small to coarsen or
/// the coarse solve fails too.
fn coarse_start(
    case: &Case,
    window: &Grid,
    params: &SolverParams,
    kernels: &mut KernelCache,
) -> Option<(Grid, Vec<f64>)> {
    if cells_across(window) < MIN_SCOUTED_CELLS {
        return None;
    }
    let grid = GridSpec {
        cells: [window.nx / 2, (window.ny / 2).max(1)],
        half_width: Some(window.half_widths()),
        centre: Some(window.centre()),
    };
    let solution = first_solution_on(case, grid, params, kernels)?;
    Some((solution.grid, solution.pressure))
}

/// Cells across a grid: along x for a line contact, the fewer of the two axes for
/// a point contact.
fn cells_across(grid: &Grid) -> usize {
    if grid.is_line() {
        grid.nx
    } else {
        grid.nx.min(grid.ny)
    }
}

/// `case` solved on the cells and window of `grid` for a coarser solve's purposes
/// (a scout's, a stalled solve's new start): its first converged solution, without
/// settled edges or dissipated power; `None` when it fails.
fn first_solution_on(
    case: &Case,
    grid: GridSpec,
    params: &SolverParams,
    kernels: &mut KernelCache,
) -> Option<Solution> {
    let mut coarse = case.clone();
    coarse.grid = grid;
    solve_on_windows(
        &coarse,
        params,
        kernels,
        &mut |_| ControlFlow::Continue(()),
        Settle::FirstSolution,
    )
    .ok()
}

/// Solves one assembled problem on its own window (no window adaptation), from the
/// pressure `warm` of another window if given: Polonsky–Keer CG when the problem is
/// symmetric, semi-smooth Newton otherwise.
pub fn solve_problem(
    problem: &mut ContactProblem,
    warm: Option<&(Grid, Vec<f64>)>,
    params: &SolverParams,
    observer: &mut dyn FnMut(Progress) -> ControlFlow<()>,
) -> Result<Solution> {
    let mut first = solve_unsettled(problem, warm, params, observer)?;
    if first.method == Method::SemismoothNewton {
        first.report = settle_edges(problem, &mut first.pressure, first.report, params, observer)?;
    }
    finish(
        problem,
        first.pressure,
        first.method,
        first.report,
        params.tolerance,
        Dissipation::Computed,
    )
}

/// A converged pressure before [`finish`], with how it was found.
struct Converged {
    pressure: Vec<f64>,
    method: Method,
    report: SolveReport,
}

/// [`solve_problem`] up to its first converged pressure, the contacts' edges where
/// the warm start (or the cells' faces) put them.
fn solve_unsettled(
    problem: &mut ContactProblem,
    warm: Option<&(Grid, Vec<f64>)>,
    params: &SolverParams,
    observer: &mut dyn FnMut(Progress) -> ControlFlow<()>,
) -> Result<Converged> {
    let grid = problem.grid;
    let mut p = match warm {
        Some((old, old_p)) => window::interpolate(old, old_p, &grid, params.parallelism),
        None => Vec::new(),
    };
    let cold = p.iter().all(|&v| v <= 0.0);
    let symmetric = problem.winkler_compliance();
    let chosen = match (params.method, symmetric) {
        (Some(Method::SemismoothNewton), _) => None,
        (Some(Method::PolonskyKeer), None) => {
            return Err(Error::invalid(
                "solver.method",
                "polonsky_keer",
                "semi-smooth Newton for a creeping or nonlinear layer (conjugate \
                 gradients need a symmetric problem)",
            ))
        }
        (_, symmetric) => symmetric,
    };
    let (method, report) = match chosen {
        Some(winkler) => {
            if cold {
                p = window::hertz_like_guess(&grid, &problem.shape, &problem.estimate);
            }
            match polonsky_keer::polonsky_keer(problem, winkler, &mut p, params, observer) {
                Ok(r) => (Method::PolonskyKeer, r),
                // Conjugate gradients carry no preconditioner: on a kernel whose
                // spectrum spans many decades (a thin coating a thousand times
                // stiffer than its substrate) they crawl or stall. Unless asked for
                // by name, semi-smooth Newton (GMRES preconditioned by the inverse
                // surface operator) takes over from their last iterate.
                Err(Error::NoConvergence { iterations, .. }) if params.method.is_none() => {
                    let mut r = newton::semismooth_newton(problem, &mut p, params, observer)?;
                    r.iterations += iterations;
                    (Method::SemismoothNewton, r)
                }
                Err(e) => return Err(e),
            }
        }
        None => {
            if cold {
                let creeps = problem
                    .estimate
                    .layer
                    .is_some_and(|l| l.relaxation_time.is_finite());
                let row_response = match &problem.layer {
                    Some(layer) if !creeps && grid.nx > 1 => {
                        // A unit pressure on the middle of the first row.
                        let n = grid.len();
                        let cell = grid.nx / 2;
                        let (mut unit, mut out) = (vec![0.0; n], vec![0.0; n]);
                        unit[cell] = 1.0;
                        layer.linearise(&vec![0.0; n]).apply(&unit, &mut out);
                        Some((out[cell], out[cell - 1]))
                    }
                    _ => None,
                };
                p = window::rigid_base_guess(
                    &grid,
                    &problem.shape,
                    &problem.estimate,
                    problem.load,
                    row_response,
                    params.parallelism,
                );
            }
            // A warm start begins from the warm pressure's edges (with the approach
            // that closes its mean gap); should that solve fail, from the same
            // pressure with the edges on the cells' faces.
            let mut fallback = None;
            if !cold && problem.layer.as_ref().is_some_and(|l| l.places_edges()) {
                let mut gap = gap_at(problem, &p, 0.0);
                let (sum, count) = p
                    .iter()
                    .zip(&gap)
                    .filter(|(&v, _)| v > 0.0)
                    .fold((0.0, 0.0), |(s, c), (_, g)| (s + g, c + 1.0));
                let approach = sum / f64::max(count, 1.0);
                gap.iter_mut().for_each(|g| *g -= approach);
                let placed = problem.layer.as_ref().and_then(|l| l.relocated(&p, &gap));
                if let Some(layer) = placed {
                    let faces = problem.layer.replace(layer);
                    fallback = faces.map(|faces| (faces, p.clone()));
                }
            }
            // A bare body that stalls is tried once more from the same start with a
            // softer contact-set rule (newton::SOFTER_ACTIVE_SET says when it helps).
            let start = problem.layer.is_none().then(|| p.clone());
            let r = match newton::semismooth_newton(problem, &mut p, params, observer) {
                Ok(r) => r,
                Err(Error::Interrupted) => return Err(Error::Interrupted),
                Err(e) => match (fallback, start) {
                    (Some((faces, warm)), _) => {
                        problem.layer = Some(faces);
                        p = warm;
                        newton::semismooth_newton(problem, &mut p, params, observer)?
                    }
                    (None, Some(start)) => {
                        let Error::NoConvergence { iterations, .. } = e else {
                            return Err(e);
                        };
                        p = start;
                        let softer = newton::SOFTER_ACTIVE_SET;
                        match newton::semismooth_newton_scaled(
                            problem, &mut p, params, observer, softer,
                        ) {
                            Ok(mut again) => {
                                again.iterations += iterations;
                                again
                            }
                            Err(Error::Interrupted) => return Err(Error::Interrupted),
                            // The first attempt's failure, whose history is the
                            // one the default rule produced.
                            Err(_) => return Err(e),
                        }
                    }
                    (None, None) => return Err(e),
                },
            };
            (Method::SemismoothNewton, r)
        }
    };
    Ok(Converged {
        pressure: p,
        method,
        report,
    })
}

/// Solves `problem` again, from its converged pressure `p` and report `r`, with the
/// contacts' leading edges located inside their cells from the last solution, until
/// they stay put (a layer whose response depends on where each edge falls inside its
/// cell; others return at once). Returns the report of the last solve, its counts
/// summed with the earlier ones.
fn settle_edges(
    problem: &mut ContactProblem,
    p: &mut [f64],
    mut r: SolveReport,
    params: &SolverParams,
    observer: &mut dyn FnMut(Progress) -> ControlFlow<()>,
) -> Result<SolveReport> {
    for _ in 0..MAX_RELOCATIONS {
        let gap = gap_at(problem, p, r.approach);
        let moved = problem.layer.as_ref().and_then(|l| l.relocated(p, &gap));
        let Some(layer) = moved else { break };
        let placed = problem.layer.replace(layer);
        let before = p.to_vec();
        // Its iterations continue the count the summary reports.
        let counted = |offset: usize| {
            move |progress: Progress| match progress {
                Progress::Iteration {
                    iteration,
                    residual,
                } => Progress::Iteration {
                    iteration: iteration + offset,
                    residual,
                },
                other => other,
            }
        };
        let offset = r.iterations;
        let relabel = counted(offset);
        let first = newton::semismooth_newton(problem, p, params, &mut |progress| {
            observer(relabel(progress))
        });
        // A relocated solve that stalls is tried once more from the same
        // start with the softer contact-set rule: the first relocation starts
        // from the faces' solution, whose leading edges ring in slow
        // sliding, and a sigmoid layer at V' = 1e-4 (paper Fig. 8, p0' =
        // 0.0025) stalled there near a residual of 2e-5 and kept the ringing
        // solution (energy balance 3 %); the retry converges.
        let again = match first {
            Err(Error::NoConvergence { iterations, .. }) => {
                p.copy_from_slice(&before);
                let relabel = counted(offset + iterations);
                newton::semismooth_newton_scaled(
                    problem,
                    p,
                    params,
                    &mut |progress| observer(relabel(progress)),
                    newton::SOFTER_ACTIVE_SET,
                )
                .map(|mut again| {
                    again.iterations += iterations;
                    again
                })
            }
            other => other,
        };
        let again = match again {
            Ok(again) => again,
            Err(Error::Interrupted) => return Err(Error::Interrupted),
            Err(_) => {
                // The last converged solution stands, with its edges.
                problem.layer = placed;
                p.copy_from_slice(&before);
                break;
            }
        };
        r.history.extend(again.history);
        r = SolveReport {
            iterations: r.iterations + again.iterations,
            linear_iterations: r.linear_iterations + again.linear_iterations,
            history: r.history,
            ..again
        };
    }
    Ok(r)
}

/// Most solves again with the contacts' leading edges located inside their cells
/// ([`crate::layer::LayerResponse::relocated`]; two or three suffice: an edge moves
/// with the approach, which hardly depends on it).
pub const MAX_RELOCATIONS: usize = 12;

/// The gap `w_body + w_layer + f - D` at the pressure `p` and approach `approach`.
fn gap_at(problem: &mut ContactProblem, p: &[f64], approach: f64) -> Vec<f64> {
    let n = p.len();
    let mut gap = vec![0.0; n];
    let layer = problem.layer.as_deref().unwrap_or(&NoLayer);
    OnCellMeans::new(problem.influence.as_mut(), layer.contact_edges())
        .apply_unchecked(p, &mut gap);
    let mut wl = vec![0.0; n];
    layer.displacement(p, &mut wl);
    gap.iter_mut().zip(&wl).for_each(|(g, w)| *g += w);
    gap.iter_mut()
        .zip(&problem.shape)
        .for_each(|(g, f)| *g += f - approach);
    gap
}

/// The slider's own height, and the body's displacement `wb` (from the solvers'
/// kernel) with the lag `c` of a viscoelastic body's creep shorter than a cell
/// given back (`ContactProblem::creep_shift`: the solvers read the slider at `f - c
/// f'`): the displacement gains `c` times its slope along x, which on the contact
/// is the slider's, `-f'` (so the gap there stays the solver's), and elsewhere its
/// central difference (one-sided at the window's ends).
fn give_back_lag(problem: &ContactProblem, p: &[f64], wb: &mut [f64]) -> Vec<f64> {
    let c = problem.creep_shift;
    let mut shape = problem.shape.clone();
    if c == 0.0 {
        return shape;
    }
    let (nx, h) = (problem.grid.nx, problem.grid.cell);
    shape
        .iter_mut()
        .zip(&problem.slope)
        .for_each(|(f, d)| *f += c * d);
    for (j, row) in wb.chunks_exact_mut(nx).enumerate() {
        let solvers = row.to_vec();
        for (i, w) in row.iter_mut().enumerate() {
            let k = j * nx + i;
            let slope = if p[k] > 0.0 {
                -problem.slope[k]
            } else if nx == 1 {
                0.0
            } else if i == 0 {
                (solvers[1] - solvers[0]) / h
            } else if i == nx - 1 {
                (solvers[i] - solvers[i - 1]) / h
            } else {
                (solvers[i + 1] - solvers[i - 1]) / (2.0 * h)
            };
            *w += c * slope;
        }
    }
    shape
}

/// Whether [`finish`] computes the power dissipated in the layer and the body (the
/// summary's energy-balance friction), or leaves it zero: a scout's solution, used
/// only to place a window and start its solve, skips it. The body's estimate
/// (`body::hysteresis`) costs about 0.04 s even on small grids, a fixed cost per
/// solve that the scouts of a creeping body paid at every level.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Dissipation {
    Computed,
    Skipped,
}

/// Clips round-off negatives, restores the load exactly and computes every field.
fn finish(
    problem: &mut ContactProblem,
    mut p: Vec<f64>,
    method: Method,
    report: SolveReport,
    tolerance: f64,
    dissipation: Dissipation,
) -> Result<Solution> {
    let grid = problem.grid;
    let n = grid.len();
    let load = problem.load;
    p.iter_mut().for_each(|v| *v = v.max(0.0));
    let entries: Vec<ContactEdge> = problem
        .layer
        .as_ref()
        .map_or(Vec::new(), |l| l.contact_edges().to_vec());
    let sum: f64 = if entries.is_empty() {
        p.iter().sum()
    } else {
        let w = load_weights(&entries, n);
        p.iter().zip(&w).map(|(p, w)| p * w).sum()
    };
    let scale = load / (sum * grid.cell_measure());
    p.iter_mut().for_each(|v| *v *= scale);
    let mut wb = vec![0.0; n];
    OnCellMeans::new(problem.influence.as_mut(), &entries).apply_unchecked(&p, &mut wb);
    let computed = dissipation == Dissipation::Computed;
    let (wl, compliance, layer_dissipated_force) = match &problem.layer {
        Some(l) => {
            let mut wl = vec![0.0; n];
            l.displacement(&p, &mut wl);
            let force = if computed {
                l.dissipated_force(&p)
            } else {
                0.0
            };
            (Some(wl), Some(l.compliance(&p)), force)
        }
        None => (None, None, 0.0),
    };
    // The body carries each cell's mean pressure; its edges fall like a square
    // root where the slider presses it directly.
    let edges = if problem.layer.is_none() {
        EdgeProfile::SquareRoot
    } else {
        EdgeProfile::Bilinear
    };
    let body_dissipated_force = if !computed {
        0.0
    } else if entries.is_empty() {
        problem
            .body
            .model()
            .dissipated_force(&grid, &p, problem.velocity, edges)?
    } else {
        let mut mean = vec![0.0; n];
        crate::layer::cell_mean_pressure(&entries, &p, &mut mean);
        problem
            .body
            .model()
            .dissipated_force(&grid, &mean, problem.velocity, edges)?
    };
    let dissipated_force = layer_dissipated_force + body_dissipated_force;
    let shape = give_back_lag(problem, &p, &mut wb);
    let gap: Vec<f64> = (0..n)
        .map(|k| wb[k] + wl.as_ref().map_or(0.0, |w| w[k]) + shape[k] - report.approach)
        .collect();
    // A line contact's kernel was lowered by a constant (its datum): the body's
    // displacement and the approach at the case's datum are higher by it times the
    // sum of the cells' (mean) pressures, load / h; the gap does not change.
    let lift = if problem.datum_shift == 0.0 {
        0.0
    } else {
        problem.datum_shift * load / grid.cell_measure()
    };
    wb.iter_mut().for_each(|w| *w += lift);
    let approach = report.approach + lift;
    if !p.iter().chain(&gap).all(|v| v.is_finite()) {
        return Err(Error::OutOfRange {
            why: OVERFLOW.into(),
        });
    }
    let solution = Solution {
        grid,
        body: problem.body.clone(),
        pressure: p,
        contact_edges: entries,
        body_displacement: wb,
        layer_displacement: wl,
        compliance,
        gap,
        shape,
        shape_slope: problem.slope.clone(),
        dissipated_force,
        approach,
        normal_load: load,
        info: SolveInfo {
            method,
            iterations: report.iterations,
            linear_iterations: report.linear_iterations,
            operator_products: problem.influence.products(),
            residual: report.residual,
            tolerance,
            windows: 1,
            history: report.history,
        },
    };
    if !solution.summary().is_finite() {
        return Err(Error::OutOfRange {
            why: "the pressure is finite but the friction sum or the moment overflows: \
                  check slider.radius against the contact's size"
                .into(),
        });
    }
    Ok(solution)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn monitor_after(
        residuals: &[f64],
        observer: &mut dyn FnMut(Progress) -> ControlFlow<()>,
    ) -> bool {
        let params = SolverParams::default();
        let mut m = Monitor::new(&params, 50, observer);
        for (k, &r) in residuals.iter().enumerate() {
            m.converged(k + 1, r);
        }
        m.stagnated()
    }

    #[test]
    fn a_creeping_residual_is_stagnation_and_a_falling_one_is_not() {
        let mut seen = 0;
        // -0.1% per iteration (a runaway Newton solve once seen): stagnated.
        let creeping: Vec<f64> = (0..60).map(|k| 0.4 * 0.999f64.powi(k)).collect();
        assert!(monitor_after(&creeping, &mut |_| {
            seen += 1;
            ControlFlow::Continue(())
        }));
        assert_eq!(seen, 60, "every iteration is reported");
        // Slow but steady CG-like progress (a factor 10 per 60 iterations) is not.
        let slow: Vec<f64> = (0..200).map(|k| 10f64.powf(-k as f64 / 60.0)).collect();
        assert!(!monitor_after(&slow, &mut |_| ControlFlow::Continue(())));
        // Too few iterations to judge.
        assert!(!monitor_after(&creeping[..40], &mut |_| {
            ControlFlow::Continue(())
        }));
        // An oscillating residual that keeps a best value is stagnation.
        let oscillating: Vec<f64> = (0..80).map(|k| 1e-3 * (1.0 + (k % 2) as f64)).collect();
        assert!(monitor_after(&oscillating, &mut |_| ControlFlow::Continue(
            ()
        )));
    }

    #[test]
    fn an_observer_that_breaks_interrupts_the_solve() {
        let case = crate::test_cases::parse(crate::test_cases::HERTZ);
        let mut iterations = 0;
        let result = solve_observed(&case, &SolverParams::default(), &mut |p| match p {
            Progress::Iteration { .. } => {
                iterations += 1;
                if iterations == 2 {
                    ControlFlow::Break(())
                } else {
                    ControlFlow::Continue(())
                }
            }
            Progress::Window { .. } => ControlFlow::Continue(()),
        });
        assert!(matches!(result, Err(Error::Interrupted)), "{result:?}");
        assert_eq!(iterations, 2, "the solve stops at the first break");
        let mut windows = 0;
        let result = solve_observed(&case, &SolverParams::default(), &mut |_| {
            windows += 1;
            ControlFlow::Break(())
        });
        assert!(matches!(result, Err(Error::Interrupted)));
        assert_eq!(windows, 1);
    }

    /// Solves `case` with the default parameters, and the iteration numbers its
    /// progress events gave in the last window.
    fn solve_numbering_iterations(case: &crate::Case) -> (Solution, Vec<usize>) {
        let mut numbers = Vec::new();
        let s = solve_observed(case, &SolverParams::default(), &mut |p| {
            match p {
                Progress::Window { .. } => numbers.clear(),
                Progress::Iteration { iteration, .. } => numbers.push(iteration),
            }
            ControlFlow::Continue(())
        })
        .unwrap();
        (s, numbers)
    }

    #[test]
    fn iterations_count_on_through_the_solves_with_located_edges() {
        // The paper's Maxwell layer places its contacts' edges and solves again:
        // the progress events number the iterations of the last window as its
        // summary counts them, one after another.
        let case = crate::test_cases::parse(crate::test_cases::MAXWELL_LAYER);
        let (s, numbers) = solve_numbering_iterations(&case);
        assert!(!s.contact_edges.is_empty(), "no edges were located");
        assert_eq!(numbers, (1..=s.info.iterations).collect::<Vec<_>>());
    }

    #[test]
    fn a_stalled_relocated_solve_is_tried_again_with_the_softer_rule() {
        // Paper Fig. 8's sigmoid layer (p0' = 0.0025) at V' = 1e-4 on 128^2: the
        // first relocated solve starts from the faces' solution, whose leading
        // edges ring, and stalls near a residual of 2e-5; alone, it left that
        // solution standing (no edges, the dissipated power 3.3 % above the
        // friction, the peak 1.8 times the located one). The softer retry converges
        // with the edges located; the progress events still count on.
        let text = "[slider]\nshape = \"sphere\"\nradius = 1.0\n\
                    [substrate]\nyoung = 1.0\npoisson = 0.3\n\
                    [layer]\ncompliance = 0.02\nrelaxation_time = 1.0\n\
                    law = \"sigmoid\"\ndelta = 0.5\np0 = 0.0025\n\
                    [loading]\nnormal_load = 25e-6\nvelocity = 1e-4\n\
                    [grid]\ncells = [128, 128]\n";
        let case = crate::test_cases::parse(text);
        let (s, numbers) = solve_numbering_iterations(&case);
        assert!(!s.contact_edges.is_empty(), "no edges were located");
        let m = s.summary();
        let balance = m.dissipation_friction_coefficient / m.friction_coefficient - 1.0;
        assert!(balance.abs() < 1e-3, "energy balance {balance:e}");
        assert_eq!(numbers, (1..=s.info.iterations).collect::<Vec<_>>());
    }
}
