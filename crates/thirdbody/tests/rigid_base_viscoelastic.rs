//! Checks of the rigid-base reference for Kelvin–Voigt and Zener layers
//! (tests/common/rigid_base_viscoelastic.rs) against independent computations: the
//! integral form of the contact condition, a marching complementarity solver that
//! knows nothing of the contact set, the closed form of the Kelvin–Voigt contact, the
//! `C_g -> 0` limit, and the fast- and slow-sliding limits.

mod common;

use common::rigid_base::gauss_legendre;
use common::rigid_base_viscoelastic::{
    kelvin_voigt, kelvin_voigt_closed_form, zener, Rheology, ViscoelasticRigidBase, ROWS,
};
use std::f64::consts::PI;

/// Relative difference.
fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// Composite 20-point Gauss–Legendre quadrature of f on [a, b] with `panels`
/// equal panels: an integrator independent of the reference's graded panels.
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

/// Numbers as `[1.2e-3, ...]`.
fn sci(values: &[f64]) -> String {
    let items: Vec<String> = values.iter().map(|v| format!("{v:.1e}")).collect();
    format!("[{}]", items.join(", "))
}

const R: f64 = 1.0;

fn base(rheology: Rheology, creep_length: f64, load: f64) -> ViscoelasticRigidBase {
    ViscoelasticRigidBase {
        radius: R,
        creep_length,
        load,
        rheology,
    }
}

const KV: Rheology = Rheology::KelvinVoigt { compliance: 0.02 };
const ZENER: Rheology = Rheology::Zener {
    glassy: 0.01,
    branch: 0.02,
};
const ZENER_STIFF_GLASS: Rheology = Rheology::Zener {
    glassy: 0.002,
    branch: 0.02,
};

#[test]
fn rows_satisfy_the_integral_contact_condition_and_leave_the_gap_open() {
    // w = C_g p + (C_1 / L) int_x^b exp(-(s - x) / L) p(s) ds, by quadrature of the
    // closed-form pressure, must equal h = (b^2 - x^2) / (2R) on (x_t, b) and exceed
    // it behind x_t; p > 0 inside, p < 0 just behind x_t (the zero is the edge).
    for rheology in [KV, ZENER, ZENER_STIFF_GLASS] {
        for &(b, l) in &[(0.05, 0.01), (0.01, 0.03), (0.2, 0.002)] {
            let s = base(rheology, l, 1.0);
            let row = s.row(b);
            let xt = row.trailing_edge;
            let (cg, c1, cr) = (rheology.glassy(), rheology.branch(), rheology.relaxed());
            let p = |x: f64| s.pressure(b, xt, x);
            let branch = |x: f64| c1 / l * quad(|t| (-(t - x) / l).exp() * p(t), x.max(xt), b, 400);
            let h = |x: f64| (b * b - x * x) / (2.0 * R);
            let scale = b * b / (2.0 * R);
            let mut worst: f64 = 0.0;
            for k in 1..10 {
                let x = xt + (b - xt) * k as f64 / 10.0;
                let w = cg * p(x) + branch(x);
                worst = worst.max((w - h(x)).abs() / scale);
                assert!(p(x) > 0.0, "{rheology:?} {b} {l}: p({x}) = {}", p(x));
            }
            assert!(
                worst < 1e-12,
                "{rheology:?} {b} {l}: contact residual {worst:e}"
            );
            // Behind: the gap is open and follows the recovery w1(x_t) e^{(x - x_t)/L}.
            let wt = branch(xt);
            assert!((wt - h(xt)).abs() < 1e-12 * scale);
            for k in 1..=10 {
                let x = xt - (b - xt) * k as f64 / 10.0;
                let w = branch(x);
                assert!(rel(w, wt * ((x - xt) / l).exp()) < 1e-10);
                assert!(
                    w - h(x) > 0.0,
                    "{rheology:?} {b} {l}: gap {} at {x}",
                    w - h(x)
                );
            }
            // Ahead of b the slider is above the unloaded layer: h < 0 = w.
            assert!(h(b * 1.001) < 0.0);
            // The trailing edge is a zero of the formula; -b < x_t < KV edge <= 0.
            let pf = |x: f64| s.pressure_formula(b, x);
            assert!(
                pf(xt).abs() < 1e-12 * row.max_pressure,
                "p(x_t) = {}",
                pf(xt)
            );
            assert!(pf(xt - 1e-6 * b) < 0.0);
            let kv_edge = l - (l * l + b * b).sqrt();
            assert!(xt > -b && xt <= kv_edge + 1e-15 * b, "{xt} vs {kv_edge}");
            // Leading edge: a jump L b / (R C) for Kelvin–Voigt; for Zener p(b) = 0
            // and the glassy Winkler slope -b / (R C_g).
            if cg == 0.0 {
                assert!(rel(pf(b), l * b / (R * c1)) < 1e-14);
            } else {
                assert!(pf(b).abs() < 1e-15 * row.max_pressure);
                let eps = 1e-6 * b.min(l * cg / cr);
                let fd = (pf(b) - pf(b - eps)) / eps;
                assert!(rel(fd, -b / (R * cg)) < 1e-4, "{fd} vs {}", -b / (R * cg));
                assert!(rel(s.pressure_slope(b, b), -b / (R * cg)) < 1e-14);
            }
            // Load, moment and maximum against quadrature and a scan.
            let load = quad(p, xt, b, 400);
            let moment = quad(|x| x * p(x), xt, b, 400);
            assert!(rel(row.load, load) < 1e-12, "{} vs {load}", row.load);
            assert!(
                rel(row.moment, moment) < 1e-10,
                "{} vs {moment}",
                row.moment
            );
            // The moment identity C_r M = L C_1 W + L h_t (x_t - L) + R h_t^2 / 2.
            let ht = h(xt);
            let identity = (l * c1 * load + l * ht * (xt - l) + R * ht * ht / 2.0) / cr;
            assert!(rel(identity, moment) < 1e-9, "{identity} vs {moment}");
            if cg == 0.0 {
                let kv = l * load - l * l * b * b / (2.0 * R * c1);
                assert!(rel(kv, moment) < 1e-9);
            }
            let scan = (0..=20_000)
                .map(|k| p(xt + (b - xt) * k as f64 / 20_000.0))
                .fold(0.0, f64::max);
            assert!(row.max_pressure >= scan * (1.0 - 1e-14));
            assert!(rel(row.max_pressure, scan) < 1e-6);
            assert!(rel(p(row.max_pressure_x), row.max_pressure) < 1e-14);
            eprintln!(
                "{rheology:?} b = {b}, L = {l}: contact residual {worst:.1e}, x_t = {xt:.6e}, \
                 W = {:.6e}, M = {:.6e}, p_max = {:.6e} at {:.5e}",
                row.load, row.moment, row.max_pressure, row.max_pressure_x
            );
        }
    }
}

