//! Very stiff coatings: Polonsky–Keer conjugate gradients broke down
//! on E1/E2 = 80-100 with h1 = 0.002 (the projected curvature of a conjugate
//! direction turned negative) and blamed `max_iterations`. Every coating ratio from
//! 10 to 1000, on thin (h1 = 0.002, ~0.1 a) and thicker (h1 = 0.02) coatings, must
//! solve on the automatic window with the load balanced to 1e-10 and the pressure of
//! the semi-smooth Newton path (a second method: another algorithm, another
//! stopping rule) on the same grid to 1e-6 of the peak.

use thirdbody::{
    solve, Body, Case, Elastic, GridSpec, Loading, Method, Slider, SolverParams, Units,
};

fn coated(ratio: f64, thickness: f64) -> Case {
    Case {
        slider: Slider::Sphere { radius: 1.0 },
        body: Body::coated(
            Elastic {
                young: ratio,
                poisson: 0.3,
            },
            thickness,
            Elastic {
                young: 1.0,
                poisson: 0.3,
            },
        ),
        layer: None,
        loading: Loading {
            normal_load: 5e-6,
            velocity: None,
            reference_distance: None,
        },
        // 128 cells reproduce the breakdown (E1/E2 = 80, 90, 95, 100 at h1 = 0.002).
        grid: GridSpec {
            cells: [128, 128],
            half_width: None,
            centre: None,
        },
        units: Units::Dimensionless,
    }
}

fn check(ratio: f64, thickness: f64) {
    let label = format!("E1/E2 = {ratio}, h1 = {thickness}");
    let case = coated(ratio, thickness);
    let cg = solve(&case, &SolverParams::default()).unwrap_or_else(|e| panic!("{label}: {e}"));
    assert_eq!(cg.info.method, Method::PolonskyKeer, "{label}");
    let load: f64 = cg.pressure.iter().sum::<f64>() * cg.grid.cell_measure();
    assert!(
        (load / 5e-6 - 1.0).abs() < 1e-10,
        "{label}: load {load:e} against 5e-6"
    );
    // The same grid, solved by both paths to a residual of 1e-12: these kernels are
    // ill-conditioned (at 1e-10 the two differ by up to 1.2e-6 of the peak).
    let mut fixed = case.clone();
    fixed.grid.half_width = Some(cg.grid.half_widths());
    fixed.grid.centre = Some(cg.grid.centre());
    let tight = |method| SolverParams {
        tolerance: 1e-12,
        method: Some(method),
        ..SolverParams::default()
    };
    let cg = solve(&fixed, &tight(Method::PolonskyKeer))
        .unwrap_or_else(|e| panic!("{label} (CG, 1e-12): {e}"));
    let newton = solve(&fixed, &tight(Method::SemismoothNewton))
        .unwrap_or_else(|e| panic!("{label} (Newton): {e}"));
    assert_eq!(newton.info.method, Method::SemismoothNewton, "{label}");
    assert_eq!(newton.grid.len(), cg.grid.len(), "{label}");
    let peak = cg.pressure.iter().fold(0.0f64, |m, &v| m.max(v));
    let worst = cg
        .pressure
        .iter()
        .zip(&newton.pressure)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    eprintln!(
        "{label}: CG {} iterations, Newton {} steps, max |dp| / p_max = {:.1e}",
        cg.info.iterations,
        newton.info.iterations,
        worst / peak
    );
    assert!(
        worst <= 1e-6 * peak,
        "{label}: max |dp| = {:e} p_max",
        worst / peak
    );
}

#[test]
fn thin_stiff_coatings_solve_and_agree_with_newton() {
    for ratio in [10.0, 30.0, 50.0, 80.0, 100.0, 300.0, 1000.0] {
        check(ratio, 0.002);
    }
}

#[test]
fn thicker_stiff_coatings_solve_and_agree_with_newton() {
    for ratio in [10.0, 30.0, 50.0, 80.0, 100.0, 300.0, 1000.0] {
        check(ratio, 0.02);
    }
}
