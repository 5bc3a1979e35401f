//! Love's rectangle stresses against independent values: direct quadrature of the
//! Boussinesq point-load stresses over the rectangle (Johnson, Contact Mechanics,
//! eq. 3.22), the point load itself far away, and sigma_z -> -p at the surface.
// Index loops over the six stress components read best as they are.
#![allow(clippy::needless_range_loop)]

use std::f64::consts::PI;

use thirdbody::stress::love_rectangle_stresses;
use thirdbody::Elastic;

const NU: f64 = 0.3;
const MAT: Elastic = Elastic {
    young: 1.0,
    poisson: NU,
};

/// Boussinesq stresses at (x, y, z) under a unit compressive point force at the
/// origin, Johnson eq. 3.22 in cylindrical form rotated to Cartesian axes
/// (`(1 - z/rho) / r^2` written `1 / (rho (rho + z))`, the same quantity).
fn point_load(x: f64, y: f64, z: f64) -> [f64; 6] {
    let r2 = x * x + y * y;
    let rho = (r2 + z * z).sqrt();
    let r = r2.sqrt();
    let k = 1.0 / (2.0 * PI);
    let m = 1.0 - 2.0 * NU;
    let q = 1.0 / (rho * (rho + z));
    let sr = k * (m * q - 3.0 * z * r2 / rho.powi(5));
    let st = -k * m * (q - z / rho.powi(3));
    let sz = -3.0 * k * z.powi(3) / rho.powi(5);
    let trz = -3.0 * k * r * z * z / rho.powi(5);
    let (c, s) = if r > 0.0 { (x / r, y / r) } else { (1.0, 0.0) };
    [
        sr * c * c + st * s * s,
        sr * s * s + st * c * c,
        sz,
        (sr - st) * s * c,
        trz * c,
        trz * s,
    ]
}

/// Gauss-Legendre nodes and weights on [-1, 1] (Newton on P_n).
fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let mut t = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 0.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, t);
                for k in 2..=n {
                    let p2 = ((2 * k - 1) as f64 * t * p1 - (k - 1) as f64 * p0) / k as f64;
                    p0 = p1;
                    p1 = p2;
                }
                dp = n as f64 * (t * p1 - p0) / (t * t - 1.0);
                let step = p1 / dp;
                t -= step;
                if step.abs() < 1e-16 {
                    break;
                }
            }
            (t, 2.0 / ((1.0 - t * t) * dp * dp))
        })
        .collect()
}

/// Adaptive Gauss-Legendre on [lo, hi] of a vector-valued function.
fn adaptive(
    f: &dyn Fn(f64) -> [f64; 6],
    lo: f64,
    hi: f64,
    tol: f64,
    rule: &[(f64, f64)],
) -> [f64; 6] {
    let panel = |a: f64, b: f64| {
        let (c, h) = (0.5 * (a + b), 0.5 * (b - a));
        let mut s = [0.0; 6];
        for &(t, w) in rule {
            let v = f(c + h * t);
            for k in 0..6 {
                s[k] += w * h * v[k];
            }
        }
        s
    };
    fn go(
        panel: &dyn Fn(f64, f64) -> [f64; 6],
        a: f64,
        b: f64,
        whole: [f64; 6],
        tol: f64,
        depth: usize,
    ) -> [f64; 6] {
        let m = 0.5 * (a + b);
        let (l, r) = (panel(a, m), panel(m, b));
        let err = (0..6).fold(0.0f64, |e, k| e.max((l[k] + r[k] - whole[k]).abs()));
        if err < tol || depth > 40 {
            std::array::from_fn(|k| l[k] + r[k])
        } else {
            let left = go(panel, a, m, l, 0.5 * tol, depth + 1);
            let right = go(panel, m, b, r, 0.5 * tol, depth + 1);
            std::array::from_fn(|k| left[k] + right[k])
        }
    }
    go(&panel, lo, hi, panel(lo, hi), tol, 0)
}

/// Stresses under unit pressure on |xi| <= a, |eta| <= b by 2-D quadrature of the
/// point-load stresses.
fn quadrature(a: f64, b: f64, x: f64, y: f64, z: f64) -> [f64; 6] {
    let rule = gauss_legendre(10);
    let inner = |xi: f64| adaptive(&|eta| point_load(x - xi, y - eta, z), -b, b, 1e-12, &rule);
    adaptive(&inner, -a, a, 1e-11, &rule)
}