/// A row solved by marching in -x from `x = b` with steps `dx`, with no knowledge of
/// the contact set: at each node the branch is advanced exactly over the step with
/// p constant (the new value), and the complementarity condition at the node,
/// `p >= 0, C_g p + w1 - h >= 0`, one of them an equality, fixes p. Valid because
/// on a rigid base w at x depends only on p upstream (s >= x).
struct Marched {
    load: f64,
    moment: f64,
    trailing_edge: f64,
    max_pressure: f64,
    /// Separate intervals of contact seen down to x = -3b.
    intervals: usize,
    /// Pressure at the first node behind b.
    first: f64,
}

fn march(rheology: Rheology, l: f64, b: f64, dx: f64, to: f64) -> Marched {
    let (cg, c1) = (rheology.glassy(), rheology.branch());
    let delta = dx / l;
    let (decay, gain) = ((-delta).exp(), -(-delta).exp_m1());
    let h = |x: f64| (b * b - x * x) / (2.0 * R);
    let (mut w1, mut p_old, mut in_contact) = (0.0, 0.0, false);
    let mut out = Marched {
        load: 0.0,
        moment: 0.0,
        trailing_edge: f64::NAN,
        max_pressure: 0.0,
        intervals: 0,
        first: 0.0,
    };
    let mut k = 0usize;
    loop {
        k += 1;
        let x = b - k as f64 * dx;
        if x < to {
            break;
        }
        let free = decay * w1;
        let trial = (h(x) - free) / (cg + c1 * gain);
        let p = trial.max(0.0);
        if k == 1 {
            out.first = p;
        }
        if p > 0.0 && !in_contact {
            in_contact = true;
            out.intervals += 1;
        }
        if p == 0.0 && in_contact {
            in_contact = false;
            // The trial value is the continuation of p: interpolate its zero.
            out.trailing_edge = x + dx * trial / (trial - p_old);
        }
        w1 = free + c1 * gain * p;
        // p holds on the step [x, x + dx].
        out.load += p * dx;
        out.moment += p * (x + 0.5 * dx) * dx;
        out.max_pressure = out.max_pressure.max(p);
        p_old = p;
    }
    out
}

