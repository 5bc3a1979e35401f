//! Subsurface stresses under a Hertz pressure against Johnson's closed forms
//! (Contact Mechanics, §3.4, with nu = 0.3):
//! along the axis `sigma_z = -p0 / (1 + z^2/a^2)`,
//! `sigma_r = -p0 [(1 + nu)(1 - (z/a) atan(a/z)) - 1 / (2 (1 + z^2/a^2))]`; the
//! maximum shear stress `tau1 = 0.31 p0` at `z = 0.48 a`; the surface radial stress
//! outside the contact `sigma_r = (1 - 2 nu) p0 a^2 / (3 r^2)`, `(1 - 2 nu) p0 / 3`
//! at the edge.
// Index loops over the six stress components read best as they are.
#![allow(clippy::needless_range_loop)]

use thirdbody::stress::{stresses, Section, SectionKind, StressRequest};
use thirdbody::{solve, Body, Case, Elastic, Grid, GridSpec, Loading, Slider, SolverParams, Units};

const NU: f64 = 0.3;
const BODY: Body = Body::Homogeneous(Elastic {
    young: 1.0,
    poisson: NU,
});

/// Johnson's axis stresses `(sigma_z, sigma_r) / p0` at depth `t = z / a`.
fn johnson_axis(t: f64) -> (f64, f64) {
    let sz = -1.0 / (1.0 + t * t);
    let sr = if t == 0.0 {
        -(1.0 + 2.0 * NU) / 2.0
    } else {
        -((1.0 + NU) * (1.0 - t * (1.0 / t).atan()) - 0.5 / (1.0 + t * t))
    };
    (sz, sr)
}

/// Maximum of `tau1 / p0 = (sigma_r - sigma_z) / 2` along the axis and its depth
/// `z / a`, by golden-section search on Johnson's closed forms.
fn johnson_tau1_max() -> (f64, f64) {
    let tau = |t: f64| {
        let (sz, sr) = johnson_axis(t);
        0.5 * (sr - sz)
    };
    let (mut lo, mut hi) = (0.2, 0.8);
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..200 {
        let (m1, m2) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if tau(m1) > tau(m2) {
            hi = m2;
        } else {
            lo = m1;
        }
    }
    let t = 0.5 * (lo + hi);
    (tau(t), t)
}

/// Hertz pressure `p0 sqrt(1 - r^2/a^2)` averaged over each cell (16 x 16 points).
fn hertz_cell_average(grid: &Grid, a: f64, p0: f64) -> Vec<f64> {
    let mut p = vec![0.0; grid.len()];
    let m = 16;
    for j in 0..grid.ny() {
        for i in 0..grid.nx() {
            let mut s = 0.0;
            for q in 0..m {
                for r in 0..m {
                    let x = grid.x(i) + ((r as f64 + 0.5) / m as f64 - 0.5) * grid.cell();
                    let y = grid.y(j) + ((q as f64 + 0.5) / m as f64 - 0.5) * grid.cell();
                    s += (1.0 - (x * x + y * y) / (a * a)).max(0.0).sqrt();
                }
            }
            p[grid.index(i, j)] = p0 * s / (m * m) as f64;
        }
    }
    p
}

/// Errors of a stress field under Hertz pressure (contact radius a, peak p0) on a
/// grid with a cell centre on the origin.
struct HertzErrors {
    /// Largest |sigma_z - Johnson| / |Johnson| at ten depths on the axis.
    sigma_z: f64,
    /// Largest |sigma_r - Johnson| / |Johnson| at ten depths on the axis.
    sigma_r: f64,
    /// Per depth: z / a, sigma_z / p0, Johnson's, sigma_r / p0, Johnson's.
    axis: Vec<[f64; 5]>,
    /// Computed max tau1 / p0 and its depth / a.
    tau1_max: (f64, f64),
    /// sigma_x (x/a)^2 / p0 at the first cell centres outside the contact on the
    /// surface (x > a, y = 0), which is (1 - 2 nu) / 3 for Hertz.
    edge_radial: Vec<(f64, f64)>,
}

