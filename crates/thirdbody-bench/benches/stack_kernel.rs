//! Speed of the stack body's surface kernel on 1024 x 1024 cells (target: under
//! 1 s on two cores): one coating a cell thick; eight alternating layers 1e-3 to
//! 1e3 cells thick with E ratios 1e3 on a soft half-space; a soft film on an elastic
//! layer bonded to a rigid base.

use criterion::{criterion_group, criterion_main, Criterion};
use thirdbody::body::layered::{Base, BaseContact, Ply, Stack};
use thirdbody::body::StackBody;
use thirdbody::Elastic;

fn ply(young: f64, poisson: f64, thickness: f64) -> Ply {
    Ply {
        material: Elastic { young, poisson },
        thickness,
    }
}

fn stack_kernel_1024(c: &mut Criterion) {
    let thickness = [1e-3, 1e3, 0.1, 10.0, 1.0, 1e2, 0.01, 1e3];
    let stacks = [
        (
            "one-layer",
            Stack {
                layers: vec![ply(10.0, 0.25, 1.0)],
                base: Base::HalfSpace(Elastic {
                    young: 1.0,
                    poisson: 0.3,
                }),
            },
        ),
        (
            "eight-layers",
            Stack {
                layers: thickness
                    .iter()
                    .enumerate()
                    .map(|(i, &t)| ply(if i % 2 == 0 { 1e3 } else { 1.0 }, 0.3, t))
                    .collect(),
                base: Base::HalfSpace(Elastic {
                    young: 1e-3,
                    poisson: 0.3,
                }),
            },
        ),
        (
            "film-on-rigid",
            Stack {
                layers: vec![ply(1e-3, 0.45, 1e-3), ply(1.0, 0.3, 5.0)],
                base: Base::Rigid(BaseContact::Bonded),
            },
        ),
    ];
    let mut group = c.benchmark_group("stack_kernel_1024x1024");
    group.sample_size(10);
    for (name, stack) in stacks {
        let body = StackBody { stack };
        group.bench_function(name, |b| {
            b.iter(|| body.surface_kernel_quadrant(1.0, 1024, 1024).unwrap())
        });
    }
    group.finish();
}

criterion_group!(benches, stack_kernel_1024);
criterion_main!(benches);
