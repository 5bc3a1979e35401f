//! Semi-smooth Newton (primal–dual active set; Hintermüller, Ito & Kunisch, SIAM J.
//! Optim. 13, 2002) for the layered contact, whose operator `K + J_layer` is not
//! symmetric because the layer's creep is causal along x (docs/architecture.md (numerics)). The
//! complementarity conditions `p >= 0, g >= 0, p g = 0` are written as
//! `min(p, c g) = 0` with `c` the inverse of a cell's own compliance; each Newton
//! step fixes the contact set `A = {p - c g > 0}`, sets `p = 0` off it and solves the
//! linearised `g = 0` on it together with the load equation (paper system 6, with D
//! as one more unknown) by GMRES. The preconditioner is the layer's row-wise
//! triangular Jacobian plus the body's self-coefficient on the diagonal, inverted by
//! forward substitution from the leading edge, with the load row eliminated through
//! its Schur complement. When the layer dominates the body (slow sliding, soft
//! layer) it is nearly exact and GMRES needs a handful of products per step. A bare
//! half-space (an elastic body on which Newton is forced, or a viscoelastic one in
//! steady sliding, whose kernel is not even in x) is preconditioned instead by the
//! inverse of its continuous surface operator, `|k| / (2 J(k_x))` by FFT, restricted
//! to the contact set (4 to 5 GMRES products per step where the diagonal alone
//! needed 30 to 40). On a bare body GMRES solves each step to 1e-4 of the residual
//! (1e-2 under a layer), restarting every 40 products, or every 120 once a step has
//! stagnated ([`LONG_RESTART`]), and a step is shortened until the merit falls, down to
//! 2^-20 (1/64 under a layer, taken even if the merit rises); three steps in a row
//! that cannot lower it stop the attempt. A bare body whose iteration stalls is
//! tried once more from the same start with a tenth of `c` ([`SOFTER_ACTIVE_SET`]):
//! a nearly glassy leading edge makes the cell's own compliance a poor scale for the
//! contact-set rule.

use std::ops::ControlFlow;

use rayon::prelude::*;

use super::{no_unique_solution, relative_complementarity_residual, Monitor, SolveReport};
use crate::contact::{Progress, SolverParams};
use crate::convolution::{ConvolutionPlan, Convolver, KernelSpectrum, Parallelism};
use crate::error::{Error, Result};
use crate::krylov::Gmres;
use crate::layer::{load_weights, LayerResponse, NoLayer};
use crate::operator::{InfluenceOperator, OnCellMeans, Unchecked};
use crate::passes::{Passes, CHUNK};
use crate::problem::ContactProblem;

/// Krylov subspace size before a restart.
const RESTART: usize = 40;
/// The same on a bare body once one of its steps has used
/// [`MAX_LINEAR_ITERATIONS`] without meeting its tolerance: restarted every 40
/// products, GMRES stagnates on the steps that cross a nearly glassy leading edge
/// (a Zener body at E_g/E_0 = 1e4, V tau / a0 = 1e-4, creeping over 109 cells of a
/// 256^2 grid: stuck in both attempts; with 120 it converges in 14 steps, 8 s). The
/// basis then holds 121 vectors of the contact cells
/// ([`crate::Case::estimated_solve_bytes`] counts them).
const LONG_RESTART: usize = 120;
/// Most GMRES products per Newton step.
const MAX_LINEAR_ITERATIONS: usize = 400;

