//! Stress sections by DC-FFT against direct summation of Love's rectangle stresses
//! over the loaded cells (the obviously-correct O(n^2) reference), and bad requests.
// Index loops over the six stress components read best as they are.
#![allow(clippy::needless_range_loop)]

use thirdbody::stress::{love_rectangle_stresses, stresses, Section};
use thirdbody::{Body, Elastic, Grid};

const MAT: Elastic = Elastic {
    young: 2.0,
    poisson: 0.25,
};

/// A lopsided pressure patch with no symmetry, on part of the grid.
fn patch(grid: &Grid) -> Vec<f64> {
    let mut p = vec![0.0; grid.len()];
    for j in 0..grid.ny() {
        for i in 0..grid.nx() {
            let (x, y) = (grid.x(i) - 0.1, grid.y(j) + 0.05);
            let r2 = (x / 0.5).powi(2) + (y / 0.35).powi(2);
            if r2 < 1.0 {
                p[grid.index(i, j)] = (1.0 - r2).sqrt() * (1.0 + 0.6 * x + 0.3 * x * y);
            }
        }
    }
    p
}

fn direct(grid: &Grid, p: &[f64], x: f64, y: f64, z: f64) -> [f64; 6] {
    let mut s = [0.0; 6];
    let a = 0.5 * grid.cell();
    for j in 0..grid.ny() {
        for i in 0..grid.nx() {
            let q = p[grid.index(i, j)];
            if q != 0.0 {
                let k = love_rectangle_stresses(MAT, a, a, x - grid.x(i), y - grid.y(j), z);
                for c in 0..6 {
                    s[c] += q * k[c];
                }
            }
        }
    }
    s
}

#[test]
fn sections_equal_direct_summation() {
    let grid = Grid::centred(20, 14, 0.1, [0.05, -0.02]).unwrap();
    let p = patch(&grid);
    let body = Body::Homogeneous(MAT);
    let depths = vec![0.0, 0.03, 0.2, 0.9];
    let check = |field: &thirdbody::stress::StressField, on_row_edge: bool| {
        for (k, &z) in field.zs.iter().enumerate() {
            for (j, &y) in field.ys.iter().enumerate() {
                for (i, &x) in field.xs.iter().enumerate() {
                    let reference = if z == 0.0 && on_row_edge {
                        // On a row edge the surface stresses jump: the mean of the
                        // two sides is reported.
                        let (lo, hi) = (
                            direct(&grid, &p, x, y - 1e-9 * grid.cell(), z),
                            direct(&grid, &p, x, y + 1e-9 * grid.cell(), z),
                        );
                        std::array::from_fn(|c| 0.5 * (lo[c] + hi[c]))
                    } else {
                        direct(&grid, &p, x, y, z)
                    };
                    let n = field.index(i, j, k);
                    for c in 0..6 {
                        let v = field.components[c][n];
                        assert!(
                            (v - reference[c]).abs() < if on_row_edge { 1e-7 } else { 1e-12 },
                            "c {c} at ({x}, {y}, {z}): {v} vs {}",
                            reference[c]
                        );
                    }
                }
            }
        }
    };
    // An XZ plane through a cell-centre row, one between rows and one off-centre.
    for (y, on_row_edge) in [
        (grid.y(6), false),
        (grid.y(6) + 0.5 * grid.cell(), true),
        (0.0123, false),
    ] {
        let field = stresses(
            &grid,
            &p,
            &body,
            &Section::XzPlane {
                y,
                depths: depths.clone(),
            },
        )
        .unwrap();
        assert_eq!((field.xs.len(), field.ys.len(), field.zs.len()), (20, 1, 4));
        check(&field, on_row_edge);
    }
    let field = stresses(
        &grid,
        &p,
        &body,
        &Section::Block {
            depths: depths.clone(),
        },
    )
    .unwrap();
    assert_eq!(
        (field.xs.len(), field.ys.len(), field.zs.len()),
        (20, 14, 4)
    );
    check(&field, false);
    let field = stresses(&grid, &p, &body, &Section::Plane { z: 0.07 }).unwrap();
    check(&field, false);
}

