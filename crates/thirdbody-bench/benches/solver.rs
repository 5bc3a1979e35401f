//! Solve times of the paper's Fig. 3 case at 256 x 256 and of
//! the layer-free Hertz case (window side 0.048, Q' = 5e-6, residual 1e-10) at
//! 256 x 256 and 1024 x 1024, including the kernel set-up. The cases are the bundled
//! `examples/paper_fig3.toml` and `examples/hertz_benchmark.toml`. Then a sphere
//! (R = 1, Q = 1.6667e-4, automatic window) at 256 x 256 on an elastic body
//! (E = 1, nu = 0.3) and on a Zener body sliding steadily (E_g = 10, E_0 = 1,
//! tau = 1, nu = 0.3, V = 0.005): one run gives both medians and their ratio.

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use std::time::Duration;
use thirdbody::body::{SolidRheology, ViscoelasticHalfSpace};
use thirdbody::*;

#[path = "../../thirdbody/tests/bundled/mod.rs"]
mod bundled;
use bundled::bundled;

/// The sphere on `body` at 256 x 256 cells, automatic window.
fn sphere_on(body: Body, velocity: Option<f64>) -> Case {
    Case {
        slider: Slider::Sphere { radius: 1.0 },
        body,
        layer: None,
        loading: Loading {
            normal_load: 1.6667e-4,
            velocity,
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

/// The elastic body of the relaxed modulus and the Zener body sliding at V = 0.005
/// (V tau about 0.1 of the relaxed Hertz radius, near the friction's maximum).
fn elastic_and_viscoelastic() -> (Case, Case) {
    let elastic = sphere_on(
        Body::Homogeneous(Elastic {
            young: 1.0,
            poisson: 0.3,
        }),
        None,
    );
    let zener = sphere_on(
        Body::Viscoelastic(ViscoelasticHalfSpace {
            rheology: SolidRheology::Zener {
                glassy_modulus: 10.0,
                relaxed_modulus: 1.0,
                relaxation_time: 1.0,
            },
            poisson: 0.3,
        }),
        Some(0.005),
    );
    (elastic, zener)
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
    let (elastic, zener) = elastic_and_viscoelastic();
    g.bench_function("elastic_256", |b| {
        b.iter(|| black_box(solve(&elastic, &params).unwrap()))
    });
    g.bench_function("viscoelastic_256", |b| {
        b.iter(|| black_box(solve(&zener, &params).unwrap()))
    });
    g.bench_function("hertz_1024", |b| {
        let case = bundled("hertz_benchmark", 1024);
        b.iter(|| black_box(solve(&case, &params).unwrap()))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
