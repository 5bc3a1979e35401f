//! Subsurface-stress speed: the XZ section of 256 points
//! along x by 128 depths under a 256 x 256 Hertz pressure field, and a
//! 128 x 128 x 64 block; the same XZ section of coated bodies (a/1000 to 1000 a
//! thick) and of stacks of three and five layers.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use thirdbody::body::layered::{Base, Ply, Stack};
use thirdbody::stress::{stresses, Section};
use thirdbody::{Body, Elastic, Grid};

/// Hertz pressure `sqrt(1 - r^2/a^2)` at cell centres, contact radius `a`.
fn hertz(grid: &Grid, a: f64) -> Vec<f64> {
    let mut p = vec![0.0; grid.len()];
    for j in 0..grid.ny() {
        for i in 0..grid.nx() {
            let r2 = grid.x(i).powi(2) + grid.y(j).powi(2);
            p[grid.index(i, j)] = (1.0 - r2 / (a * a)).max(0.0).sqrt();
        }
    }
    p
}

fn bench(c: &mut Criterion) {
    let body = Body::Homogeneous(Elastic {
        young: 1.0,
        poisson: 0.3,
    });
    let mut group = c.benchmark_group("stress");
    group.sample_size(10);

    // Window = 2 contact radii each side of the centre.
    let grid = Grid::centred(256, 256, 1.0 / 64.0, [0.0, 0.0]).unwrap();
    let p = hertz(&grid, 1.0);
    let depths: Vec<f64> = (0..128).map(|k| 2.0 * k as f64 / 127.0).collect();
    let section = Section::XzPlane { y: 0.0, depths };
    group.bench_function("xz_256x128_from_256x256", |b| {
        b.iter(|| black_box(stresses(&grid, &p, &body, &section).unwrap()))
    });

    let grid = Grid::centred(128, 128, 1.0 / 32.0, [0.0, 0.0]).unwrap();
    let p = hertz(&grid, 1.0);
    let depths: Vec<f64> = (0..64).map(|k| 2.0 * k as f64 / 63.0).collect();
    let section = Section::Block { depths };
    group.bench_function("block_128x128x64", |b| {
        b.iter(|| black_box(stresses(&grid, &p, &body, &section).unwrap()))
    });

    // Coated body (E1/E2 = 3): a thick coating (h1 = a/2) and a thin one (h1 = a/40,
    // the paper's Fig. 11a ratio), XZ section as above and the interface plane; the
    // ends of the range of coatings, a/1000 thick (1/16 of a cell: the sub-cell split
    // at the surface) and 1000 a (far thicker than the window), the XZ section.
    let grid = Grid::centred(256, 256, 1.0 / 64.0, [0.0, 0.0]).unwrap();
    let p = hertz(&grid, 1.0);
    let depths: Vec<f64> = (0..128).map(|k| 2.0 * k as f64 / 127.0).collect();
    let xz = Section::XzPlane { y: 0.0, depths };
    for (name, h1, interface) in [
        ("thick", 0.5, true),
        ("thin", 0.025, true),
        ("micro", 1e-3, false),
        ("kilo", 1e3, false),
    ] {
        let coated = Body::coated(
            Elastic {
                young: 3.0,
                poisson: 0.3,
            },
            h1,
            Elastic {
                young: 1.0,
                poisson: 0.3,
            },
        );
        group.bench_function(format!("coated_{name}_xz_256x128_from_256x256"), |b| {
            b.iter(|| black_box(stresses(&grid, &p, &coated, &xz).unwrap()))
        });
        if interface {
            let interface = Section::Interface {
                index: 0,
                side: thirdbody::stress::Side::Above,
            };
            group.bench_function(format!("coated_{name}_interface_256x256"), |b| {
                b.iter(|| black_box(stresses(&grid, &p, &coated, &interface).unwrap()))
            });
        }
    }

    // Stacks of three and five layers on a half-space (E from 0.5 to 4, total
    // thickness a / 2 and a, layers from a / 40 to a / 4), the XZ section as above.
    let elastic = |young| Elastic {
        young,
        poisson: 0.3,
    };
    let stack = |plies: &[(f64, f64)]| {
        Body::Layered(Stack {
            layers: plies
                .iter()
                .map(|&(young, thickness)| Ply {
                    material: elastic(young),
                    thickness,
                })
                .collect(),
            base: Base::HalfSpace(elastic(1.0)),
        })
    };
    let three = stack(&[(3.0, 0.025), (0.5, 0.225), (2.0, 0.25)]);
    let five = stack(&[
        (4.0, 0.025),
        (1.5, 0.1),
        (0.5, 0.125),
        (2.0, 0.25),
        (3.0, 0.5),
    ]);
    for (name, body) in [("three", three), ("five", five)] {
        group.bench_function(format!("layers_{name}_xz_256x128_from_256x256"), |b| {
            b.iter(|| black_box(stresses(&grid, &p, &body, &xz).unwrap()))
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
