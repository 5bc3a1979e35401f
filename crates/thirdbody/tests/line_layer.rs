//! The paper's third-body layer in a line contact (plane strain). On a rigid base
//! the rows of the layer are independent, so a line contact is exactly one row of
//! the semi-analytic rigid-base solution of `tests/common/rigid_base.rs` (the row
//! ODE along x, shared with the point-contact tests and independent of the
//! solver), with its leading edge b fixed by the load per unit length. On an
//! elastic body the solution converges with the grid, and its friction equals the
//! energy balance's.

mod cases;
mod common;

use common::rigid_base::{brent, Law, RigidBase};
use thirdbody::*;

const RADIUS: f64 = 1.0;
const COMPLIANCE: f64 = 0.02;
const VELOCITY: f64 = 0.01;
const LOAD: f64 = 2e-4;

/// The shared cylinder (radius `RADIUS`) under `LOAD` on a body of Young's modulus
/// `young` with `layer` at `VELOCITY`.
fn line_case(layer: Layer, young: f64, cells: usize) -> Case {
    let mut case = cases::cylinder(LOAD, cells);
    case.body = Body::Homogeneous(Elastic {
        young,
        poisson: 0.3,
    });
    case.layer = Some(layer);
    case.loading.velocity = Some(VELOCITY);
    case
}

/// The paper's sigmoid law (eq. 11), written out independently of the library.
fn sigmoid(c0: f64, delta: f64, p0: f64) -> impl Fn(f64) -> f64 {
    move |p: f64| c0 * (1.0 + delta - 2.0 * delta / (1.0 + (-p / p0).exp()))
}

struct RowReference {
    leading_edge: f64,
    trailing_edge: f64,
    approach: f64,
    max_pressure: f64,
    friction: f64,
}

/// The row whose load per unit length is `LOAD`.
fn row_reference(law: &Law) -> RowReference {
    row_reference_at(law, VELOCITY, LOAD)
}

/// The row of creep length `creep_length` (T = 1) whose load per unit length is
/// `load`.
fn row_reference_at(law: &Law, creep_length: f64, load: f64) -> RowReference {
    let base = RigidBase {
        radius: RADIUS,
        creep_length,
        load,
    };
    let b = brent(|b| base.row(law, b).load - load, 1e-4, 0.5, 1e-15);
    let row = base.row(law, b);
    RowReference {
        leading_edge: b,
        trailing_edge: row.trailing_edge,
        approach: b * b / (2.0 * RADIUS),
        max_pressure: row.max_pressure,
        friction: row.moment / (RADIUS * row.load),
    }
}

fn errors(case: &Case, reference: &RowReference) -> [f64; 5] {
    let s = solve(case, &SolverParams::default()).unwrap();
    let m = s.summary();
    let h = m.cell_size;
    [
        m.max_pressure / reference.max_pressure - 1.0,
        m.friction_coefficient / reference.friction - 1.0,
        m.penetration / reference.approach - 1.0,
        (m.contact_x_max - reference.leading_edge) / h,
        (m.contact_x_min - reference.trailing_edge) / h,
    ]
}