#[test]
fn a_marching_complementarity_solver_reproduces_the_rows() {
    // First order in dx; the extrapolation 2 F(dx/2) - F(dx) must agree with the
    // closed forms to a few 1e-6, and the raw error must halve with dx.
    for rheology in [KV, ZENER, ZENER_STIFF_GLASS] {
        for &(b, l) in &[(0.05, 0.01), (0.01, 0.03), (0.2, 0.002)] {
            let s = base(rheology, l, 1.0);
            let row = s.row(b);
            let dx = b.min(l) / 2000.0;
            let coarse = march(rheology, l, b, dx, -3.0 * b);
            let fine = march(rheology, l, b, dx / 2.0, -3.0 * b);
            assert_eq!(fine.intervals, 1, "{rheology:?} {b} {l}: contact resumed");
            let x_scale = b - row.trailing_edge;
            let errors = [
                (rel(fine.load, row.load), rel(coarse.load, row.load)),
                (rel(fine.moment, row.moment), rel(coarse.moment, row.moment)),
                (
                    (fine.trailing_edge - row.trailing_edge).abs() / x_scale,
                    (coarse.trailing_edge - row.trailing_edge).abs() / x_scale,
                ),
                (
                    rel(fine.max_pressure, row.max_pressure),
                    rel(coarse.max_pressure, row.max_pressure),
                ),
            ];
            let extrapolated = [
                rel(2.0 * fine.load - coarse.load, row.load),
                rel(2.0 * fine.moment - coarse.moment, row.moment),
            ];
            eprintln!(
                "{rheology:?} b = {b}, L = {l}, dx = {dx:.1e}: marched rel errors (dx/2) \
                 W {:.1e}, M {:.1e}, x_t {:.1e}, p_max {:.1e}; extrapolated W {:.1e}, M {:.1e}",
                errors[0].0,
                errors[1].0,
                errors[2].0,
                errors[3].0,
                extrapolated[0],
                extrapolated[1]
            );
            for (fine, _) in errors {
                assert!(fine < 2e-3, "{rheology:?} {b} {l}: {errors:?}");
            }
            // W and M converge at first order, to the closed forms.
            for (fine, coarse) in &errors[..2] {
                assert!(fine < &(0.6 * coarse), "{rheology:?} {b} {l}: {errors:?}");
            }
            for e in extrapolated {
                assert!(
                    e < 1e-5,
                    "{rheology:?} {b} {l}: extrapolated {extrapolated:?}"
                );
            }
            if rheology.glassy() == 0.0 {
                // The Kelvin–Voigt jump is resolved at the first node behind b.
                assert!(rel(fine.first, l * b / (R * rheology.branch())) < 1e-3);
            } else {
                // Zener: no jump, the first node sees the glassy slope b / (R C_g).
                let glassy = (dx / 2.0) * b / (R * rheology.glassy());
                assert!(fine.first < glassy, "{} vs {glassy}", fine.first);
                assert!(fine.first > 0.5 * glassy * rheology.glassy() / rheology.relaxed());
            }
        }
    }
}

#[test]
fn kelvin_voigt_contact_matches_its_closed_form_and_mu_identity() {
    // Row quadrature in theta against the half disc plus circular segment.
    let c = KV.relaxed();
    for &ratio in &[0.05, 0.3, 1.0, 5.0] {
        let a = 0.03;
        let l = ratio * a;
        let s = base(KV, l, 1.0);
        let (q, m, _) = s.contact(a, ROWS);
        let (qc, mc) = kelvin_voigt_closed_form(R, c, l, a);
        eprintln!(
            "KV contact L/a = {ratio}: Q rel err {:.1e}, M rel err {:.1e}",
            rel(q, qc),
            rel(m, mc)
        );
        assert!(
            rel(q, qc) < 1e-12 && rel(m, mc) < 1e-11,
            "{q} {qc} {m} {mc}"
        );
        // mu = (L / R)(1 - 2 L a^3 / (3 R C Q)) exactly, at the solved contact.
        let solved = base(KV, l, q).solve();
        assert!(rel(solved.contact_radius, a) < 1e-12);
        let mu = l / R * (1.0 - 2.0 * l * a.powi(3) / (3.0 * R * c * q));
        assert!(rel(solved.friction_coefficient, mu) < 1e-11);
        // Extents and maximum of the paraboloid centred at (L, 0).
        let xm = l.min(a);
        assert_eq!(solved.max_pressure_x, xm);
        let pm = (a * a + l * l - (xm - l) * (xm - l)) / (2.0 * R * c);
        assert!(rel(solved.max_pressure, pm) < 1e-14);
        assert!(rel(solved.x_min, l - (l * l + a * a).sqrt()) < 1e-12);
    }
}

