//! Frictionless indentation of an elastic layer on a rigid base by a rigid sphere
//! (thirdbody's paraboloid gap `r^2 / 2R`), bonded to the base or sliding on it
//! without friction, solved by the production solver on its default grid
//! (128 x 128 cells, automatic window) and compared through the stiffening
//! `f = F / F_Hertz(delta)`, `F_Hertz = 4 E* sqrt(R) delta^(3/2) / 3`,
//! `E* = E / (1 - nu^2)`, F the load and delta the approach, with
//!
//! (a) an exact linear-elastic reference: the Hankel-transform reduction of the
//!     axisymmetric layer contact to a Fredholm equation of the second kind, solved
//!     by Nystrom quadrature to ten digits. It is computed by
//!     `tests/data/rigid_base_reference.py` (method, checks and how to re-run in its
//!     docstring: its layer kernels are checked against an independent transfer-matrix
//!     derivation, its thick-layer limit against Hertz, its small-layer-effect slope
//!     against the integral of the kernel); its output is `EXACT` below. Tolerance
//!     1 % on f, for every case (chi = sqrt(R delta) / h = 0.2, 0.4, 0.6; nu = 0.3,
//!     0.45, 0.49, and 0.499 bonded);
//!
//! (b) the thin-layer correction of E. K. Dimitriadis, F. Horkay, J. Maresca,
//!     B. Kachar, R. S. Chadwick, "Determination of elastic moduli of thin layers of
//!     soft material using the atomic force microscope", Biophys. J. 82(5):2798-2810
//!     (2002), doi:10.1016/S0006-3495(02)75620-8: the fourth-order series in chi with
//!     the fitted alpha0(nu), beta0(nu) of the bonded and the non-bonded layer
//!     (`dimitriadis` below). The paper states no accuracy. Against the exact
//!     reference its bonded series is within 0.6 % / 0.85 % at chi = 0.2 for nu = 0.3 /
//!     0.45 and 1.0-1.1 % for nu = 0.49 / 0.499, and drifts to -6 % ... -11 % at
//!     chi = 0.6; its non-bonded alpha0 varies with nu while the exact frictionless-base
//!     kernel does not (the stiffening f is the same for every nu), so it errs by
//!     +2 % ... +9 % at nu = 0.45, 0.49. It is therefore asserted (1 %) only for the
//!     bonded layer at chi = 0.2 with nu = 0.3 and 0.45, and reported elsewhere.
//!
//! Everything is small-strain linear elasticity with the contact on the undeformed
//! surface, as in the solver. R = 1, E = 1, h = 0.1; the load is the exact F at
//! delta = chi^2 h^2 / R, so the solver's approach should come out as that delta.

use std::f64::consts::PI;
use std::time::Instant;

use thirdbody::body::layered::{Base, BaseContact, Ply, Stack};
mod cases;

use thirdbody::{solve, Body, Elastic, SolverParams};

/// One exact case: (bonded?, nu, chi, h, delta, F_exact, f_exact, a_exact / h).
type Exact = (bool, f64, f64, f64, f64, f64, f64, f64);

