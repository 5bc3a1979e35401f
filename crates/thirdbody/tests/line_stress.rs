//! Plane-strain (line contact) stresses against independent values: Hertz's line
//! contact against McEwen's closed form on the axis (Johnson, Contact Mechanics,
//! eq. 4.49), equilibrium of a deep plane, a coated body's strip kernel against
//! adaptive quadrature of its Fourier integral, and the errors of sections a line
//! contact does not have.

mod cases;

use cases::cylinder;
use std::f64::consts::PI;
use std::time::Instant;

use thirdbody::body::layered::{Base, LayeredSolver, Ply, Stack};
use thirdbody::body::{SolidRheology, ViscoelasticHalfSpace};
use thirdbody::stress::{
    stresses, LayeredStressKernels, Section, Side, StressKernels, StressRequest, COMPONENTS,
};
use thirdbody::*;

const Q: f64 = 1e-3;

/// Hertz's half-width and peak pressure (Johnson eq. 4.43-4.45) for E = 1, nu = 0.3.
fn hertz() -> (f64, f64) {
    let e_star = 1.0 / (1.0 - 0.09);
    let a = (4.0 * Q / (PI * e_star)).sqrt();
    (a, 2.0 * Q / (PI * a))
}

/// McEwen's stresses on the axis of a Hertz line contact, per p0, at depth
/// `zeta = z / a` (Johnson eq. 4.49): `sigma_x = -[(1 + 2 zeta^2) / (1 +
/// zeta^2)^(1/2) - 2 zeta]`, `sigma_z = -1 / (1 + zeta^2)^(1/2)`.
fn mcewen_axis(zeta: f64) -> (f64, f64) {
    let r = (1.0 + zeta * zeta).sqrt();
    (-((1.0 + 2.0 * zeta * zeta) / r - 2.0 * zeta), -1.0 / r)
}

#[test]
fn hertz_line_contact_subsurface_field_is_mcewens() {
    let (a, p0) = hertz();
    let s = solve(&cylinder(Q, 1024), &SolverParams::default()).unwrap();
    let nx = s.grid.nx();
    // The axis x = 0 lies between the two middle cells (an even window centred on
    // the contact): their mean, whose error is O((h / a)^2).
    let (left, right) = (nx / 2 - 1, nx / 2);
    assert!((s.grid.x(left) + s.grid.x(right)).abs() < 1e-9 * a);
    let depths: Vec<f64> = (0..=150).map(|k| a * (0.01 + 0.02 * k as f64)).collect();
    let field = s
        .stresses(&Section::XzPlane {
            y: 0.0,
            depths: depths.clone(),
        })
        .unwrap();
    let axis = |c: usize, k: usize| {
        0.5 * (field.components[c][field.index(left, 0, k)]
            + field.components[c][field.index(right, 0, k)])
    };
    let mut worst: f64 = 0.0;
    for (k, &z) in depths.iter().enumerate() {
        let (_, sz) = mcewen_axis(z / a);
        let error = (axis(2, k) / p0 - sz).abs();
        worst = worst.max(error);
    }
    eprintln!("sigma_z on the axis vs McEwen: worst {worst:.1e} p0");
    assert!(worst < 2e-3, "sigma_z on the axis: {worst:e} p0");
    // tau1's maximum: McEwen's, located by a fine scan of the closed form.
    let (zeta_max, tau_max) = (1..200_000)
        .map(|i| {
            let zeta = i as f64 * 1e-5;
            let (sx, sz) = mcewen_axis(zeta);
            (zeta, 0.5 * (sx - sz))
        })
        .fold((0.0, 0.0), |m, v| if v.1 > m.1 { v } else { m });
    assert!((tau_max - 0.300).abs() < 1e-3 && (zeta_max - 0.786).abs() < 1e-3);
    // The field's: tau1 over the whole XZ section (off-axis points included), the
    // depth refined by a parabola through the best depth and its neighbours.
    let tau1 = field.tau1();
    let (n, &t) = tau1
        .iter()
        .enumerate()
        .max_by(|x, y| x.1.total_cmp(y.1))
        .unwrap();
    let (i, k) = (n % nx, n / nx);
    assert!(i == left || i == right, "tau1 max off the axis at cell {i}");
    let (t0, t2) = (tau1[n - nx], tau1[n + nx]);
    let shift = 0.5 * (t0 - t2) / (t0 - 2.0 * t + t2);
    let z_max = depths[k] + shift * (depths[1] - depths[0]);
    let t_max = t - 0.25 * (t0 - t2) * shift;
    eprintln!(
        "tau1 max {:.5} p0 at z = {:.5} a (McEwen {tau_max:.5} at {zeta_max:.5})",
        t_max / p0,
        z_max / a
    );
    assert!((t_max / p0 / tau_max - 1.0).abs() < 5e-3);
    assert!((z_max / a / zeta_max - 1.0).abs() < 5e-3);
    // Equilibrium: the resultant of sigma_z over a plane is the load per length,
    // less the part beyond the window's edges (Flamant's, `inside`).
    let w = nx as f64 * s.grid.cell();
    for &z in &[0.5 * a, a, 2.0 * a] {
        let f = s
            .stresses(&Section::XzPlane {
                y: 0.0,
                depths: vec![z],
            })
            .unwrap();
        let resultant = -f.components[2].iter().sum::<f64>() * s.grid.cell();
        let expected = flamant_inside(&s.grid, &s.mean_pressure(), 0.5 * w, z);
        let error = resultant / expected - 1.0;
        eprintln!("equilibrium at z = {:.1} a: {error:.1e}", z / a);
        assert!(error.abs() < 1e-6, "z {z}: resultant {resultant} of {Q}");
    }
    // The request: defaults (XZ and the surface) on a line case, with its summary.
    let results = s.stress_results(&StressRequest::default()).unwrap();
    let m = &results.summary;
    assert!((m.tau1_max.unwrap() / p0 / tau_max - 1.0).abs() < 1e-2);
    assert!((m.sigma_x_min.unwrap() / p0 + 1.0).abs() < 2e-2);
    for (named, field) in &results.sections {
        assert_eq!(field.ys, vec![0.0], "{}", named.name());
        assert_eq!(field.xs.len(), nx);
    }
}

