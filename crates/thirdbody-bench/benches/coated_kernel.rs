//! Speed of a coating (a stack of one layer): the influence kernel on a 256 x 256 grid
//! (target: under 1 s) on the grid of the paper's Fig. 7 case (window
//! 0.12 R wide, cell = 0.12 / 256 R, E1/E2 = 3, coating thickness h1' = 0.001 and
//! 0.02, R = E2 = 1), and the whole Fig. 7 solve on 256 x 256 cells with the
//! automatic window (Q' = 5e-6, V' = 1e-3, nu1 = nu2 = 0.3, C' = 0.02, sigmoid law
//! delta = 0.5, p0' = 0.005), kernel included: each iteration changes the
//! thickness in its last bits so that the kernel cache does not hide its cost.

use criterion::{criterion_group, criterion_main, Criterion};
use thirdbody::{
    solve, Body, Case, ComplianceLaw, Elastic, GridSpec, Integration, Layer, Loading, Slider,
    SolverParams, Units,
};

const COATING: Elastic = Elastic {
    young: 3.0,
    poisson: 0.3,
};
const SUBSTRATE: Elastic = Elastic {
    young: 1.0,
    poisson: 0.3,
};

fn coated_kernel_256(c: &mut Criterion) {
    let cell = 0.12 / 256.0;
    let mut group = c.benchmark_group("coated_kernel_256x256");
    group.sample_size(10);
    for thickness in [0.001, 0.02] {
        group.bench_function(format!("h1={thickness}"), |b| {
            let body = Body::coated(COATING, thickness, SUBSTRATE).model();
            b.iter(|| {
                body.surface_kernel(cell, 256, 256, f64::INFINITY, true)
                    .unwrap()
            })
        });
    }
    group.finish();
}

fn fig7_case(thickness: f64) -> Case {
    Case {
        slider: Slider::Sphere { radius: 1.0 },
        body: Body::coated(COATING, thickness, SUBSTRATE),
        layer: Some(Layer::maxwell(
            0.02,
            1.0,
            ComplianceLaw::Sigmoid {
                delta: 0.5,
                p0: 0.005,
            },
            Integration::Exact,
        )),
        loading: Loading {
            normal_load: 5e-6,
            velocity: Some(1e-3),
            reference_distance: None,
        },
        grid: GridSpec {
            cells: [256, 256],
            half_width: None,
            centre: None,
        },
        units: Units::Dimensionless,
    }
}

fn coated_fig7_solve_256(c: &mut Criterion) {
    let mut group = c.benchmark_group("coated_fig7_solve_256x256");
    group.sample_size(10);
    for thickness in [0.001f64, 0.02] {
        let mut bump = 0u64;
        group.bench_function(format!("h1={thickness}"), |b| {
            b.iter(|| {
                bump += 1;
                let h = f64::from_bits(thickness.to_bits() + bump);
                solve(&fig7_case(h), &SolverParams::default()).unwrap()
            })
        });
    }
    group.finish();
}

criterion_group!(benches, coated_kernel_256, coated_fig7_solve_256);
criterion_main!(benches);
