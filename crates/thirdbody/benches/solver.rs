//! Solve times of the paper's Fig. 3 case at 256 x 256 and of
//! the layer-free Hertz case (window side 0.048, Q' = 5e-6, residual 1e-10) at
//! 256 x 256 and 1024 x 1024, including the kernel set-up. The cases are the bundled
//! `examples/paper_fig3.toml` and `examples/hertz_benchmark.toml`.

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use std::time::Duration;
use thirdbody::*;

#[path = "../tests/bundled/mod.rs"]
mod bundled;
use bundled::bundled;

fn bench(c: &mut Criterion) {
    let params = SolverParams::default();
    let mut g = c.benchmark_group("solve");
    g.sample_size(10).measurement_time(Duration::from_secs(20));
    g.bench_function("paper_fig3_256", |b| {
        let case = bundled("paper_fig3", 256);
        b.iter(|| black_box(solve(&case, &params).unwrap()))
    });
    g.bench_function("hertz_256", |b| {
        let case = bundled("hertz_benchmark", 256);
        b.iter(|| black_box(solve(&case, &params).unwrap()))
    });
    g.bench_function("hertz_1024", |b| {
        let case = bundled("hertz_benchmark", 1024);
        b.iter(|| black_box(solve(&case, &params).unwrap()))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
