//! A 10-branch Prony layer at 256 x 256 against the paper's
//! Maxwell layer on the same case (paper Fig. 3: sphere, Q' = 5e-6, sigmoid law
//! delta = 0.5, p0' = 0.001, V' = 1e-3), each solve including its kernel set-up.

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use std::time::Duration;
use thirdbody::*;

#[path = "../../thirdbody/tests/bundled/mod.rs"]
mod bundled;

fn fig3(n: usize) -> Case {
    bundled::bundled("paper_fig3", n)
}

/// The Fig. 3 case with a Prony layer of the same zero-pressure compliance 0.02:
/// glassy 0.005 and ten branches of 0.0015 with times from 0.1 to 1e3, and a flow
/// of viscosity 1 / 0.02 (the Maxwell layer's T / C0).
fn prony(n: usize) -> Case {
    let mut case = fig3(n);
    let layer = case.layer.as_mut().unwrap();
    layer.rheology = Rheology::Prony {
        glassy_compliance: 0.005,
        branches: (0..10)
            .map(|k| RetardationBranch {
                compliance: 0.0015,
                time: 0.1 * 10f64.powf(k as f64 * 4.0 / 9.0),
            })
            .collect(),
        viscosity: Some(1.0 / 0.02),
    };
    case
}

fn bench(c: &mut Criterion) {
    let params = SolverParams::default();
    let mut g = c.benchmark_group("rheology");
    g.sample_size(10).measurement_time(Duration::from_secs(20));
    g.bench_function("maxwell_256", |b| {
        let case = fig3(256);
        b.iter(|| black_box(solve(&case, &params).unwrap()))
    });
    g.bench_function("prony10_256", |b| {
        let case = prony(256);
        b.iter(|| black_box(solve(&case, &params).unwrap()))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
