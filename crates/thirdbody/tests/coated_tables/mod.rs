//! Helpers of the coating tests (`coated_*.rs`): a coating as a stack of one layer
//! on a half-space, its transfers from [`LayeredSolver`], its surface kernel, one
//! cell's stress coefficient tables by a chosen method on square lattices of offsets
//! (cell 1), and their peak and differences.

#![allow(dead_code)]

use thirdbody::body::layered::{Base, LayeredSolver, Ply, Stack, StressTransfer};
use thirdbody::body::StackBody;
use thirdbody::case::Elastic;
use thirdbody::stress::{InfluenceTable, LayeredStressKernels, OffsetLattice, Side, StressMethod};
use thirdbody::Result;

pub fn elastic(young: f64, poisson: f64) -> Elastic {
    Elastic { young, poisson }
}

/// A coating of thickness `h1` on a substrate half-space.
pub fn coating(coating: Elastic, h1: f64, substrate: Elastic) -> Stack {
    Stack {
        layers: vec![Ply {
            material: coating,
            thickness: h1,
        }],
        base: Base::HalfSpace(substrate),
    }
}

/// The stress kernels of a coating.
pub fn coated_kernels(c: Elastic, h1: f64, s: Elastic, side: Side) -> LayeredStressKernels {
    LayeredStressKernels {
        stack: coating(c, h1, s),
        interface_side: side,
    }
}

/// The wave-frame transfer `[xixi, etaeta, zz, xiz / i]` at k >= 0, depth z, on
/// `side` of the interface (the coating above it, the substrate below); at k = 0
/// its limit, extrapolated from two small wavenumbers.
pub fn plane_stress_transfer(
    c: Elastic,
    h1: f64,
    s: Elastic,
    k: f64,
    z: f64,
    side: Side,
) -> [f64; 4] {
    let layer = usize::from(side == Side::Below);
    let mut solver = LayeredSolver::new(&coating(c, h1, s)).unwrap();
    if k == 0.0 {
        let e = 1e-7 / (h1 + z);
        let a = solver.plane_response(e, layer, z).stress;
        let b = solver.plane_response(2.0 * e, layer, z).stress;
        return std::array::from_fn(|q| 2.0 * a[q] - b[q]);
    }
    solver.plane_response(k, layer, z).stress
}

/// The stress transfer at depth z (the coating's side at z = h1).
pub fn coated_stress_transfer(
    c: Elastic,
    h1: f64,
    s: Elastic,
    kx: f64,
    ky: f64,
    z: f64,
) -> StressTransfer {
    let layer = usize::from(z > h1);
    LayeredSolver::new(&coating(c, h1, s))
        .unwrap()
        .stress_transfer(kx, ky, layer, z)
}

/// The stress transfer on both sides of the interface.
pub fn interface_stress_transfer(
    c: Elastic,
    h1: f64,
    s: Elastic,
    kx: f64,
    ky: f64,
) -> (StressTransfer, StressTransfer) {
    let mut solver = LayeredSolver::new(&coating(c, h1, s)).unwrap();
    (
        solver.stress_transfer(kx, ky, 0, h1),
        solver.stress_transfer(kx, ky, 1, h1),
    )
}

/// The surface factor `A(t)` at `t = k h1`.
pub fn coating_factor(c: Elastic, s: Elastic, t: f64) -> f64 {
    LayeredSolver::new(&coating(c, 1.0, s))
        .unwrap()
        .surface_factor(t)
}

/// The surface kernel quadrant of a coating on cells of side `cell`.
pub fn coated_surface_kernel(
    c: Elastic,
    h1: f64,
    s: Elastic,
    cell: f64,
    nx: usize,
    ny: usize,
) -> Result<Vec<f64>> {
    StackBody {
        stack: coating(c, h1, s),
    }
    .surface_kernel_quadrant(cell, nx, ny)
}

/// A lattice of `n x n` offsets starting at `first` (cells) on both axes, cell 1.
pub fn square_lattice(n: usize, first: f64) -> OffsetLattice {
    OffsetLattice {
        cell: 1.0,
        x_first: first,
        cols: n,
        y_first: first,
        rows: n,
    }
}

/// The coefficients of `k` at depth `z` on `l` by method `m`.
pub fn table(
    k: &LayeredStressKernels,
    z: f64,
    l: &OffsetLattice,
    m: StressMethod,
) -> InfluenceTable {
    let mut t = InfluenceTable::default();
    k.fill_with(z, l, &mut t, m);
    t
}

/// Largest magnitude over all components and offsets.
pub fn peak(t: &InfluenceTable) -> f64 {
    t.values
        .iter()
        .flatten()
        .fold(0.0f64, |m, v| m.max(v.abs()))
}

/// Largest difference over all components and offsets.
pub fn max_difference(a: &InfluenceTable, b: &InfluenceTable) -> f64 {
    a.values
        .iter()
        .flatten()
        .zip(b.values.iter().flatten())
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
}
