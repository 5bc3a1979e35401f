//! Validation of the coated-body influence kernel: equal materials give
//! the homogeneous closed form, thin and thick coatings tend to the substrate and
//! the coating, an independent quadrature of the Fourier integral (paper eq. 10)
//! agrees, Burmister's two-layer deflection factor is reproduced, bad input is
//! rejected with the field named.

use std::f64::consts::PI;

use thirdbody::body::homogeneous::love_rectangle_displacement;
use thirdbody::{Elastic, Error};

mod coated_tables;
#[allow(unused_imports)]
use coated_tables::*;

fn elastic(young: f64, poisson: f64) -> Elastic {
    Elastic { young, poisson }
}

/// Love's closed form for a homogeneous body on the same grid (di, dj >= 0).
fn homogeneous_kernel(m: Elastic, cell: f64, nx: usize, ny: usize) -> Vec<f64> {
    let mut k = vec![0.0; nx * ny];
    for dj in 0..ny {
        for di in 0..nx {
            k[dj * nx + di] = love_rectangle_displacement(
                m,
                0.5 * cell,
                0.5 * cell,
                di as f64 * cell,
                dj as f64 * cell,
            );
        }
    }
    k
}

/// `max |a - b| / max |b|`.
fn relative_max_difference(a: &[f64], b: &[f64]) -> f64 {
    let diff = a
        .iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    diff / b.iter().map(|x| x.abs()).fold(0.0, f64::max)
}

#[test]
fn equal_materials_give_the_homogeneous_closed_form() {
    let m = elastic(2.5, 0.27);
    let cell = 0.3;
    let expected = homogeneous_kernel(m, cell, 24, 16);
    for thickness in [0.01, 0.3, 3.0, 100.0] {
        let k = coated_surface_kernel(m, thickness, m, cell, 24, 16).unwrap();
        let err = relative_max_difference(&k, &expected);
        assert!(err < 1e-6, "h1 = {thickness}: {err:e}");
    }
}

#[test]
fn thin_coating_tends_to_the_substrate_at_first_order() {
    // The kernel differs from the substrate's by O(h1) (docs/architecture.md (numerics)): halving h1
    // halves the difference once h1 is well below the cell (the next term, of
    // order h1^2 log h1, slows the approach to 1/2 at larger h1).
    let (coating, substrate) = (elastic(3.0, 0.3), elastic(1.0, 0.25));
    let (cell, n) = (1.0, 16);
    let sub = homogeneous_kernel(substrate, cell, n, n);
    let mut previous = f64::NAN;
    eprintln!("h1/cell  max|K - K_sub|/max|K_sub|  ratio");
    for k in 0..9 {
        let h = 0.04 / 2f64.powi(k);
        let kern = coated_surface_kernel(coating, h, substrate, cell, n, n).unwrap();
        let err = relative_max_difference(&kern, &sub);
        let ratio = err / previous;
        eprintln!("{h:8.4}  {err:.4e}  {ratio:.4}");
        if k >= 6 {
            assert!((ratio - 0.5).abs() < 0.01, "h1 = {h}: ratio {ratio}");
        }
        previous = err;
    }
    assert!(previous < 1e-3);
}

#[test]
fn thick_coating_tends_to_the_coating_like_one_over_thickness() {
    let (coating, substrate) = (elastic(0.4, 0.35), elastic(1.0, 0.2));
    let (cell, n) = (1.0, 12);
    let coat = homogeneous_kernel(coating, cell, n, n);
    let mut previous = f64::NAN;
    eprintln!("h1/cell  max|K - K_coat|/max|K_coat|  ratio");
    for k in 0..5 {
        let h = 25.0 * 2f64.powi(k);
        let kern = coated_surface_kernel(coating, h, substrate, cell, n, n).unwrap();
        let err = relative_max_difference(&kern, &coat);
        let ratio = err / previous;
        eprintln!("{h:8.1}  {err:.4e}  {ratio:.4}");
        if k >= 2 {
            assert!((ratio - 0.5).abs() < 0.03, "h1 = {h}: ratio {ratio}");
        }
        previous = err;
    }
    assert!(previous < 0.02);
}

/// Gauss–Legendre nodes on [-1, 1] (Golub–Welsch would do; Newton on P_n here).
fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let mut x = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..60 {
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                    p0 = p1;
                    p1 = p2;
                }
                dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                x -= p1 / dp;
            }
            (x, 2.0 / ((1.0 - x * x) * dp * dp))
        })
        .collect()
}

/// Transform of the unit square [-a, a]: `2 sin(q a) / q`.
fn square_transform(q: f64, a: f64) -> f64 {
    if (q * a).abs() < 1e-8 {
        2.0 * a
    } else {
        2.0 * (q * a).sin() / q
    }
}

