//! A sphere sliding steadily over a linear viscoelastic half-space (no layer):
//! the speed limits are Hertz with the glassy and with the relaxed modulus; the
//! friction vanishes at both ends and has one maximum in between; a one-branch
//! Prony body is the Zener preset and a body whose branches have no compliance is
//! the elastic body; the contact matches an independent boundary-element solution
//! of the same discrete problem (`tests/data/sls_sphere_reference.py`, its own
//! kernel quadrature and its own active-set GMRES solver); the solver is chosen
//! from the body (never conjugate gradients on its non-symmetric operator); the
//! stresses do not depend on the modulus, so the elastic stress kernels apply; the
//! friction equals the power dissipated in the body (energy balance); in slow
//! sliding the friction is its first-order closed form, where the solvers' kernel
//! gives creep shorter than a cell to the gap as a lag, which the solution gives
//! back to the body's displacement and which a layer on the body turns off.

mod cases;

use thirdbody::body::{SolidRheology, ViscoelasticHalfSpace};
use thirdbody::stress::{stresses, Section};
use thirdbody::*;

/// Relaxed Hertz radius a0 = 0.05 R in every case here: with E0* = 1 and R = 1,
/// Q = 4 E0* a0^3 / (3 R).
const A0: f64 = 0.05;

/// The default solver settings.
const P: SolverParams = SolverParams {
    tolerance: 1e-10,
    max_iterations: 2000,
    parallelism: Parallelism::Rayon,
    max_windows: 6,
    method: None,
};

fn zener(glassy: f64, relaxed: f64, tau: f64, poisson: f64) -> Body {
    Body::Viscoelastic(ViscoelasticHalfSpace {
        rheology: SolidRheology::Zener {
            glassy_modulus: glassy,
            relaxed_modulus: relaxed,
            relaxation_time: tau,
        },
        poisson,
    })
}

/// The sphere (R = 1) under the load that gives the relaxed Hertz radius A0 on a
/// body of relaxed plane-strain modulus 1, at `velocity`, on `cells`^2 over a
/// window of +-`half` a0 (automatic if `None`).
fn sliding(body: Body, velocity: f64, cells: usize, half: Option<f64>) -> Case {
    let mut c = cases::sphere(4.0 * A0.powi(3) / 3.0, cells);
    c.body = body;
    c.loading.velocity = Some(velocity);
    if let Some(h) = half {
        c.grid.half_width = Some([h * A0, h * A0]);
        c.grid.centre = Some([0.0, 0.0]);
    }
    c
}

