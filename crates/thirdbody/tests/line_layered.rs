//! Coated line contacts (plane strain): a cylinder on a coating bonded to a
//! half-space, against Hertz's line contact (Johnson, Contact Mechanics, eq.
//! 4.43-4.45) in the limits where the coating is the substrate's own material, far
//! thinner than the contact (the substrate's Hertz) or far thicker (the coating's);
//! between them the contact converges with the grid. The stack's plane-strain
//! kernel itself is checked against direct quadrature of its transfer function in
//! `body::stack_line`.

mod cases;

use std::f64::consts::PI;
use thirdbody::body::layered::{Base, BaseContact, Ply, Stack};
use thirdbody::*;

const LOAD: f64 = 1e-3;

fn coated(coating: f64, thickness: f64, cells: usize) -> Case {
    let material = |young: f64| Elastic {
        young,
        poisson: 0.3,
    };
    let mut case = cases::cylinder(LOAD, cells);
    case.body = Body::coated(material(coating), thickness, material(1.0));
    case
}

/// Hertz's half-width and peak pressure on a half-space of Young's modulus `young`.
fn hertz(young: f64) -> (f64, f64) {
    let e_star = young / (1.0 - 0.09);
    let a = (4.0 * LOAD / (PI * e_star)).sqrt();
    (a, 2.0 * LOAD / (PI * a))
}

fn half_width_and_peak(case: &Case) -> (f64, f64) {
    let m = solve(case, &SolverParams::default()).unwrap().summary();
    (0.5 * (m.contact_x_max - m.contact_x_min), m.max_pressure)
}

#[test]
fn coated_line_contacts_reach_hertz_in_their_limits() {
    let (a_sub, _) = hertz(1.0);
    for (name, coating, thickness, young) in [
        ("own material", 1.0, 0.5 * a_sub, 1.0),
        ("thin stiff", 10.0, 1e-5 * a_sub, 1.0),
        ("thin soft", 0.1, 1e-5 * a_sub, 1.0),
        ("thick stiff", 10.0, 1e4 * a_sub, 10.0),
        ("thick soft", 0.1, 1e4 * a_sub, 0.1),
    ] {
        let (a, p0) = hertz(young);
        let (half_width, peak) = half_width_and_peak(&coated(coating, thickness, 2048));
        let errors = (half_width / a - 1.0, peak / p0 - 1.0);
        eprintln!(
            "{name}: half-width {:+.2e}, peak {:+.2e}",
            errors.0, errors.1
        );
        assert!(
            errors.0.abs() < 2e-3 && errors.1.abs() < 2e-3,
            "{name}: {errors:?}"
        );
    }
}

/// A cylinder on a thin compressible layer bonded to a rigid base, against the
/// published thin-layer limit: Kalker's first-order (Winkler) theory, `w = L_z p`
/// with `L_z = t (1 + nu) (1 - 2 nu) / ((1 - nu) E)` (J. J. Kalker, Three-Dimensional
/// Elastic Bodies in Rolling Contact, Kluwer, 1990, section 3.2, as quoted in the
/// CONTACT user guide, "Compressible elastic layer", github.com/eve70a/CONTACT,
/// doc/user-guide.tex). Under a cylinder of radius R such a foundation carries
/// `p = (delta - x^2 / (2 R)) / L_z` on `|x| < a`, so `a^3 = 3 Q R L_z / 2` and
/// `p0 = a^2 / (2 R L_z)`. The layer's own shear spreads the load over about its
/// thickness t: the peak differs by O((t / a)^2), the half-width (set where the
/// pressure vanishes, inside a boundary layer of width t) by O(t / a).
#[test]
fn a_thin_bonded_layer_on_a_rigid_base_carries_a_cylinder_as_kalkers_foundation() {
    let (young, poisson, radius) = (1.0, 0.3, 1.0f64);
    let a_winkler: f64 = 2e-3;
    let mut previous_peak_error: Option<f64> = None;
    for ratio in [0.02, 0.01, 0.005] {
        let thickness = ratio * a_winkler;
        let flexibility =
            thickness * (1.0 + poisson) * (1.0 - 2.0 * poisson) / ((1.0 - poisson) * young);
        let load = a_winkler.powi(3) / (1.5 * radius * flexibility);
        let p0_winkler = a_winkler * a_winkler / (2.0 * radius * flexibility);
        let mut case = cases::cylinder(load, 4096);
        case.body = Body::Layered(Stack {
            layers: vec![Ply {
                material: Elastic { young, poisson },
                thickness,
            }],
            base: Base::Rigid(BaseContact::Bonded),
        });
        let solution = solve(&case, &SolverParams::default()).unwrap();
        let m = solution.summary();
        let half_width = 0.5 * (m.contact_x_max - m.contact_x_min);
        let width_error = half_width / a_winkler - 1.0;
        let peak_error = m.max_pressure / p0_winkler - 1.0;
        let cell = m.cell_size / a_winkler;
        eprintln!(
            "t / a = {ratio}: half-width {width_error:+.2e} (cell {cell:.1e} a), peak {peak_error:+.2e}"
        );
        // Measured: half-width -2.4e-3, -1.3e-3, -6.2e-4 (0.12 t / a plus the edge's
        // place in its cell), peak -2.9e-5, -7.3e-6, -1.9e-6 (0.075 (t / a)^2).
        assert!(
            width_error.abs() < 0.2 * ratio + cell,
            "t / a = {ratio}: half-width {width_error:+.2e}"
        );
        assert!(
            peak_error.abs() < 0.15 * ratio * ratio,
            "t / a = {ratio}: peak {peak_error:+.2e}"
        );
        if let Some(before) = previous_peak_error {
            let order = (before / peak_error).log2();
            assert!(
                (1.6..2.4).contains(&order),
                "t / a = {ratio}: the peak's error falls as (t / a)^{order:.2}"
            );
        }
        previous_peak_error = Some(peak_error);
    }
}