#[test]
fn love_stresses_equal_quadrature_of_boussinesq() {
    let (a, b) = (0.5, 0.8);
    let points = [
        (0.0, 0.0, 0.3),
        (0.2, -0.3, 0.05),
        (0.5, 0.8, 0.2),
        (-0.7, 0.1, 0.4),
        (1.3, -1.9, 0.9),
        (0.45, 0.75, 0.02),
        (-2.0, 3.0, 2.5),
        (0.1, 0.2, 6.0),
    ];
    let mut worst = 0.0f64;
    for &(x, y, z) in &points {
        let love = love_rectangle_stresses(MAT, a, b, x, y, z);
        let quad = quadrature(a, b, x, y, z);
        for c in 0..6 {
            let err = (love[c] - quad[c]).abs();
            worst = worst.max(err);
            assert!(
                err < 1e-7,
                "component {c} at ({x}, {y}, {z}): Love {} vs quadrature {}",
                love[c],
                quad[c]
            );
        }
    }
    eprintln!("largest |Love - quadrature| = {worst:.2e} (unit pressure)");
}

/// Point-load stresses integrated over a far rectangle with a 6 x 6 Gauss rule: the
/// multipole error is ~ (a / r)^12, far below rounding.
fn far_rectangle(a: f64, b: f64, x: f64, y: f64, z: f64) -> [f64; 6] {
    let rule = gauss_legendre(6);
    let mut s = [0.0; 6];
    for &(t, wt) in &rule {
        for &(u, wu) in &rule {
            let v = point_load(x - a * t, y - b * u, z);
            for k in 0..6 {
                s[k] += wt * wu * a * b * v[k];
            }
        }
    }
    s
}

#[test]
fn far_field_keeps_its_digits() {
    // Cells of side 1 at 30 and 1000 cells: no cancellation in the four-corner sums.
    let (a, b) = (0.5, 0.5);
    let mut worst = 0.0f64;
    for &r in &[30.0, 1000.0] {
        for &(dx, dy, dz) in &[
            (0.6f64, 0.0, 0.8),
            (0.3, 0.4, 0.866),
            (0.9, -0.3, 0.3),
            (-0.2, 0.1, 0.97),
        ] {
            let n = (dx * dx + dy * dy + dz * dz).sqrt();
            let (x, y, z) = (r * dx / n, r * dy / n, r * dz / n);
            let love = love_rectangle_stresses(MAT, a, b, x, y, z);
            let reference = far_rectangle(a, b, x, y, z);
            let point = point_load(x, y, z);
            let scale = 4.0 * a * b / (2.0 * PI * r * r);
            for c in 0..6 {
                let err = (love[c] - reference[c]).abs() / scale;
                worst = worst.max(err);
                assert!(err < 1e-8, "r {r} c {c}: {} vs {}", love[c], reference[c]);
                // And the point load itself, to O((a / r)^2).
                let err_point = (love[c] - 4.0 * a * b * point[c]).abs() / scale;
                assert!(
                    err_point < 10.0 * (a / r).powi(2),
                    "r {r} c {c}: {err_point:.2e}"
                );
            }
        }
    }
    eprintln!("far field: largest relative error {worst:.2e}");
}

#[test]
fn surface_under_the_load_has_sigma_z_equal_to_minus_p() {
    let (a, b) = (0.5, 0.8);
    for &(x, y) in &[(0.0, 0.0), (0.3, -0.7), (-0.49, 0.1)] {
        for &z in &[0.0, 1e-9] {
            let s = love_rectangle_stresses(MAT, a, b, x, y, z);
            assert!((s[2] + 1.0).abs() < 1e-8, "({x}, {y}, {z}): {}", s[2]);
            assert!(s[4].abs() < 1e-8 && s[5].abs() < 1e-8, "no surface shear");
        }
    }
    // Outside the load the surface carries no normal stress.
    for &(x, y) in &[(0.7, 0.0), (0.1, -1.2), (3.0, 4.0)] {
        let s = love_rectangle_stresses(MAT, a, b, x, y, 0.0);
        assert!(s[2].abs() < 1e-15);
        assert!(s.iter().all(|v| v.is_finite()));
    }
}

#[test]
fn surface_values_are_the_limit_from_below() {
    // z = 0 uses the surface branch of the formulas; it must be the z -> 0+ limit.
    let (a, b) = (0.5, 0.8);
    for &(x, y) in &[(0.0, 0.0), (0.3, -0.7), (1.5, 0.2), (-0.9, 2.0)] {
        let s0 = love_rectangle_stresses(MAT, a, b, x, y, 0.0);
        let s1 = love_rectangle_stresses(MAT, a, b, x, y, 1e-10);
        for c in 0..6 {
            assert!(
                (s0[c] - s1[c]).abs() < 1e-8,
                "c {c} ({x}, {y}): {} vs {}",
                s0[c],
                s1[c]
            );
        }
    }
}
