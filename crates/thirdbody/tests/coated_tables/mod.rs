//! Helpers of the coated stress-kernel tests (`coated_stress_limits.rs`,
//! `coated_stress_sub_cell.rs`): one cell's coefficient tables by a chosen method,
//! on square lattices of offsets (cell 1), and their peak and differences.

use thirdbody::body::coated_stress::StressMethod;
use thirdbody::case::Elastic;
use thirdbody::stress::{CoatedStressKernels, InfluenceTable, OffsetLattice};

pub fn elastic(young: f64, poisson: f64) -> Elastic {
    Elastic { young, poisson }
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
    k: &CoatedStressKernels,
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
