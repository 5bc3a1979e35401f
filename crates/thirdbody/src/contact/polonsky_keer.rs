//! Polonsky–Keer conjugate gradients (Polonsky & Keer, Wear 231, 1999) for the
//! contact problem with a symmetric positive definite operator `A = K + c_w I`: the
//! bare body (`c_w = 0`) or a body under a creep-free linear layer (a Winkler bed of
//! compliance `c_w`). Minimises the complementary energy over `p >= 0` with the load
//! constraint `sum(p) h^2 = Q`; the approach D is the mean of `A p + f` over the
//! contact. The product `A t` of each step also updates `A p`; where the projection
//! changed the step on a few cells, the operator adds their part directly
//! ([`InfluenceOperator::add_sparse`]), so an iteration costs one convolution.

use std::ops::ControlFlow;

use rayon::prelude::*;

use super::{Monitor, SolveReport};
use crate::contact::{Progress, SolverParams};
use crate::error::Result;
use crate::operator::{InfluenceOperator, Unchecked};
use crate::passes::{add_in_order, lane_sum, lane_sum_max, Passes, CHUNK};
use crate::problem::ContactProblem;

/// What the user can try when CG stops short.
const HINT: &str = "raise solver.max_iterations or solver.tolerance";

/// Exact recomputation of `A p` at least this often, against drift of the updates
/// (each adds a rounding of the step's size; the stopping test is always confirmed
/// on an exact product).
const REFRESH_EVERY: usize = 64;

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
    let cell_measure = problem.grid.cell_measure();
    let mut monitor = Monitor::new(params, super::CG_STAGNATION_WINDOW, observer);
    let n = f.len();
    // Every pass over the cells below is split into fixed chunks (crate::passes), so
    // the iterates are the same bits on any number of threads.
    let passes = Passes::new(n, params.parallelism);
    let min_len = passes.min_len();
    let target_sum = load / cell_measure;
    let scale = target_sum / passes.sum(n, |a, b| [p[a..b].iter().sum::<f64>()])[0];
    if scale.is_finite() {
        passes.scale(p, scale);
    }
    let mut u = vec![0.0; n];
    let mut g = vec![0.0; n];
    let mut t = vec![0.0; n];
    let mut r = vec![0.0; n];
    let apply = |op: &mut dyn InfluenceOperator, x: &[f64], out: &mut [f64]| {
        op.apply_unchecked(x, out);
        if winkler != 0.0 {
            out.par_chunks_mut(CHUNK)
                .zip(x.par_chunks(CHUNK))
                .with_min_len(min_len)
                .for_each(|(o, x)| o.iter_mut().zip(x).for_each(|(o, xi)| *o += winkler * xi));
        }
    };
    apply(op, p, &mut u);
    let mut sums = GapSums::of(&passes, &u, f, p);
    let mut conjugate = false;
    let mut g_old = 1.0;
    let mut since_refresh = 0;
    let mut chunks = vec![ChunkKind::default(); n.div_ceil(CHUNK)];
    for iteration in 1..=params.max_iterations {
        let GapSums {
            gap_sum,
            contact,
            p_sum,
            w_max,
        } = sums;
        let approach = gap_sum / contact.max(1.0);
        // The gap g = u + f - D with D the mean of u + f over the contact; the
        // complementarity residual's sums (see `relative_complementarity_residual`)
        // and the squared gap over the contact.
        let c_scale = p_sum / contact / w_max;
        // On the way, which chunks hold contact cells and which cells that would
        // join it (outside the contact, the surfaces overlap): the passes of the
        // step skip the others, whose terms are zero.
        let (num, den, big_g) = {
            let parts: Vec<([f64; 3], Chunk)> = g
                .par_chunks_mut(CHUNK)
                .with_min_len(min_len)
                .enumerate()
                .map(|(c, gc)| {
                    let s = c * CHUNK;
                    let (uc, fc, pc) = (&u[s..], &f[s..], &p[s..]);
                    let sums = lane_sum(0, gc.len(), |k| {
                        let (gk, pk) = (uc[k] + fc[k] - approach, pc[k]);
                        gc[k] = gk;
                        let m = pk.min(c_scale * gk);
                        let on = if pk > 0.0 { gk * gk } else { 0.0 };
                        [m * m, pk * pk, on]
                    });
                    let pc = &pc[..gc.len()];
                    let chunk = Chunk {
                        contact: pc.iter().any(|&v| v > 0.0),
                        joining: pc.iter().zip(gc.iter()).any(|(&p, &g)| p <= 0.0 && g < 0.0),
                    };
                    (sums, chunk)
                })
                .collect();
            for (kind, (_, chunk)) in chunks.iter_mut().zip(&parts) {
                kind.now = *chunk;
            }
            let sums: Vec<[f64; 3]> = parts.iter().map(|(s, _)| *s).collect();
            let [num, den, big_g] = add_in_order(&sums);
            (num, den, big_g)
        };
        let residual = if contact == 0.0 || w_max == 0.0 {
            f64::INFINITY
        } else {
            (num / den).sqrt()
        };
        if monitor.converged(iteration, residual) {
            if since_refresh == 0 {
                return Ok(monitor.report(iteration, 0, approach));
            }
            // Confirm on an exactly recomputed A p before stopping.
            apply(op, p, &mut u);
            sums = GapSums::of(&passes, &u, f, p);
            since_refresh = 0;
            continue;
        }
        if let Some(error) = monitor.stop(iteration, residual, || None) {
            return Err(error);
        }
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
            t.par_chunks_mut(CHUNK)
                .with_min_len(min_len)
                .enumerate()
                .filter(|(c, _)| chunks[*c].direction || chunks[*c].now.contact)
                .for_each(|(c, tc)| {
                    let s = c * CHUNK;
                    for (k, tk) in tc.iter_mut().enumerate() {
                        *tk = if p[s + k] > 0.0 {
                            g[s + k] + beta * *tk
                        } else {
                            0.0
                        };
                    }
                });
            for kind in chunks.iter_mut() {
                kind.direction = kind.now.contact;
            }
            apply(op, &t, &mut r);
            // Over the contact: sum of r, g.t, r.t and sum of t; the projected
            // curvature is sum((r - rbar) t) = r.t - rbar sum(t).
            let [r_sum, g_t, r_t, t_sum] = passes.sum(n, |a, b| {
                if !chunks[a / CHUNK].now.contact {
                    return [0.0; 4];
                }
                lane_sum(a, b, |k| {
                    if p[k] > 0.0 {
                        [r[k], g[k] * t[k], r[k] * t[k], t[k]]
                    } else {
                        [0.0; 4]
                    }
                })
            });
            let rbar = r_sum / contact.max(1.0);
            let den = r_t - rbar * t_sum;
            if (den > 0.0 && den.is_finite()) || beta == 0.0 {
                break (g_t, den);
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
        // The step on the contact, projected onto p >= 0; cells that were not loaded
        // but where the surfaces overlap join the contact. Where either happened, the
        // new pressure differs from the plain step `p - tau t` by `delta` (projected:
        // `tau t - p`; joined: `-tau g`), listed in cell order.
        let parts: Vec<(f64, Changed, bool)> = p
            .par_chunks_mut(CHUNK)
            .with_min_len(min_len)
            .enumerate()
            .map(|(c, pc)| {
                let s = c * CHUNK;
                let (tc, gc) = (&t[s..], &g[s..]);
                let mut changed = Vec::new();
                let mut overlap = false;
                if !(chunks[c].now.contact || chunks[c].now.joining) {
                    return (0.0, changed, overlap);
                }
                let [sum] = lane_sum(0, pc.len(), |k| {
                    let pk = &mut pc[k];
                    if *pk > 0.0 {
                        let step = *pk - tau * tc[k];
                        if step < 0.0 {
                            changed.push((s + k, -step));
                            *pk = 0.0;
                        } else {
                            *pk = step;
                        }
                    } else if gc[k] < 0.0 {
                        *pk -= tau * gc[k];
                        changed.push((s + k, *pk));
                        overlap = true;
                    }
                    [*pk]
                });
                (sum, changed, overlap)
            })
            .collect();
        let new_sum = parts.iter().fold(0.0, |total, (sum, _, _)| total + sum);
        // Chunks that hold contact after the step (a sum of pressures >= 0).
        let loaded: Vec<bool> = parts.iter().map(|(sum, _, _)| *sum > 0.0).collect();
        conjugate = !parts.iter().any(|(_, _, overlap)| *overlap);
        let changed: Changed = parts.into_iter().flat_map(|(_, c, _)| c).collect();
        let scale = if new_sum > 0.0 {
            target_sum / new_sum
        } else {
            1.0
        };
        // `A p` follows the step as `A p - tau r + A delta`, with `A delta` added
        // directly when the operator finds that cheaper than a product; else (and
        // every REFRESH_EVERY iterations) it is recomputed.
        let corrected = !changed.is_empty() && op.add_sparse_unchecked(&changed, &mut u);
        if corrected && winkler != 0.0 {
            for &(k, delta) in &changed {
                u[k] += winkler * delta;
            }
        }
        if (!changed.is_empty() && !corrected) || since_refresh >= REFRESH_EVERY {
            passes.scale(p, scale);
            apply(op, p, &mut u);
            sums = GapSums::of(&passes, &u, f, p);
            since_refresh = 0;
        } else {
            // The scaled step, and the next iteration's gap sums on the way.
            let parts: Vec<([f64; 3], f64)> = p
                .par_chunks_mut(CHUNK)
                .zip(u.par_chunks_mut(CHUNK))
                .with_min_len(min_len)
                .enumerate()
                .map(|(c, (pc, uc))| {
                    let s = c * CHUNK;
                    let (rc, fc) = (&r[s..], &f[s..]);
                    if !loaded[c] {
                        // No pressure to scale and no gap sums: only A p.
                        let largest = uc.iter_mut().zip(rc).fold(0.0f64, |m, (uk, rk)| {
                            *uk = scale * (*uk - tau * rk);
                            m.max(uk.abs())
                        });
                        return ([0.0; 3], largest);
                    }
                    lane_sum_max(0, pc.len(), |k| {
                        pc[k] *= scale;
                        uc[k] = scale * (uc[k] - tau * rc[k]);
                        GapSums::term(uc[k], fc[k], pc[k])
                    })
                })
                .collect();
            sums = GapSums::add(&parts);
            since_refresh += 1;
        }
    }
    let residual = monitor.last_residual();
    Err(monitor.failure(params.max_iterations, residual, HINT.into()))
}