/// Hertz: (radius, peak pressure, approach) for load q, radius 1, modulus e_star.
fn hertz(q: f64, e_star: f64) -> (f64, f64, f64) {
    let a = (3.0 * q / (4.0 * e_star)).cbrt();
    (a, 3.0 * q / (2.0 * std::f64::consts::PI * a * a), a * a)
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// Two solutions with the same pressure (1e-12 of `b`'s peak) and approach (1e-12).
fn assert_same_contact(a: &Solution, b: &Solution) {
    let peak = b.pressure.iter().fold(0.0f64, |m, &v| m.max(v));
    let diff = a
        .pressure
        .iter()
        .zip(&b.pressure)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    assert!(diff < 1e-12 * peak, "{diff}");
    assert!(rel(a.approach, b.approach) < 1e-12);
}

#[test]
fn the_speed_limits_are_hertz_with_the_glassy_and_the_relaxed_modulus() {
    // E0 = 1, Eg = 10, nu = 0: plane-strain moduli 1 and 10. Creep lengths
    // V tau_c = 1e-9 a0 (slow) and 1e13 a0 (fast); the elastic bodies of the two
    // moduli on the same window are the grid's Hertz, and the closed form is
    // checked with the tolerances that grid meets for an elastic body.
    let body = zener(10.0, 1.0, 1.0, 0.0);
    let q = 4.0 * A0.powi(3) / 3.0;
    for (velocity, modulus) in [(1e-10 * A0, 1.0), (1e12 * A0, 10.0)] {
        let (a, p0, d) = hertz(q, modulus);
        let half = 1.3 * a / A0;
        let ve_case = sliding(body.clone(), velocity, 128, Some(half));
        let ve = solve(&ve_case, &P).unwrap();
        // Friction at the rounding level raises no energy-balance warning.
        let warnings = thirdbody::report::model_warnings(&ve_case, &ve);
        assert!(warnings.is_empty(), "{warnings:?}");
        let mut elastic_case = sliding(
            Body::Homogeneous(Elastic {
                young: modulus,
                poisson: 0.0,
            }),
            velocity,
            128,
            Some(half),
        );
        elastic_case.loading.velocity = None;
        let elastic = solve(&elastic_case, &P).unwrap();
        let (sv, se) = (ve.summary(), elastic.summary());
        // The same discrete problem up to the creep the limit leaves: 1e-6.
        assert!(rel(sv.penetration, se.penetration) < 1e-6, "{sv:?}\n{se:?}");
        assert!(rel(sv.max_pressure, se.max_pressure) < 1e-5);
        // The grid's Hertz accuracy (cell a / 49): approach 0.1 %, peak 1 %.
        assert!(rel(se.penetration, d) < 1e-3, "{} vs {d}", se.penetration);
        assert!(rel(sv.penetration, d) < 1e-3, "{} vs {d}", sv.penetration);
        assert!(
            rel(sv.max_pressure, p0) < 0.01,
            "{} vs {p0}",
            sv.max_pressure
        );
        let radius = (sv.contact_area / std::f64::consts::PI).sqrt();
        assert!(rel(radius, a) < 0.02, "{radius} vs {a}");
        // The friction vanishes in both limits.
        assert!(sv.friction_coefficient.abs() < 1e-6 * A0, "{sv:?}");
    }
}

#[test]
fn friction_vanishes_at_both_ends_and_has_one_maximum() {
    // Zener E_g / E_0 = 10 (nu = 0, so A0 is the relaxed Hertz radius) on 64^2
    // (automatic window) from V tau / a0 = 1e-4 to 1e3. Measured: the peak 0.396
    // a0 / R at V tau / a0 = 0.1, 7e-4 and 2e-4 of it at the ends.
    let body = zener(10.0, 1.0, 1.0, 0.0);
    let zetas: Vec<f64> = (0..15).map(|k| 10f64.powf(-4.0 + 0.5 * k as f64)).collect();
    let mu: Vec<f64> = zetas
        .iter()
        .map(|z| {
            solve(&sliding(body.clone(), z * A0, 64, None), &P)
                .unwrap()
                .summary()
                .friction_coefficient
        })
        .collect();
    let (peak, &max) = mu
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(b.1))
        .unwrap();
    // One maximum: rising before it, falling after it.
    assert!(mu[..=peak].windows(2).all(|w| w[0] < w[1]), "{mu:?}");
    assert!(mu[peak..].windows(2).all(|w| w[0] > w[1]), "{mu:?}");
    assert!(0 < peak && peak < mu.len() - 1);
    // Near V tau / a0 = 0.1 (the reference's peak is at 0.12, 0.40 a0 / R).
    assert!(
        (0.03..=0.4).contains(&zetas[peak]),
        "peak at {}",
        zetas[peak]
    );
    assert!(rel(max, 0.40 * A0) < 0.03, "{max}");
    // Both ends below 2.5 % of the peak, and falling toward them.
    assert!(
        mu[0] < 0.025 * max && mu[mu.len() - 1] < 0.025 * max,
        "{mu:?}"
    );
    // The small-speed closed form mu = (E_g / E_0 - 1) V tau / R, to first order in
    // V tau_c / a0 = 1e-3. Where the creep length is far below the cell the grid
    // resolves the friction slowly (it comes from the pressure's slope at the
    // contact's edge): measured 5.2 %, 2.9 %, 1.4 % and 0.5 % low at 64^2, 128^2,
    // 256^2 and 512^2 (docs/validation.md).
    assert!(
        rel(mu[0], 9.0 * 1e-4 * A0) < 0.06,
        "{} vs {}",
        mu[0],
        9.0e-4 * A0
    );
    assert!(mu[0] < 9.0 * 1e-4 * A0);
}

/// The independent boundary-element solution (`tests/data/sls_sphere_reference.py`,
/// run with N = 128 over +-1.6 a0; values printed to 5 digits: tables of
/// `/tests/data/sls_sphere_reference.py 10 128` and `... 3 128`): (E_g / E_0,
/// V tau / a0, mu R / a0, D R / a0^2).
const REFERENCE: [(f64, f64, f64, f64); 7] = [
    (10.0, 0.1, 0.39561, 0.86396),
    (10.0, 0.15, 0.39511, 0.77475),
    (10.0, 1.0, 0.12898, 0.37501),
    (10.0, 10.0, 0.01514, 0.23984),
    (3.0, 0.3, 0.23656, 0.90313),
    (3.0, 1.0, 0.15875, 0.71945),
    (3.0, 10.0, 0.02389, 0.52590),
];