#[test]
fn zener_with_a_vanishing_glassy_compliance_tends_to_kelvin_voigt() {
    // The leading-edge layer of width lambda = L C_g / C_r shrinks to the KV jump.
    let (l, q) = (0.01, 2e-5);
    let kv = base(KV, l, q);
    let reference = kv.solve();
    let mut previous = f64::INFINITY;
    for &g in &[1e-2, 1e-3, 1e-4] {
        let c = KV.relaxed();
        let z = base(
            Rheology::Zener {
                glassy: g * c,
                branch: c,
            },
            l,
            q,
        );
        let (rk, rz) = (kv.row(0.03), z.row(0.03));
        let s = z.solve();
        let errors = [
            rel(rz.load, rk.load),
            rel(rz.moment, rk.moment),
            rel(rz.max_pressure, rk.max_pressure),
            rel(s.approach, reference.approach),
            rel(s.max_pressure, reference.max_pressure),
            rel(s.friction_coefficient, reference.friction_coefficient),
            (s.x_min - reference.x_min).abs() / reference.x_max,
        ];
        let worst = errors.iter().cloned().fold(0.0, f64::max);
        eprintln!("Zener C_g/C = {g:e} vs KV: rel errors {}", sci(&errors));
        assert!(worst < 3.0 * g, "{g}: {errors:?}");
        assert!(worst < previous / 5.0);
        previous = worst;
    }
}

/// Winkler bed of compliance c: contact radius, p_max = D / c.
fn winkler(c: f64, q: f64) -> (f64, f64) {
    let a = (4.0 * R * c * q / PI).powf(0.25);
    (a, a * a / (2.0 * R * c))
}

#[test]
fn fast_sliding_zener_is_the_glassy_winkler_bed() {
    let q = 4e-5;
    let (cg, c1) = (ZENER.glassy(), ZENER.branch());
    let (a, pmax) = winkler(cg, q);
    let mut previous = f64::INFINITY;
    for &ratio in &[1e2, 1e3, 1e4] {
        let l = ratio * a;
        let s = base(ZENER, l, q).solve();
        // Q = pi R D^2 / C_g on the disc of radius a.
        assert!(rel(PI * R * s.approach.powi(2) / cg, q) < 3.0 / ratio);
        let mu = c1 * a * a / (3.0 * R * l * cg);
        let errors = [
            rel(s.contact_radius, a),
            rel(s.max_pressure, pmax),
            rel(s.x_min, -a),
            s.max_pressure_x.abs() / a,
            rel(s.friction_coefficient, mu),
        ];
        eprintln!(
            "Zener L/a = {ratio:e}: vs glassy Winkler rel errors {}, mu = {:.3e}",
            sci(&errors),
            s.friction_coefficient
        );
        let worst = errors.iter().cloned().fold(0.0, f64::max);
        assert!(worst < 3.0 / ratio, "{ratio}: {errors:?}");
        assert!(worst < previous / 5.0);
        previous = worst;
    }
}

