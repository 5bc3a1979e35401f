//! The layer-free sphere against Hertz's closed form
//! (Johnson, Contact Mechanics, eq. 4.22-4.23), and the limits of the layer model.

use crate::cases;

use std::f64::consts::PI;

use cases::*;
use thirdbody::*;

/// Hertz for a rigid paraboloid of radius R on a half-space (E, nu) under Q:
/// `a = (3 Q R / 4 E*)^(1/3)`, `p0 = 3 Q / (2 pi a^2)`, `D = a^2 / R`.
fn hertz(q: f64, r: f64, e: f64, nu: f64) -> (f64, f64, f64) {
    let e_star = e / (1.0 - nu * nu);
    let a = (3.0 * q * r / (4.0 * e_star)).cbrt();
    (a, 3.0 * q / (2.0 * PI * a * a), a * a / r)
}

#[test]
fn sphere_without_layer_matches_hertz() {
    let (a, p0, d) = hertz(5e-6, 1.0, 1.0, 0.3);
    // Automatic window (refitted around the contact) and a fixed one.
    for case in [
        sphere(5e-6, 96),
        fixed_window(sphere(5e-6, 128), 0.024, [0.0, 0.0]),
    ] {
        let s = solve_to(&case, 1e-10);
        let m = s.summary();
        let across = 2.0 * a / m.cell_size;
        let radius = (m.contact_area / PI).sqrt();
        eprintln!(
            "{across:.0} cells across: p0 {:.2e}, D {:.2e}, a {:.2e} (windows {})",
            rel(m.max_pressure, p0),
            rel(m.penetration, d),
            rel(radius, a),
            s.info.windows
        );
        assert!(across >= 60.0, "{across} cells across the contact");
        assert!(rel(m.max_pressure, p0) < 5e-3);
        assert!(rel(m.penetration, d) < 5e-3);
        assert!(rel(radius, a) < 1e-2);
        assert!(
            m.friction_coefficient.abs() < 1e-10,
            "no layer, no hysteresis"
        );
        assert!(s.info.residual <= 1e-10);
    }
}

#[test]
fn ellipsoid_matches_hertz_for_equal_radii_and_elongates_otherwise() {
    let mut case = sphere(5e-6, 64);
    case.slider = Slider::Ellipsoid {
        radius_x: 1.0,
        radius_y: 1.0,
    };
    let sphere_solution = solve_to(&sphere(5e-6, 64), 1e-10);
    let s = solve_to(&case, 1e-10);
    assert!(
        rel(
            s.summary().max_pressure,
            sphere_solution.summary().max_pressure
        ) < 1e-12
    );
    // A slider flatter along y gives a contact longer along y (Johnson §4.2(b)).
    case.slider = Slider::Ellipsoid {
        radius_x: 1.0,
        radius_y: 4.0,
    };
    let m = solve_to(&case, 1e-10).summary();
    let (lx, ly) = (
        m.contact_x_max - m.contact_x_min,
        m.contact_y_max - m.contact_y_min,
    );
    assert!(ly > 1.5 * lx, "{lx} {ly}");
}

#[test]
fn load_balance_holds_to_round_off() {
    let cases = [
        sphere(5e-6, 48),
        layered(
            5e-6,
            48,
            0.02,
            1e-3,
            sigmoid(0.5, 0.001),
            Integration::Exact,
        ),
        layered(
            5e-6,
            48,
            0.02,
            1e-2,
            stiffening_table(),
            Integration::Secant,
        ),
    ];
    for case in cases {
        let s = solve_to(&case, 1e-10);
        // The load the cells carry on average (a located contact edge's cell
        // carries less than its centre value).
        let total: f64 = s.mean_pressure().iter().sum::<f64>() * s.grid.cell_measure();
        assert!(rel(total, 5e-6) < 1e-12, "{}", rel(total, 5e-6));
        assert!(s.pressure.iter().all(|&p| p >= 0.0));
    }
}

/// The largest difference of the pressure from its mirror image in x.
fn asymmetry(s: &Solution) -> f64 {
    let g = s.grid;
    let mut asym = 0.0f64;
    for j in 0..g.ny() {
        for i in 0..g.nx() {
            let mirror = g.nx() - 1 - i;
            asym = asym.max((s.pressure[g.index(i, j)] - s.pressure[g.index(mirror, j)]).abs());
        }
    }
    asym
}