#[test]
fn the_contact_matches_an_independent_boundary_element_solution() {
    // The same cells (128^2 over +-1.6 a0, plane-strain relaxed modulus 1 with
    // nu = 0), so both solve nearly the same discrete problem; they differ in the
    // kernel's quadrature (the reference interpolates it linearly on eighths of a
    // cell), in the solver, and in the solvers' leading-edge damping, which the
    // reference does not add (`body::viscoelastic`; here its weight is at most 1e-4
    // of the relaxed compliance).
    for (ratio, zeta, mu_ref, d_ref) in REFERENCE {
        let case = sliding(zener(ratio, 1.0, 1.0, 0.0), zeta * A0, 128, Some(1.6));
        let s = solve(&case, &P).unwrap().summary();
        let (mu, d) = (s.friction_coefficient / A0, s.penetration / (A0 * A0));
        eprintln!(
            "E_g/E_0 {ratio}, V tau / a0 {zeta}: mu {:.1e}, D {:.1e}",
            rel(mu, mu_ref),
            rel(d, d_ref)
        );
        // Measured: mu within 2.1e-5 (1.4e-5 without the damping) but at E_g / E_0 =
        // 10, V tau / a0 = 10 (4.4e-4, where the creep length is 100 a0, beyond the
        // reference's near field: its own N = 96 and N = 128 tables differ by 3e-3
        // there); D within 1.1e-5.
        assert!(
            rel(mu, mu_ref) < 6e-4,
            "k {ratio} zeta {zeta}: mu {mu} vs {mu_ref}"
        );
        assert!(
            rel(d, d_ref) < 3e-5,
            "k {ratio} zeta {zeta}: D {d} vs {d_ref}"
        );
    }
}

#[test]
fn one_prony_branch_is_the_zener_preset_and_no_creep_is_the_elastic_body() {
    let (eg, e0, tau, nu) = (8.0, 2.0, 0.5, 0.3);
    let zener_body = zener(eg, e0, tau, nu);
    let prony = Body::Viscoelastic(ViscoelasticHalfSpace {
        rheology: SolidRheology::Prony {
            glassy_compliance: 1.0 / eg,
            branch_compliances: vec![1.0 / e0 - 1.0 / eg],
            branch_times: vec![tau * (eg / e0)],
        },
        poisson: nu,
    });
    let velocity = 0.3 * A0 / tau;
    let a = solve(&sliding(zener_body, velocity, 64, Some(2.0)), &P).unwrap();
    let b = solve(&sliding(prony, velocity, 64, Some(2.0)), &P).unwrap();
    assert_same_contact(&a, &b);

    // Branches without compliance: the elastic body of the glassy compliance, on
    // the same solver (the kernel is even, so conjugate gradients).
    let still = Body::Viscoelastic(ViscoelasticHalfSpace {
        rheology: SolidRheology::Prony {
            glassy_compliance: 1.0 / eg,
            branch_compliances: vec![0.0, 0.0],
            branch_times: vec![0.1, 10.0],
        },
        poisson: nu,
    });
    let elastic = Body::Homogeneous(Elastic {
        young: eg,
        poisson: nu,
    });
    let a = solve(&sliding(still, velocity, 64, Some(1.0)), &P).unwrap();
    let b = solve(&sliding(elastic, velocity, 64, Some(1.0)), &P).unwrap();
    assert_eq!(a.info.method, Method::PolonskyKeer);
    assert_same_contact(&a, &b);
}

#[test]
fn a_creeping_body_is_solved_by_newton_and_refuses_conjugate_gradients() {
    let case = sliding(zener(10.0, 1.0, 1.0, 0.3), 0.1 * A0, 32, None);
    assert_eq!(case.solver_method(None), Method::SemismoothNewton);
    assert_eq!(
        solve(&case, &P).unwrap().info.method,
        Method::SemismoothNewton
    );
    let forced = SolverParams {
        method: Some(Method::PolonskyKeer),
        ..SolverParams::default()
    };
    let err = solve(&case, &forced).unwrap_err().to_string();
    assert!(err.contains("solver.method"), "{err}");
    // Without a velocity the body has no steady state to give.
    let mut no_speed = case.clone();
    no_speed.loading.velocity = None;
    let err = solve(&no_speed, &P).unwrap_err().to_string();
    assert!(err.contains("loading.velocity"), "{err}");
}