#[test]
fn xz_plane_equals_the_matching_row_of_a_block() {
    let grid = Grid::centred(16, 12, 0.2, [0.0, 0.0]).unwrap();
    let p = patch(&grid);
    let body = Body::Homogeneous(MAT);
    let depths = vec![0.0, 0.15, 0.6];
    let block = stresses(
        &grid,
        &p,
        &body,
        &Section::Block {
            depths: depths.clone(),
        },
    )
    .unwrap();
    let j = 5;
    let xz = stresses(
        &grid,
        &p,
        &body,
        &Section::XzPlane {
            y: grid.y(j),
            depths,
        },
    )
    .unwrap();
    for k in 0..3 {
        for i in 0..16 {
            for c in 0..6 {
                let (a, b) = (
                    xz.components[c][xz.index(i, 0, k)],
                    block.components[c][block.index(i, j, k)],
                );
                assert!((a - b).abs() < 1e-12, "{a} vs {b}");
            }
        }
    }
}

#[test]
fn bad_requests_name_the_field() {
    let grid = Grid::centred(8, 8, 0.1, [0.0, 0.0]).unwrap();
    let p = vec![1.0; grid.len()];
    let body = Body::Homogeneous(MAT);
    let err = |s: Section| stresses(&grid, &p, &body, &s).unwrap_err().to_string();
    let e = err(Section::XzPlane {
        y: 0.0,
        depths: vec![0.1, -0.2],
    });
    assert!(e.contains("stress.depths[1]") && e.contains(">= 0"), "{e}");
    let e = err(Section::Block { depths: vec![] });
    assert!(
        e.contains("stress.depths") && e.contains("at least one depth"),
        "{e}"
    );
    let e = err(Section::XzPlane {
        y: 0.0,
        depths: vec![],
    });
    assert!(e.contains("stress.depths"), "{e}");
    let e = err(Section::Plane { z: f64::NAN });
    assert!(e.contains("stress.z") && e.contains("finite"), "{e}");
    let e = err(Section::Block {
        depths: vec![f64::INFINITY],
    });
    assert!(e.contains("stress.depths[0]"), "{e}");
    let e = err(Section::XzPlane {
        y: f64::NAN,
        depths: vec![0.1],
    });
    assert!(e.contains("stress.y"), "{e}");
    // Pressure of the wrong size, or not finite.
    let e = stresses(&grid, &p[1..], &body, &Section::Plane { z: 0.0 })
        .unwrap_err()
        .to_string();
    assert!(e.contains("pressure") && e.contains("64"), "{e}");
    let mut q = p.clone();
    q[3] = f64::NAN;
    let e = stresses(&grid, &q, &body, &Section::Plane { z: 0.0 })
        .unwrap_err()
        .to_string();
    assert!(e.contains("pressure[3]"), "{e}");
    // An interface section needs a coated body: a clear error, not an empty field.
    let e = stresses(
        &grid,
        &p,
        &body,
        &Section::Interface {
            index: 0,
            side: thirdbody::stress::Side::Above,
        },
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("stress.sections") && e.contains("body with interfaces"),
        "{e}"
    );
    // A bad material.
    let bad = Body::Homogeneous(Elastic {
        young: 1.0,
        poisson: 0.5,
    });
    let e = stresses(&grid, &p, &bad, &Section::Plane { z: 0.0 })
        .unwrap_err()
        .to_string();
    assert!(e.contains("poisson"), "{e}");
}

#[test]
fn derived_fields_have_the_field_length() {
    let grid = Grid::centred(10, 10, 0.1, [0.0, 0.0]).unwrap();
    let p = patch(&grid);
    let body = Body::Homogeneous(MAT);
    let f = stresses(
        &grid,
        &p,
        &body,
        &Section::XzPlane {
            y: 0.0,
            depths: vec![0.0, 0.1],
        },
    )
    .unwrap();
    let [s1, s2, s3] = f.principal();
    let (t, vm) = (f.tau1(), f.von_mises());
    assert_eq!(t.len(), 20);
    for n in 0..20 {
        assert!(s1[n] >= s2[n] && s2[n] >= s3[n]);
        assert!((t[n] - 0.5 * (s1[n] - s3[n])).abs() < 1e-15);
        // Von Mises lies between sqrt(3) tau1 and 2 tau1 for any stress state.
        assert!(vm[n] >= 3f64.sqrt() * t[n] - 1e-12 && vm[n] <= 2.0 * t[n] + 1e-12);
    }
}