/// The kernel at offset (x, y) by direct quadrature of eq. 10 in polar
/// coordinates: Love's closed form for the coating plus
/// `(1/pi^2) int_0^inf dk int_0^{pi/2} dtheta C (A(k h1) - 1) S(k cos) S(k sin)
/// cos(k x cos) cos(k y sin)`, composite Gauss–Legendre with panels shorter than
/// half a period of the oscillation in both variables.
fn kernel_by_fourier_quadrature(c: Elastic, h: f64, s: Elastic, cell: f64, x: f64, y: f64) -> f64 {
    let a = 0.5 * cell;
    let constant = 2.0 * (1.0 - c.poisson * c.poisson) / c.young;
    let rule = gauss_legendre(10);
    let reach = x.abs() + y.abs() + 2.0 * a;
    let t_max: f64 = 20.0;
    let mut total = 0.0;
    let mut t: f64 = 0.0;
    while t < t_max {
        let width = (0.005 + 0.1 * t).min(h * PI / (2.0 * reach)).min(0.25);
        let end = (t + width).min(t_max);
        for &(xi, wi) in &rule {
            let tk = 0.5 * (t + end) + 0.5 * (end - t) * xi;
            let k = tk / h;
            let weight_k = wi * 0.5 * (end - t) / h;
            let excess = coating_factor(c, s, tk) - 1.0;
            let panels = (k * reach / PI).ceil().max(2.0) as usize;
            let dtheta = 0.5 * PI / panels as f64;
            let mut angular = 0.0;
            for p in 0..panels {
                for &(xj, wj) in &rule {
                    let th = (p as f64 + 0.5 + 0.5 * xj) * dtheta;
                    let (kx, ky) = (k * th.cos(), k * th.sin());
                    angular += wj
                        * 0.5
                        * dtheta
                        * square_transform(kx, a)
                        * square_transform(ky, a)
                        * (kx * x).cos()
                        * (ky * y).cos();
                }
            }
            total += weight_k * constant * excess * angular;
        }
        t = end;
    }
    love_rectangle_displacement(c, a, a, x, y) + total / (PI * PI)
}

#[test]
fn kernel_agrees_with_direct_quadrature_of_eq_10() {
    let substrate = elastic(1.0, 0.3);
    let cell = 1.0;
    let n = 8;
    let mut worst: f64 = 0.0;
    for ratio in [10.0, 0.1] {
        let coating = elastic(ratio, 0.25);
        for (h, offsets) in [
            (0.05, vec![(0, 0), (1, 0), (2, 1)]),
            (20.0, vec![(0, 0), (1, 0), (3, 2), (7, 4)]),
        ] {
            let k = coated_surface_kernel(coating, h, substrate, cell, n, n).unwrap();
            for (di, dj) in offsets {
                let quad = kernel_by_fourier_quadrature(
                    coating,
                    h,
                    substrate,
                    cell,
                    di as f64 * cell,
                    dj as f64 * cell,
                );
                let prod = k[dj * n + di];
                let err = ((prod - quad) / quad).abs();
                eprintln!("E1/E2 = {ratio}, h1 = {h}, ({di}, {dj}): {prod:.12e} vs {quad:.12e}, {err:.2e}");
                worst = worst.max(err);
                assert!(
                    err < 1e-5,
                    "E1/E2 = {ratio}, h1 = {h}, ({di}, {dj}): {prod} vs {quad}"
                );
            }
        }
    }
    eprintln!("worst relative difference {worst:.2e}");
}

/// `J1(x) = (1/pi) int_0^pi cos(tau - x sin tau) dtau` by the midpoint rule, which
/// converges geometrically for this periodic analytic integrand (Trefethen &
/// Weideman, SIAM Review 56, 2014).
fn bessel_j1(x: f64) -> f64 {
    let n = 200;
    (0..n)
        .map(|k| {
            let tau = PI * (k as f64 + 0.5) / n as f64;
            (tau - x * tau.sin()).cos()
        })
        .sum::<f64>()
        / n as f64
}