#[test]
fn stresses_under_given_tractions_do_not_depend_on_the_modulus() {
    // The viscoelastic body's pressure; its stresses through the body, and those of
    // the same pressure on elastic bodies of very different moduli (same nu): the
    // correspondence principle with a constant Poisson ratio says they are equal.
    let body = zener(10.0, 1.0, 1.0, 0.3);
    let solution = solve(&sliding(body.clone(), 0.1 * A0, 48, None), &P).unwrap();
    let section = Section::XzPlane {
        y: 0.0,
        depths: (1..=12).map(|k| k as f64 * 0.1 * A0).collect(),
    };
    let pressure = solution.mean_pressure();
    let ve = stresses(&solution.grid, &pressure, &body, &section).unwrap();
    let all = |f: &thirdbody::stress::StressField| f.components.concat();
    let peak = all(&ve).iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(peak > 0.0);
    for young in [1e-3, 1.0, 7e5] {
        let elastic = Body::Homogeneous(Elastic {
            young,
            poisson: 0.3,
        });
        let e = stresses(&solution.grid, &pressure, &elastic, &section).unwrap();
        let diff = all(&ve)
            .iter()
            .zip(all(&e))
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(diff < 1e-12 * peak, "E = {young}: {diff} of {peak}");
    }
    // And another Poisson ratio does change them (the check can fail).
    let other = Body::Homogeneous(Elastic {
        young: 1.0,
        poisson: 0.45,
    });
    let e = stresses(&solution.grid, &pressure, &other, &section).unwrap();
    let diff = all(&ve)
        .iter()
        .zip(all(&e))
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(diff > 1e-3 * peak);
}

#[test]
fn friction_equals_the_power_dissipated_in_the_body() {
    // Energy balance of steady sliding: mu Q V (mu from the slider's slope) equals
    // the power dissipated in the body's dashpots, computed from the pressure alone
    // by the loss-compliance form (`body::hysteresis`). Zener E_g / E_0 = 10, nu = 0,
    // automatic window.
    let body = zener(10.0, 1.0, 1.0, 0.0);
    for zeta in [1e-4, 1e-3, 1e-2, 0.1, 1.0, 10.0] {
        let mut imbalance = Vec::new();
        for cells in [64, 128, 256] {
            let s = solve(&sliding(body.clone(), zeta * A0, cells, None), &P)
                .unwrap()
                .summary();
            imbalance.push(rel(
                s.dissipation_friction_coefficient,
                s.friction_coefficient,
            ));
        }
        eprintln!("V tau / a0 {zeta}: energy imbalance {imbalance:?}");
        // Measured (64^2, 128^2, 256^2), V tau / a0 = 1e-4: 0.68 %, 0.37 %, 0.090 %;
        // 1e-3: 0.28 %, 0.014 %, 0.17 %; 1e-2: 0.053 %, 0.079 %, 0.017 %; 0.1: 0.26 %,
        // 0.057 %, 0.015 %; 1: 0.080 %, 0.013 %, 0.0036 %; 10: 0.16 %, 0.012 %,
        // 0.0011 %. Against the 768^2 and 1024^2 solutions (4.494e-5, 4.469e-4 at
        // the two slowest speeds) the dissipation on 128^2 is 0.04 % and 0.29 % low,
        // the friction 0.32 % high and 0.28 % low. Before the finer grid for creep far
        // below a cell (`body::hysteresis`, "Square-root edges") the dissipation at
        // 1e-4 was 0.21 % low and the imbalance 0.53 %; before the square-root edges
        // (the bilinear field of the cell values) 1.0 % and 0.82 % low, the
        // imbalance 1.3 % and 0.54 %.
        assert!(imbalance[1] < 5e-3, "zeta {zeta}: {imbalance:?}");
        // Shrinking with the grid.
        assert!(imbalance[2] < imbalance[0], "zeta {zeta}: {imbalance:?}");
    }
}

