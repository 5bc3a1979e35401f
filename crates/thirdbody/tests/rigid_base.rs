//! Rigid-base limit of the layer contact (issue 2, acceptance 2 and the second half
//! of 3): the solver on a very stiff body against the semi-analytic per-row
//! solution of `tests/common/rigid_base.rs`, and checks of that oracle itself.

mod common;

use common::rigid_base::{
    gauss_legendre, linear_pressure, trailing_edge_depth, Law, RigidBase, ROWS,
};

/// Relative difference.
fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// Composite Gauss–Legendre quadrature of f on [a, b], an independent integrator
/// for the closed forms.
fn quad(f: impl Fn(f64) -> f64, a: f64, b: f64, panels: usize) -> f64 {
    let (t, w) = gauss_legendre(20);
    let h = (b - a) / panels as f64;
    (0..panels)
        .map(|k| {
            let mid = a + (k as f64 + 0.5) * h;
            t.iter()
                .zip(&w)
                .map(|(t, w)| 0.5 * h * w * f(mid + 0.5 * h * t))
                .sum::<f64>()
        })
        .sum()
}

/// The paper's sigmoid law (eq. 11), written out here independently of the library.
fn sigmoid(c0: f64, delta: f64, p0: f64) -> impl Fn(f64) -> f64 {
    move |p: f64| c0 * (1.0 + delta - 2.0 * delta / (1.0 + (-p / p0).exp()))
}

#[test]
fn gauss_legendre_integrates_polynomials_exactly() {
    let (t, w) = gauss_legendre(7);
    for k in 0..14 {
        let q: f64 = t.iter().zip(&w).map(|(t, w)| w * t.powi(k)).sum();
        let exact = if k % 2 == 1 {
            0.0
        } else {
            2.0 / (k as f64 + 1.0)
        };
        assert!((q - exact).abs() < 1e-14, "x^{k}: {q} vs {exact}");
    }
}

#[test]
fn linear_row_closed_form_satisfies_the_integral_contact_condition() {
    // w3 = C0 p + (C0 / L) int_x^b p ds must equal (b^2 - x^2) / (2R) on (x_t, b),
    // with the integral done by quadrature of the closed-form pressure.
    let (r, c0) = (1.0, 0.02);
    for &(b, l) in &[(0.05, 0.01), (0.01, 0.03), (0.2, 0.002)] {
        let base = RigidBase {
            radius: r,
            creep_length: l,
            load: 1.0,
        };
        let row = base.row(&Law::Linear { compliance: c0 }, b);
        let p = |x: f64| linear_pressure(x, b, l, r, c0);
        let xt = row.trailing_edge;
        let scale = b * b / (2.0 * r);
        for k in 1..10 {
            let x = xt + (b - xt) * k as f64 / 10.0;
            let w3 = c0 * p(x) + c0 / l * quad(p, x, b, 40);
            assert!(
                (w3 - (b * b - x * x) / (2.0 * r)).abs() < 1e-12 * scale,
                "{b} {l} {x}"
            );
            assert!(p(x) > 0.0);
        }
        // The trailing edge is a zero of p, and p is negative beyond it.
        assert!(p(xt).abs() < 1e-12 * row.max_pressure, "p(x_t) = {}", p(xt));
        assert!(p(xt - 1e-6 * b) < 0.0);
        assert!(xt < 0.0 && xt > -b);
        // Load, moment and maximum against quadrature and a scan.
        assert!(rel(row.load, quad(p, xt, b, 40)) < 1e-12);
        assert!(rel(row.moment, quad(|x| x * p(x), xt, b, 40)) < 1e-10);
        let scan = (0..=20_000)
            .map(|k| p(xt + (b - xt) * k as f64 / 20_000.0))
            .fold(0.0, f64::max);
        assert!(row.max_pressure >= scan && rel(row.max_pressure, scan) < 1e-6);
        assert!(rel(p(row.max_pressure_x), row.max_pressure) < 1e-14);
    }
}

