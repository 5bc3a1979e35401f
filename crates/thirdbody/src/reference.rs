//! The paper's own method, kept as a test oracle and a benchmark baseline: the dense
//! system (6) — influence matrix `A = A^(1) + A^(3)` (eq. 7) assembled entry by entry
//! from the closed-form kernel (eq. 9) and the layer's row relation (eq. 8, read
//! with the loaded cell's compliance; design.md §1), plus the approach column and
//! the load row — solved by dense LU inside an active-set loop: cells with negative
//! pressure leave the contact, cells where the surfaces overlap join it, until the
//! set no longer changes. Nonlinear compliance laws are handled by Newton iterations
//! on the dense system at each fixed set. O(n^3): for small grids only.
//!
//! It shares with the production solver only the case, the kernel formula and the
//! compliance law; the operator application (direct sums instead of DC-FFT), the
//! linear solver (LU instead of GMRES/CG) and the contact-set rule are its own.

use faer::linalg::solvers::Solve;
use faer::{Col, Mat};

use crate::body::homogeneous::homogeneous_surface_kernel;
use crate::case::{Body, Case};
use crate::error::{Error, Result};
use crate::grid::Grid;
use crate::layer::Layer;
use crate::solution::{Method, Solution, SolveInfo};

/// Largest grid the dense reference accepts (cells).
pub const MAX_REFERENCE_CELLS: usize = 80 * 80;

/// Solves `case` on the fixed window `grid` with the dense method.
pub fn solve_dense(case: &Case, grid: &Grid, tolerance: f64) -> Result<Solution> {
    case.validate()?;
    let n = grid.len();
    if n > MAX_REFERENCE_CELLS {
        return Err(Error::invalid(
            "grid.cells",
            format!("{} x {}", grid.nx, grid.ny),
            "at most 80 x 80 cells for the dense reference solver",
        ));
    }
    let Body::Homogeneous(material) = case.body else {
        return Err(Error::invalid(
            "coating",
            "a coated body",
            "a homogeneous body for the dense reference solver",
        ));
    };
    let kernel = homogeneous_surface_kernel(material, grid.cell);
    let (nx, h) = (grid.nx, grid.cell);
    let body = Mat::<f64>::from_fn(n, n, |a, b| {
        let (ia, ja) = ((a % nx) as i64, (a / nx) as i64);
        let (ib, jb) = ((b % nx) as i64, (b / nx) as i64);
        kernel(ia - ib, ja - jb)
    });
    let mut f = vec![0.0; n];
    let mut slope = vec![0.0; n];
    case.slider.sample(grid, &mut f, &mut slope)?;
    let creep_per_cell =
        h / (case.velocity() * case.layer.as_ref().map_or(1.0, |l| l.relaxation_time));
    let layer = case.layer.as_ref().map(|l| DenseLayer {
        layer: l,
        nx,
        creep_per_cell: if creep_per_cell.is_finite() {
            creep_per_cell
        } else {
            0.0
        },
    });
    let load = case.loading.normal_load;
    let area = grid.cell_area();

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
            let compliance = layer
                .as_ref()
                .map(|l| p.iter().map(|&v| l.layer.law_at(v).compliance).collect());
            return Ok(Solution {
                grid: *grid,
                pressure: p,
                body_displacement: wb,
                layer_displacement: wl,
                compliance,
                gap,
                shape: f,
                shape_slope: slope,
                approach,
                normal_load: load,
                info: SolveInfo {
                    method: Method::DenseReference,
                    iterations: iteration,
                    linear_iterations: 0,
                    residual: history.last().copied().unwrap_or(0.0),
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

/// The layer's eq. 8 written out entry by entry (no sweeps).
struct DenseLayer<'a> {
    layer: &'a Layer,
    nx: usize,
    creep_per_cell: f64,
}

impl DenseLayer<'_> {
    /// `w3_i`: own instantaneous part plus creep from every cell upstream in the row.
    fn displacement(&self, p: &[f64]) -> Vec<f64> {
        let nx = self.nx;
        (0..p.len())
            .map(|i| {
                let row = i / nx;
                let mut creep = 0.5 * self.layer.creep(p[i]).0;
                for &pj in &p[i + 1..(row + 1) * nx] {
                    creep += self.layer.creep(pj).0;
                }
                self.layer.instantaneous(p[i]).0 + self.creep_per_cell * creep
            })
            .collect()
    }

    /// `d w3_i / d p_j`.
    fn derivative(&self, p: &[f64], i: usize, j: usize) -> f64 {
        if i / self.nx != j / self.nx || j < i {
            0.0
        } else if i == j {
            self.layer.instantaneous(p[i]).1 + 0.5 * self.creep_per_cell * self.layer.creep(p[i]).1
        } else {
            self.creep_per_cell * self.layer.creep(p[j]).1
        }
    }
}

fn apply_dense(a: &Mat<f64>, p: &[f64]) -> Vec<f64> {
    (0..a.nrows())
        .map(|i| (0..a.ncols()).map(|j| a[(i, j)] * p[j]).sum())
        .collect()
}

fn gap_of(body: &Mat<f64>, layer: Option<&DenseLayer>, f: &[f64], p: &[f64], d: f64) -> Vec<f64> {
    let wb = apply_dense(body, p);
    let wl = layer.map(|l| l.displacement(p));
    (0..f.len())
        .map(|k| wb[k] + wl.as_ref().map_or(0.0, |w| w[k]) + f[k] - d)
        .collect()
}

/// Newton on `gap_A(p_A, D) = 0`, `sum(p_A) h^2 = Q` with `p = 0` off the set.
#[allow(clippy::too_many_arguments)]
fn newton_on_set(
    body: &Mat<f64>,
    layer: Option<&DenseLayer>,
    f: &[f64],
    load: f64,
    area: f64,
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
        let load_error = p.iter().sum::<f64>() * area - load;
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
        previous = worst;
        let jac = Mat::<f64>::from_fn(m + 1, m + 1, |r, c| match (r < m, c < m) {
            (true, true) => {
                body[(idx[r], idx[c])] + layer.map_or(0.0, |l| l.derivative(p, idx[r], idx[c]))
            }
            (true, false) => -1.0,
            (false, true) => area,
            (false, false) => 0.0,
        });
        let rhs = Col::<f64>::from_fn(m + 1, |r| if r < m { -gap[idx[r]] } else { -load_error });
        let delta = jac.partial_piv_lu().solve(&rhs);
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