#[test]
fn a_layer_on_a_rigid_base_is_one_row_of_the_row_solution() {
    let linear = Layer::maxwell(COMPLIANCE, 1.0, ComplianceLaw::Linear, Integration::Exact);
    let c = sigmoid(COMPLIANCE, 0.5, 0.005);
    // The paper's layer: COMPLIANCE, T = 1, sigmoid delta = 0.5, p0 = 0.005.
    let nonlinear = cases::paper_sigmoid_layer();
    for (name, layer, law) in [
        (
            "linear",
            linear,
            Law::Linear {
                compliance: COMPLIANCE,
            },
        ),
        ("sigmoid", nonlinear, Law::Exact(&c)),
    ] {
        let reference = row_reference(&law);
        for cells in [1024, 4096] {
            let e = errors(&line_case(layer.clone(), 1e9, cells), &reference);
            eprintln!(
                "{name} {cells}: p_max {:+.2e}, mu {:+.2e}, D {:+.2e}, edges / h [{:+.2}, {:+.2}]",
                e[0], e[1], e[2], e[3], e[4]
            );
            // Measured at 4096 cells: p_max 7e-10 and 5e-8, mu 5e-8 and 9e-8, D 2e-8
            // and 3e-8 (linear and sigmoid); the edges within 0.51 cell.
            let tolerance = if cells == 4096 { 1e-6 } else { 1e-5 };
            for (what, v) in ["p_max", "mu", "D"].iter().zip(&e[..3]) {
                assert!(v.abs() < tolerance, "{name} {cells}: {what} {v:e}");
            }
            assert!(
                e[3].abs() < 1.0 && e[4].abs() < 1.0,
                "{name} {cells}: edges {e:?}"
            );
        }
    }
}

/// The paper's nonlinear layer on an elastic half-space (E' = 1) in a line contact:
/// mu, the peak pressure and D converge with the grid (measured: every grid from
/// 512 to 4096 cells within 1.6e-6 of the finest, the changes at the level of the
/// edges' placement), and the friction equals the energy balance's (5.9e-9 at
/// 4096 cells).
#[test]
fn the_paper_layer_on_an_elastic_body_converges_with_the_grid() {
    let layer = cases::paper_sigmoid_layer();
    let results: Vec<[f64; 4]> = [512, 1024, 2048, 4096]
        .iter()
        .map(|&cells| {
            let s = solve(
                &line_case(layer.clone(), 1.0, cells),
                &SolverParams::default(),
            )
            .unwrap();
            let m = s.summary();
            eprintln!(
                "{cells}: mu {:.9e}, mu by energy {:.9e}, p_max {:.9e}, D {:.9e}",
                m.friction_coefficient,
                m.dissipation_friction_coefficient,
                m.max_pressure,
                m.penetration
            );
            [
                m.friction_coefficient,
                m.max_pressure,
                m.penetration,
                m.dissipation_friction_coefficient,
            ]
        })
        .collect();
    for k in 0..3 {
        for r in &results[..3] {
            let off = (r[k] / results[3][k] - 1.0).abs();
            assert!(off < 1e-5, "quantity {k}: {off:.2e} from the finest grid");
        }
    }
    let finest = results[3];
    assert!(
        (finest[3] / finest[0] - 1.0).abs() < 1e-6,
        "energy balance {} vs {}",
        finest[3],
        finest[0]
    );
}

