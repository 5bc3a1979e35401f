//! Solve times of 4,096-cell line contacts (plane strain), kernel set-up included,
//! automatic window, residual 1e-10: a cylinder (R = 1, Q = 1e-3 per unit length)
//! on an elastic half-space (E = 1, nu = 0.3), on a Zener body sliding steadily
//! (E_g = 10, E_0 = 1, tau = 1, V = 0.0042: V tau / a0 = 0.12, near the friction's
//! maximum), on a coating as thick as the contact (E1 = 10 on E2 = 1), and with the
//! paper's nonlinear Maxwell layer (C' = 0.02, T = 1, sigmoid delta = 0.5,
//! p0' = 0.005, V' = 0.01) on the elastic half-space; one run gives every median
//! and their ratios.

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use std::time::Duration;
use thirdbody::body::{SolidRheology, ViscoelasticHalfSpace};
use thirdbody::*;

fn cylinder_on(body: Body) -> Case {
    Case {
        slider: Slider::Cylinder { radius: 1.0 },
        body,
        layer: None,
        loading: Loading {
            normal_load: 1e-3,
            velocity: None,
            reference_distance: None,
        },
        grid: GridSpec {
            cells: [4096, 1],
            half_width: None,
            centre: None,
        },
        units: Units::Dimensionless,
    }
}

fn elastic(young: f64) -> Elastic {
    Elastic {
        young,
        poisson: 0.3,
    }
}

fn bench(c: &mut Criterion) {
    let params = SolverParams::default();
    let homogeneous = cylinder_on(Body::Homogeneous(elastic(1.0)));
    let mut zener = cylinder_on(Body::Viscoelastic(ViscoelasticHalfSpace {
        rheology: SolidRheology::Zener {
            glassy_modulus: 10.0,
            relaxed_modulus: 1.0,
            relaxation_time: 1.0,
        },
        poisson: 0.3,
    }));
    zener.loading.velocity = Some(0.0042);
    let coated = cylinder_on(Body::coated(elastic(10.0), 0.035, elastic(1.0)));
    let mut layer = homogeneous.clone();
    layer.layer = Some(Layer::maxwell(
        0.02,
        1.0,
        ComplianceLaw::Sigmoid {
            delta: 0.5,
            p0: 0.005,
        },
        Integration::Exact,
    ));
    layer.loading.velocity = Some(0.01);
    let mut g = c.benchmark_group("line_4096");
    g.sample_size(20).measurement_time(Duration::from_secs(10));
    for (name, case) in [
        ("elastic", &homogeneous),
        ("viscoelastic", &zener),
        ("coated", &coated),
        ("layer", &layer),
    ] {
        g.bench_function(name, |b| {
            b.iter(|| black_box(solve(case, &params).unwrap()))
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
