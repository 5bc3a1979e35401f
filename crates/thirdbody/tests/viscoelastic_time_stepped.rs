mod time_stepped;

use thirdbody::body::viscoelastic::{CreepBranch, CreepSeries};
use time_stepped::{Setup, Simulator, Start};

fn zener(glassy: f64, branch: f64, tau: f64) -> CreepSeries {
    CreepSeries {
        glassy,
        branches: vec![CreepBranch {
            compliance: branch,
            retardation_time: tau,
        }],
    }
}

#[test]
#[ignore]
fn explore() {
    let a_r: f64 = 0.1;
    let creep = zener(1.0, 2.0, 1.0);
    let q = 4.0 * a_r.powi(3) / (3.0 * creep.relaxed());
    for &(n, m) in &[(32usize, 1usize), (64, 1), (64, 2)] {
        let t0 = std::time::Instant::now();
        let mut sim = Simulator::new(Setup {
            creep: creep.clone(),
            radius: 1.0,
            load: q,
            speed: 0.1,
            cells: n,
            half_width: 1.25 * a_r,
            substeps: m,
            upstream: 1.0,
            start: Start::Fresh,
            tolerance: 1e-11,
        });
        let snaps = sim.run_to(15.0 * a_r);
        for s in snaps.iter().step_by(snaps.len() / 10) {
            eprintln!("{:?}", s);
        }
        eprintln!("{:?}", snaps.last().unwrap());
        eprintln!(
            "n {n} m {m}: {:.2?}, {} steps, {} cg, residual {:.1e}, edge {}",
            t0.elapsed(),
            sim.steps,
            sim.cg_iterations,
            sim.worst_residual,
            sim.touches_edge()
        );
    }
}

mod stand_in {
    use std::ops::ControlFlow;
    use std::sync::Arc;
    use thirdbody::body::viscoelastic::{steady_sliding_kernel, CreepSeries};
    use thirdbody::convolution::ConvolutionPlan;
    use thirdbody::operator::ConvolutionOperator;
    use thirdbody::*;

    pub struct Steady {
        pub pressure: Vec<f64>,
        pub approach: f64,
        pub friction: f64,
        pub max_pressure: f64,
    }

    pub fn steady(
        creep: &CreepSeries,
        radius: f64,
        load: f64,
        speed: f64,
        n: usize,
        half_width: f64,
    ) -> Steady {
        let mut case = Case {
            slider: Slider::Sphere { radius },
            body: Body::Homogeneous(Elastic {
                young: 1.0 / creep.relaxed(),
                poisson: 0.0,
            }),
            layer: None,
            loading: Loading {
                normal_load: load,
                velocity: Some(speed),
            },
            grid: GridSpec {
                cells: [n, n],
                half_width: Some([half_width, half_width]),
                centre: Some([0.0, 0.0]),
            },
            units: Units::Dimensionless,
        };
        case.loading.velocity = Some(speed);
        let grid = Grid::centred(n, n, 2.0 * half_width / n as f64, [0.0, 0.0]).unwrap();
        let h = grid.cell();
        let kernel = steady_sliding_kernel(creep, h, n, n, speed).unwrap();
        let width = 2 * n - 1;
        let plan = ConvolutionPlan::new(n, n, Parallelism::Sequential);
        let spectrum = plan.kernel_spectrum(|di, dj| {
            kernel[dj.unsigned_abs() as usize * width + (di + n as i64 - 1) as usize]
        });
        let op = ConvolutionOperator::new(plan.convolver(), Arc::new(spectrum)).unwrap();
        let mut shape = vec![0.0; n * n];
        let mut slope = vec![0.0; n * n];
        for j in 0..n {
            for i in 0..n {
                let (x, y) = (grid.x(i), grid.y(j));
                shape[j * n + i] = (x * x + y * y) / (2.0 * radius);
                slope[j * n + i] = x / radius;
            }
        }
        let mut problem =
            ContactProblem::from_parts(&case, &grid, Box::new(op), shape, slope).unwrap();
        let params = SolverParams {
            tolerance: 1e-12,
            method: Some(Method::SemismoothNewton),
            parallelism: Parallelism::Sequential,
            ..SolverParams::default()
        };
        let s = solve_problem(&mut problem, None, &params, &mut |_| {
            ControlFlow::Continue(())
        })
        .unwrap();
        let summary = s.summary();
        Steady {
            approach: s.approach,
            friction: summary.friction_coefficient,
            max_pressure: summary.max_pressure,
            pressure: s.pressure,
        }
    }
}

#[test]
#[ignore]
fn explore_stand_in() {
    let a_r: f64 = 0.1;
    let creep = zener(1.0, 2.0, 1.0);
    let q = 4.0 * a_r.powi(3) / (3.0 * creep.relaxed());
    for &(n, m) in &[(32usize, 1usize), (64, 1), (64, 2)] {
        let t0 = std::time::Instant::now();
        let st = stand_in::steady(&creep, 1.0, q, 0.1, n, 1.25 * a_r);
        eprintln!("steady {:.2?}", t0.elapsed());
        let mut sim = Simulator::new(Setup {
            creep: creep.clone(),
            radius: 1.0,
            load: q,
            speed: 0.1,
            cells: n,
            half_width: 1.25 * a_r,
            substeps: m,
            upstream: 1.0,
            start: Start::Fresh,
            tolerance: 1e-11,
        });
        let s = *sim.run_to(15.0 * a_r).last().unwrap();
        let l2 = (sim
            .pressure
            .iter()
            .zip(&st.pressure)
            .map(|(a, b)| (a - b).powi(2))
            .sum::<f64>()
            / st.pressure.iter().map(|b| b * b).sum::<f64>())
        .sqrt();
        let mx = sim
            .pressure
            .iter()
            .zip(&st.pressure)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
            / st.max_pressure;
        eprintln!(
            "n {n} m {m}: pmax {:.3e} D {:.3e} mu {:.3e} | L2 {l2:.2e} max {mx:.2e}  steady mu {:.6} D {:.6e} pmax {:.6e}",
            s.max_pressure / st.max_pressure - 1.0,
            s.approach / st.approach - 1.0,
            s.friction / st.friction - 1.0,
            st.friction, st.approach, st.max_pressure
        );
    }
}
