use thirdbody::body::{SolidRheology, ViscoelasticHalfSpace};
use thirdbody::*;
fn main() {
    let args: Vec<f64> = std::env::args()
        .skip(1)
        .map(|a| a.parse().unwrap())
        .collect();
    let (ratio, speed, cells) = (args[0], args[1], args[2] as usize);
    let a0 = 0.01;
    let relaxed_star = 1.0 / (1.0 - 0.09);
    let load = std::f64::consts::PI * relaxed_star * a0 * a0 / 4.0;
    let case = Case {
        slider: Slider::Cylinder { radius: 1.0 },
        body: Body::Viscoelastic(ViscoelasticHalfSpace {
            rheology: SolidRheology::Zener {
                glassy_modulus: ratio,
                relaxed_modulus: 1.0,
                relaxation_time: 1.0,
            },
            poisson: 0.3,
        }),
        layer: None,
        loading: Loading {
            normal_load: load,
            velocity: Some(speed * a0),
            reference_distance: None,
        },
        grid: GridSpec {
            cells: [cells, 1],
            half_width: None,
            centre: None,
        },
        units: Units::Dimensionless,
    };
    let t = std::time::Instant::now();
    let mut obs = |p: Progress| {
        if let Progress::Window { attempt, grid } = p {
            eprintln!(
                "window {attempt}: cell {:e} x0 {:e}",
                grid.cell(),
                grid.x0()
            );
        }
        if let Progress::Iteration {
            iteration,
            residual,
        } = p
        {
            if iteration % 10 == 0 {
                eprintln!("  it {iteration} {residual:e}");
            }
        }
        std::ops::ControlFlow::Continue(())
    };
    match solve_observed(&case, &SolverParams::default(), &mut obs) {
        Ok(s) => {
            let m = s.summary();
            eprintln!(
                "ok {:?}: a {} c {} pmax {} mu {} iters {} windows {}",
                t.elapsed(),
                0.5 * (m.contact_x_max - m.contact_x_min) / a0,
                0.5 * (m.contact_x_max + m.contact_x_min) / a0,
                m.max_pressure,
                m.friction_coefficient,
                m.iterations,
                s.info.windows
            );
        }
        Err(e) => eprintln!(
            "err {:?}: {}",
            t.elapsed(),
            format!("{e}").chars().take(200).collect::<String>()
        ),
    }
}
