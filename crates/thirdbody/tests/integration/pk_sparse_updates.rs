//! Conjugate gradients keep `A p` up to date through a step that the projection
//! changed on a few cells by adding those cells' part directly
//! (`InfluenceOperator::add_sparse_update`) instead of recomputing the product. The
//! solution must be the one the recomputing solver finds, and the direct sums must
//! actually have been used (second method: the same operator with them refused).

use crate::cases;

use std::ops::ControlFlow;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;

use cases::*;
use thirdbody::operator::{ConvolutionOperator, InfluenceOperator, Product, SparseUpdate};
use thirdbody::*;

/// A contact operator that counts its direct sums (in a counter the test keeps:
/// the problem owns the operator), or refuses them.
struct Watched {
    inner: ConvolutionOperator,
    allow_sparse: bool,
    sparse_sums: Arc<AtomicUsize>,
}

impl InfluenceOperator for Watched {
    fn len(&self) -> usize {
        self.inner.len()
    }
    fn self_coefficient(&self) -> f64 {
        self.inner.self_coefficient()
    }
    fn is_symmetric(&self) -> bool {
        self.inner.is_symmetric()
    }
    fn apply_product(&mut self, product: Product<'_>) {
        self.inner.apply_product(product)
    }
    fn add_sparse_update(&mut self, update: SparseUpdate<'_>) -> bool {
        let added = self.allow_sparse && self.inner.add_sparse_update(update);
        self.sparse_sums
            .fetch_add(usize::from(added), Ordering::Relaxed);
        added
    }
    fn products(&self) -> usize {
        self.inner.products()
    }
}

/// Solves `case` on `grid` with the direct sums allowed or refused: the solution
/// and the number of direct sums used.
fn solve_on(case: &Case, grid: &Grid, allow_sparse: bool) -> (Solution, usize) {
    let params = SolverParams {
        tolerance: 1e-12,
        ..SolverParams::default()
    };
    let mut kernels = KernelCache::new();
    let plan = kernels
        .plan(grid.nx(), grid.ny(), params.parallelism)
        .unwrap();
    let spectrum = kernels
        .surface_spectrum(
            &case.body,
            grid,
            &plan,
            case.velocity(),
            case.layer.is_none(),
        )
        .unwrap();
    let shape = case
        .assemble(grid, &mut kernels, params.parallelism)
        .unwrap()
        .shape()
        .to_vec();
    let sparse_sums = Arc::new(AtomicUsize::new(0));
    let watched = Watched {
        inner: ConvolutionOperator::new(plan.convolver(), spectrum).unwrap(),
        allow_sparse,
        sparse_sums: Arc::clone(&sparse_sums),
    };
    let mut problem =
        ContactProblem::from_parts(case, grid, Box::new(watched), shape, vec![0.0; grid.len()])
            .unwrap();
    let solution = solve_problem(&mut problem, None, &params, &mut |_| {
        ControlFlow::Continue(())
    })
    .unwrap_or_else(|e| panic!("{e}"));
    (solution, sparse_sums.load(Ordering::Relaxed))
}

fn compare(case: &Case, label: &str) {
    let grid = solve_to(case, 1e-10).grid;
    let (direct, sums) = solve_on(case, &grid, true);
    let (recomputed, _) = solve_on(case, &grid, false);
    assert!(sums > 0, "{label}: no step used the direct sums");
    assert!(
        direct.info.operator_products < recomputed.info.operator_products,
        "{label}: the direct sums saved no product"
    );
    // The same path: an error in the sums would show in the residuals (which the
    // exact product that confirms convergence hides at the end: 0.9 times the sums
    // makes the solve stagnate). Rounding differences grow over the iterations as
    // in any CG (to 1e-4 near 1e-12), so the first six decades are compared.
    assert_eq!(
        direct.info.iterations, recomputed.info.iterations,
        "{label}"
    );
    let first = recomputed.info.history[0];
    let worst = direct
        .info
        .history
        .iter()
        .zip(&recomputed.info.history)
        .take_while(|(_, b)| **b > 1e-6 * first)
        .map(|(a, b)| rel(*a, *b))
        .fold(0.0f64, f64::max);
    assert!(
        worst < 1e-4,
        "{label}: residual histories differ by {worst:e}"
    );
    let (scale, dp) = peak_and_largest_difference(&direct.pressure, &recomputed.pressure);
    assert!(dp <= 1e-9 * scale, "{label}: pressures differ by {dp:e}");
    assert!(
        rel(direct.approach, recomputed.approach) < 1e-10,
        "{label}: approach"
    );
}

#[test]
fn direct_sums_give_the_recomputed_solution_with_and_without_a_winkler_bed() {
    compare(&fixed_window(sphere(5e-6, 128), 0.024, [0.0, 0.0]), "hertz");
    let winkler = winkler_bed(5e-6, 128);
    compare(&fixed_window(winkler, 0.026, [0.0, 0.0]), "winkler");
}
