//! XZ sections of layered bodies sum their remainder's short waves against the
//! pressure's spectrum on a periodic box (one row of outputs, no kernel table); the
//! planes and blocks keep the kernel tables. Here the XZ section is checked against
//! the direct sum `sigma_c(x_i, y) = sum_{k,l} K_c(x_i - x_k, y - y_l) p_{k,l}` of
//! the kernel table (`StressKernels::fill`, checked against brute-force quadrature in
//! `coated_stress_brute_force.rs` and `layered_stress_kernels.rs`) on the same
//! offsets, for rows on a cell edge, on a cell centre and in between, at depths in
//! the top layer and below it, for a coating and a stack of three layers, with an
//! asymmetric pressure. The two routes share the kernels' split and box; the row
//! interpolates the transfer on Chebyshev panels shared by all depths where the table
//! has one set per depth, so they agree to about 1e-13 of the peak. A depth summed in
//! bands takes the part below the rows' band split from the rows' box, where the
//! table goes on in bands on boxes of their own: the two then differ by their boxes'
//! truncation (the bands' reach, `REACH` in `layered_kernels.rs`), measured at 1.3e-12
//! of the peak on the small windows of the uneven-window test; each route is within
//! 8.2e-12 (rows) and 7.0e-12 (table) of its own sums with 1.5 times the reach there.

use thirdbody::body::layered::{Base, Ply, Stack};
use thirdbody::stress::{stress_kernels, stresses, InfluenceTable, OffsetLattice, Section, Side};
use thirdbody::{Body, Elastic, Grid};

fn elastic(young: f64) -> Elastic {
    Elastic {
        young,
        poisson: 0.3,
    }
}

/// A lopsided bump, nonzero on every cell.
fn pressure(grid: &Grid) -> Vec<f64> {
    let mut p = vec![0.0; grid.len()];
    for j in 0..grid.ny() {
        for i in 0..grid.nx() {
            let (x, y) = (grid.x(i), grid.y(j));
            p[grid.index(i, j)] =
                (-(x - 0.2).powi(2) - 2.0 * (y + 0.1).powi(2)).exp() * (1.3 + 0.4 * x - 0.2 * y);
        }
    }
    p
}

/// The direct sum of the kernel table along the row y at depth z.
fn direct(grid: &Grid, p: &[f64], body: &Body, y: f64, z: f64) -> [Vec<f64>; 6] {
    let (nx, ny, h) = (grid.nx(), grid.ny(), grid.cell());
    let kernels = stress_kernels(body, Side::Below).unwrap();
    let lattice = OffsetLattice {
        cell: h,
        x_first: -(nx as f64 - 1.0),
        cols: 2 * nx - 1,
        y_first: (y - grid.y(ny - 1)) / h,
        rows: ny,
    };
    let mut table = InfluenceTable::default();
    kernels.fill(z, &lattice, &mut table);
    std::array::from_fn(|c| {
        (0..nx)
            .map(|i| {
                let mut sum = 0.0;
                for l in 0..ny {
                    for k in 0..nx {
                        // Offset i - k along x, row m = ny - 1 - l along y.
                        let col = i + nx - 1 - k;
                        sum += table.get(c, col, ny - 1 - l) * p[grid.index(k, l)];
                    }
                }
                sum
            })
            .collect()
    })
}

fn check(body: &Body, depths: &[f64]) {
    check_on(
        Grid::centred(20, 14, 0.1, [0.0, 0.0]).unwrap(),
        body,
        depths,
    );
}

fn check_on(grid: Grid, body: &Body, depths: &[f64]) {
    let p = pressure(&grid);
    // A cell edge (y = 0), a cell centre, and in between.
    for y in [0.0, grid.y(5), 0.237] {
        let section = Section::XzPlane {
            y,
            depths: depths.to_vec(),
        };
        let field = stresses(&grid, &p, body, &section).unwrap();
        for (k, &z) in depths.iter().enumerate() {
            let expected = direct(&grid, &p, body, y, z);
            let peak = expected
                .iter()
                .flatten()
                .fold(0.0f64, |m, v| m.max(v.abs()));
            let mut worst = 0.0f64;
            for (c, e) in expected.iter().enumerate() {
                for (i, v) in e.iter().enumerate() {
                    let got = field.components[c][field.index(i, 0, k)];
                    worst = worst.max((got - v).abs());
                }
            }
            println!("y {y:.3} z {z}: {:.2e} of the peak {peak:.3}", worst / peak);
            assert!(worst < 1e-12 * peak, "y {y} z {z}: {worst:e} of {peak}");
        }
    }
}

#[test]
fn coating_xz_section_is_the_direct_sum_of_the_table() {
    // h1 = 8 cells: the top layer's depths here decay over more than 10 cells (one
    // box, no bands), as do the substrate's.
    let body = Body::coated(elastic(3.0), 0.8, elastic(1.0));
    check(&body, &[0.0, 0.3, 0.55, 1.2, 2.5]);
}

#[test]
fn soft_coating_xz_section_is_the_direct_sum_of_the_table() {
    let body = Body::coated(elastic(0.2), 0.8, elastic(1.0));
    check(&body, &[0.1, 1.5]);
}

#[test]
fn three_layer_xz_section_is_the_direct_sum_of_the_table() {
    let body = Body::Layered(Stack {
        layers: vec![
            Ply {
                material: elastic(3.0),
                thickness: 0.3,
            },
            Ply {
                material: elastic(0.5),
                thickness: 0.3,
            },
            Ply {
                material: elastic(2.0),
                thickness: 0.4,
            },
        ],
        base: Base::HalfSpace(elastic(1.0)),
    });
    // In the top layer (bands), in the second and third layers and the base.
    check(&body, &[0.05, 0.45, 1.1, 1.5, 3.0]);
}

