//! Case builders shared by the integration tests: the paper's dimensionless cases
//! (R = E2 = T = 1, section 4), Hertz's sphere and cylinder.
#![allow(dead_code)]

use thirdbody::layer::Table;
use thirdbody::*;

/// The paper's sphere on a homogeneous half-space (nu = 0.3) under Q'.
pub fn sphere(load: f64, cells: usize) -> Case {
    Case {
        slider: Slider::Sphere { radius: 1.0 },
        body: Body::Homogeneous(Elastic {
            young: 1.0,
            poisson: 0.3,
        }),
        layer: None,
        loading: Loading {
            normal_load: load,
            velocity: None,
            reference_distance: None,
        },
        grid: GridSpec {
            cells: [cells, cells],
            half_width: None,
            centre: None,
        },
        units: Units::Dimensionless,
    }
}

/// A cylinder of radius 1 (a line contact) on a homogeneous half-space (E = 1,
/// nu = 0.3) under `load` per unit length, on `cells` cells, automatic window.
pub fn cylinder(load: f64, cells: usize) -> Case {
    let mut case = sphere(load, cells);
    case.slider = Slider::Cylinder { radius: 1.0 };
    case.grid.cells = [cells, 1];
    case
}

/// The paper's nonlinear layer of Figs. 7-12: C' = 0.02, T = 1, sigmoid law
/// delta = 0.5, p0' = 0.005, exact integration (`examples/paper_fig12a_thin_coating.toml`).
pub fn paper_sigmoid_layer() -> Layer {
    Layer::maxwell(
        0.02,
        1.0,
        ComplianceLaw::Sigmoid {
            delta: 0.5,
            p0: 0.005,
        },
        Integration::Exact,
    )
}

/// `body` under the paper's sphere (Q' = 5e-6) on a fixed window of `cells` over
/// 0.12 R, with the paper's nonlinear layer at V' = 1e-3 when `layered`.
pub fn on_fixed_window(body: Body, layered: bool, cells: usize) -> Case {
    let mut c = sphere(5e-6, cells);
    c.body = body;
    c.grid.half_width = Some([0.06, 0.06]);
    c.grid.centre = Some([0.0, 0.0]);
    if layered {
        c.layer = Some(paper_sigmoid_layer());
        c.loading.velocity = Some(1e-3);
    }
    c
}

/// A Maxwell layer of compliance C0 with a law and an integration.
pub fn layered(
    load: f64,
    cells: usize,
    c0: f64,
    velocity: f64,
    law: ComplianceLaw,
    integration: Integration,
) -> Case {
    let mut c = sphere(load, cells);
    c.layer = Some(Layer::maxwell(c0, 1.0, law, integration));
    c.loading.velocity = Some(velocity);
    c
}

/// A linear layer of compliance 0.02 at infinite velocity: a Winkler bed on the
/// half-space (no creep, so conjugate gradients solve it).
pub fn winkler_bed(load: f64, cells: usize) -> Case {
    layered(
        load,
        cells,
        0.02,
        f64::INFINITY,
        ComplianceLaw::Linear,
        Integration::Exact,
    )
}

/// The largest pressure of `reference` and the largest difference of `p` from it.
pub fn peak_and_largest_difference(p: &[f64], reference: &[f64]) -> (f64, f64) {
    let peak = reference.iter().fold(0.0f64, |m, v| m.max(*v));
    let diff = p
        .iter()
        .zip(reference)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    (peak, diff)
}

/// The paper's sigmoid law (eq. 11).
pub fn sigmoid(delta: f64, p0: f64) -> ComplianceLaw {
    ComplianceLaw::Sigmoid { delta, p0 }
}

/// A tabulated law that stiffens with pressure.
pub fn stiffening_table() -> ComplianceLaw {
    ComplianceLaw::Table(
        Table::new(vec![0.0, 1e-3, 2e-3, 5e-3], vec![0.02, 0.016, 0.012, 0.01]).unwrap(),
    )
}

/// Fixes the window to a square of half width `w` centred at `centre`.
pub fn fixed_window(mut c: Case, w: f64, centre: [f64; 2]) -> Case {
    c.grid.half_width = Some([w, w]);
    c.grid.centre = Some(centre);
    c
}

/// Solves with a tolerance.
pub fn solve_to(case: &Case, tolerance: f64) -> Solution {
    let params = SolverParams {
        tolerance,
        ..SolverParams::default()
    };
    solve(case, &params).unwrap_or_else(|e| panic!("{e}"))
}

/// Relative difference of two numbers.
pub fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

/// The FFT solver's solution of `case` (to 1e-13) against the dense reference on the
/// same grid: `(max |dp| / max p, relative difference of D, loaded cells)`.
pub fn against_dense_reference(case: &Case, label: &str) -> (f64, f64, usize) {
    let fast = solve_to(case, 1e-13);
    let dense = thirdbody_reference::solve_dense(case, &fast.grid, 1e-13)
        .unwrap_or_else(|e| panic!("{label}: {e}"));
    let (pmax, diff) = peak_and_largest_difference(&fast.pressure, &dense.pressure);
    let loaded = fast.pressure.iter().filter(|&&p| p > 0.0).count();
    eprintln!(
        "{label}: max|dp|/max p = {:.2e}, D {:.3e} vs {:.3e}, {loaded} loaded cells, {:?}",
        diff / pmax,
        fast.approach,
        dense.approach,
        fast.info.method
    );
    (diff / pmax, rel(fast.approach, dense.approach), loaded)
}