/// Output of `tests/data/rigid_base_reference.py` (R = 1, E = 1; its last column,
/// Dimitriadis' f, is recomputed here by `dimitriadis`).
#[rustfmt::skip]
const EXACT: [Exact; 21] = [
    (true, 0.3, 0.2, 0.1, 4.000000e-04, 1.4249236564e-05, 1.21563799, 0.213105),
    (true, 0.3, 0.4, 0.1, 1.600000e-03, 1.4304623450e-04, 1.52545399, 0.454439),
    (true, 0.3, 0.6, 0.1, 3.600000e-03, 6.1073460822e-04, 1.92975171, 0.718087),
    (true, 0.45, 0.2, 0.1, 4.000000e-04, 1.6935026381e-05, 1.26615783, 0.215884),
    (true, 0.45, 0.4, 0.1, 1.600000e-03, 1.8052382884e-04, 1.68712211, 0.467364),
    (true, 0.45, 0.6, 0.1, 3.600000e-03, 8.2807974765e-04, 2.29303333, 0.747689),
    (true, 0.49, 0.2, 0.1, 4.000000e-04, 1.8115885911e-05, 1.29058703, 0.217200),
    (true, 0.49, 0.4, 0.1, 1.600000e-03, 1.9920773051e-04, 1.77396040, 0.473922),
    (true, 0.49, 0.6, 0.1, 3.600000e-03, 9.5275086165e-04, 2.51387285, 0.763980),
    (false, 0.3, 0.2, 0.1, 4.000000e-04, 1.3797444282e-05, 1.17709447, 0.210959),
    (false, 0.3, 0.4, 0.1, 1.600000e-03, 1.3311369620e-04, 1.41953278, 0.445840),
    (false, 0.3, 0.6, 0.1, 3.600000e-03, 5.4763863919e-04, 1.73038598, 0.701823),
    (false, 0.45, 0.2, 0.1, 4.000000e-04, 1.5743792222e-05, 1.17709447, 0.210959),
    (false, 0.45, 0.4, 0.1, 1.600000e-03, 1.5189149034e-04, 1.41953278, 0.445840),
    (false, 0.45, 0.6, 0.1, 3.600000e-03, 6.2489173876e-04, 1.73038598, 0.701823),
    (false, 0.49, 0.2, 0.1, 4.000000e-04, 1.6522798127e-05, 1.17709447, 0.210959),
    (false, 0.49, 0.4, 0.1, 1.600000e-03, 1.5940711086e-04, 1.41953278, 0.445840),
    (false, 0.49, 0.6, 0.1, 3.600000e-03, 6.5581150370e-04, 1.73038598, 0.701823),
    (true, 0.499, 0.2, 0.1, 4.000000e-04, 1.8424285879e-05, 1.29718315, 0.217552),
    (true, 0.499, 0.4, 0.1, 1.600000e-03, 2.0435573595e-04, 1.79848773, 0.475727),
    (true, 0.499, 0.6, 0.1, 3.600000e-03, 9.8939061166e-04, 2.57997000, 0.768632),
];

const RADIUS: f64 = 1.0;
const YOUNG: f64 = 1.0;
/// Tolerance on f against the exact reference (and Dimitriadis where asserted).
const TOLERANCE: f64 = 0.01;

fn hertz_force(delta: f64, poisson: f64) -> f64 {
    4.0 * YOUNG / (1.0 - poisson * poisson) * RADIUS.sqrt() * delta.powf(1.5) / 3.0
}

/// Dimitriadis et al. (2002): `F / F_Hertz` as a series in chi.
fn dimitriadis(chi: f64, nu: f64, bonded: bool) -> f64 {
    let (a0, b0) = if bonded {
        (
            -(1.2876 - 1.4678 * nu + 1.3442 * nu * nu) / (1.0 - nu),
            (0.6387 - 1.0277 * nu + 1.5164 * nu * nu) / (1.0 - nu),
        )
    } else {
        (
            -0.347 * (3.0 - 2.0 * nu) / (1.0 - nu),
            0.056 * (5.0 - 2.0 * nu) / (1.0 - nu),
        )
    };
    1.0 - 2.0 * a0 / PI * chi + 4.0 * a0 * a0 / (PI * PI) * chi * chi
        - 8.0 / PI.powi(3) * (a0.powi(3) + 4.0 * PI * PI * b0 / 15.0) * chi.powi(3)
        + 16.0 * a0 / PI.powi(4) * (a0.powi(3) + 3.0 * PI * PI * b0 / 5.0) * chi.powi(4)
}

struct Measured {
    /// Solver's stiffening F / F_Hertz(approach).
    f: f64,
    approach: f64,
    /// Radius of the contact area's equivalent disc.
    radius: f64,
    seconds: f64,
}