/// Newton steps between checks for a folding row relation.
const FOLD_CHECK_EVERY: usize = 20;
/// Smallest damping factor of a Newton step under a layer: a step that shortens
/// no further is taken even if it raises the merit.
const MIN_STEP: f64 = 1.0 / 64.0;
/// Smallest damping factor of a Newton step on a bare body, `2^-20`: the step is
/// shortened until the merit falls. A glassy leading edge (a Zener body at E_g/E_0 =
/// 1e4, V tau / a0 = 1e-4, in a line contact on 256 to 4,096 cells) makes a step
/// whose contact set is off by one cell there swing the pressures by most of the
/// peak; taking 1/64 of it anyway raised the residual from 9e-6 to 3e-2, from where
/// the iteration never returned.
const BARE_BODY_MIN_STEP: f64 = 1.0 / 1_048_576.0;
/// The inexact Newton step's GMRES tolerance relative to the current residual under
/// a layer (whose triangular preconditioner leaves GMRES little to do).
const FORCING: f64 = 1e-2;
/// The same on a bare body. With 1e-2 the steps near a glassy leading edge were not
/// descent directions: a Zener body at E_g/E_0 = 1000, V tau / a0 = 1e-3 to 3e-3, on
/// 192^2 and 256^2 cells stalled near a residual of 0.08 in both attempts; with 1e-4
/// it converges in 12 to 17 steps, and Newton takes 2 to 7 times fewer steps on
/// the cases that converged before (the same friction to 8 digits). Measured
/// alternatives: 1e-3, or 1e-2 tightened to 1e-4 after the first step that does not
/// lower the merit, leave those cases to the second attempt (12 to 47 s instead of
/// 1 s); 1e-2 in line contacts (45 % faster on the Zener line bench) leaves 4 of 25
/// glassy line probes stalled short of the tolerance. It costs time on easy cases:
/// the Zener bench solves go from 175 to 194 ms (256^2) and from 46 to 67 ms (line).
const BARE_BODY_FORCING: f64 = 1e-4;
/// Consecutive steps of a bare body, each shortened to [`BARE_BODY_MIN_STEP`]
/// without lowering the merit, after which the iteration stops (and a first attempt
/// is retried with a softer contact-set rule): it is at a point its steps cannot
/// leave, and waiting for the stagnation test cost 50 steps of 400 GMRES products
/// each (30 s on 192^2, E_g/E_0 = 1000, V tau / a0 = 3e-4).
const STUCK_STEPS: usize = 3;
/// A solve whose residual stops falling after it has been at or below this is
/// returned at its best iterate (the solution's `residual` then exceeds the
/// tolerance, and the report warns). Where the discrete problem has no closer
/// solution, Newton cycles between contact sets that differ at an edge cell: a Zener
/// body at E_g/E_0 = 1000 whose leading edge is glassy over a length far below a
/// cell, warm-started at a residual of 5e-8, cycled near 7e-5 (a line contact on
/// 4,096 cells; since the viscoelastic kernel's leading-edge damping and the bare
/// body's deeper backtracking it converges, and no case we know of still stalls).
pub const STALLED_BUT_SOLVED: f64 = 1e-6;

/// An approximate inverse of a bare half-space's contact operator: the inverse of
/// its continuous surface operator, `|k| / (2 J(k_x))` in Fourier space
/// ([`crate::body::BodyModel::surface_compliance`]), applied to a field on the
/// window's cells taken as periodic. Restricted to the contact set it preconditions
/// the Newton step's `K_AA`: it inverts the short waves, which set the operator's
/// condition number, exactly up to the cells' discreteness.
struct SurfaceInverse {
    convolver: Convolver,
    spectrum: KernelSpectrum,
}

impl SurfaceInverse {
    /// The inverse for `problem`'s body on its grid, if it has no layer and its
    /// surface operator has the half-space form.
    fn of(problem: &ContactProblem, parallelism: Parallelism) -> Option<Self> {
        if problem.layer.is_some() {
            return None;
        }
        let model = problem.body.model();
        let (h, velocity) = (problem.grid.cell, problem.velocity);
        model.surface_compliance(0.0, velocity)?;
        let (nx, ny) = (problem.grid.nx, problem.grid.ny);
        // No padding: the inverse operator's kernel decays as 1 / r^3, so the
        // periodic images of a window away hardly matter (measured: the 2n padding
        // saves one product in 22 and costs four times as much per product).
        let period = |n: usize| n.next_multiple_of(2);
        let plan = ConvolutionPlan::padded(nx, ny, [period(nx), period(ny)], parallelism);
        let [px, py] = plan.padding();
        // The mean (zero wavenumber) is given the factor of a wave twice the period
        // long (it hardly matters: the load row fixes the mean).
        let floor = std::f64::consts::PI / px.max(py) as f64;
        let spectrum = plan.symbol_spectrum(|xi_x, xi_y| {
            let k = xi_x.hypot(xi_y).max(floor);
            let compliance = model
                .surface_compliance(xi_x / h, velocity)
                .expect("checked above");
            k / (2.0 * h * compliance)
        });
        Some(SurfaceInverse {
            convolver: plan.convolver(),
            spectrum,
        })
    }

    /// `out = M^-1 r` for an `r` that is zero off the contact set; the caller reads
    /// `out` on the contact set only.
    fn apply(&mut self, r: &[f64], out: &mut [f64]) {
        self.convolver.convolve(&self.spectrum, r, out);
    }
}