#[test]
fn a_line_contact_has_no_block_and_no_other_y() {
    let s = solve(&cylinder(Q, 256), &SolverParams::default()).unwrap();
    let e = s
        .stresses(&Section::Block { depths: vec![0.1] })
        .unwrap_err()
        .to_string();
    assert!(e.contains("stress.sections") && e.contains("xz"), "{e}");
    let e = s
        .stresses(&Section::XzPlane {
            y: 0.01,
            depths: vec![0.1],
        })
        .unwrap_err()
        .to_string();
    assert!(e.contains("stress.y"), "{e}");
    let request = StressRequest {
        y: 0.01,
        ..StressRequest::default()
    };
    let e = s.stress_results(&request).unwrap_err().to_string();
    assert!(e.contains("stress.y"), "{e}");
    let request = StressRequest {
        sections: Some(vec![stress::SectionKind::Block]),
        ..StressRequest::default()
    };
    let e = s.stress_results(&request).unwrap_err().to_string();
    assert!(e.contains("stress.sections") && e.contains("block"), "{e}");
    // A plane is one row of the XZ section.
    let plane = s.stresses(&Section::Plane { z: 0.02 }).unwrap();
    let xz = s
        .stresses(&Section::XzPlane {
            y: 0.0,
            depths: vec![0.02],
        })
        .unwrap();
    assert_eq!(plane.components, xz.components);
}

fn coated() -> Stack {
    Stack {
        layers: vec![Ply {
            material: Elastic {
                young: 10.0,
                poisson: 0.2,
            },
            thickness: 1.0,
        }],
        base: Base::HalfSpace(Elastic {
            young: 1.0,
            poisson: 0.35,
        }),
    }
}

