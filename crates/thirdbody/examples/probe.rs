use thirdbody::*;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).map(|s| s.parse().unwrap()).unwrap_or(128);
    let which = args.get(2).map(|s| s.as_str()).unwrap_or("hertz");
    let mut case = Case {
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
            half_width: None,
            centre: None,
        },
        units: Units::Dimensionless,
    };
    if which != "hertz" {
        case.grid.half_width = None;
        let law = match which {
            "linear" => ComplianceLaw::Linear,
            _ => ComplianceLaw::Sigmoid {
                delta: 0.5,
                p0: 0.001,
            },
        };
        case.layer = Some(Layer {
            compliance: 0.02,
            relaxation_time: 1.0,
            law,
            integration: Integration::Exact,
        });
        case.loading.velocity = Some(args.get(3).map(|s| s.parse().unwrap()).unwrap_or(1e-3));
    } else {
        case.grid.half_width = Some([0.024, 0.024]);
    }
    let t = std::time::Instant::now();
    let mut windows = 0;
    let s = solve_observed(&case, &SolverParams::default(), &mut |pr| {
        if let Progress::Window { grid, .. } = pr {
            windows += 1;
            eprintln!("window {:?}", grid.half_widths());
        }
        if let Progress::Iteration {
            iteration,
            residual,
        } = pr
        {
            if iteration < 40 || iteration % 200 == 0 {
                eprintln!("  it {iteration} res {residual:.3e}");
            }
        }
    });
    let dt = t.elapsed().as_secs_f64();
    match s {
        Ok(s) => {
            let m = s.summary();
            println!("{which} n={n} t={dt:.3}s it={} lin={} res={:.2e} win={} pmax={:.6e} D={:.6e} area={:.6e} mu={:.6e} x=[{:.4},{:.4}] y=[{:.4},{:.4}]",
              s.info.iterations, s.info.linear_iterations, s.info.residual, s.info.windows, m.max_pressure, m.penetration, m.contact_area, m.friction_coefficient,
              m.contact_x_min, m.contact_x_max, m.contact_y_min, m.contact_y_max);
            let e: f64 = 1.0 / (1.0 - 0.09);
            let q = 5e-6;
            let r = 1.0;
            let a = (3.0 * q * r / (4.0 * e)).cbrt();
            let p0 = 3.0 * q / (2.0 * std::f64::consts::PI * a * a);
            let d = a * a / r;
            if which == "hertz" {
                println!(
                    "hertz a={a:.6e} p0={p0:.6e} d={d:.6e}; err p0 {:.3e} d {:.3e} a {:.3e}",
                    m.max_pressure / p0 - 1.0,
                    m.penetration / d - 1.0,
                    (m.contact_area / std::f64::consts::PI).sqrt() / a - 1.0
                );
            }
        }
        Err(e) => println!("error after {dt:.3}s: {e}"),
    }
}