#[test]
fn fast_sliding_kelvin_voigt_is_rigid() {
    // Half disc of radius a = (3 R C Q / (2 L))^(1/3), b0 = a (1 - pi a / (16 L)),
    // p_max = L b0 / (R C) at x = b0, mu -> 3 pi a / (16 R), x_min -> -a^2 / (2L).
    let (q, c) = (4e-5, KV.relaxed());
    let mut previous = f64::INFINITY;
    for &l in &[1.0, 10.0, 100.0] {
        let a = (3.0 * R * c * q / (2.0 * l)).powf(1.0 / 3.0);
        let s = base(KV, l, q).solve();
        let first_order = PI * a / (16.0 * l);
        let e_radius = 1.0 - s.contact_radius / a;
        assert!(
            (e_radius - first_order).abs() < 0.05 * first_order,
            "{l}: {e_radius} vs {first_order}"
        );
        assert_eq!(s.max_pressure_x, s.contact_radius);
        assert!(rel(s.max_pressure, l * s.contact_radius / (R * c)) < 1e-14);
        assert!(s.approach < a * a / (2.0 * R));
        let errors = [
            rel(s.friction_coefficient, 3.0 * PI * a / (16.0 * R)),
            rel(s.x_min, -a * a / (2.0 * l)),
        ];
        eprintln!(
            "KV L = {l}, L/a = {:.1e}: b0/a - 1 = {:.2e} (first order {:.2e}); mu, x_min rel \
             errors {}",
            l / a,
            -e_radius,
            -first_order,
            sci(&errors)
        );
        let worst = errors.iter().cloned().fold(0.0, f64::max);
        assert!(worst < 3.0 * a / l, "{l}: {errors:?}");
        assert!(worst < previous / 5.0);
        previous = worst;
    }
}

#[test]
fn slow_sliding_is_the_relaxed_winkler_bed() {
    // Both layers: Winkler with C_r, mu = L C_1 / (R C_r) to first order.
    let q = 4e-5;
    for rheology in [KV, ZENER] {
        let (a, pmax) = winkler(rheology.relaxed(), q);
        let mut previous = f64::INFINITY;
        for &ratio in &[1e-2, 1e-3, 1e-4] {
            let l = ratio * a;
            let s = base(rheology, l, q).solve();
            let mu = l * rheology.branch() / (R * rheology.relaxed());
            let errors = [
                rel(s.contact_radius, a),
                rel(s.max_pressure, pmax),
                rel(s.x_min, -a),
                s.max_pressure_x.abs() / a,
                rel(s.friction_coefficient, mu),
            ];
            eprintln!(
                "{rheology:?} L/a = {ratio:e}: vs relaxed Winkler rel errors {}",
                sci(&errors)
            );
            let worst = errors.iter().cloned().fold(0.0, f64::max);
            assert!(worst < 3.0 * ratio, "{ratio}: {errors:?}");
            assert!(worst < previous / 5.0);
            previous = worst;
        }
    }
}

#[test]
fn zener_contact_load_and_moment_agree_with_marched_rows() {
    // The whole contact through independently marched rows (Richardson-extrapolated),
    // integrated over y with a different rule (midpoint in y), at the reference's b0.
    for &l in &[0.003, 0.02] {
        let q = 2e-5;
        let s = base(ZENER, l, q);
        let reference = s.solve();
        let b0 = reference.contact_radius;
        let rows = 400;
        let totals = |steps: f64| {
            let (mut load, mut moment) = (0.0, 0.0);
            for j in 0..rows {
                // Midpoint rule in theta, y = b0 sin(theta), dy = b0 cos(theta) dtheta.
                let theta = PI / 2.0 * (j as f64 + 0.5) / rows as f64;
                let b = b0 * theta.cos();
                let m = march(ZENER, l, b, b.min(l) / steps, -b);
                let jac = 2.0 * PI / 2.0 / rows as f64 * b;
                load += jac * m.load;
                moment += jac * m.moment;
            }
            (load, moment)
        };
        let (q1, m1) = totals(400.0);
        let (q2, m2) = totals(800.0);
        let (qe, me) = (2.0 * q2 - q1, 2.0 * m2 - m1);
        let mu = me / (R * qe);
        eprintln!(
            "Zener L = {l}, b0 = {b0:.4e}: marched Q rel err {:.1e} (raw {:.1e}), mu rel err \
             {:.1e}",
            rel(qe, q),
            rel(q2, q),
            rel(mu, reference.friction_coefficient)
        );
        assert!(rel(qe, q) < 1e-5);
        assert!(rel(mu, reference.friction_coefficient) < 1e-4);
    }
}

