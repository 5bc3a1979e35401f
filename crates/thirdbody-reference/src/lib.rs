//! The paper's own method, kept as a test oracle and a benchmark baseline (a crate
//! of its own, used by the tests and the scaling example of `thirdbody`): the dense system (6) — influence matrix
//! `A = A^(1) + A^(3)` (eq. 7), the body's part assembled entry by entry from the
//! body's kernel formula ([`thirdbody::body::BodyModel`]; eq. 9 or 10) and the layer's
//! part column by column from the layer's Jacobian (any rheology; for the paper's
//! layer eq. 8 read with the loaded cell's compliance), plus the approach column and
//! the load row — solved by dense LU inside an active-set loop: cells with negative
//! pressure leave the contact, cells where the surfaces overlap join it, until the
//! set no longer changes. Nonlinear compliance laws are handled by Newton iterations
//! on the dense system at each fixed set. O(n^3): for small grids only.
//!
//! It shares with the production solver the assembled problem (the kernel formula,
//! the slider's sampling and the layer's response, each tested on its own against
//! closed forms and explicit sums); the operator application (direct sums instead
//! of DC-FFT), the linear solver (LU instead of GMRES/CG), the contact-set rule and
//! the treatment of the layer (a dense Jacobian instead of row sweeps and a
//! triangular preconditioner) are its own. The module also holds the direct
//! summation the DC-FFT is tested against ([`direct_convolution`]), and FFT plans
//! for the tests' own transforms ([`fft`]).

pub mod fft;

use nalgebra::{DMatrix, DVector};

use thirdbody::case::Case;
use thirdbody::convolution::Parallelism;
use thirdbody::error::{Error, Result};
use thirdbody::grid::Grid;
use thirdbody::layer::{load_weights, LayerResponse};
use thirdbody::problem::ContactProblem;
use thirdbody::solution::{Method, Solution, SolveInfo};
use thirdbody::KernelCache;

/// Largest grid the dense reference accepts (cells).
pub const MAX_REFERENCE_CELLS: usize = 80 * 80;

/// `out = K (*) field` by direct O(n^2) summation over the `nx x ny` cells, `K` given
/// at every cell offset `(di, dj)`: the obviously correct convolution the DC-FFT
/// ([`thirdbody::convolution`]) is tested against. A `field` or `out` of another length
/// than `nx * ny` is an [`Error::InvalidValue`] naming it.
pub fn direct_convolution(
    nx: usize,
    ny: usize,
    kernel: impl Fn(i64, i64) -> f64,
    field: &[f64],
    out: &mut [f64],
) -> Result<()> {
    direct_convolution_rows(nx, ny, kernel, field, 0..ny, out)
}

/// [`direct_convolution`] on the output rows `rows` only (the others of `out` are
/// left as they are): for grids whose full direct sum would take too long.
pub fn direct_convolution_rows(
    nx: usize,
    ny: usize,
    kernel: impl Fn(i64, i64) -> f64,
    field: &[f64],
    rows: impl IntoIterator<Item = usize>,
    out: &mut [f64],
) -> Result<()> {
    for (name, len) in [("field", field.len()), ("out", out.len())] {
        if len != nx * ny {
            return Err(Error::invalid(
                name,
                format!("{len} values"),
                &format!("{} values, one per cell of {nx} x {ny}", nx * ny),
            ));
        }
    }
    let rows: Vec<usize> = rows.into_iter().collect();
    if let Some(&j) = rows.iter().find(|&&j| j >= ny) {
        return Err(Error::invalid("rows", j, &format!("rows below {ny}")));
    }
    for j in rows {
        for i in 0..nx {
            let mut s = 0.0;
            for l in 0..ny {
                for k in 0..nx {
                    s += kernel(i as i64 - k as i64, j as i64 - l as i64) * field[l * nx + k];
                }
            }
            out[j * nx + i] = s;
        }
    }
    Ok(())
}

/// Solves `case` on the fixed window `grid` with the dense method.
pub fn solve_dense(case: &Case, grid: &Grid, tolerance: f64) -> Result<Solution> {
    case.validate()?;
    let n = grid.len();
    if n > MAX_REFERENCE_CELLS {
        return Err(Error::invalid(
            "grid.cells",
            format!("{} x {}", grid.nx(), grid.ny()),
            "at most 80 x 80 cells for the dense reference solver",
        ));
    }
    let problem = case.assemble(
        grid,
        &mut KernelCache::with_capacity(0),
        Parallelism::Sequential,
    )?;
    solve_dense_problem(&problem, tolerance)
}