#[test]
fn a_rubbers_glassy_ratio_converges_across_the_friction_maximum() {
    // A rubber's ratio of glassy to relaxed modulus, E_g / E_0 = 1000 (nu = 0), at
    // V tau / a0 = 3e-4, 1e-3 and 3e-3, around the friction's maximum: the body is
    // glassy over a few 1e-3 a0 behind the leading edge, a fraction of a cell, and
    // the creep part's collocation left the odd–even mode along x almost free
    // there. Before the kernel's leading-edge damping and Newton's tighter linear
    // solves, 3e-4 and 1e-3 failed on every grid from 64^2 to 256^2 and 3e-3 needed
    // a second attempt on 192^2. Independent checks: the energy balance, and the
    // friction and approach of the coarser grid.
    let body = zener(1000.0, 1.0, 1.0, 0.0);
    for (zeta, grids) in [(3e-4, [96, 128]), (1e-3, [128, 192]), (3e-3, [128, 192])] {
        let velocity = zeta * A0;
        let [coarse, fine] = grids.map(|cells| {
            let s = solve(&sliding(body.clone(), velocity, cells, None), &P)
                .unwrap_or_else(|e| panic!("zeta {zeta}, {cells}^2: {e}"))
                .summary();
            assert!(s.residual <= P.tolerance, "{}", s.residual);
            s
        });
        let balance = rel(
            fine.dissipation_friction_coefficient,
            fine.friction_coefficient,
        );
        let mu = rel(fine.friction_coefficient, coarse.friction_coefficient);
        let approach = rel(fine.penetration, coarse.penetration);
        eprintln!(
            "zeta {zeta}: mu {:.6e}, balance {balance:.2e}, mu against the coarser grid \
             {mu:.2e}, D {approach:.2e}",
            fine.friction_coefficient
        );
        // Measured: balance 2.2e-3, 1.5e-3, 2.0e-3; mu against the coarser grid
        // 3.0e-4, 7.8e-5, 4.8e-5; D 2.5e-5, 1.9e-5, 1.9e-5.
        assert!(balance < 5e-3, "zeta {zeta}: {balance}");
        assert!(mu < 1e-3, "zeta {zeta}: {mu}");
        assert!(approach < 1e-3, "zeta {zeta}: {approach}");
    }
}

/// Long creep over a nearly glassy leading edge: E_g / E_0 = 1e6 at V tau / a0 =
/// 1e-5 on 128^2 (the body creeps over 550 cells), 1e4 at 1e-4 and 1e6 at 1e-6 on
/// 256^2 (109 cells). All stopped with "did not converge": the first until the
/// leading-edge damping's share rose for long creep (`body::viscoelastic`, "The
/// solvers' kernel"), the second also until Newton's GMRES took a longer restart
/// after a stagnating step, the third until the window's scout solved at half the
/// cells (the warm start from 51 cells across sent Newton's first step far off).
/// Independent checks: the energy balance, and on 256^2 the friction and approach
/// on 128^2.
#[test]
fn long_creep_over_a_nearly_glassy_edge_converges() {
    for (ratio, zeta, cells) in [(1e6, 1e-5, 128), (1e4, 1e-4, 256), (1e6, 1e-6, 256)] {
        let body = zener(ratio, 1.0, 1.0, 0.0);
        let s = solve(&sliding(body, zeta * A0, cells, None), &P)
            .unwrap_or_else(|e| panic!("E_g/E_0 {ratio}, {cells}^2: {e}"))
            .summary();
        assert!(s.residual <= P.tolerance, "{}", s.residual);
        let balance = rel(s.dissipation_friction_coefficient, s.friction_coefficient);
        eprintln!(
            "E_g/E_0 {ratio:e}, zeta {zeta:e}, {cells}^2: mu {:.6e}, balance {balance:.2e}",
            s.friction_coefficient
        );
        // Measured: 1.1e-3, 2.6e-4 and 2.0e-4.
        assert!(balance < 5e-3, "E_g/E_0 {ratio}: {balance}");
        if cells == 256 {
            let coarse = solve(
                &sliding(zener(ratio, 1.0, 1.0, 0.0), zeta * A0, 128, None),
                &P,
            )
            .unwrap()
            .summary();
            let mu = rel(s.friction_coefficient, coarse.friction_coefficient);
            let approach = rel(s.penetration, coarse.penetration);
            eprintln!("against 128^2: mu {mu:.2e}, D {approach:.2e}");
            // Measured: mu 2.0e-4 and 2.1e-4, D 3.8e-5 both.
            assert!(mu < 1e-3, "{mu}");
            assert!(approach < 1e-3, "{approach}");
        }
    }
}