#[test]
fn burmister_two_layer_deflection_factor() {
    // Uniform pressure q on a circle of radius a: centre deflection
    // w = 1.5 q a F2 / E2 for nu = 0.5 (Burmister 1943; Huang, Pavement Analysis
    // and Design, 2nd ed., Fig. 2.19: F2 = 0.511 for E1/E2 = 5, h1/a = 1.333, read
    // from the chart). In Fourier space w = int_0^inf W(k) q a J1(k a) dk, so
    // F2 = (E2/E1) int_0^inf A(x h1/a) J1(x) / x dx = (E2/E1)(1 + int f J1 / x).
    // nu -> 0.5 (the library's range ends just below it).
    let coating = elastic(5.0, 0.4999999);
    let substrate = elastic(1.0, 0.4999999);
    let thickness_ratio = 1.333;
    let (x_max, steps) = (30.0, 30_000);
    let dx = x_max / steps as f64;
    let mut integral = 0.0;
    for i in 0..steps {
        let x = (i as f64 + 0.5) * dx;
        integral +=
            (coating_factor(coating, substrate, x * thickness_ratio) - 1.0) * bessel_j1(x) / x * dx;
    }
    let f2 = (1.0 + integral) / 5.0;
    eprintln!("Burmister F2 = {f2:.5} (chart 0.511)");
    assert!((f2 - 0.511).abs() < 0.005, "F2 = {f2}");
    // The same factor with nu = 0.49999 (the library's admissible range) differs
    // by far less than the chart's precision.
    let near = |m: Elastic| elastic(m.young, 0.49999);
    let mut integral = 0.0;
    for i in 0..steps {
        let x = (i as f64 + 0.5) * dx;
        integral += (coating_factor(near(coating), near(substrate), x * thickness_ratio) - 1.0)
            * bessel_j1(x)
            / x
            * dx;
    }
    let f2_near = (1.0 + integral) / 5.0;
    assert!((f2_near - f2).abs() < 1e-4, "{f2_near} vs {f2}");
}

fn field_of(e: Error) -> String {
    match e {
        Error::InvalidValue { field, .. } => field,
        other => panic!("unexpected error {other}"),
    }
}

#[test]
fn bad_input_names_the_field() {
    let (c, s) = (elastic(3.0, 0.3), elastic(1.0, 0.3));
    for h in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let e = coated_surface_kernel(c, h, s, 1.0, 8, 8).unwrap_err();
        assert!(e.to_string().contains("> 0"), "{e}");
        assert_eq!(field_of(e), "body.layers[0].thickness");
    }
    for nu in [0.5, 0.7, -1.0, f64::NAN] {
        let e = coated_surface_kernel(elastic(3.0, nu), 0.1, s, 1.0, 8, 8).unwrap_err();
        assert!(e.to_string().contains("poisson < 0.5"), "{e}");
        assert_eq!(field_of(e), "body.layers[0].poisson");
    }
    for young in [0.0, -2.0, f64::NAN] {
        let e = coated_surface_kernel(elastic(young, 0.3), 0.1, s, 1.0, 8, 8).unwrap_err();
        assert_eq!(field_of(e), "body.layers[0].young");
        let e = coated_surface_kernel(c, 0.1, elastic(young, 0.3), 1.0, 8, 8).unwrap_err();
        assert_eq!(field_of(e), "body.base.young");
    }
    let e = coated_surface_kernel(c, 0.1, s, 0.0, 8, 8).unwrap_err();
    assert_eq!(field_of(e), "grid.cell");
}

#[test]
fn case_with_a_bad_coating_is_rejected_with_the_field_named() {
    use thirdbody::{Body, Case, GridSpec, Loading, Slider, Units};
    let case = |coating: Elastic, thickness: f64| Case {
        slider: Slider::Sphere { radius: 1.0 },
        body: Body::coated(coating, thickness, elastic(1.0, 0.3)),
        layer: None,
        loading: Loading {
            normal_load: 1e-5,
            velocity: None,
            reference_distance: None,
        },
        grid: GridSpec {
            cells: [32, 32],
            half_width: None,
            centre: None,
        },
        units: Units::Dimensionless,
    };
    assert!(case(elastic(3.0, 0.3), 0.01).validate().is_ok());
    for (coating, thickness, field) in [
        (elastic(3.0, 0.3), 0.0, "body.layers[0].thickness"),
        (elastic(3.0, 0.3), -0.01, "body.layers[0].thickness"),
        (elastic(3.0, 0.5), 0.01, "body.layers[0].poisson"),
        (elastic(0.0, 0.3), 0.01, "body.layers[0].young"),
        (elastic(-1.0, 0.3), 0.01, "body.layers[0].young"),
    ] {
        let e = case(coating, thickness).validate().unwrap_err();
        let message = e.to_string();
        assert_eq!(field_of(e), field, "{message}");
        assert!(message.contains(field), "{message}");
    }
}