#[test]
fn rigid_based_xz_section_is_the_direct_sum_of_the_table() {
    let body = Body::Layered(Stack {
        layers: vec![Ply {
            material: elastic(2.0),
            thickness: 2.0,
        }],
        base: Base::Rigid(thirdbody::body::layered::BaseContact::Bonded),
    });
    check(&body, &[0.2, 1.4]);
}

/// A 1.5-cell layer (on a 0.05 grid) four times stiffer than the soft layer below it,
/// on a half-space.
fn thin_topped_stack() -> Body {
    Body::Layered(Stack {
        layers: vec![
            Ply {
                material: elastic(4.0),
                thickness: 0.075,
            },
            Ply {
                material: elastic(0.5),
                thickness: 0.3,
            },
        ],
        base: Base::HalfSpace(elastic(1.0)),
    })
}

/// A window wide enough (72 cells) that the row sums its short waves in two families
/// on two boxes (above and below a second split), with depths summed in bands (in
/// the 1.5-cell top layer and just below it), deep ones, and one deeper than the
/// rows serve (twice the offsets' reach, about 4: summed per depth).
#[test]
fn wide_window_xz_section_is_the_direct_sum_of_the_table() {
    let body = thin_topped_stack();
    let grid = Grid::centred(72, 40, 0.05, [0.0, 0.0]).unwrap();
    check_on(grid, &body, &[0.0, 0.05, 0.2, 0.9, 1.6, 9.0]);
}

/// Top layers thinner than a cell (the sub-cell split at the surface and in the
/// layer: a stiff one a third of a cell thick, a soft one a fiftieth), on the wide
/// window: the split's capped and tapered top band on small boxes, the rest of its
/// remainder from the rows.
#[test]
fn sub_cell_layers_xz_section_is_the_direct_sum_of_the_table() {
    let grid = Grid::centred(72, 40, 0.05, [0.0, 0.0]).unwrap();
    for (young, h1) in [(30.0, 0.05 / 3.0), (0.1, 0.001)] {
        let body = Body::coated(elastic(young), h1, elastic(1.0));
        check_on(grid, &body, &[0.0, 0.5 * h1, 0.05, 0.9]);
    }
}

/// Rows the y pairing meets unevenly: the smallest windows (odd and even, taller than
/// wide), rows outside the window (every source row on one side: no pairs) and on
/// the last row's centre; each against the direct sum of the table at every signed
/// offset.
#[test]
fn uneven_windows_and_rows_are_the_direct_sum_of_the_table() {
    let body = thin_topped_stack();
    for (nx, ny, cell) in [(9, 8, 0.1), (8, 11, 0.1), (12, 8, 0.05)] {
        let grid = Grid::centred(nx, ny, cell, [0.0, 0.0]).unwrap();
        let p = pressure(&grid);
        for y in [0.37, 2.5, -1.0, grid.y(ny - 1)] {
            let depths = [0.0, 0.05, 0.6];
            let section = Section::XzPlane {
                y,
                depths: depths.to_vec(),
            };
            let field = stresses(&grid, &p, &body, &section).unwrap();
            for (k, &z) in depths.iter().enumerate() {
                let expected = direct(&grid, &p, &body, y, z);
                let peak = expected
                    .iter()
                    .flatten()
                    .fold(0.0f64, |m, v| m.max(v.abs()));
                for (c, e) in expected.iter().enumerate() {
                    for (i, v) in e.iter().enumerate() {
                        let got = field.components[c][field.index(i, 0, k)];
                        // The boxes' truncation (see the module's head): 1.3e-12.
                        assert!(
                            (got - v).abs() < 5e-12 * peak,
                            "{nx} x {ny}, y {y}, z {z}, component {c}: {got} against {v}"
                        );
                    }
                }
            }
        }
    }
}

/// A depth's stresses do not depend on the other depths of its section: the rows
/// are built from the lattice, the stack and the pressure only (the Python package
/// computes a section a few depths at a time and must equal the CLI's).
#[test]
fn a_depth_does_not_depend_on_the_other_depths_of_its_section() {
    let body = thin_topped_stack();
    let grid = Grid::centred(72, 40, 0.05, [0.0, 0.0]).unwrap();
    let p = pressure(&grid);
    let depths = [0.0, 0.05, 0.2, 0.6, 0.9, 1.6];
    let all = stresses(
        &grid,
        &p,
        &body,
        &Section::XzPlane {
            y: 0.0,
            depths: depths.to_vec(),
        },
    )
    .unwrap();
    for part in [&depths[..1], &depths[1..3], &depths[3..]] {
        let some = stresses(
            &grid,
            &p,
            &body,
            &Section::XzPlane {
                y: 0.0,
                depths: part.to_vec(),
            },
        )
        .unwrap();
        for (k, &z) in part.iter().enumerate() {
            let k_all = depths.iter().position(|&d| d == z).unwrap();
            for c in 0..6 {
                for i in 0..grid.nx() {
                    assert_eq!(
                        some.components[c][some.index(i, 0, k)].to_bits(),
                        all.components[c][all.index(i, 0, k_all)].to_bits(),
                        "z {z}, component {c}, column {i}"
                    );
                }
            }
        }
    }
}