fn indent(case: &Exact, cells: usize) -> Measured {
    let &(bonded, poisson, _, thickness, _, load, _, _) = case;
    let base = if bonded {
        BaseContact::Bonded
    } else {
        BaseContact::Frictionless
    };
    // The shared sphere of radius 1 (= RADIUS) under the load on the default grid.
    let mut case = cases::sphere(load, cells);
    case.body = Body::Layered(Stack {
        layers: vec![Ply {
            material: Elastic {
                young: YOUNG,
                poisson,
            },
            thickness,
        }],
        base: Base::Rigid(base),
    });
    let start = Instant::now();
    let solution = solve(&case, &SolverParams::default()).expect("the solve converges");
    let seconds = start.elapsed().as_secs_f64();
    let summary = solution.summary();
    assert!(
        solution.approach.is_finite() && solution.approach > 0.0,
        "approach {}",
        solution.approach
    );
    assert!(solution.pressure.iter().all(|p| p.is_finite() && *p >= 0.0));
    Measured {
        f: load / hertz_force(solution.approach, poisson),
        approach: solution.approach,
        radius: (summary.contact_area / PI).sqrt(),
        seconds,
    }
}

fn name(case: &Exact) -> String {
    let base = if case.0 { "bonded" } else { "frictionless" };
    format!("{base} nu {} chi {}", case.1, case.2)
}

/// Solves the cases whose Poisson's ratio is in `poissons` and checks them.
fn check(poissons: &[f64]) {
    let mut failures = Vec::new();
    for case in EXACT.iter().filter(|c| poissons.contains(&c.1)) {
        let &(bonded, nu, chi, h, delta, _, f_exact, a_exact) = case;
        let m = indent(case, 128);
        let error = m.f / f_exact - 1.0;
        // Dimitriadis at the solver's own approach: F against F_Dimitriadis(delta).
        let chi_solved = (RADIUS * m.approach).sqrt() / h;
        let versus_dimitriadis = m.f / dimitriadis(chi_solved, nu, bonded) - 1.0;
        let dimitriadis_asserted = bonded && chi <= 0.2 && nu <= 0.45;
        eprintln!(
            "{}: f = {:.5} (exact {f_exact:.5}): {:+.3} %; delta {:+.3} %; a/h {:.4} (exact {a_exact:.4}); vs Dimitriadis {:+.2} %{}; {:.1} s",
            name(case),
            m.f,
            100.0 * error,
            100.0 * (m.approach / delta - 1.0),
            m.radius / h,
            100.0 * versus_dimitriadis,
            if dimitriadis_asserted { " (asserted)" } else { "" },
            m.seconds,
        );
        if error.abs() > TOLERANCE {
            failures.push(format!(
                "{}: {:+.3} % from the exact f",
                name(case),
                100.0 * error
            ));
        }
        if dimitriadis_asserted && versus_dimitriadis.abs() > TOLERANCE {
            failures.push(format!(
                "{}: {:+.3} % from Dimitriadis",
                name(case),
                100.0 * versus_dimitriadis
            ));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn compressible_layers_match_the_exact_solution() {
    check(&[0.3, 0.45]);
}

#[test]
fn nearly_incompressible_layers_match_the_exact_solution() {
    check(&[0.49, 0.499]);
}

/// The default grid is converged: finer grids (192 x 192 and 256 x 256) also match
/// the exact f, on the stiffest case (bonded, nu = 0.499, chi = 0.6); their change
/// from the default grid is printed (not asserted: both are solver outputs).
#[test]
fn finer_grids_confirm_the_default_one() {
    let case = EXACT
        .iter()
        .find(|c| c.0 && c.1 == 0.499 && c.2 == 0.6)
        .unwrap();
    let default = indent(case, 128);
    assert!((default.f / case.6 - 1.0).abs() < TOLERANCE);
    for cells in [192, 256] {
        let fine = indent(case, cells);
        eprintln!(
            "{}: f {cells}² {:.6} ({:+.4} %, {:.1} s) against 128² {:.6} ({:+.4} %, {:.1} s); a/h {:.4} against {:.4}",
            name(case),
            fine.f,
            100.0 * (fine.f / case.6 - 1.0),
            fine.seconds,
            default.f,
            100.0 * (default.f / case.6 - 1.0),
            default.seconds,
            fine.radius / case.3,
            default.radius / case.3,
        );
        assert!((fine.f / case.6 - 1.0).abs() < TOLERANCE);
    }
}
