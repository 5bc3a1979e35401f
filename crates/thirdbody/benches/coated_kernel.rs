//! Speed of the coated-body influence kernel on a 256 x 256 grid (issue 3,
//! acceptance 6: under 1 s), on the grid of the paper's Fig. 7 case: window
//! 0.12 R wide, cell = 0.12 / 256 R, E1/E2 = 3, coating thickness h1' = 0.001 and
//! 0.02 (dimensionless, R = E2 = 1).

use criterion::{criterion_group, criterion_main, Criterion};
use thirdbody::body::coated::coated_surface_kernel;
use thirdbody::Elastic;

fn coated_kernel_256(c: &mut Criterion) {
    let coating = Elastic {
        young: 3.0,
        poisson: 0.3,
    };
    let substrate = Elastic {
        young: 1.0,
        poisson: 0.3,
    };
    let cell = 0.12 / 256.0;
    let mut group = c.benchmark_group("coated_kernel_256x256");
    group.sample_size(10);
    for thickness in [0.001, 0.02] {
        group.bench_function(format!("h1={thickness}"), |b| {
            b.iter(|| coated_surface_kernel(coating, thickness, substrate, cell, 256, 256).unwrap())
        });
    }
    group.finish();
}

criterion_group!(benches, coated_kernel_256);
criterion_main!(benches);