/// Solves an assembled problem on its window with the dense method.
pub fn solve_dense_problem(problem: &ContactProblem, tolerance: f64) -> Result<Solution> {
    let mut relocated: Option<Box<dyn LayerResponse>> = None;
    let mut solves = 0;
    loop {
        let response = relocated.as_deref().or(problem.layer());
        let solution = solve_dense_with(problem, response, tolerance)?;
        solves += 1;
        let moved = response.and_then(|l| l.relocated(&solution.pressure, &solution.gap));
        match moved {
            Some(l) if solves <= thirdbody::contact::MAX_RELOCATIONS => relocated = Some(l),
            _ => return Ok(solution),
        }
    }
}

/// [`solve_dense_problem`] with the layer's response `response`.
fn solve_dense_with(
    problem: &ContactProblem,
    response: Option<&dyn LayerResponse>,
    tolerance: f64,
) -> Result<Solution> {
    let grid = problem.grid();
    let n = grid.len();
    let (nx, ny) = (grid.nx(), grid.ny());
    let kernel = problem.body().model().surface_kernel(
        grid.cell(),
        nx,
        ny,
        problem.velocity(),
        problem.body_lag(),
    )?;
    let influence = DMatrix::<f64>::from_fn(n, n, |a, b| {
        let di = (a % nx) as i64 - (b % nx) as i64;
        let dj = (a / nx) as i64 - (b / nx) as i64;
        kernel.at(di, dj)
    });
    // The body carries each cell's mean pressure: K W, column j being
    // `K_j W_jj + sum over edges k with neighbour j of K_k b_k`.
    let entries = response.map_or(Vec::new(), |l| l.contact_edges().to_vec());
    let mut body = influence.clone();
    for e in &entries {
        let (a, b) = e.mean_weights();
        for r in 0..n {
            body[(r, e.cell)] += (a - 1.0) * influence[(r, e.cell)];
            if let Some(d) = e.neighbour {
                body[(r, d)] += b * influence[(r, e.cell)];
            }
        }
    }
    let weights = load_weights(&entries, n);
    let f = problem.shape().to_vec();
    let slope = problem.slope().to_vec();
    let layer = response.map(|response| DenseLayer { response });
    let load = problem.load();
    let area = grid.cell_measure();

    // Start: every cell where the undeformed slider is below the mean height.
    let fmean = f.iter().sum::<f64>() / n as f64;
    let mut active: Vec<bool> = f.iter().map(|&v| v <= fmean).collect();
    let mut p = vec![0.0; n];
    let mut approach = 0.0;
    let mut history = Vec::new();
    for iteration in 1..=200 {
        newton_on_set(
            &body,
            layer.as_ref(),
            &f,
            load,
            area,
            &weights,
            &active,
            &mut p,
            &mut approach,
            tolerance,
        )?;
        let gap = gap_of(&body, layer.as_ref(), &f, &p, approach);
        // Leave: negative pressure; join: overlap.
        let mut changed = false;
        let scale = gap
            .iter()
            .fold(0.0f64, |m, v| m.max(v.abs()))
            .max(f64::MIN_POSITIVE);
        for k in 0..n {
            if active[k] && p[k] < 0.0 {
                active[k] = false;
                p[k] = 0.0;
                changed = true;
            } else if !active[k] && gap[k] < -tolerance * scale {
                active[k] = true;
                changed = true;
            }
        }
        let worst_overlap = gap
            .iter()
            .zip(&active)
            .filter(|(_, &a)| !a)
            .fold(0.0f64, |m, (g, _)| m.max(-g));
        history.push(worst_overlap / scale);
        if !changed {
            let wb = apply_dense(&body, &p);
            let wl = layer.as_ref().map(|l| l.displacement(&p));
            let compliance = layer.as_ref().map(|l| l.response.compliance(&p));
            let dissipated_force = layer
                .as_ref()
                .map_or(0.0, |l| l.response.dissipated_force(&p));
            return Ok(Solution {
                grid: *grid,
                body: problem.body().clone(),
                pressure: p,
                contact_edges: entries,
                body_displacement: wb,
                layer_displacement: wl,
                compliance,
                gap,
                shape: f,
                shape_slope: slope,
                dissipated_force,
                approach,
                normal_load: load,
                info: SolveInfo {
                    method: Method::DenseReference,
                    iterations: iteration,
                    linear_iterations: 0,
                    operator_products: 0,
                    residual: history.last().copied().unwrap_or(0.0),
                    tolerance,
                    windows: 1,
                    history,
                },
            });
        }
    }
    Err(Error::NoConvergence {
        iterations: 200,
        residual: history.last().copied().unwrap_or(f64::INFINITY),
        tolerance,
        history,
        hint: "the dense reference's active set did not settle".into(),
    })
}

/// The layer's part of the dense system: its displacement, and its Jacobian
/// assembled column by column.
struct DenseLayer<'a> {
    response: &'a dyn LayerResponse,
}