#[test]
fn trailing_edge_depth_solves_its_equation_for_small_and_large_rows() {
    for &beta in &[1e-8f64, 1e-4, 0.3, 1.0, 7.0, 300.0] {
        let z = trailing_edge_depth(beta);
        let lhs = (1.0 + beta) * (1.0 - (-z).exp());
        assert!(
            (lhs - z).abs() < 1e-14 * z.max(1e-300) / beta.min(1.0),
            "{beta}: {z}"
        );
        // Small rows: z = 2 beta / (1 + beta) to leading order (Winkler, x_t = -b).
        if beta < 1e-3 {
            assert!(rel(z, 2.0 * beta) < 2.0 * beta, "{beta}: {z}");
        }
    }
}

#[test]
fn nonlinear_rows_satisfy_the_integrated_contact_condition_at_the_trailing_edge() {
    // At x_t, p = 0: the instantaneous part vanishes and the frozen creep
    // (1/L) int C[p] p dx must equal D - f(x_t) = (b^2 - x_t^2) / (2R).
    let (r, l) = (1.0, 0.01);
    let base = RigidBase {
        radius: r,
        creep_length: l,
        load: 1.0,
    };
    let c = sigmoid(0.02, 0.5, 0.05);
    for law in [Law::Exact(&c), Law::Secant(&c)] {
        for &b in &[0.002, 0.03, 0.08] {
            let row = base.row(&law, b);
            let xt = row.trailing_edge;
            let expect = (b * b - xt * xt) / (2.0 * r);
            assert!(
                rel(row.creep_integral / l, expect) < 1e-9,
                "b = {b}: {row:?}"
            );
            assert!(xt < 0.0 && xt > -b);
        }
    }
}

#[test]
fn exact_and_secant_with_constant_compliance_reproduce_the_linear_closed_form() {
    // Oracle check (a): delta = 0 through the numerical paths.
    let c0 = 0.02;
    let constant = move |_: f64| c0;
    let sig0 = sigmoid(c0, 0.0, 0.05);
    let base = RigidBase {
        radius: 1.0,
        creep_length: 0.01,
        load: 4e-5,
    };
    let linear = Law::Linear { compliance: c0 };
    for &b in &[1e-4f64, 0.01, 0.06] {
        let reference = base.row(&linear, b);
        for law in [Law::Exact(&constant), Law::Exact(&sig0), Law::Secant(&sig0)] {
            let row = base.row(&law, b);
            let scale = b.max(base.creep_length);
            assert!(
                rel(row.load, reference.load) < 1e-8,
                "{row:?} vs {reference:?}"
            );
            assert!(rel(row.moment, reference.moment) < 1e-8);
            assert!(rel(row.max_pressure, reference.max_pressure) < 1e-8);
            assert!((row.trailing_edge - reference.trailing_edge).abs() < 1e-8 * scale);
        }
    }
    let reference = base.solve(&linear);
    for law in [Law::Exact(&sig0), Law::Secant(&sig0)] {
        let s = base.solve(&law);
        assert!(
            rel(s.approach, reference.approach) < 1e-8,
            "{s:?} vs {reference:?}"
        );
        assert!(rel(s.max_pressure, reference.max_pressure) < 1e-8);
        assert!(rel(s.friction_coefficient, reference.friction_coefficient) < 1e-8);
        assert!((s.x_min - reference.x_min).abs() < 1e-8 * reference.x_max);
    }
    // The y quadrature has converged: doubling the rows changes nothing visible.
    let fine = base.solve_with(&linear, 2 * ROWS);
    assert!(rel(fine.approach, reference.approach) < 1e-12);
    assert!(rel(fine.friction_coefficient, reference.friction_coefficient) < 1e-12);
}