/// Computes the body and layer displacements and the gap at `(p, D)`; returns the
/// merit `sum min(p, c g)^2`.
#[allow(clippy::too_many_arguments)]
fn evaluate(
    passes: &Passes,
    op: &mut dyn InfluenceOperator,
    layer: &dyn LayerResponse,
    f: &[f64],
    p: &[f64],
    approach: f64,
    stiffness: f64,
    wb: &mut [f64],
    wl: &mut [f64],
    g: &mut [f64],
) -> f64 {
    op.apply_unchecked(p, wb);
    layer.displacement(p, wl);
    let (wb, wl) = (&*wb, &*wl);
    let parts: Vec<f64> = g
        .par_chunks_mut(CHUNK)
        .with_min_len(passes.min_len())
        .enumerate()
        .map(|(c, gc)| {
            let s = c * CHUNK;
            let mut merit = 0.0;
            for (k, gk) in gc.iter_mut().enumerate() {
                let k2 = s + k;
                *gk = wb[k2] + wl[k2] + f[k2] - approach;
                let m = p[k2].min(stiffness * *gk);
                merit += m * m;
            }
            merit
        })
        .collect();
    parts.iter().sum()
}

/// The factor on the complementarity's scale `c` of a second attempt at a bare body
/// whose first attempt stalled. `c`, the inverse of a cell's own compliance, is too
/// stiff a scale where the body's instantaneous (glassy) compliance is a small part of
/// its response over the contact's passage: a Zener body with E_g/E_0 = 300 to 1000 at
/// V tau / a0 = 1e-3 to 1e-2 on 192^2 or 256^2 cells, whose own-cell compliance is
/// 1/700 of the relaxed one. A cell that ends a damped step with a small gap then
/// leaves the set, and the sets swing at the leading edge (measured: 12 such cases
/// stalled near a residual of 1e-3; with a tenth of `c`, 5 of them converged, to the
/// same friction as on the neighbouring grids).
pub(crate) const SOFTER_ACTIVE_SET: f64 = 0.1;

/// Runs the semi-smooth Newton iteration on `problem` from `p`
/// (overwritten), returning D.
pub(crate) fn semismooth_newton(
    problem: &mut ContactProblem,
    p: &mut [f64],
    params: &SolverParams,
    observer: &mut dyn FnMut(Progress) -> ControlFlow<()>,
) -> Result<SolveReport> {
    semismooth_newton_scaled(problem, p, params, observer, 1.0)
}