fn body_name(body: &Body) -> String {
    match body {
        Body::Viscoelastic(v) => format!("{:?}", v.rheology),
        other => format!("{other:?}"),
    }
}

/// Slow sliding, where every creep length lies far below the cell: the friction
/// against its first-order closed form `mu = V sum_k J_k tau_k / (J_r R)` (`tau_k`
/// the retardation times; `(E_g / E_0 - 1) V tau / R` for a Zener body of
/// relaxation time tau), at speeds where the retardation length is 1e-3 a0 or
/// less, so that the next order (a few tenths of `l / a`, as in Hunter's line
/// contact) stays below 1e-3. Before the solvers' kernel gave such creep to the
/// gap as a lag (`body::viscoelastic`, "creep shorter than a cell") the friction
/// came out 5.5 % low on 64^2 and 2.6 % on 128^2, whatever the speed.
#[test]
fn slow_sliding_friction_is_the_first_order_closed_form() {
    let three = Body::Viscoelastic(ViscoelasticHalfSpace {
        rheology: SolidRheology::Prony {
            glassy_compliance: 0.4,
            branch_compliances: vec![0.3, 0.2, 0.1],
            branch_times: vec![1.0, 0.1, 10.0],
        },
        poisson: 0.0,
    });
    // (body, V / a0, closed-form mu R / a0 per unit V / a0)
    let cases = [
        (zener(3.0, 1.0, 1.0, 0.0), 1e-4, 2.0),
        (zener(10.0, 1.0, 1.0, 0.0), 1e-4, 9.0),
        (zener(100.0, 1.0, 1.0, 0.0), 1e-5, 99.0),
        (three, 1e-5, (0.3 * 1.0 + 0.2 * 0.1 + 0.1 * 10.0) / 1.0),
    ];
    let mut worst = [0.0f64; 2];
    for (body, speed, slope) in cases {
        for (g, cells) in [64, 128].into_iter().enumerate() {
            let s = solve(&sliding(body.clone(), speed * A0, cells, None), &P)
                .unwrap()
                .summary();
            let expected = slope * speed * A0;
            let e = s.friction_coefficient / expected - 1.0;
            eprintln!(
                "{:?} V/a0 {speed:e} {cells}^2: mu {e:+.2e}",
                body_name(&body)
            );
            worst[g] = worst[g].max(e.abs());
        }
    }
    eprintln!("worst: 64^2 {:.2e}, 128^2 {:.2e}", worst[0], worst[1]);
    assert!(worst[0] < 1e-2 && worst[1] < 5e-3, "{worst:?}");
}

