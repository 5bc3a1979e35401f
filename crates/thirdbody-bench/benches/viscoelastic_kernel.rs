//! Speed of the steady-sliding kernel of a viscoelastic half-space (target: a
//! 10-branch body on 256 x 256 cells under 0.5 s): glassy compliance 0.2 and ten
//! Kelvin–Voigt branches of compliance 0.1 with retardation times 1e-4 to 1e5, at
//! speed 1 on cells of 1/256 (creep lengths from 0.0256 cells to 2.6e7 cells), and
//! the Zener body of one branch on the same cells.

use criterion::{criterion_group, criterion_main, Criterion};
use thirdbody::body::viscoelastic::{steady_sliding_kernel, CreepBranch, CreepSeries};

fn series(branches: usize) -> CreepSeries {
    CreepSeries {
        glassy: 0.2,
        branches: (0..branches)
            .map(|k| CreepBranch {
                compliance: 0.1,
                retardation_time: 10f64.powi(k as i32 - 4),
            })
            .collect(),
    }
}

fn viscoelastic_kernel_256(c: &mut Criterion) {
    let mut group = c.benchmark_group("viscoelastic_kernel_256x256");
    group.sample_size(10);
    for branches in [1, 10] {
        let s = series(branches);
        group.bench_function(format!("{branches}_branches"), |b| {
            b.iter(|| steady_sliding_kernel(&s, 1.0 / 256.0, 256, 256, 1.0).unwrap())
        });
    }
    group.finish();
}

criterion_group!(benches, viscoelastic_kernel_256);
criterion_main!(benches);