/// A Zener layer (glassy 0.01 in series with a Kelvin–Voigt branch 0.01, tau = 1)
/// at V = 1e7: a cell is 1e-10 of the branch's creep length, so the layer is its
/// glassy spring bed; the pressure is symmetric and the friction, the branch's
/// barely moving lag, equals the power it dissipates. Before the nearly frozen
/// branch stopped placing the contacts' edges: mu -7.4e-8 against the dissipation's
/// 5.4e-12, the pressure asymmetric by 4e-4 of its peak, and an energy warning.
#[test]
fn a_nearly_frozen_branch_leaves_the_glassy_spring_bed() {
    let mut case = sphere(5e-6, 48);
    case.layer = Some(Layer {
        rheology: Rheology::Zener {
            glassy_compliance: 0.01,
            compliance: 0.01,
            retardation_time: 1.0,
        },
        law: ComplianceLaw::Linear,
        integration: Integration::Exact,
    });
    case.loading.velocity = Some(1e7);
    let s = solve_to(&case, 1e-12);
    let (asym, pmax) = (asymmetry(&s), s.summary().max_pressure);
    let m = s.summary();
    eprintln!(
        "asymmetry {:.1e}, mu {:.3e}, dissipation {:.3e}",
        asym / pmax,
        m.friction_coefficient,
        m.dissipation_friction_coefficient
    );
    assert!(asym < 1e-6 * pmax, "asymmetry {:e}", asym / pmax);
    // Measured 0.9 % on these 48^2 cells (both estimates resolve the contact's
    // edges to first order).
    let balance = m.friction_coefficient / m.dissipation_friction_coefficient - 1.0;
    assert!(balance.abs() < 2e-2, "energy balance {balance:e}");
    assert!(thirdbody::report::model_warnings(&case, &s).is_empty());
}

#[test]
fn infinite_velocity_gives_a_symmetric_pressure_and_no_friction() {
    // No time to creep: the layer is an elastic bed, the pressure is symmetric in x
    // and the hysteresis friction vanishes. A finite V large enough that the creep
    // per cell h / (V T) is 1e-9 goes through the Newton path and must agree.
    for velocity in [f64::INFINITY, 1e7] {
        for law in [ComplianceLaw::Linear, sigmoid(0.5, 0.001)] {
            let case = fixed_window(
                layered(5e-6, 48, 0.02, velocity, law.clone(), Integration::Exact),
                0.03,
                [0.0, 0.0],
            );
            let s = solve_to(&case, 1e-11);
            let (asym, pmax) = (asymmetry(&s), s.summary().max_pressure);
            let mu = s.summary().friction_coefficient;
            eprintln!(
                "V = {velocity:e}, {law:?}: asymmetry {:.1e}, mu {mu:.1e}",
                asym / pmax
            );
            assert!(asym <= 1e-7 * pmax, "asymmetry {}", asym / pmax);
            assert!(mu.abs() < 1e-7, "mu = {mu}");
        }
    }
    // And mu falls towards 0 as V grows (paper Fig. 8).
    let mu = |v: f64| {
        solve_to(
            &layered(5e-6, 48, 0.02, v, ComplianceLaw::Linear, Integration::Exact),
            1e-10,
        )
        .summary()
        .friction_coefficient
    };
    let (slow, fast) = (mu(1e-2), mu(10.0));
    assert!(fast < 0.05 * slow, "{slow} {fast}");
}

#[test]
fn delta_zero_is_exactly_the_linear_law() {
    for integration in [Integration::Exact, Integration::Secant] {
        let lin = solve_to(
            &layered(5e-6, 48, 0.02, 1e-3, ComplianceLaw::Linear, integration),
            1e-10,
        );
        let sig = solve_to(
            &layered(5e-6, 48, 0.02, 1e-3, sigmoid(0.0, 0.003), integration),
            1e-10,
        );
        assert_eq!(lin.grid, sig.grid);
        assert_eq!(lin.pressure, sig.pressure, "bitwise equal pressures");
        assert_eq!(lin.approach, sig.approach);
    }
}

#[test]
fn fixed_window_that_cuts_the_contact_is_an_error() {
    let case = fixed_window(sphere(5e-6, 32), 0.01, [0.0, 0.0]);
    let e = solve(&case, &SolverParams::default()).unwrap_err();
    assert!(matches!(e, Error::ContactAtWindowEdge { .. }), "{e}");
    assert!(e.to_string().contains("edge of the window"), "{e}");
    // Far too coarse: the contact spans fewer than 3 cells.
    let case = fixed_window(sphere(5e-6, 8), 1.0, [0.0, 0.0]);
    let e = solve(&case, &SolverParams::default()).unwrap_err();
    assert!(e.to_string().contains("grid.half_width"), "{e}");
}

#[test]
fn automatic_window_grows_until_it_holds_the_contact() {
    // A load 1000 times the estimate's: the first window is far too small.
    let mut case = layered(
        5e-6,
        32,
        0.02,
        1e-3,
        ComplianceLaw::Linear,
        Integration::Exact,
    );
    case.body = Body::Homogeneous(Elastic {
        young: 1e-3,
        poisson: 0.3,
    });
    case.layer.as_mut().unwrap().rheology = Rheology::Maxwell {
        compliance: 20.0,
        relaxation_time: 1.0,
    };
    let s = solve_to(&case, 1e-10);
    assert!(!s.grid.touches_edge(&s.pressure));
    assert!(s.info.windows >= 1);
}