/// `int_lo^hi f` by adaptive Simpson's rule to the absolute tolerance `tol`.
fn adaptive(f: &mut dyn FnMut(f64) -> f64, lo: f64, hi: f64, tol: f64) -> f64 {
    fn step(
        f: &mut dyn FnMut(f64) -> f64,
        (a, fa): (f64, f64),
        (m, fm): (f64, f64),
        (b, fb): (f64, f64),
        whole: f64,
        tol: f64,
        depth: usize,
    ) -> f64 {
        let (l, r) = (0.5 * (a + m), 0.5 * (m + b));
        let (fl, fr) = (f(l), f(r));
        let left = (m - a) / 6.0 * (fa + 4.0 * fl + fm);
        let right = (b - m) / 6.0 * (fm + 4.0 * fr + fb);
        if depth == 0 || (left + right - whole).abs() <= 15.0 * tol {
            return left + right + (left + right - whole) / 15.0;
        }
        step(f, (a, fa), (l, fl), (m, fm), left, 0.5 * tol, depth - 1)
            + step(f, (m, fm), (r, fr), (b, fb), right, 0.5 * tol, depth - 1)
    }
    let m = 0.5 * (lo + hi);
    let (fa, fm, fb) = (f(lo), f(m), f(hi));
    let whole = (hi - lo) / 6.0 * (fa + 4.0 * fm + fb);
    step(f, (lo, fa), (m, fm), (hi, fb), whole, tol, 40)
}

/// The coated strip's stresses `[sigma_x, sigma_y, sigma_z, tau_xz]` at (x, z) read
/// in `layer`: `(1/pi) int_0^inf Re[T(k, z) P(k) e^{ikx}] dk`, `P = 2 sin(k b) / k`,
/// integrated directly (T decays like e^{-kz}: cut where it is below 1e-15), panel
/// by panel of a quarter oscillation.
fn fourier_strip(stack: &Stack, x: f64, z: f64, cell: f64, layer: usize) -> [f64; 4] {
    let mut solver = LayeredSolver::new(stack).unwrap();
    let b = 0.5 * cell;
    let top = 45.0 / z;
    let panel = (0.5 * PI / (x.abs() + b)).min(0.5 / z);
    let panels = (top / panel).ceil() as usize;
    let mut out = [0.0; 4];
    for (q, o) in out.iter_mut().enumerate() {
        let mut f = |k: f64| {
            let k = k.max(1e-12);
            let t = solver.plane_response(k, layer, z).stress;
            let p = 2.0 * (k * b).sin() / k;
            if q < 3 {
                t[q] * p * (k * x).cos()
            } else {
                -t[3] * p * (k * x).sin()
            }
        };
        *o = (0..panels)
            .map(|j| {
                let lo = j as f64 * top / panels as f64;
                adaptive(&mut f, lo, lo + top / panels as f64, 1e-13 / panels as f64)
            })
            .sum::<f64>()
            / PI;
    }
    out
}

#[test]
fn coated_strip_kernel_is_its_fourier_integral() {
    let stack = coated();
    let (cell, count) = (0.1, 200);
    let mut worst: f64 = 0.0;
    for (z, side, layer) in [
        (0.3, Side::Above, 0),
        (1.0, Side::Above, 0),
        (1.0, Side::Below, 1),
        (2.5, Side::Above, 1),
    ] {
        let kernels = LayeredStressKernels {
            stack: stack.clone(),
            interface_side: side,
        };
        let mut table: [Vec<f64>; COMPONENTS] = Default::default();
        kernels.fill_strip(z, cell, count, &mut table).unwrap();
        let peak = table[2].iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for d in [0i64, 3, -7, 20, 80, -199] {
            let m = (d + count as i64 - 1) as usize;
            let want = fourier_strip(&stack, d as f64 * cell, z, cell, layer);
            let got = [table[0][m], table[1][m], table[2][m], table[4][m]];
            for (g, w) in got.iter().zip(want) {
                let error = (g - w).abs() / peak;
                worst = worst.max(error);
                assert!(error < 1e-6, "z {z} {side:?} d {d}: {got:?} vs {want:?}");
            }
            assert_eq!([table[3][m], table[5][m]], [0.0, 0.0]);
        }
    }
    eprintln!("coated strip vs adaptive Fourier quadrature: worst {worst:.1e} of the peak");
}

/// The part of a line load's resultant that the plane at depth z carries within
/// `|x| <= half` (Flamant: `sigma_z = -(2 Q / pi) z^3 / r^4`).
fn inside(half: f64, z: f64) -> f64 {
    2.0 / PI * ((half / z).atan() + half * z / (half * half + z * z))
}