#[test]
fn coated_body_goes_through_the_dc_fft_operator() {
    use thirdbody::body::surface_kernel;
    use thirdbody::convolution::ConvolutionPlan;
    use thirdbody::operator::{ConvolutionOperator, InfluenceOperator};
    use thirdbody::{Body, Grid, Parallelism};
    use thirdbody_reference::direct_convolution;
    let (coating, substrate, thickness) = (elastic(3.0, 0.3), elastic(1.0, 0.3), 0.7);
    let (nx, ny, cell) = (12, 10, 0.5);
    let grid = Grid::centred(nx, ny, cell, [0.0, 0.0]).unwrap();
    let plan = ConvolutionPlan::new(nx, ny, Parallelism::Sequential).unwrap();
    let body = Body::coated(coating, thickness, substrate);
    // The kernel as the cache keeps it (its quadrant); the operator builds its
    // spectrum on the plan's padding.
    let spectrum = surface_kernel(&body, &grid, &plan, f64::INFINITY, true).unwrap();
    let kernel = coated_surface_kernel(coating, thickness, substrate, cell, nx, ny).unwrap();
    assert_eq!(spectrum.self_coefficient(), kernel[0]);
    // A fixed pseudo-random field (LCG), convolved both ways.
    let mut state = 12345u64;
    let field: Vec<f64> = (0..nx * ny)
        .map(|_| {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        })
        .collect();
    let mut fast = vec![0.0; nx * ny];
    let mut operator =
        ConvolutionOperator::new(plan.convolver(), std::sync::Arc::new(spectrum)).unwrap();
    operator.apply(&field, &mut fast).unwrap();
    let mut slow = vec![0.0; nx * ny];
    let dense =
        |di: i64, dj: i64| kernel[dj.unsigned_abs() as usize * nx + di.unsigned_abs() as usize];
    direct_convolution(nx, ny, dense, &field, &mut slow).unwrap();
    assert!(relative_max_difference(&fast, &slow) < 1e-12);
}

#[test]
fn thin_coating_far_field_matches_the_multipole_tail() {
    // Far from the loaded cell the coated and substrate kernels differ by the
    // tail of the point response, g_D(r) = -C f2 h1^2 / (2 pi r^3) (the t^2 term
    // of f(t) = A(t) - 1 gives a |k| term in the transform), times the cell area
    // and the cell-averaging factor 1 + 9 cell^2 / (24 r^2). f2 is taken here by
    // central differences of A, independently of the kernel's Taylor series. The
    // next term, from t^4, is smaller by ~ 9 (f4 / f2) (h1 / r)^2: ~1.5e-3 at
    // r = 22 cells, falling like 1/r^2 (measured 1.5e-3, 4.5e-4, 3.7e-4, 2.2e-4).
    let (coating, substrate) = (elastic(3.0, 0.3), elastic(1.0, 0.25));
    let (h, cell, n) = (0.05, 1.0, 64);
    let kernel = coated_surface_kernel(coating, h, substrate, cell, n, n).unwrap();
    let sub = homogeneous_kernel(substrate, cell, n, n);
    let d = 1e-3;
    let f = |t: f64| coating_factor(coating, substrate, t);
    // The t^2 coefficient of A from forward differences (A is taken at t > 0 only),
    // Richardson-extrapolated: g(d) = a2 + 6 a3 d + O(d^2).
    let g = |d: f64| (f(3.0 * d) - 2.0 * f(2.0 * d) + f(d)) / (2.0 * d * d);
    let f2 = 2.0 * g(0.5 * d) - g(d);
    let c = 2.0 * (1.0 - 0.09) / 3.0;
    for (di, dj) in [(40usize, 25usize), (63, 0), (30, 30), (20, 10)] {
        let r = ((di * di + dj * dj) as f64).sqrt() * cell;
        let tail = -c * f2 * h * h / (2.0 * PI * r.powi(3))
            * cell
            * cell
            * (1.0 + 9.0 * cell * cell / (24.0 * r * r));
        let got = kernel[dj * n + di] - sub[dj * n + di];
        eprintln!("({di}, {dj}): K - K_sub = {got:.6e}, tail {tail:.6e}");
        assert!(
            ((got - tail) / tail).abs() < 2e-3,
            "({di}, {dj}): {got} vs {tail}"
        );
    }
}

#[test]
fn elongated_grids_give_the_same_kernel_and_symmetry_holds() {
    let (c, s, h) = (elastic(4.0, 0.3), elastic(1.0, 0.3), 0.8);
    let square = coated_surface_kernel(c, h, s, 1.0, 20, 20).unwrap();
    let wide = coated_surface_kernel(c, h, s, 1.0, 20, 6).unwrap();
    let tall = coated_surface_kernel(c, h, s, 1.0, 5, 20).unwrap();
    for dj in 0..6 {
        for di in 0..20 {
            let v = square[dj * 20 + di];
            assert!(
                (wide[dj * 20 + di] - v).abs() < 1e-12 * square[0],
                "wide ({di}, {dj})"
            );
        }
    }
    for dj in 0..20 {
        for di in 0..5 {
            let v = square[dj * 20 + di];
            assert!(
                (tall[dj * 5 + di] - v).abs() < 1e-12 * square[0],
                "tall ({di}, {dj})"
            );
            // The square cell's kernel is symmetric under x <-> y.
            assert!((square[di * 20 + dj] - v).abs() < 1e-12 * square[0]);
        }
    }
}