#[test]
fn surface_normal_stress_is_minus_the_cell_pressure() {
    // On z = 0 only the loaded cell itself carries sigma_z (= -p) at its centre, and
    // there is no shear traction (normal loading).
    let grid = Grid::centred(24, 18, 0.05, [0.0, 0.0]).unwrap();
    let p = patch(&grid);
    let body = Body::Homogeneous(MAT);
    let f = stresses(&grid, &p, &body, &Section::Plane { z: 0.0 }).unwrap();
    for j in 0..grid.ny() {
        for i in 0..grid.nx() {
            let n = f.index(i, j, 0);
            assert!((f.components[2][n] + p[grid.index(i, j)]).abs() < 1e-12);
            assert!(f.components[4][n].abs() < 1e-12 && f.components[5][n].abs() < 1e-12);
        }
    }
}

/// The observed computation reports every depth plane it computes (what the CLI's
/// stress progress bar counts) and gives exactly the unobserved results.
#[test]
fn observed_stresses_count_every_plane_and_equal_the_unobserved_ones() {
    use std::sync::atomic::{AtomicUsize, Ordering};
    use std::sync::Mutex;
    use thirdbody::stress::{SectionKind, StressProgress, StressRequest};

    let grid = Grid::centred(24, 20, 0.1, [0.0, 0.0]).unwrap();
    let p = patch(&grid);
    let body = Body::Homogeneous(MAT);
    let request = StressRequest {
        sections: Some(vec![
            SectionKind::Xz,
            SectionKind::Surface,
            SectionKind::Block,
        ]),
        max_depth: Some(0.5),
        depth_points: 5,
        planes: vec![0.2],
        ..StressRequest::default()
    };
    let announced = AtomicUsize::new(0);
    let done = AtomicUsize::new(0);
    let names = Mutex::new(Vec::new());
    let observed = request
        .compute_observed(&body, &grid, &p, &|e| match e {
            StressProgress::Start { planes } => announced.store(planes, Ordering::SeqCst),
            StressProgress::Section { name, planes } => {
                names.lock().unwrap().push((name.to_string(), planes))
            }
            StressProgress::PlaneDone => {
                done.fetch_add(1, Ordering::SeqCst);
            }
        })
        .unwrap();
    // XZ and block at 5 depths, the surface and the extra plane at one each.
    assert_eq!(announced.into_inner(), 5 + 1 + 5 + 1);
    assert_eq!(done.into_inner(), 12);
    let names = names.into_inner().unwrap();
    assert_eq!(names.len(), 4, "{names:?}");
    assert_eq!(names.iter().map(|n| n.1).sum::<usize>(), 12);
    let plain = request.compute(&body, &grid, &p).unwrap();
    assert_eq!(observed.sections, plain.sections);
}

#[test]
fn layered_requests_name_the_interface_and_the_rigid_base() {
    use thirdbody::body::layered::{Base, BaseContact, Ply, Stack};
    use thirdbody::stress::Side;
    let grid = Grid::centred(16, 16, 0.1, [0.0, 0.0]).unwrap();
    let p = patch(&grid);
    let ply = |thickness: f64| Ply {
        material: MAT,
        thickness,
    };
    // Two layers on a half-space: interfaces 0 and 1; index 2 does not exist.
    let on_half_space = Body::Layered(Stack {
        layers: vec![ply(0.1), ply(0.2)],
        base: Base::HalfSpace(Elastic {
            young: 1.0,
            poisson: 0.3,
        }),
    });
    for index in [0, 1] {
        let section = Section::Interface {
            index,
            side: Side::Below,
        };
        let f = stresses(&grid, &p, &on_half_space, &section).unwrap();
        assert!((f.zs[0] - [0.1, 0.3][index]).abs() < 1e-15, "{:?}", f.zs);
    }
    let e = stresses(
        &grid,
        &p,
        &on_half_space,
        &Section::Interface {
            index: 2,
            side: Side::Above,
        },
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("stress.interface") && e.contains("0 to 1"),
        "{e}"
    );
    // On a rigid base the base's face is no interface, and nothing lies below it.
    let on_rigid = Body::Layered(Stack {
        layers: vec![ply(0.1), ply(0.2)],
        base: Base::Rigid(BaseContact::Bonded),
    });
    let e = stresses(
        &grid,
        &p,
        &on_rigid,
        &Section::Interface {
            index: 1,
            side: Side::Above,
        },
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("stress.interface") && e.contains("0 to 0"),
        "{e}"
    );
    let e = stresses(&grid, &p, &on_rigid, &Section::Plane { z: 0.31 })
        .unwrap_err()
        .to_string();
    assert!(e.contains("rigid base") && !e.contains('\n'), "{e}");
    let at_base = stresses(&grid, &p, &on_rigid, &Section::Plane { z: 0.3 }).unwrap();
    assert!(at_base.components.iter().flatten().all(|v| v.is_finite()));
}
