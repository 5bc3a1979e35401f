//! The speed-up of a sweep on 2 cores. The paper's Fig. 8 sweep
//! (`examples/sweeps/paper_fig8.toml`: 8 velocities x 3 sigmoid laws + the linear law,
//! 32 cases at 128 x 128) is run into a fresh folder with 1 and with 2 threads; each
//! iteration solves every case and writes the records, results.csv and the plot. The
//! case checks of `Sweep::from_file` are done once, outside the timing.

use std::hint::black_box;
use std::path::Path;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BatchSize, Criterion};
use thirdbody_cli::sweep::{run, RunOptions, Sweep};

fn bench(c: &mut Criterion) {
    let case = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/sweeps/paper_fig8.toml");
    let sweep = Sweep::from_file(&case, &[]).expect("valid sweep");
    let mut g = c.benchmark_group("sweep_fig8_32_cases_128");
    g.sample_size(10).measurement_time(Duration::from_secs(30));
    for threads in [1, 2] {
        g.bench_function(format!("threads_{threads}"), |b| {
            b.iter_batched(
                || tempfile::tempdir().expect("temporary folder"),
                |dir| {
                    let options = RunOptions {
                        out: dir.path().join("sweep"),
                        shard: None,
                        threads: Some(threads),
                        retry_failed: false,
                    };
                    let report = run(&sweep, &options, &|_| {}).expect("sweep runs");
                    assert_eq!(report.computed, 32);
                    black_box(report);
                    dir
                },
                BatchSize::PerIteration,
            )
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
