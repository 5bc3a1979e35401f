//! Every rheology preset over a box of parameters (C'/R from
//! 1e-3 to 1e-1, V' tau from 1e-4 to 1e1, delta 0 to 1, p0' 1e-3 to 1e-2; sphere
//! R = E2 = 1, Q' = 5e-6, sigmoid law, 64^2, automatic window) must converge or stop
//! with a clear diagnosis. Prints the counts per preset and every failure's message.
//!
//!     cargo run --release -p thirdbody --example rheology_box

use thirdbody::*;

fn presets(c: f64, tau: f64) -> Vec<(&'static str, Rheology)> {
    vec![
        (
            "maxwell",
            Rheology::Maxwell {
                compliance: c,
                relaxation_time: tau,
            },
        ),
        (
            "kelvin_voigt",
            Rheology::KelvinVoigt {
                compliance: c,
                retardation_time: tau,
            },
        ),
        (
            "zener",
            Rheology::Zener {
                glassy_compliance: 0.5 * c,
                compliance: 0.5 * c,
                retardation_time: tau,
            },
        ),
        (
            "burgers",
            Rheology::Burgers {
                glassy_compliance: 0.5 * c,
                relaxation_time: 10.0 * tau,
                compliance: 0.5 * c,
                retardation_time: tau,
            },
        ),
        (
            "prony",
            Rheology::Prony {
                glassy_compliance: 0.25 * c,
                branches: (0..10)
                    .map(|k| RetardationBranch {
                        compliance: 0.075 * c,
                        time: tau * 10f64.powf(k as f64 / 3.0 - 1.5),
                    })
                    .collect(),
                viscosity: None,
            },
        ),
    ]
}

fn main() {
    let mut counts: Vec<(&str, usize, usize, usize)> = Vec::new();
    for (k, name) in ["maxwell", "kelvin_voigt", "zener", "burgers", "prony"]
        .iter()
        .enumerate()
    {
        let (mut ok, mut diagnosed, mut other) = (0, 0, 0);
        for c in [1e-3, 1e-2, 1e-1] {
            for vtau in [1e-4, 1e-2, 1.0, 1e1] {
                for delta in [0.0, 0.5, 1.0] {
                    for p0 in [1e-3, 1e-2] {
                        let rheology = presets(c, 1.0)[k].1.clone();
                        let case = Case {
                            slider: Slider::Sphere { radius: 1.0 },
                            body: Body::Homogeneous(Elastic {
                                young: 1.0,
                                poisson: 0.3,
                            }),
                            layer: Some(Layer {
                                rheology,
                                law: ComplianceLaw::Sigmoid { delta, p0 },
                                integration: Integration::Exact,
                            }),
                            loading: Loading {
                                normal_load: 5e-6,
                                velocity: Some(vtau),
                                reference_distance: None,
                            },
                            grid: GridSpec {
                                cells: [64, 64],
                                half_width: None,
                                centre: None,
                            },
                            units: Units::Dimensionless,
                        };
                        match solve(&case, &SolverParams::default()) {
                            Ok(s) if s.summary().is_finite() => ok += 1,
                            Ok(_) => {
                                other += 1;
                                println!("{name} C'={c:e} V'tau={vtau:e} delta={delta} p0={p0:e}: non-finite summary");
                            }
                            Err(e) => {
                                let m = e.to_string();
                                if m.contains("folds")
                                    || m.contains("window")
                                    || m.contains("did not converge")
                                {
                                    diagnosed += 1;
                                } else {
                                    other += 1;
                                }
                                println!(
                                    "{name} C'={c:e} V'tau={vtau:e} delta={delta} p0={p0:e}: {m}"
                                );
                            }
                        }
                    }
                }
            }
        }
        counts.push((name, ok, diagnosed, other));
    }
    println!("\npreset: converged / stopped with a diagnosis / other (of 72)");
    for (name, ok, d, o) in counts {
        println!("{name}: {ok} / {d} / {o}");
    }
}