/// The slow limit on a rigid base: creep lengths V T of 0.4 and 0.04 of the
/// default grid's cell (the load scaled with them, `W = L b^2 / (2 R C0)` in the
/// slow limit, so that the contact keeps its half-width b = 0.02). The pressure
/// rises at the leading edge within the first cell (over `V T`) and the flow's
/// discrete row relation has an odd-even mode decaying only as `(r - 2) / (r + 2)`
/// per cell (r = h / V T); before the flow's upwind correction and its located
/// edges the peak pressure came out 33 % high (mu and D were right), and before
/// the rise was modelled inside the entry cell up to 3.4 % high. Now the peak is
/// within 1 % (measured +0.45 % and -0.007 %), with no warning, mu and D within
/// 1e-4 and the energy balance within 1e-3.
#[test]
fn a_creep_length_far_below_the_cell_is_one_row_of_the_row_solution() {
    let b: f64 = 0.02;
    for creep_length in [1e-5, 1e-6] {
        let load = creep_length * b * b / (2.0 * RADIUS * COMPLIANCE);
        let reference = row_reference_at(
            &Law::Linear {
                compliance: COMPLIANCE,
            },
            creep_length,
            load,
        );
        let mut case = line_case(
            Layer::maxwell(COMPLIANCE, 1.0, ComplianceLaw::Linear, Integration::Exact),
            1e9,
            1024,
        );
        case.loading.normal_load = load;
        case.loading.velocity = Some(creep_length);
        let s = solve(&case, &SolverParams::default()).unwrap();
        let m = s.summary();
        let e = [
            m.max_pressure / reference.max_pressure - 1.0,
            m.friction_coefficient / reference.friction - 1.0,
            m.penetration / reference.approach - 1.0,
            m.dissipation_friction_coefficient / m.friction_coefficient - 1.0,
        ];
        eprintln!(
            "L = {creep_length:e}, h / L = {:.1}: p_max {:+.2e}, mu {:+.2e}, D {:+.2e}, \
             energy balance {:+.2e}",
            m.cell_size / creep_length,
            e[0],
            e[1],
            e[2],
            e[3]
        );
        assert!(e[0].abs() < 0.01, "p_max {:e}", e[0]);
        let warnings = report::model_warnings(&case, &s);
        assert!(warnings.is_empty(), "{warnings:?}");
        assert!(e[1].abs() < 1e-4, "mu {:e}", e[1]);
        assert!(e[2].abs() < 1e-4, "D {:e}", e[2]);
        assert!(e[3].abs() < 1e-3, "energy balance {:e}", e[3]);
    }
}

/// A Burgers layer (the paper's Maxwell element and a Kelvin–Voigt branch, C_1 =
/// C0, tau = 0.1, 1 and 10 T) in a line contact on a rigid base against one row of
/// its closed form (`tests/common/rigid_base_burgers.rs`): at the paper-like V T =
/// 0.01 on 1024 and 4096 cells, and in the slow limit (V T = 1e-5 and 1e-6, a
/// quarter and a fortieth of the cell, the load scaled so that the half-width stays
/// near 0.02), where the pressure rises behind the leading edge over the layer's two
/// exponentials inside the entry cell (`layer::Rise`).
#[test]
fn a_burgers_layer_on_a_rigid_base_is_one_row_of_its_closed_form() {
    use common::rigid_base_burgers::BurgersRigidBase;
    let b0: f64 = 0.02;
    let mut worst = [0.0f64; 4];
    for ratio in [0.1, 1.0, 10.0] {
        for (creep_length, cells) in [(0.01, 1024), (0.01, 4096), (1e-5, 1024), (1e-6, 1024)] {
            let load = if creep_length < 1e-3 {
                creep_length * b0 * b0 / (2.0 * RADIUS * COMPLIANCE)
            } else {
                LOAD
            };
            let oracle = BurgersRigidBase {
                radius: RADIUS,
                load,
                glassy: COMPLIANCE,
                branch: COMPLIANCE,
                branch_length: ratio * creep_length,
                flow: COMPLIANCE,
                flow_length: creep_length,
            };
            let b = brent(|b| oracle.row(b).load() - load, 1e-4, 0.5, 1e-15);
            let row = oracle.row(b);
            let (peak, _) = row.peak();
            let friction = row.moment() / (RADIUS * row.load());
            let mut case = line_case(
                Layer {
                    rheology: Rheology::Burgers {
                        glassy_compliance: COMPLIANCE,
                        relaxation_time: 1.0,
                        compliance: COMPLIANCE,
                        retardation_time: ratio,
                    },
                    law: ComplianceLaw::Linear,
                    integration: Integration::Exact,
                },
                1e9,
                cells,
            );
            case.loading.normal_load = load;
            case.loading.velocity = Some(creep_length);
            let m = solve(&case, &SolverParams::default()).unwrap().summary();
            let e = [
                m.max_pressure / peak - 1.0,
                m.friction_coefficient / friction - 1.0,
                m.penetration / (b * b / (2.0 * RADIUS)) - 1.0,
                m.dissipation_friction_coefficient / m.friction_coefficient - 1.0,
            ];
            eprintln!(
                "tau = {ratio} T, V T = {creep_length:e}, {cells} cells (h / V T = {:.1}): \
                 p_max {:+.2e}, mu {:+.2e}, D {:+.2e}, energy balance {:+.2e}",
                m.cell_size / creep_length,
                e[0],
                e[1],
                e[2],
                e[3]
            );
            for (w, v) in worst.iter_mut().zip(e) {
                *w = w.max(v.abs());
            }
            // Measured: at V T = 0.01 within 5.9e-6 (1024 cells) and 4.8e-7 (4096);
            // in the slow limit p_max within 6.8e-4, mu and D 1.6e-4, the energy
            // balance 1.6e-4.
            let (tolerance, peak_tolerance) = match (creep_length < 1e-3, cells) {
                (false, 4096) => (1e-6, 1e-6),
                (false, _) => (1e-5, 1e-5),
                (true, _) => (5e-4, 2e-3),
            };
            assert!(
                e[0].abs() < peak_tolerance,
                "tau {ratio}, L {creep_length}: {e:?}"
            );
            for v in &e[1..3] {
                assert!(v.abs() < tolerance, "tau {ratio}, L {creep_length}: {e:?}");
            }
            assert!(e[3].abs() < 1e-3, "tau {ratio}, L {creep_length}: {e:?}");
        }
    }
    eprintln!("worst (p_max, mu, D, energy balance): {worst:?}");
}

