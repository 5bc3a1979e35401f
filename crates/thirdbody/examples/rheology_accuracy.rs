//! The friction coefficient of the creep-form layer rheologies against the
//! grid-converged value, over creep lengths V tau from far below a cell to far above
//! the contact: for each preset and V, mu and the energy-balance friction at the
//! default 128^2 against a 512^2 solve (rigid base, E = 1e6, or elastic body,
//! E = 1), for Kelvin–Voigt, Zener, Burgers, a 10-branch Prony series, fractional
//! Zener and a box spectrum. Sphere R = 1, Q = 5e-6, linear law, automatic window. Prints one
//! line per case: V, V tau / h, mu(128), mu(512), their relative difference, and the
//! energy balance (mu_dissipation - mu) / mu at both grids.
//!
//!     cargo run --release -p thirdbody --example rheology_accuracy [fine cells]

use thirdbody::*;

fn case(rheology: Rheology, young: f64, velocity: f64, cells: usize) -> Case {
    Case {
        slider: Slider::Sphere { radius: 1.0 },
        body: Body::Homogeneous(Elastic {
            young,
            poisson: 0.3,
        }),
        layer: Some(Layer {
            rheology,
            law: ComplianceLaw::Linear,
            integration: Integration::Exact,
        }),
        loading: Loading {
            normal_load: 5e-6,
            velocity: Some(velocity),
            reference_distance: None,
        },
        grid: GridSpec {
            cells: [cells, cells],
            half_width: None,
            centre: None,
        },
        units: Units::Dimensionless,
    }
}

fn main() {
    let fine: usize = std::env::args()
        .nth(1)
        .map_or(512, |s| s.parse().expect("fine cells"));
    let presets = [
        (
            "kelvin_voigt",
            Rheology::KelvinVoigt {
                compliance: 0.02,
                retardation_time: 1.0,
            },
        ),
        (
            "zener",
            Rheology::Zener {
                glassy_compliance: 0.01,
                compliance: 0.01,
                retardation_time: 1.0,
            },
        ),
        (
            "burgers",
            Rheology::Burgers {
                glassy_compliance: 0.01,
                relaxation_time: 100.0,
                compliance: 0.01,
                retardation_time: 1.0,
            },
        ),
        (
            "prony_10",
            Rheology::Prony {
                glassy_compliance: 0.005,
                branches: (0..10)
                    .map(|k| RetardationBranch {
                        compliance: 0.0015,
                        time: 0.2 * 10f64.powf(k as f64 * 4.0 / 9.0),
                    })
                    .collect(),
                viscosity: None,
            },
        ),
        (
            "fractional_zener",
            Rheology::FractionalZener {
                glassy_compliance: 0.01,
                compliance: 0.01,
                retardation_time: 1.0,
                order: 0.5,
                branch_count: None,
            },
        ),
        (
            "box_spectrum",
            Rheology::BoxSpectrum {
                glassy_compliance: 0.005,
                compliance: 0.015,
                shortest_time: 0.2,
                longest_time: 2e3,
            },
        ),
    ];
    let params = SolverParams {
        tolerance: 1e-11,
        ..SolverParams::default()
    };
    for (body, young) in [("rigid", 1e6), ("elastic", 1.0)] {
        for (name, rheology) in &presets {
            for v in [1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 1e-1, 1.0] {
                let coarse = solve(&case(rheology.clone(), young, v, 128), &params);
                let finer = solve(&case(rheology.clone(), young, v, fine), &params);
                match (coarse, finer) {
                    (Ok(c), Ok(f)) => {
                        let (sc, sf) = (c.summary(), f.summary());
                        let (mc, mf) = (sc.friction_coefficient, sf.friction_coefficient);
                        println!(
                            "{body:7} {name:12} V {v:7.0e} Vtau/h {:8.2e} a/h {:5.1}: mu {mc:.5e} \
                             fine {mf:.5e} err {:+.2e}; energy {:+.2e} fine {:+.2e}",
                            v / sc.cell_size,
                            0.5 * (sc.contact_x_max - sc.contact_x_min) / sc.cell_size,
                            mc / mf - 1.0,
                            sc.dissipation_friction_coefficient / mc - 1.0,
                            sf.dissipation_friction_coefficient / mf - 1.0,
                        );
                    }
                    (c, f) => println!(
                        "{body} {name} V {v:e}: {:?} {:?}",
                        c.err().map(|e| e.to_string()),
                        f.err().map(|e| e.to_string())
                    ),
                }
            }
        }
    }
}