/// The resultant within `|x| <= half` at depth z of the cells' pressure, each cell
/// a sum of Flamant line loads (4-point Gauss–Legendre over the cell).
fn flamant_inside(grid: &Grid, pressure: &[f64], half: f64, z: f64) -> f64 {
    let h = grid.cell();
    let nodes = [
        (0.339_981_043_584_856, 0.652_145_154_862_546),
        (0.861_136_311_594_053, 0.347_854_845_137_454),
    ];
    (0..grid.nx())
        .map(|i| {
            let mut sum = 0.0;
            for &(t, w) in &nodes {
                for s in [grid.x(i) - 0.5 * h * t, grid.x(i) + 0.5 * h * t] {
                    sum += 0.5 * w * (inside(half - s, z) + inside(half + s, z)) * 0.5 * h;
                }
            }
            pressure[i] * sum
        })
        .sum()
}

/// Hertz's pressure on a line grid, as cell values.
fn hertz_pressure(grid: &Grid, a: f64, p0: f64) -> Vec<f64> {
    (0..grid.nx())
        .map(|i| p0 * (1.0 - (grid.x(i) / a).powi(2)).max(0.0).sqrt())
        .collect()
}

#[test]
fn section_of_1024_cells_and_64_depths_timing() {
    let (a, p0) = (1.0, 1.0);
    let grid = Grid::line(1024, 16.0 * a / 1024.0, 0.0, 1.0).unwrap();
    let pressure = hertz_pressure(&grid, a, p0);
    let section = Section::XzPlane {
        y: 0.0,
        depths: (0..64).map(|k| 3.0 * a * k as f64 / 63.0).collect(),
    };
    let homogeneous = Body::Homogeneous(Elastic {
        young: 1.0,
        poisson: 0.3,
    });
    let mut stack = coated();
    stack.layers[0].thickness = 0.5 * a;
    let layered = Body::Layered(stack);
    for (name, body) in [("homogeneous", homogeneous), ("coated", layered)] {
        let start = Instant::now();
        let field = stresses(&grid, &pressure, &body, &section).unwrap();
        eprintln!(
            "{name}: 1024 cells x 64 depths in {:.3} s",
            start.elapsed().as_secs_f64()
        );
        // Equilibrium at the deepest depth, against the tail of a line load.
        let load = pressure.iter().sum::<f64>() * grid.cell();
        let k = 63;
        let resultant: f64 = -(0..1024)
            .map(|i| field.components[2][field.index(i, 0, k)])
            .sum::<f64>()
            * grid.cell();
        if name == "homogeneous" {
            let expected = flamant_inside(&grid, &pressure, 8.0 * a, 3.0 * a);
            let error = resultant / expected - 1.0;
            eprintln!("{name}: equilibrium at z = 3a {error:.1e} (load {load})");
            assert!(error.abs() < 1e-6);
        }
    }
}

/// A viscoelastic half-space of constant nu has the elastic stresses under the same
/// pressure (plane strain: only sigma_y carries nu, no modulus appears).
#[test]
fn a_viscoelastic_line_section_is_the_elastic_one() {
    let grid = Grid::line(256, 4.0 / 256.0, 0.0, 1.0).unwrap();
    let pressure = hertz_pressure(&grid, 1.0, 1.0);
    let section = Section::XzPlane {
        y: 0.0,
        depths: vec![0.0, 0.3, 0.78, 2.0],
    };
    let elastic = Body::Homogeneous(Elastic {
        young: 1.0,
        poisson: 0.4,
    });
    let solid = Body::Viscoelastic(ViscoelasticHalfSpace {
        rheology: SolidRheology::Zener {
            glassy_modulus: 100.0,
            relaxed_modulus: 3.0,
            relaxation_time: 0.1,
        },
        poisson: 0.4,
    });
    let a = stresses(&grid, &pressure, &elastic, &section).unwrap();
    let b = stresses(&grid, &pressure, &solid, &section).unwrap();
    for (x, y) in a
        .components
        .iter()
        .flatten()
        .zip(b.components.iter().flatten())
    {
        assert!((x - y).abs() < 1e-14, "{x} vs {y}");
    }
}