/// The paper's layer with its linear law (C0 = 0.02, T = 1) in slow sliding under a
/// cylinder, well inside the model: V = 1e-5 under 1e-6 per unit length (contact
/// half-width about 0.02 R, D = 0.002 R) and V = 3e-5 under 1e-4. Newton stalled on
/// some grids and converged on others ("did not converge" at 4,096 to 16,384 cells
/// for the first, at 1,024 and 2,048 for the second, the default 1,024 among them);
/// a window whose solve stalls is now solved again from the same window at half the
/// cells. Every grid converges, to the same friction and approach, and the friction
/// equals the energy balance's (measured: mu within 1.5e-6 and D within 9e-7 of
/// 16,384 cells, the energy balance within 7.3e-6).
#[test]
fn slow_sliding_converges_on_every_grid() {
    const TOL_GRID: f64 = 1e-5;
    const TOL_BALANCE: f64 = 2e-5;
    let layer = Layer::maxwell(0.02, 1.0, ComplianceLaw::Linear, Integration::Exact);
    for (velocity, load) in [(1e-5, 1e-6), (3e-5, 1e-4)] {
        let results: Vec<[f64; 3]> = [1024, 2048, 4096, 8192, 16384]
            .iter()
            .map(|&cells| {
                let mut case = cases::cylinder(load, cells);
                case.layer = Some(layer.clone());
                case.loading.velocity = Some(velocity);
                let s = solve(&case, &SolverParams::default())
                    .unwrap_or_else(|e| panic!("V = {velocity}, {cells} cells: {e}"));
                let m = s.summary();
                eprintln!(
                    "V = {velocity}, {cells}: mu {:.9e}, by energy {:.9e}, D {:.9e}",
                    m.friction_coefficient, m.dissipation_friction_coefficient, m.penetration
                );
                [
                    m.friction_coefficient,
                    m.dissipation_friction_coefficient,
                    m.penetration,
                ]
            })
            .collect();
        let finest = results[results.len() - 1];
        for r in &results {
            for (k, what) in [(0, "mu"), (2, "D")] {
                let off = (r[k] / finest[k] - 1.0).abs();
                assert!(
                    off < TOL_GRID,
                    "V = {velocity}: {what} {off:.2e} from the finest grid"
                );
            }
            let balance = (r[1] / r[0] - 1.0).abs();
            assert!(
                balance < TOL_BALANCE,
                "V = {velocity}: energy balance {balance:.2e}"
            );
        }
    }
}
