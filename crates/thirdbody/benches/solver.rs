//! Issue 2, acceptance 6: solve times of the paper's Fig. 3 case at 256 x 256 and of
//! the layer-free Hertz case (window side 0.048, Q' = 5e-6, residual 1e-10) at
//! 256 x 256 and 1024 x 1024, including the kernel set-up. The cases are the bundled
//! `examples/paper_fig3.toml` and `examples/hertz_benchmark.toml`.

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use std::time::Duration;
use thirdbody::*;

/// A bundled case file with `n x n` cells.
fn bundled(name: &str, n: usize) -> Case {
    let path = format!("{}/../../examples/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).expect("bundled example");
    let mut no_maps = |_: &str, _: f64| -> Result<HeightMap> { unreachable!("no height map") };
    let mut case = thirdbody::case_file::parse_case_file(&text, &mut no_maps)
        .expect("valid example")
        .case;
    case.grid.cells = [n, n];
    case
}

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