const AXIS_DEPTHS: [f64; 10] = [0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9];

fn hertz_errors(grid: &Grid, p: &[f64], a: f64, p0: f64) -> HertzErrors {
    let centre = grid.nx() / 2;
    assert!(
        grid.x(centre).abs() < 1e-12 * a,
        "needs a cell centre on the axis"
    );
    // Axis.
    let depths: Vec<f64> = AXIS_DEPTHS.iter().map(|t| t * a).collect();
    let f = stresses(grid, p, &BODY, &Section::XzPlane { y: 0.0, depths }).unwrap();
    let (mut ez, mut er) = (0.0f64, 0.0f64);
    let mut axis = Vec::new();
    for (k, &t) in AXIS_DEPTHS.iter().enumerate() {
        let n = f.index(centre, 0, k);
        let (sz, sr) = johnson_axis(t);
        axis.push([t, f.components[2][n] / p0, sz, f.components[0][n] / p0, sr]);
        ez = ez.max((f.components[2][n] / p0 - sz).abs() / sz.abs());
        er = er.max((f.components[0][n] / p0 - sr).abs() / sr.abs());
        // Axisymmetry: sigma_x = sigma_y on the axis.
        assert!((f.components[0][n] - f.components[1][n]).abs() < 1e-3 * p0);
    }
    // tau1 maximum over an XZ plane, refined by a parabola through the best depth.
    let depths: Vec<f64> = (0..41).map(|k| (0.38 + 0.005 * k as f64) * a).collect();
    let f = stresses(
        grid,
        p,
        &BODY,
        &Section::XzPlane {
            y: 0.0,
            depths: depths.clone(),
        },
    )
    .unwrap();
    let tau1 = f.tau1();
    let best = (0..tau1.len())
        .max_by(|&m, &n| tau1[m].total_cmp(&tau1[n]))
        .unwrap();
    let (i, k) = (best % f.xs.len(), best / f.xs.len());
    assert_eq!(i, centre, "tau1 peaks on the axis");
    assert!(
        k > 0 && k + 1 < depths.len(),
        "tau1 peak inside the scanned depths"
    );
    let (y0, y1, y2) = (
        tau1[f.index(i, 0, k - 1)],
        tau1[best],
        tau1[f.index(i, 0, k + 1)],
    );
    let dz = depths[1] - depths[0];
    let shift = 0.5 * (y0 - y2) / (y0 - 2.0 * y1 + y2);
    let tau_max = y1 - 0.25 * (y0 - y2) * shift;
    let z_max = depths[k] + shift * dz;
    // Surface radial stress just outside the contact. The cell centred on r = a
    // straddles the edge (its own pressure is a partial average) and does not sample
    // the edge value; the first cell centres wholly outside do, through Hertz's
    // exterior law sigma_r = (1 - 2 nu) p0 a^2 / (3 r^2) (Johnson, Contact
    // Mechanics §3.4, surface stresses of the Hertz pressure).
    let f = stresses(
        grid,
        p,
        &BODY,
        &Section::XzPlane {
            y: 0.0,
            depths: vec![0.0],
        },
    )
    .unwrap();
    let edge_radial = (0..grid.nx())
        .filter(|&i| grid.x(i) > a + 0.5 * grid.cell())
        .take(3)
        .map(|i| {
            let x = grid.x(i);
            (
                x / a,
                f.components[0][f.index(i, 0, 0)] * (x / a).powi(2) / p0,
            )
        })
        .collect();
    HertzErrors {
        sigma_z: ez,
        sigma_r: er,
        axis,
        tau1_max: (tau_max / p0, z_max / a),
        edge_radial,
    }
}

