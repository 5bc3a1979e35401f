//! Issue 2, acceptance 6: solve times of the paper's Fig. 3 case at 256 x 256 and of
//! the layer-free Hertz case (window side 0.048, Q' = 5e-6, residual 1e-10) at
//! 256 x 256 and 1024 x 1024, including the kernel set-up.

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use std::time::Duration;
use thirdbody::*;

fn sphere(n: usize) -> Case {
    Case {
        slider: Slider::Sphere { radius: 1.0 },
        body: Body::Homogeneous(Elastic {
            young: 1.0,
            poisson: 0.3,
        }),
        layer: None,
        loading: Loading {
            normal_load: 5e-6,
            velocity: None,
        },
        grid: GridSpec {
            cells: [n, n],
            half_width: Some([0.024, 0.024]),
            centre: None,
        },
        units: Units::Dimensionless,
    }
}

/// The paper's Fig. 3 case (examples/paper_fig3.toml).
fn paper_fig3(n: usize) -> Case {
    let mut c = sphere(n);
    c.grid.half_width = None;
    c.layer = Some(Layer {
        compliance: 0.02,
        relaxation_time: 1.0,
        law: ComplianceLaw::Sigmoid {
            delta: 0.5,
            p0: 0.001,
        },
        integration: Integration::Exact,
    });
    c.loading.velocity = Some(1e-3);
    c
}

fn bench(c: &mut Criterion) {
    let params = SolverParams::default();
    let mut g = c.benchmark_group("solve");
    g.sample_size(10).measurement_time(Duration::from_secs(20));
    g.bench_function("paper_fig3_256", |b| {
        let case = paper_fig3(256);
        b.iter(|| black_box(solve(&case, &params).unwrap()))
    });
    g.bench_function("hertz_256", |b| {
        let case = sphere(256);
        b.iter(|| black_box(solve(&case, &params).unwrap()))
    });
    g.bench_function("hertz_1024", |b| {
        let case = sphere(1024);
        b.iter(|| black_box(solve(&case, &params).unwrap()))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