#[test]
fn without_creep_the_oracle_is_the_winkler_foundation() {
    // Oracle check (b): V -> infinity leaves p = (D - f) / C0 on a disc of radius
    // a = (4 R C0 Q / pi)^(1/4), p_max = D / C0, mu = 0. Corrections are O(a / L).
    let (r, c0, q) = (1.0, 0.02, 4e-5);
    let a = (4.0 * r * c0 * q / std::f64::consts::PI).powf(0.25);
    let base = RigidBase {
        radius: r,
        creep_length: 1e4 * a,
        load: q,
    };
    let s = base.solve(&Law::Linear { compliance: c0 });
    eprintln!("Winkler: a = {a:.6e}, oracle b0 = {:.6e}", s.contact_radius);
    assert!(rel(s.contact_radius, a) < 1e-3, "{s:?}");
    assert!(rel(s.max_pressure, a * a / (2.0 * r * c0)) < 1e-3);
    assert!(rel(s.x_min, -a) < 1e-3);
    // mu = (R C0 / (L R Q)) int int p^2 = a^2 / (3 R L) to leading order.
    assert!(
        rel(
            s.friction_coefficient,
            a * a / (3.0 * r * base.creep_length)
        ) < 1e-3
    );
    // The sigmoid law with a vanishing drop goes the same way through RK4.
    let c = sigmoid(c0, 0.0, 1.0);
    let e = base.solve(&Law::Exact(&c));
    assert!(rel(e.contact_radius, a) < 1e-3);
}

#[test]
fn fast_creep_gives_the_half_disc_asymptote() {
    // Oracle check (c): for V T << contact size, p ~ V T x / (C0 R) on the half
    // disc 0 < x < sqrt(r^2 - y^2), r = (3 Q C0 R / (2 V T))^(1/3), p_max = L r / (C0 R).
    let (r, c0, q): (f64, f64, f64) = (1.0, 0.02, 5e-6);
    let mut errors = Vec::new();
    for &l in &[1e-3, 1e-4, 1e-5] {
        let base = RigidBase {
            radius: r,
            creep_length: l,
            load: q,
        };
        let s = base.solve(&Law::Linear { compliance: c0 });
        let radius = (3.0 * q * c0 * r / (2.0 * l)).powf(1.0 / 3.0);
        let e = rel(s.contact_radius, radius);
        eprintln!(
            "half disc: V T = {l:e}: r = {radius:.5}, oracle b0 = {:.5} (rel {e:.2e}), \
             x_min = {:.3e}, p_max / (L r / C0 R) = {:.4}",
            s.contact_radius,
            s.x_min,
            s.max_pressure / (l * radius / (c0 * r))
        );
        // The trailing edge sits within one creep length behind x = 0.
        assert!(s.x_min < 0.0 && s.x_min >= -l);
        errors.push((l / radius, e, rel(s.max_pressure, l * radius / (c0 * r))));
    }
    // design.md §1a quotes r ~ 0.053 for V' = 1e-3.
    assert!((0.0531 - (3.0 * 5e-6 * 0.02 / 2e-3f64).powf(1.0 / 3.0)).abs() < 1e-4);
    for &(ratio, e_radius, e_pmax) in &errors {
        // Next order: a row of half width b >> L carries (L / (R C0)) (b^2 - L^2) / 2,
        // so Q = (2 L r^3 / (3 R C0)) (1 - 3 L^2 / (2 r^2)) and b0 = r (1 + (L / r)^2 / 2).
        assert!(
            (e_radius - 0.5 * ratio * ratio).abs() < 0.05 * ratio * ratio,
            "{ratio}: {e_radius}"
        );
        // p_max = L x_m / (R C0), x_m = b0 - L ln(1 + b0 / L): falls like (L / r) ln(r / L).
        assert!(
            e_pmax < 2.0 * ratio * (1.0 / ratio).ln(),
            "{ratio}: {e_pmax}"
        );
    }
    assert!(errors[2].1 < errors[0].1 / 10.0);
}