#[test]
fn a_coating_as_thick_as_the_contact_converges_with_the_grid() {
    let (a_sub, _) = hertz(1.0);
    for coating in [10.0, 0.1] {
        let results: Vec<(f64, f64)> = [512, 1024, 2048, 4096]
            .iter()
            .map(|&cells| half_width_and_peak(&coated(coating, a_sub, cells)))
            .collect();
        let finest = results[3];
        for (k, r) in results.iter().enumerate() {
            eprintln!(
                "E1/E2 = {coating}, grid {k}: half-width {:+.2e}, peak {:+.2e} from the finest",
                r.0 / finest.0 - 1.0,
                r.1 / finest.1 - 1.0
            );
        }
        let (a, p) = results[2];
        assert!((a / finest.0 - 1.0).abs() < 1e-3 && (p / finest.1 - 1.0).abs() < 1e-3);
    }
}

/// A coating a thousand times stiffer than its substrate and a hundredth of the
/// contact's half-width thick: unpreconditioned conjugate gradients crawl on its
/// kernel (about 3,800 iterations at 256 cells, past the default 2,000; on finer
/// grids they stall), and the automatic choice hands the solve to semi-smooth Newton
/// from their last iterate. The answer must be the discrete problem's: the pressure
/// of conjugate gradients allowed to run to the end on the same window (another
/// algorithm and stopping rule), and the load balanced.
#[test]
fn a_thin_coating_far_stiffer_than_its_substrate_solves_on_the_default_parameters() {
    let (a_sub, _) = hertz(1.0);
    let case = coated(1000.0, 0.01 * a_sub, 256);
    let auto = solve(&case, &SolverParams::default()).unwrap();
    assert_eq!(auto.info.method, Method::SemismoothNewton);
    let load: f64 = auto.pressure.iter().sum::<f64>() * auto.grid.cell_measure();
    assert!((load / LOAD - 1.0).abs() < 1e-10, "load {load:e}");
    let mut fixed = case.clone();
    fixed.grid.half_width = Some(auto.grid.half_widths());
    fixed.grid.centre = Some(auto.grid.centre());
    // Both to a residual of 1e-12: on a kernel this ill-conditioned two solutions
    // at 1e-10 differ by 3e-5 of the peak.
    let tight = |method, max_iterations| SolverParams {
        tolerance: 1e-12,
        max_iterations,
        method,
        ..SolverParams::default()
    };
    let auto = solve(&fixed, &tight(None, 2000)).unwrap();
    assert_eq!(auto.info.method, Method::SemismoothNewton);
    let cg = solve(&fixed, &tight(Some(Method::PolonskyKeer), 100_000)).unwrap();
    assert_eq!(cg.grid.len(), auto.grid.len());
    assert!(
        cg.info.iterations > 2000,
        "{} iterations",
        cg.info.iterations
    );
    let peak = cg.pressure.iter().fold(0.0f64, |m, &v| m.max(v));
    let worst = cg
        .pressure
        .iter()
        .zip(&auto.pressure)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    eprintln!(
        "CG {} iterations; automatic: {} iterations, {} linear; max |dp| / p_max = {:.1e}",
        cg.info.iterations,
        auto.info.iterations,
        auto.info.linear_iterations,
        worst / peak
    );
    assert!(worst <= 1e-6 * peak, "max |dp| = {:e} p_max", worst / peak);
}

/// Under the same coating the pressure peaks at the contact's edges over about a
/// third of the coating's thickness. The summary warns while the peak sits within a
/// few cells of the edge, exactly where max_pressure is still off: at 1,024 cells
/// (1.7 % below the 8,192-cell value), not at 4,096 (within 1e-3); Hertz's peak in
/// the middle is never flagged.
#[test]
fn an_unresolved_edge_peak_is_flagged_until_the_grid_resolves_it() {
    let (a_sub, _) = hertz(1.0);
    let edge_warning = |case: &Case| {
        let s = solve(case, &SolverParams::default()).unwrap();
        let flagged = report::model_warnings(case, &s)
            .iter()
            .any(|w| w.contains("peaks within"));
        (s.summary().max_pressure, flagged)
    };
    let (reference, _) = edge_warning(&coated(1000.0, 0.01 * a_sub, 8192));
    for (cells, warned) in [(1024, true), (4096, false)] {
        let (peak, flagged) = edge_warning(&coated(1000.0, 0.01 * a_sub, cells));
        let error = peak / reference - 1.0;
        eprintln!("{cells} cells: peak {error:+.2e} from 8,192 cells, flagged {flagged}");
        assert_eq!(flagged, warned, "{cells} cells");
        assert!(if warned {
            error.abs() > 1e-2
        } else {
            error.abs() < 1e-3
        });
    }
    for cells in [256, 4096] {
        assert!(
            !edge_warning(&coated(1.0, a_sub, cells)).1,
            "Hertz, {cells} cells"
        );
    }
}