/// Where the solvers' kernel gave creep shorter than a cell to the gap, the
/// solution gives it back: its body displacement is the exact steady-sliding kernel
/// (`body::viscoelastic::steady_sliding_kernel`, summed directly here) applied to
/// its pressure, the slider's shape is the slider's own, and the gap is
/// `w_body + f - D`, zero on the contact. Zener E_g / E_0 = 10 at V tau / a0 = 1e-4
/// (creep length 0.03 cells) on 48^2. The exact kernel's lag term on the cells cut
/// by the contact's edge is the slope of the discrete displacement there, the
/// first-order error the lag removes: those cells are compared apart.
#[test]
fn the_solution_gives_the_lag_back_to_the_body() {
    let case = sliding(zener(10.0, 1.0, 1.0, 0.0), 1e-4 * A0, 48, None);
    let s = solve(&case, &P).unwrap();
    let g = s.grid;
    let (nx, ny) = (g.nx(), g.ny());
    let Body::Viscoelastic(solid) = &case.body else {
        unreachable!()
    };
    let kernel = thirdbody::body::viscoelastic::steady_sliding_kernel(
        &solid.model().creep,
        g.cell(),
        nx,
        ny,
        1e-4 * A0,
    )
    .unwrap();
    let width = 2 * nx - 1;
    let peak = s
        .body_displacement
        .iter()
        .fold(0.0f64, |m, v| m.max(v.abs()));
    let loaded = |i: i64, j: i64| {
        (0..nx as i64).contains(&i)
            && (0..ny as i64).contains(&j)
            && s.pressure[j as usize * nx + i as usize] > 0.0
    };
    // Inside (the cell and its four neighbours loaded), outside (none loaded), and
    // the cells between.
    let mut worst = [0.0f64; 3];
    let (mut worst_gap, mut worst_shape) = (0.0f64, 0.0f64);
    for j in 0..ny {
        for i in 0..nx {
            let mut w = 0.0;
            for l in 0..ny {
                for k in 0..nx {
                    let di = i as i64 - k as i64 + nx as i64 - 1;
                    w += kernel[j.abs_diff(l) * width + di as usize] * s.pressure[l * nx + k];
                }
            }
            let c = j * nx + i;
            let (ii, jj) = (i as i64, j as i64);
            let around = [
                (ii, jj),
                (ii + 1, jj),
                (ii - 1, jj),
                (ii, jj + 1),
                (ii, jj - 1),
            ];
            let n_loaded = around.iter().filter(|&&(a, b)| loaded(a, b)).count();
            let where_ = match n_loaded {
                5 => 0,
                0 => 1,
                _ => 2,
            };
            worst[where_] = worst[where_].max((w - s.body_displacement[c]).abs() / peak);
            let f = g.x(i).powi(2) / 2.0 + g.y(j).powi(2) / 2.0;
            worst_shape = worst_shape.max((s.shape[c] - f).abs());
            let gap = s.body_displacement[c] + s.shape[c] - s.approach;
            worst_gap = worst_gap.max((gap - s.gap[c]).abs());
            if s.pressure[c] > 0.0 {
                worst_gap = worst_gap.max(s.gap[c].abs());
            }
        }
    }
    eprintln!(
        "body displacement against the exact kernel's: inside {:.2e}, outside {:.2e}, \
         at the edge {:.2e}; shape {:.2e}, gap {:.2e} of the peak displacement",
        worst[0],
        worst[1],
        worst[2],
        worst_shape / peak,
        worst_gap / peak
    );
    // Against the lag's own size, c times the slider's largest slope on the contact
    // (9e-4 of the peak here): without its return the difference outside was 1.2
    // times it. Measured: 4 % inside, 2 % outside, 20 % on the edge's cells.
    let lag = thirdbody::body::viscoelastic::creep_lag(&solid.model().creep, g.cell(), 1e-4 * A0);
    let steepest = (0..nx * ny)
        .filter(|&c| s.pressure[c] > 0.0)
        .fold(0.0f64, |m, c| m.max(s.shape_slope[c].abs()));
    let size = lag * steepest / peak;
    eprintln!("lag {:.3e} a0, its size {size:.2e} of the peak", lag / A0);
    assert!(
        worst[0] < 0.1 * size && worst[1] < 0.1 * size,
        "{worst:?} vs {size:e}"
    );
    assert!(worst[2] < 0.3 * size, "{worst:?} vs {size:e}");
    assert!(worst_shape < 1e-12 * peak && worst_gap < 1e-9 * peak);
}

/// With a layer between the slider and the body the body's displacement on the
/// contact is not the slider's shape, so the lag that the solvers' kernel gives to
/// the gap would be wrong there: a problem with a layer keeps the body's whole
/// creep in its kernel, the same problem without one gives it to the gap.
#[test]
fn a_layer_on_the_body_keeps_the_whole_creep_in_the_kernel() {
    let mut case = sliding(zener(10.0, 1.0, 1.0, 0.0), 1e-4 * A0, 32, None);
    let grid = Grid::centred(32, 32, 2.5 * A0 / 32.0, [0.0, 0.0]).unwrap();
    let mut kernels = KernelCache::new();
    let bare = case
        .assemble(&grid, &mut kernels, Parallelism::Rayon)
        .unwrap();
    assert!(bare.body_lag());
    let lag = thirdbody::body::viscoelastic::creep_lag(
        &match &case.body {
            Body::Viscoelastic(v) => v.model().creep,
            _ => unreachable!(),
        },
        grid.cell(),
        1e-4 * A0,
    );
    // 0.9 of the creep length V tau_c = 1e-3 a0.
    assert!((lag / (0.9e-3 * A0) - 1.0).abs() < 1e-12, "{lag}");
    case.layer = Some(cases::paper_sigmoid_layer());
    let layered = case
        .assemble(&grid, &mut kernels, Parallelism::Rayon)
        .unwrap();
    assert!(!layered.body_lag());
    // The slider's height is read at f - lag f' only without the layer.
    let moved = bare
        .shape()
        .iter()
        .zip(layered.shape())
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    let steepest = layered.slope().iter().fold(0.0f64, |m, d| m.max(d.abs()));
    assert!((moved / (lag * steepest) - 1.0).abs() < 1e-9, "{moved}");
}
