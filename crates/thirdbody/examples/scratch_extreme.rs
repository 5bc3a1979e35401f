use thirdbody::body::hysteresis::{dissipated_force, dissipated_force_square_root_edges};
use thirdbody::body::solid::{SolidRheology, ViscoelasticHalfSpace};
use thirdbody::body::viscoelastic::{CreepBranch, CreepSeries};
use thirdbody::*;

const A0: f64 = 0.05;

fn main() {
    let p = SolverParams {
        tolerance: 1e-10,
        max_iterations: 2000,
        parallelism: Parallelism::Rayon,
        max_windows: 6,
        method: None,
    };
    let cells: usize = std::env::args().nth(1).map_or(128, |s| s.parse().unwrap());
    for ratio in [10.0f64, 1000.0] {
        for zeta in [1e-4, 1e-2, 0.1, 1.0] {
            let case = Case {
                slider: Slider::Sphere { radius: 1.0 },
                body: Body::Viscoelastic(ViscoelasticHalfSpace {
                    rheology: SolidRheology::Zener {
                        glassy_modulus: ratio,
                        relaxed_modulus: 1.0,
                        relaxation_time: 1.0,
                    },
                    poisson: 0.0,
                }),
                layer: None,
                loading: Loading {
                    normal_load: 4.0 * A0.powi(3) / 3.0,
                    velocity: Some(zeta * A0 / ratio),
                    reference_distance: None,
                },
                grid: GridSpec {
                    cells: [cells, cells],
                    half_width: None,
                    centre: None,
                },
                units: Units::Dimensionless,
            };
            // creep time tau * ratio; V tau_c / a0 = zeta
            let creep = CreepSeries {
                glassy: 1.0 / ratio,
                branches: vec![CreepBranch {
                    compliance: 1.0 - 1.0 / ratio,
                    retardation_time: ratio,
                }],
            };
            let t = std::time::Instant::now();
            let sol = match solve(&case, &p) {
                Ok(s) => s,
                Err(e) => {
                    println!("ratio {ratio:e} zeta {zeta:e}: {e}");
                    continue;
                }
            };
            let el = t.elapsed().as_secs_f64();
            let s = sol.summary();
            let (nx, ny, h) = (sol.grid.nx(), sol.grid.ny(), sol.grid.cell());
            let v = zeta * A0 / ratio;
            let q = s.normal_load;
            let d0 = dissipated_force(&creep, v, &sol.pressure, nx, ny, h).unwrap() / q;
            let d1 = dissipated_force_square_root_edges(&creep, v, &sol.pressure, nx, ny, h)
                .unwrap()
                / q;
            let mu = s.friction_coefficient;
            println!("ratio {ratio:e} zeta {zeta:e} lam {:.3e} mu {mu:.5e} summary {:.3e} bilinear {:.3e} sqrt {:.3e} ({el:.2}s)", v * ratio / h, s.dissipation_friction_coefficient / mu - 1.0, d0 / mu - 1.0, d1 / mu - 1.0);
        }
    }
}