/// [`semismooth_newton`] with the complementarity's scale `c` (which decides which
/// cells are in the contact set of each step, not the solution) multiplied by
/// `active_set_scale`.
pub(crate) fn semismooth_newton_scaled(
    problem: &mut ContactProblem,
    p: &mut [f64],
    params: &SolverParams,
    observer: &mut dyn FnMut(Progress) -> ControlFlow<()>,
    active_set_scale: f64,
) -> Result<SolveReport> {
    // A bare half-space's step is preconditioned by the inverse of its surface
    // operator; a layered problem keeps the layer's triangular preconditioner.
    let mut inverse = SurfaceInverse::of(problem, params.parallelism);
    let (forcing, min_step) = if inverse.is_some() {
        (BARE_BODY_FORCING, BARE_BODY_MIN_STEP)
    } else {
        (FORCING, MIN_STEP)
    };
    let f = &problem.shape;
    // A bare body is solved as one under a layer that does not deform.
    let layer = problem.layer.as_deref().unwrap_or(&NoLayer);
    // Where the layer places contacts' edges inside cells, the body and the load
    // see each cell's mean pressure (the centre value elsewhere).
    let entries = layer.contact_edges();
    let mut on_means = OnCellMeans::new(problem.influence.as_mut(), entries);
    let op: &mut dyn InfluenceOperator = &mut on_means;
    let weights = (!entries.is_empty()).then(|| load_weights(entries, f.len()));
    let weighted = |k: usize, v: f64| weights.as_ref().map_or(v, |w| w[k] * v);
    let load = problem.load;
    let cell_measure = problem.grid.cell_measure();
    let mut monitor = Monitor::new(params, super::NEWTON_STAGNATION_WINDOW, observer);
    let n = f.len();
    // Passes over the cells are split in fixed chunks (crate::passes): the same bits
    // on any number of threads.
    let passes = Passes::new(n, params.parallelism);
    let min_len = passes.min_len();
    let self_coefficient = op.self_coefficient();
    let layer0 = layer.zero_pressure_self_compliance();
    let stiffness = active_set_scale / (self_coefficient + layer0);
    let target_sum = load / cell_measure;

    let mut wb = vec![0.0; n];
    let mut wl = vec![0.0; n];
    let mut g = vec![0.0; n];
    let mut jp = vec![0.0; n];
    let mut active = vec![false; n];
    let mut full_in = vec![0.0; n];
    let mut full_out = vec![0.0; n];
    let mut full_aux = vec![0.0; n];
    let mut full_pre = vec![0.0; n];
    let mut full_tri = vec![0.0; n];

    // Approach consistent with the initial pressure: zero mean gap over its support.
    op.apply_unchecked(p, &mut wb);
    layer.displacement(p, &mut wl);
    let [s, c] = passes.sum(n, |a, b| {
        let mut part = [0.0, 0.0];
        for k in a..b {
            if p[k] > 0.0 {
                part[0] += wb[k] + wl[k] + f[k];
                part[1] += 1.0;
            }
        }
        part
    });
    let mut approach = s / c.max(1.0);
    let mut linear_iterations = 0;
    let mut gmres = Gmres::new(0, 0);
    let mut z1 = vec![0.0; n];
    let mut last_residual = f64::INFINITY;
    // Consecutive bare-body steps that could not lower the merit (STUCK_STEPS).
    let mut stuck = 0;
    let mut restart = RESTART;

    // The lowest residual met so far, with its approach and pressure.
    let mut best = (f64::INFINITY, approach);
    let mut best_p = vec![0.0; n];
    let mut trial = vec![0.0; n];
    let mut merit = evaluate(
        &passes, op, layer, f, p, approach, stiffness, &mut wb, &mut wl, &mut g,
    );
    for iteration in 1..=params.max_iterations {
        jp.par_chunks_mut(CHUNK)
            .zip(wb.par_chunks(CHUNK).zip(wl.par_chunks(CHUNK)))
            .with_min_len(min_len)
            .for_each(|(j, (b, l))| {
                j.iter_mut()
                    .zip(b.iter().zip(l))
                    .for_each(|(j, (b, l))| *j = b + l)
            });
        let residual = relative_complementarity_residual(&passes, p, &g, &jp);
        if monitor.converged(iteration, residual) {
            return Ok(monitor.report(iteration, linear_iterations, approach));
        }
        if residual < best.0 {
            best = (residual, approach);
            best_p.copy_from_slice(p);
        }
        let stop = match monitor.stop(iteration, residual, || layer.stall_diagnosis(p)) {
            None if stuck >= STUCK_STEPS => Some(monitor.stuck(iteration, residual, stuck)),
            stop => stop,
        };
        if let Some(error) = stop {
            return match error {
                Error::NoConvergence { history, .. } if best.0 <= STALLED_BUT_SOLVED => {
                    p.copy_from_slice(&best_p);
                    Ok(SolveReport {
                        iterations: iteration,
                        linear_iterations,
                        residual: best.0,
                        approach: best.1,
                        history,
                    })
                }
                error => Err(error),
            };
        }
        last_residual = residual;
        // A folding row relation is a property of the discrete model, not of the
        // iteration: stop early and say so rather than iterate to the limit.
        if iteration % FOLD_CHECK_EVERY == 0 && residual > 1e-3 {
            if let Some(diagnosis) = layer.stall_diagnosis(p) {
                return Err(no_unique_solution(iteration, residual, diagnosis));
            }
        }

        // Contact set of this step.
        let mut indices = Vec::with_capacity(n);
        for k in 0..n {
            active[k] = p[k] - stiffness * g[k] > 0.0;
            if active[k] {
                indices.push(k);
            }
        }
        if indices.is_empty() {
            // Keep the cell of least gap in contact so that the load can be carried.
            let k = (0..n).min_by(|&a, &b| g[a].total_cmp(&g[b])).unwrap_or(0);
            active[k] = true;
            indices.push(k);
        }
        let m = indices.len();
        let jac = layer.linearise(p);
        jac.apply(p, &mut jp);
        // Scaled system: rows of A times c, the load row times 1/sqrt(m).
        let load_scale = 1.0 / (m as f64).sqrt();
        let mut rhs = vec![0.0; m + 1];
        for (a, &k) in indices.iter().enumerate() {
            rhs[a] = stiffness * (jp[k] - wl[k] - f[k]);
        }
        rhs[m] = load_scale * target_sum;
        let mut x = vec![0.0; m + 1];
        for (a, &k) in indices.iter().enumerate() {
            x[a] = p[k];
        }
        x[m] = approach;

        // Off the contact set the scattered vectors below stay zero for the whole
        // step: clear them once here, then only the contact cells are written.
        full_in
            .par_chunks_mut(CHUNK)
            .zip(full_pre.par_chunks_mut(CHUNK))
            .with_min_len(min_len)
            .for_each(|(a, b)| {
                a.fill(0.0);
                b.fill(0.0);
            });
        // Preconditioner pieces: z1 = M^-1 1 on the contact set.
        for &k in &indices {
            full_in[k] = 1.0;
        }
        match inverse.as_mut() {
            Some(inverse) => inverse.apply(&full_in, &mut z1),
            None => jac.solve_restricted(self_coefficient, &active, &full_in, &mut z1),
        }
        let z1_sum: f64 = indices.iter().map(|&k| weighted(k, z1[k])).sum();

        let min_gather = passes.min_cells();
        let mut apply = |y: &[f64], out: &mut [f64]| {
            for (a, &k) in indices.iter().enumerate() {
                full_in[k] = y[a];
            }
            op.apply_unchecked(&full_in, &mut full_out);
            jac.apply(&full_in, &mut full_aux);
            let (full_out, full_aux) = (&full_out, &full_aux);
            out[..m]
                .par_iter_mut()
                .zip(&indices[..])
                .with_min_len(min_gather)
                .for_each(|(o, &k)| *o = stiffness * (full_out[k] + full_aux[k] - y[m]));
            out[m] = load_scale
                * y[..m]
                    .iter()
                    .zip(&indices[..])
                    .map(|(&v, &k)| weighted(k, v))
                    .sum::<f64>();
        };
        let mut precondition = |r: &[f64], out: &mut [f64]| {
            for (a, &k) in indices.iter().enumerate() {
                full_pre[k] = r[a] / stiffness;
            }
            let rd = r[m] / load_scale;
            match inverse.as_mut() {
                Some(inverse) => inverse.apply(&full_pre, &mut full_tri),
                None => jac.solve_restricted(self_coefficient, &active, &full_pre, &mut full_tri),
            }
            let t_sum: f64 = indices.iter().map(|&k| weighted(k, full_tri[k])).sum();
            let d = (rd - t_sum) / z1_sum;
            let (full_tri, z1) = (&full_tri, &z1);
            out[..m]
                .par_iter_mut()
                .zip(&indices[..])
                .with_min_len(min_gather)
                .for_each(|(o, &k)| *o = full_tri[k] + d * z1[k]);
            out[m] = d;
        };
        let eta = (forcing * residual).clamp(1e-13, 1e-2);
        gmres.reshape(m + 1, restart.min(m + 1));
        let info = gmres.solve(
            &mut apply,
            &mut precondition,
            &rhs,
            &mut x,
            eta,
            MAX_LINEAR_ITERATIONS,
        );
        linear_iterations += info.iterations;
        if inverse.is_some() && !info.converged && info.iterations >= MAX_LINEAR_ITERATIONS {
            restart = LONG_RESTART;
        }
        if !x.iter().all(|v| v.is_finite()) {
            break;
        }
        // Newton point: x on the contact set, zero off it.
        full_in.fill(0.0);
        for (a, &k) in indices.iter().enumerate() {
            full_in[k] = x[a];
        }
        // Backtracking on the merit ||min(p, c g)||^2: full steps where they help,
        // shorter ones where the creep's long reach makes the linearisation poor.
        let mut alpha = 1.0;
        loop {
            trial
                .par_chunks_mut(CHUNK)
                .zip(p.par_chunks(CHUNK).zip(full_in.par_chunks(CHUNK)))
                .with_min_len(min_len)
                .for_each(|(t, (p, x))| {
                    t.iter_mut()
                        .zip(p.iter().zip(x))
                        .for_each(|(t, (p, x))| *t = p + alpha * (x - p))
                });
            let d = approach + alpha * (x[m] - approach);
            let m_trial = evaluate(
                &passes, op, layer, f, &trial, d, stiffness, &mut wb, &mut wl, &mut g,
            );
            let lowered = m_trial <= (1.0 - 1e-4 * alpha) * merit;
            if lowered || alpha <= min_step {
                stuck = if lowered || inverse.is_none() {
                    0
                } else {
                    stuck + 1
                };
                p.copy_from_slice(&trial);
                approach = d;
                merit = m_trial;
                break;
            }
            alpha *= 0.5;
        }
    }
    if let Some(diagnosis) = layer.stall_diagnosis(p) {
        return Err(no_unique_solution(
            params.max_iterations,
            last_residual,
            diagnosis,
        ));
    }
    let hint = "raise solver.max_iterations or solver.tolerance, or refine the grid";
    Err(monitor.failure(params.max_iterations, last_residual, hint.into()))
}