/// What a chunk of cells holds: contact cells, cells about to join the contact.
#[derive(Debug, Clone, Copy, Default)]
struct Chunk {
    contact: bool,
    joining: bool,
}

/// A chunk now, and whether the search direction may be non-zero there (it held
/// contact when the direction was last formed).
#[derive(Debug, Clone, Copy)]
struct ChunkKind {
    now: Chunk,
    direction: bool,
}

impl Default for ChunkKind {
    /// Before the first direction: every chunk may hold one.
    fn default() -> Self {
        ChunkKind {
            now: Chunk::default(),
            direction: true,
        }
    }
}

/// Cells where the projection changed a step, in cell order, with the change of
/// their pressure.
type Changed = Vec<(usize, f64)>;

/// The sums of the gap `u + f` over the contact (`p > 0`), of the contact's cells
/// and of the pressure, and the largest `|u|`: what an iteration needs first.
#[derive(Debug, Clone, Copy)]
struct GapSums {
    gap_sum: f64,
    contact: f64,
    p_sum: f64,
    w_max: f64,
}

impl GapSums {
    /// The sums over all cells, in one pass.
    fn of(passes: &Passes, u: &[f64], f: &[f64], p: &[f64]) -> Self {
        let parts = passes.partials(u.len(), |a, b| {
            lane_sum_max(a, b, |k| GapSums::term(u[k], f[k], p[k]))
        });
        GapSums::add(&parts)
    }

    /// One cell's terms.
    #[inline(always)]
    fn term(u: f64, f: f64, p: f64) -> ([f64; 3], f64) {
        let sums = if p > 0.0 { [u + f, 1.0, p] } else { [0.0; 3] };
        (sums, u.abs())
    }

    /// The chunks' partials added in order.
    fn add(parts: &[([f64; 3], f64)]) -> Self {
        let sums: Vec<[f64; 3]> = parts.iter().map(|(s, _)| *s).collect();
        let [gap_sum, contact, p_sum] = add_in_order(&sums);
        GapSums {
            gap_sum,
            contact,
            p_sum,
            w_max: parts.iter().fold(0.0f64, |m, (_, w)| m.max(*w)),
        }
    }
}