impl DenseLayer<'_> {
    /// `w3` of every cell.
    fn displacement(&self, p: &[f64]) -> Vec<f64> {
        let mut w = vec![0.0; p.len()];
        self.response.displacement(p, &mut w);
        w
    }

    /// `d w3_i / d p_j` for `i, j` in `idx`, as a dense `m x m` block.
    fn jacobian(&self, p: &[f64], idx: &[usize]) -> DMatrix<f64> {
        let lin = self.response.linearise(p);
        let n = p.len();
        let (mut unit, mut column) = (vec![0.0; n], vec![0.0; n]);
        let mut jac = DMatrix::<f64>::zeros(idx.len(), idx.len());
        for (c, &j) in idx.iter().enumerate() {
            unit[j] = 1.0;
            lin.apply(&unit, &mut column);
            unit[j] = 0.0;
            for (r, &i) in idx.iter().enumerate() {
                jac[(r, c)] = column[i];
            }
        }
        jac
    }
}

fn apply_dense(a: &DMatrix<f64>, p: &[f64]) -> Vec<f64> {
    (0..a.nrows())
        .map(|i| (0..a.ncols()).map(|j| a[(i, j)] * p[j]).sum())
        .collect()
}

fn gap_of(
    body: &DMatrix<f64>,
    layer: Option<&DenseLayer>,
    f: &[f64],
    p: &[f64],
    d: f64,
) -> Vec<f64> {
    let wb = apply_dense(body, p);
    let wl = layer.map(|l| l.displacement(p));
    (0..f.len())
        .map(|k| wb[k] + wl.as_ref().map_or(0.0, |w| w[k]) + f[k] - d)
        .collect()
}

/// Newton on `gap_A(p_A, D) = 0`, `sum(p_A) h^2 = Q` with `p = 0` off the set.
#[allow(clippy::too_many_arguments)]
fn newton_on_set(
    body: &DMatrix<f64>,
    layer: Option<&DenseLayer>,
    f: &[f64],
    load: f64,
    area: f64,
    weights: &[f64],
    active: &[bool],
    p: &mut [f64],
    approach: &mut f64,
    tolerance: f64,
) -> Result<()> {
    let idx: Vec<usize> = (0..f.len()).filter(|&k| active[k]).collect();
    let m = idx.len();
    for k in 0..f.len() {
        if !active[k] {
            p[k] = 0.0;
        }
    }
    let mut previous = f64::INFINITY;
    for step in 0..100 {
        let gap = gap_of(body, layer, f, p, *approach);
        let load_error = p.iter().zip(weights).map(|(p, w)| p * w).sum::<f64>() * area - load;
        let scale = f
            .iter()
            .fold(0.0f64, |a, v| a.max(v.abs()))
            .max(approach.abs());
        let worst = idx.iter().fold(0.0f64, |a, &k| a.max(gap[k].abs())) / scale;
        // Newton has converged when it no longer reduces the gap (round-off level),
        // provided that level is small.
        let settled = worst <= 1e-3 * tolerance || worst >= 0.5 * previous;
        if step > 0 && settled && worst <= 1e-9 && load_error.abs() <= 1e-12 * load {
            return Ok(());
        }
        // A set whose solution has a negative pressure is left by the caller
        // anyway; the layer's law is not smooth below zero pressure (its slope is
        // cut there), where Newton can cycle without converging: hand the set back
        // once the iterate settles on a negative pressure.
        if step >= 20 && idx.iter().any(|&k| p[k] < 0.0) {
            return Ok(());
        }
        previous = worst;
        let layer_jac = layer.map(|l| l.jacobian(p, &idx));
        let jac = DMatrix::<f64>::from_fn(m + 1, m + 1, |r, c| match (r < m, c < m) {
            (true, true) => body[(idx[r], idx[c])] + layer_jac.as_ref().map_or(0.0, |j| j[(r, c)]),
            (true, false) => -1.0,
            (false, true) => area * weights[idx[c]],
            (false, false) => 0.0,
        });
        let rhs =
            DVector::<f64>::from_fn(m + 1, |r, _| if r < m { -gap[idx[r]] } else { -load_error });
        // A singular Jacobian (no solution) ends the iteration like a non-finite step.
        let Some(delta) = jac.lu().solve(&rhs) else {
            break;
        };
        for (r, &k) in idx.iter().enumerate() {
            p[k] += delta[r];
        }
        *approach += delta[m];
        if !delta.iter().all(|v| v.is_finite()) {
            break;
        }
    }
    Err(Error::NoConvergence {
        iterations: 100,
        residual: previous,
        tolerance,
        history: Vec::new(),
        hint: "Newton on the dense reference system did not converge".into(),
    })
}