fn check(name: &str, e: &HertzErrors) {
    let (tau_ref, z_ref) = johnson_tau1_max();
    eprintln!(
        "{name}: axis sigma_z rel err {:.2e}, sigma_r rel err {:.2e}; tau1 max {:.5} p0 at \
         {:.4} a (closed form {tau_ref:.5} at {z_ref:.4}); edge sigma_r (x/a)^2/p0 {:?} \
         (expected {:.5})",
        e.sigma_z,
        e.sigma_r,
        e.tau1_max.0,
        e.tau1_max.1,
        e.edge_radial,
        (1.0 - 2.0 * NU) / 3.0
    );
    for r in &e.axis {
        eprintln!(
            "  z/a {:.1}: sigma_z {:.5} (Johnson {:.5}), sigma_r {:.5} (Johnson {:.5})",
            r[0], r[1], r[2], r[3], r[4]
        );
    }
    assert!(e.sigma_z < 0.01, "sigma_z on the axis");
    assert!(e.sigma_r < 0.01, "sigma_r on the axis");
    // Johnson's published values, and the closed form's own maximum.
    assert!((e.tau1_max.0 - 0.31).abs() < 0.01 * 0.31);
    assert!((e.tau1_max.1 - 0.48).abs() < 0.01 * 0.48);
    assert!((e.tau1_max.0 - tau_ref).abs() < 0.01 * tau_ref);
    assert!((e.tau1_max.1 - z_ref).abs() < 0.01 * z_ref);
    let expected = (1.0 - 2.0 * NU) / 3.0;
    let (_, first) = e.edge_radial[0];
    assert!(
        (first - expected).abs() < 0.02 * expected,
        "edge radial stress"
    );
}

#[test]
fn hertz_pressure_sampled_on_the_grid() {
    // a = 32 cells; 129 cells so that a cell centre sits on the axis.
    let (a, p0) = (1.0, 1.0);
    let grid = Grid::centred(129, 129, a / 32.0, [0.0, 0.0]).unwrap();
    let p = hertz_cell_average(&grid, a, p0);
    check("analytic Hertz pressure", &hertz_errors(&grid, &p, a, p0));
}

/// The solver's pressure for a rigid sphere (R = 1) on E = 1, nu = 0.3 loaded for a
/// Hertz radius a = 0.02 (Johnson eq. 4.22-4.23), on 129 x 129 cells with a = 32
/// cells (a cell centre on the axis). Returns the case, the solution, a and p0.
fn solved_hertz() -> (Case, thirdbody::Solution, f64, f64) {
    let (radius, a) = (1.0f64, 0.02f64);
    let e_star = 1.0 / (1.0 - NU * NU);
    let load = 4.0 * e_star * a.powi(3) / (3.0 * radius);
    let p0 = 2.0 * e_star * a / (std::f64::consts::PI * radius);
    let n = 129;
    let w = 0.5 * n as f64 * a / 32.0;
    let case = Case {
        slider: Slider::Sphere { radius },
        body: BODY,
        layer: None,
        loading: Loading {
            normal_load: load,
            velocity: None,
            reference_distance: None,
        },
        grid: GridSpec {
            cells: [n, n],
            half_width: Some([w, w]),
            centre: None,
        },
        units: Units::Dimensionless,
    };
    let solution = solve(&case, &SolverParams::default()).unwrap();
    assert_eq!((solution.grid.nx(), solution.grid.ny()), (n, n));
    (case, solution, a, p0)
}

#[test]
fn hertz_pressure_from_the_solver() {
    let (_, solution, a, p0) = solved_hertz();
    let grid = solution.grid;
    let e = hertz_errors(&grid, &solution.pressure, a, p0);
    check("solver Hertz pressure", &e);
    // The convenience on Solution gives the same field.
    let section = Section::XzPlane {
        y: 0.0,
        depths: vec![0.5 * a],
    };
    let direct = stresses(&grid, &solution.pressure, &BODY, &section).unwrap();
    assert_eq!(solution.stresses(&section).unwrap(), direct);
}