#[test]
fn rows_are_monotone_in_b_and_the_y_quadrature_has_converged() {
    // The centre row carries the largest pressure and the smallest trailing edge.
    for rheology in [KV, ZENER, ZENER_STIFF_GLASS] {
        let s = base(rheology, 0.01, 2e-5);
        let mut last = s.row(1e-4);
        for k in 2..=200 {
            let row = s.row(1e-4 * k as f64);
            assert!(row.trailing_edge < last.trailing_edge);
            assert!(row.max_pressure > last.max_pressure);
            // Pointwise: the larger row's pressure exceeds the smaller's.
            let x = 0.5 * (last.trailing_edge + last.leading_edge);
            assert!(
                s.pressure(row.leading_edge, row.trailing_edge, x)
                    > s.pressure(last.leading_edge, last.trailing_edge, x)
            );
            last = row;
        }
        let coarse = s.solve();
        let fine = s.solve_with(2 * ROWS);
        assert!(rel(fine.approach, coarse.approach) < 1e-12);
        assert!(rel(fine.friction_coefficient, coarse.friction_coefficient) < 1e-12);
        assert!(rel(fine.max_pressure, coarse.max_pressure) < 1e-12);
    }
    // The plain-number entry points are the same solves.
    let kv = kelvin_voigt(R, 2e-5, 0.02, 1.0, 0.01);
    assert_eq!(kv, base(KV, 0.01, 2e-5).solve());
    let z = zener(R, 2e-5, 0.01, 0.02, 2.0, 0.005);
    assert_eq!(z, base(ZENER, 0.01, 2e-5).solve());
}

/// Cases where a solver comparison is meaningful (R = tau = 1, so L = V): the creep
/// length comparable to the contact (0.07 < L / b0 < 1.5).
///
/// Notes for the comparison, from a model of the natural cell-centred scheme (p
/// constant per cell, the branch integrated exactly, contact at cell centres; the
/// analogue of the Maxwell row sweep's `upstream + q / 2`), solved on a rigid base:
/// its error factor from one cell to the next along x is
/// `e^(-h/L) - e^(-h/2L) C_1 (1 - e^(-h/L)) / (C_g + C_1 (1 - e^(-h/2L)))`,
/// `-e^(-h/2L)` for Kelvin–Voigt: the leading-edge jump seeds an odd-even pressure
/// mode that decays only over 2L (p_max up to 2x the jump, not converging with h);
/// D and mu still converge (~h^2). For Zener the mode is absent while
/// `h < 2 L C_g / C_1`. mu needs `h <~ L / 7` when L << b0; p_max `h <~ b0 / 30`.
/// Leading edge and y extent: compare `sqrt(2 R D)`; trailing edge: extrapolate p
/// linearly to 0 from the last two contact cells of the centre row.
/// `(name, rheology, Q, V, expected L / b0 band)`.
const SUGGESTED: [(&str, Rheology, f64, f64, [f64; 2]); 6] = [
    (
        "Z1",
        Rheology::Zener {
            glassy: 0.01,
            branch: 0.01,
        },
        2e-5,
        0.01,
        [0.3, 0.45],
    ),
    (
        "Z2",
        Rheology::Zener {
            glassy: 0.01,
            branch: 0.01,
        },
        2e-5,
        0.03,
        [1.0, 1.4],
    ),
    (
        "Z3",
        Rheology::Zener {
            glassy: 0.01,
            branch: 0.01,
        },
        1e-4,
        0.03,
        [0.7, 0.9],
    ),
    (
        "Z4",
        Rheology::Zener {
            glassy: 0.005,
            branch: 0.015,
        },
        2e-5,
        0.01,
        [0.3, 0.45],
    ),
    (
        "K1",
        Rheology::KelvinVoigt { compliance: 0.02 },
        1e-4,
        0.003,
        [0.06, 0.09],
    ),
    (
        "K2",
        Rheology::KelvinVoigt { compliance: 0.02 },
        2e-5,
        0.03,
        [1.1, 1.5],
    ),
];

#[test]
fn suggested_comparison_cases_are_in_their_regimes() {
    for (name, rheology, q, v, [lo, hi]) in SUGGESTED {
        let s = base(rheology, v, q).solve();
        let ratio = v / s.contact_radius;
        println!(
            "{name} {rheology:?} Q = {q:e} V = {v:e}: L/b0 = {ratio:.3}, D = {:.9e}, p_max = \
             {:.9e} at x = {:.6e}, mu = {:.9e}, x in [{:.6e}, {:.6e}], |y| <= {:.6e}",
            s.approach,
            s.max_pressure,
            s.max_pressure_x,
            s.friction_coefficient,
            s.x_min,
            s.x_max,
            s.y_max
        );
        assert!(ratio > lo && ratio < hi, "{name}: L/b0 = {ratio}");
        // A body of E = 1e6 is rigid against the layer: w_body / w_layer ~ b0 / (C_r E).
        assert!(s.contact_radius / (rheology.relaxed() * 1e6) < 1e-5);
    }
}
