//! Polonsky–Keer conjugate gradients (Polonsky & Keer, Wear 231, 1999) for the
//! contact problem with a symmetric positive definite operator `A = K + c_w I`: the
//! bare body (`c_w = 0`) or a body under a creep-free linear layer (a Winkler bed of
//! compliance `c_w`). Minimises the complementary energy over `p >= 0` with the load
//! constraint `sum(p) h^2 = Q`; the approach D is the mean of `A p + f` over the
//! contact. The product `A t` of each step also updates `A p` when the projection
//! leaves the step unchanged, so late iterations cost one convolution each.

use std::ops::ControlFlow;

use super::{relative_complementarity_residual, Monitor, SolveReport};
use crate::contact::{Progress, SolverParams};
use crate::error::Result;
use crate::operator::InfluenceOperator;
use crate::problem::ContactProblem;

/// What the user can try when CG stops short.
const HINT: &str = "raise solver.max_iterations or solver.tolerance";

/// Exact recomputation of `A p` at least this often, against drift of the updates.
const REFRESH_EVERY: usize = 20;

/// Runs PK-CG on `problem` (whose operator is `K + winkler I`) from the positive
/// initial pressure in `p` (overwritten).
pub(crate) fn polonsky_keer(
    problem: &mut ContactProblem,
    winkler: f64,
    p: &mut [f64],
    params: &SolverParams,
    observer: &mut dyn FnMut(Progress) -> ControlFlow<()>,
) -> Result<SolveReport> {
    let f = &problem.shape;
    let op = problem.influence.as_mut();
    let load = problem.load;
    let cell_area = problem.grid.cell_area();
    let mut monitor = Monitor::new(params, super::CG_STAGNATION_WINDOW, observer);
    let n = f.len();
    let target_sum = load / cell_area;
    normalise(p, target_sum);
    let mut u = vec![0.0; n];
    let mut g = vec![0.0; n];
    let mut t = vec![0.0; n];
    let mut r = vec![0.0; n];
    let mut in_contact = vec![false; n];
    let apply = |op: &mut dyn InfluenceOperator, x: &[f64], out: &mut [f64]| {
        op.apply(x, out);
        if winkler != 0.0 {
            out.iter_mut().zip(x).for_each(|(o, xi)| *o += winkler * xi);
        }
    };
    apply(op, p, &mut u);
    let mut conjugate = false;
    let mut g_old = 1.0;
    let mut since_refresh = 0;
    for iteration in 1..=params.max_iterations {
        // Gap with D chosen as the mean over the contact.
        let (mut sum, mut count) = (0.0, 0usize);
        for k in 0..n {
            g[k] = u[k] + f[k];
            if p[k] > 0.0 {
                sum += g[k];
                count += 1;
            }
        }
        let approach = sum / count.max(1) as f64;
        g.iter_mut().for_each(|v| *v -= approach);
        let residual = relative_complementarity_residual(p, &g, &u);
        if monitor.converged(iteration, residual) {
            if since_refresh == 0 {
                return Ok(monitor.report(iteration, 0, approach));
            }
            // Confirm on an exactly recomputed A p before stopping.
            apply(op, p, &mut u);
            since_refresh = 0;
            continue;
        }
        if let Some(error) = monitor.stop(iteration, residual, || None) {
            return Err(error);
        }
        in_contact
            .iter_mut()
            .zip(p.iter())
            .for_each(|(c, pk)| *c = *pk > 0.0);
        let big_g: f64 = (0..n).filter(|&k| in_contact[k]).map(|k| g[k] * g[k]).sum();
        let mut beta = if conjugate { big_g / g_old } else { 0.0 };
        g_old = big_g;
        // The step along t minimises the energy under the load constraint only if
        // the projected curvature `den` is positive. A conjugate direction carried
        // across a change of the contact set need not sum to zero over the new set;
        // with a very flat kernel (a stiff coating spreads the load: E1/E2 ~ 100 on
        // h1 ~ 0.1 a) the load term `rbar sum(t)` then exceeds `t.At` and `den` turns
        // negative. Steepest descent (t = g, whose sum over the contact is zero
        // because D is the gap's mean there) always has `den = g.Ag > 0`: restart.
        let (num, den) = loop {
            for k in 0..n {
                t[k] = if p[k] > 0.0 { g[k] + beta * t[k] } else { 0.0 };
            }
            apply(op, &t, &mut r);
            let (mut rsum, mut rcount) = (0.0, 0usize);
            for k in 0..n {
                if p[k] > 0.0 {
                    rsum += r[k];
                    rcount += 1;
                }
            }
            let rbar = rsum / rcount.max(1) as f64;
            let (mut num, mut den) = (0.0, 0.0);
            for k in 0..n {
                if p[k] > 0.0 {
                    num += g[k] * t[k];
                    den += (r[k] - rbar) * t[k];
                }
            }
            if (den > 0.0 && den.is_finite()) || beta == 0.0 {
                break (num, den);
            }
            beta = 0.0;
        };
        if den <= 0.0 || !den.is_finite() {
            let hint = format!(
                "conjugate gradients broke down: the body's influence operator is not \
                 positive definite along the steepest-descent direction (curvature \
                 {den:.3e}), so the kernel is not a valid elastic response at this grid"
            );
            return Err(monitor.failure(iteration, residual, hint));
        }
        let tau = num / den;
        let mut projected = false;
        for k in 0..n {
            if p[k] > 0.0 {
                p[k] -= tau * t[k];
                if p[k] < 0.0 {
                    p[k] = 0.0;
                    projected = true;
                }
            }
        }
        let mut overlap = false;
        for k in 0..n {
            // Cells that were not loaded but where the surfaces overlap join the contact.
            if !in_contact[k] && g[k] < 0.0 {
                p[k] -= tau * g[k];
                overlap = true;
            }
        }
        conjugate = !overlap;
        let scale = normalise(p, target_sum);
        if projected || overlap || since_refresh >= REFRESH_EVERY {
            apply(op, p, &mut u);
            since_refresh = 0;
        } else {
            u.iter_mut()
                .zip(&r)
                .for_each(|(ui, ri)| *ui = scale * (*ui - tau * ri));
            since_refresh += 1;
        }
    }
    let residual = monitor.last_residual();
    Err(monitor.failure(params.max_iterations, residual, HINT.into()))
}

/// Scales `p` to the given sum; returns the factor.
fn normalise(p: &mut [f64], target_sum: f64) -> f64 {
    let s: f64 = p.iter().sum();
    let scale = if s > 0.0 { target_sum / s } else { 1.0 };
    p.iter_mut().for_each(|v| *v *= scale);
    scale
}