#[test]
fn stress_request_summary_on_the_solver_hertz_pressure() {
    // The case file's [stress] request (XZ plane y = 0 and the surface) with depths
    // every a/40 to 1.5 a: its summary against Johnson's closed forms.
    let (case, solution, a, p0) = solved_hertz();
    let request = StressRequest {
        max_depth: Some(1.5 * a),
        depth_points: 61,
        ..StressRequest::default()
    };
    let results = request
        .compute(&case.body, &solution.grid, &solution.pressure)
        .unwrap();
    let names: Vec<String> = results.sections.iter().map(|(n, _)| n.name()).collect();
    assert_eq!(names, ["xz", "surface"]);
    let s = results.summary;
    let (tau_ref, z_ref) = johnson_tau1_max();
    let (t, x, z) = (
        s.tau1_max.unwrap(),
        s.tau1_max_x.unwrap(),
        s.tau1_max_z.unwrap(),
    );
    eprintln!(
        "summary: tau1_max {:.5} p0 at x = {:.4} a, z = {:.4} a (Johnson {tau_ref:.5} at \
         {z_ref:.4}); surface sigma_x {:.5} .. {:.5} p0",
        t / p0,
        x / a,
        z / a,
        s.sigma_x_min.unwrap() / p0,
        s.sigma_x_max.unwrap() / p0
    );
    assert!((t / p0 - tau_ref).abs() < 0.01 * tau_ref);
    // The depth grid has steps of a/40: the maximum is within half a step.
    assert!((z / a - z_ref).abs() < 0.0125 + 0.01 * z_ref);
    assert!(x.abs() <= solution.grid.cell());
    // Surface: -(1 + 2 nu)/2 p0 at the centre. The most tensile sigma_x lies on the x
    // axis at the edge, (1 - 2 nu)/3 p0, falling outside as a^2/r^2 (Johnson §3.4).
    // The cell centred on r = a straddles the edge, so the grid's largest value lies
    // between the exterior law at the first centre wholly outside (r = a + h) and
    // the edge value.
    let centre = -(1.0 + 2.0 * NU) / 2.0;
    assert!((s.sigma_x_min.unwrap() / p0 - centre).abs() < 0.01 * centre.abs());
    let edge = (1.0 - 2.0 * NU) / 3.0;
    let outside = edge * (a / (a + solution.grid.cell())).powi(2);
    let got = s.sigma_x_max.unwrap() / p0;
    assert!(
        got > 0.99 * outside && got < 1.01 * edge,
        "{got} not in [{outside}, {edge}]"
    );
    assert_eq!(s.interface_sigma_x_max_coating, None);
    assert_eq!(s.interface_sigma_x_max_substrate, None);
}

#[test]
fn interface_summary_of_a_coating_of_the_substrate_material() {
    // E1 = E2: both sides of the interface carry the homogeneous body's stresses, so
    // their largest sigma_x equals that of the homogeneous plane z = h1.
    let (_, solution, a, _) = solved_hertz();
    let h1 = 0.4 * a;
    let material = Elastic {
        young: 1.0,
        poisson: NU,
    };
    let coated = Body::coated(material, h1, material);
    let request = StressRequest {
        sections: Some(vec![SectionKind::Interface]),
        ..StressRequest::default()
    };
    let s = request
        .compute(&coated, &solution.grid, &solution.pressure)
        .unwrap()
        .summary;
    let plane = solution.stresses(&Section::Plane { z: h1 }).unwrap();
    let expected = plane.components[0]
        .iter()
        .fold(f64::NEG_INFINITY, |m, &v| m.max(v));
    for got in [
        s.interface_sigma_x_max_coating.unwrap(),
        s.interface_sigma_x_max_substrate.unwrap(),
    ] {
        assert!(
            (got - expected).abs() < 1e-6 * expected.abs(),
            "{got} vs {expected}"
        );
    }
    assert_eq!(s.tau1_max, None);
}
