//! Line contacts (plane strain) against closed forms: Hertz's cylinder on an
//! elastic half-space (Johnson, Contact Mechanics, eq. 4.43-4.45).

mod cases;

use cases::cylinder;
use thirdbody::*;

/// Hertz: half-width `a = (4 Q R / (pi E*))^(1/2)`, peak `p0 = 2 Q / (pi a)`,
/// pressure `p0 (1 - x^2 / a^2)^(1/2)` (Johnson eq. 4.43-4.45), and the approach
/// against the surface at distance L from the load,
/// `D = (2 Q / (pi E*)) (ln(2 L / a) + 1/2)`: `(2 / (pi E*)) int p(s) ln(L / |s|) ds`
/// with `int_{-1}^{1} (1 - t^2)^(1/2) ln|t| dt = -(pi / 2)(ln 2 + 1/2)`.
#[test]
fn hertz_line_contact_half_width_peak_pressure_and_approach() {
    use std::f64::consts::PI;
    let (q, r) = (1e-3, 1.0);
    let e_star = 1.0 / (1.0 - 0.09);
    let a = (4.0 * q * r / (PI * e_star)).sqrt();
    let p0 = 2.0 * q / (PI * a);
    for (cells, datum) in [(1024, None), (1024, Some(20.0)), (4096, None)] {
        let mut case = cylinder(q, cells);
        case.loading.reference_distance = datum;
        let s = solve(&case, &SolverParams::default()).unwrap();
        let m = s.summary();
        let half_width = 0.5 * (m.contact_x_max - m.contact_x_min);
        assert!(
            (half_width / a - 1.0).abs() < 1e-3,
            "{cells}: a {half_width} vs {a}"
        );
        assert!(
            (m.max_pressure / p0 - 1.0).abs() < 1e-3,
            "{cells}: p0 {}",
            m.max_pressure
        );
        assert!((m.contact_x_max + m.contact_x_min).abs() < 1e-6 * a);
        let load: f64 = s.pressure.iter().sum::<f64>() * s.grid.cell();
        assert!((load / q - 1.0).abs() < 1e-12, "load balance {load}");
        let l = datum.unwrap_or(r);
        let approach = 2.0 * q / (PI * e_star) * ((2.0 * l / a).ln() + 0.5);
        assert!(
            (m.penetration / approach - 1.0).abs() < 1e-4,
            "{cells}: D {} vs {approach}",
            m.penetration
        );
        // The profile, cell by cell, within a small part of p0 (the cells cut by
        // the edges carry the discretisation's error).
        let worst = (0..s.grid.nx())
            .map(|i| {
                let x = s.grid.x(i);
                let exact = p0 * (1.0 - (x / a).powi(2)).max(0.0).sqrt();
                (s.pressure[i] - exact).abs()
            })
            .fold(0.0, f64::max);
        assert!(worst < 0.02 * p0, "{cells}: worst {worst:e}");
        assert!(
            m.friction_coefficient.abs() < 1e-9 * a / r,
            "mu {}",
            m.friction_coefficient
        );
        assert!(s.grid.is_line() && m.ny == 1);
    }
}

/// The datum moves the approach only: `D(L1) - D(L2) = (2 Q / (pi E*)) ln(L1 / L2)`
/// for any body whose long-wave compliance is `1 / E*` (a line load's displacement
/// at distance L is `(2 Q / (pi E*)) ln(L / r)`), and the pressure not at all, also
/// with a datum inside the contact and far beyond it, and on a creeping body whose
/// relaxed far field lies beyond the window.
#[test]
fn the_datum_moves_the_approach_only() {
    use std::f64::consts::PI;
    use thirdbody::body::{SolidRheology, ViscoelasticHalfSpace};
    let q = 1e-3;
    let elastic = cylinder(q, 512);
    let mut zener = cylinder(q, 512);
    zener.body = Body::Viscoelastic(ViscoelasticHalfSpace {
        rheology: SolidRheology::Zener {
            glassy_modulus: 10.0,
            relaxed_modulus: 1.0,
            relaxation_time: 1.0,
        },
        poisson: 0.3,
    });
    zener.loading.velocity = Some(3.0);
    let relaxed_star = 1.0 / (1.0 - 0.09);
    for base in [elastic, zener] {
        let solved = |datum: f64| {
            let mut c = base.clone();
            c.loading.reference_distance = Some(datum);
            let tight = SolverParams {
                tolerance: 1e-13,
                ..SolverParams::default()
            };
            solve(&c, &tight).unwrap()
        };
        let reference = solved(1.0);
        for datum in [1e-4, 1e-2, 1e3, 1e8] {
            let s = solved(datum);
            let expected = 2.0 * q / (PI * relaxed_star) * (datum.ln() - 1.0f64.ln());
            let moved = s.approach - reference.approach;
            assert!(
                (moved - expected).abs() < 1e-9 * expected.abs().max(reference.approach),
                "datum {datum}: {moved} vs {expected}"
            );
            let worst = s
                .pressure
                .iter()
                .zip(&reference.pressure)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            let peak = reference.summary().max_pressure;
            assert!(
                worst < 1e-9 * peak,
                "datum {datum}: pressure moved by {worst:e}"
            );
        }
    }
}

/// A profile sampled from the cylinder `x^2 / (2 R)` every 1e-6 R (heights shifted
/// by a constant) gives the cylinder's contact: the linear interpolant is within
/// `s^2 / (8 R)` of the parabola, which moves the pressure by about `E* s^2 / (8 R h)`
/// (1.6e-6 of the peak with samples every 1e-5 R; 1.6e-8 here).
#[test]
fn a_sampled_profile_is_the_cylinder() {
    let n = 120_001;
    let spacing = 1e-6;
    let heights: Vec<f64> = (0..n)
        .map(|i| {
            let x = (i as f64 + 0.5 - 0.5 * n as f64) * spacing;
            x * x / 2.0 + 0.25
        })
        .collect();
    // The same fixed window for both (an automatic one follows the curvature the
    // profile's samples give, 1e-7 off R by rounding).
    let mut fixed = cylinder(1e-3, 1024);
    fixed.grid.half_width = Some([0.05, 0.0]);
    let tight = SolverParams {
        tolerance: 1e-13,
        ..SolverParams::default()
    };
    let cylinder = solve(&fixed, &tight).unwrap();
    let mut case = cylinder_case_with(Slider::Profile(Profile {
        cell_size: spacing,
        heights,
    }));
    case.loading.reference_distance = Some(1.0);
    case.grid.half_width = Some([0.05, 0.0]);
    let profile = solve(&case, &tight).unwrap();
    let (a, b) = (cylinder.summary(), profile.summary());
    for (what, x, y) in [
        ("peak", a.max_pressure, b.max_pressure),
        (
            "half-width",
            a.contact_x_max - a.contact_x_min,
            b.contact_x_max - b.contact_x_min,
        ),
        ("approach", a.penetration, b.penetration),
    ] {
        assert!((x / y - 1.0).abs() < 1e-6, "{what}: {x} vs {y}");
    }
    assert!(b.friction_coefficient.abs() < 1e-5 * 0.034);
    // A profile of two samples, or one with a NaN, is refused naming the file.
    for heights in [vec![0.0, 1.0], vec![0.0, f64::NAN, 1.0]] {
        let e = solve(
            &cylinder_case_with(Slider::Profile(Profile {
                cell_size: 1.0,
                heights,
            })),
            &SolverParams::default(),
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("slider.file"), "{e}");
    }
}

fn cylinder_case_with(slider: Slider) -> Case {
    Case {
        slider,
        ..cylinder(1e-3, 1024)
    }
}
