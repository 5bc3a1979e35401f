//! Rigid-base limit of the layer contact: the solver on a very stiff body against
//! the semi-analytic per-row solution of `tests/common/rigid_base.rs`, and checks of that oracle itself.

mod common;

use common::rigid_base::{
    gauss_legendre, linear_pressure, trailing_edge_depth, Law, Reference, RigidBase, ROWS,
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
    // docs/architecture.md (readings of the paper) quotes r ~ 0.053 for V' = 1e-3.
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

// ---------------------------------------------------------------------------
// The solver against the oracle.
//
// Parameters (R = T = 1): C0 = 0.02, V = 0.01 (creep length L = V T = 0.01),
// Q = 2e-5. The oracle's contact is then a near half disc of radius b0 ~ 0.04 = 4 L
// with its trailing edge at x ~ -L: creep and the instantaneous compliance both
// matter (b0 / L = 4), and the leading-edge boundary layer, of width ~L, spans
// 5 cells on the 32 x 48 grid and 10 on the 64 x 96 grid, enough for the 1%
// tolerance (the paper's V' = 1e-3 would need ~10 times finer cells).
// The fixed window x in [-0.016, 0.048], y in [-0.048, 0.048] holds every case's
// contact with a margin of at least two coarse cells (checked below).
// The body (E = 1e9) is ~1e9 times stiffer than the layer over the contact size
// (b0 / (E* C0) ~ 2e-9): a rigid base to every digit that matters (checked below).

use thirdbody::layer::Table;
use thirdbody::{
    Body, Case, ComplianceLaw, Elastic, GridSpec, Integration, Layer, Loading, Slider,
    SolverParams, Units,
};

const RADIUS: f64 = 1.0;
const COMPLIANCE: f64 = 0.02;
const RELAXATION_TIME: f64 = 1.0;
const VELOCITY: f64 = 0.01;
const LOAD: f64 = 2e-5;
const WINDOW_CENTRE: [f64; 2] = [0.016, 0.0];
const WINDOW_HALF_WIDTH: [f64; 2] = [0.032, 0.048];
/// Coarse and fine grids: square cells of L / 5 and L / 10.
const GRIDS: [[usize; 2]; 2] = [[32, 48], [64, 96]];

fn oracle_problem() -> RigidBase {
    RigidBase {
        radius: RADIUS,
        creep_length: VELOCITY * RELAXATION_TIME,
        load: LOAD,
    }
}

fn layer(law: ComplianceLaw, integration: Integration) -> Layer {
    Layer::maxwell(COMPLIANCE, RELAXATION_TIME, law, integration)
}

fn rigid_base_case(layer: Layer, cells: [usize; 2]) -> Case {
    Case {
        slider: Slider::Sphere { radius: RADIUS },
        body: Body::Homogeneous(Elastic {
            young: 1e9,
            poisson: 0.3,
        }),
        layer: Some(layer),
        loading: Loading {
            normal_load: LOAD,
            velocity: Some(VELOCITY),
            reference_distance: None,
        },
        grid: GridSpec {
            cells,
            half_width: Some(WINDOW_HALF_WIDTH),
            centre: Some(WINDOW_CENTRE),
        },
        units: Units::Dimensionless,
    }
}

/// Solves `layer` on both grids, prints the errors against `reference`, and
/// asserts: max pressure, mu and D within 1% on the fine grid, every contact
/// extent within one cell on both grids, a body that is rigid against the layer.
fn compare_with_oracle(name: &str, layer: Layer, reference: Reference) {
    let b0 = reference.contact_radius;
    let [wx, wy] = WINDOW_HALF_WIDTH;
    let coarse = 2.0 * wx / GRIDS[0][0] as f64;
    assert!(reference.x_min > WINDOW_CENTRE[0] - wx + 2.0 * coarse);
    assert!(b0 < WINDOW_CENTRE[0] + wx - 2.0 * coarse);
    assert!(b0 < wy - 2.0 * coarse);
    eprintln!(
        "{name}: oracle D = {:.6e}, p_max = {:.6e}, mu = {:.6e}, x in [{:.4e}, {:.4e}], \
         |y| <= {:.4e}",
        reference.approach,
        reference.max_pressure,
        reference.friction_coefficient,
        reference.x_min,
        reference.x_max,
        b0
    );
    for (k, &cells) in GRIDS.iter().enumerate() {
        let case = rigid_base_case(layer.clone(), cells);
        let errors = solve_and_compare(name, &case, &reference);
        if k == GRIDS.len() - 1 {
            errors.assert_within(0.01, &format!("{name}, {cells:?}"));
        }
    }
}

/// Relative errors of one solve against the oracle.
struct Errors {
    max_pressure: f64,
    friction_coefficient: f64,
    approach: f64,
}

impl Errors {
    fn assert_within(&self, tolerance: f64, what: &str) {
        let e = self;
        assert!(
            e.max_pressure.abs() < tolerance,
            "{what}: max pressure error {:+.3e}",
            e.max_pressure
        );
        assert!(
            e.friction_coefficient.abs() < tolerance,
            "{what}: mu error {:+.3e}",
            e.friction_coefficient
        );
        assert!(
            e.approach.abs() < tolerance,
            "{what}: approach error {:+.3e}",
            e.approach
        );
    }
}

/// Solves `case`, checks that its body is rigid against the layer and that every
/// contact extent is within one cell of the oracle's, prints and returns the errors.
fn solve_and_compare(name: &str, case: &Case, reference: &Reference) -> Errors {
    let b0 = reference.contact_radius;
    let solution = thirdbody::solve(case, &SolverParams::default())
        .unwrap_or_else(|e| panic!("{name}, {:?}: {e}", case.grid.cells));
    let s = solution.summary();
    let h = s.cell_size;
    // The base is rigid: body displacement negligible against the layer's.
    let largest = |w: &[f64]| w.iter().fold(0.0f64, |m, w| m.max(w.abs()));
    let body = largest(&solution.body_displacement);
    let layer_w = largest(
        solution
            .layer_displacement
            .as_deref()
            .expect("w3 of a layer case"),
    );
    assert!(
        body < 1e-4 * layer_w,
        "{name}: body {body:e} vs layer {layer_w:e}"
    );
    let errors = Errors {
        max_pressure: s.max_pressure / reference.max_pressure - 1.0,
        friction_coefficient: s.friction_coefficient / reference.friction_coefficient - 1.0,
        approach: s.penetration / reference.approach - 1.0,
    };
    let extents = [
        s.contact_x_min - reference.x_min,
        s.contact_x_max - reference.x_max,
        s.contact_y_min + b0,
        s.contact_y_max - b0,
    ];
    eprintln!(
        "{name}: {}x{} (h = L/{:.1}): p_max {:.6e} (err {:+.2e}), mu {:.6e} (err {:+.2e}), \
         D err {:+.2e}, extents - ref [x_min, x_max, y_min, y_max] / h = [{:+.2}, {:+.2}, \
         {:+.2}, {:+.2}], body/layer w = {:.1e}, iterations {}, residual {:.1e}",
        s.nx,
        s.ny,
        case.loading.velocity.unwrap() * RELAXATION_TIME / h,
        s.max_pressure,
        errors.max_pressure,
        s.friction_coefficient,
        errors.friction_coefficient,
        errors.approach,
        extents[0] / h,
        extents[1] / h,
        extents[2] / h,
        extents[3] / h,
        body / layer_w,
        s.iterations,
        s.residual,
    );
    for (what, e) in ["x_min", "x_max", "y_min", "y_max"].iter().zip(extents) {
        assert!(
            e.abs() <= h,
            "{name}, {}x{}: {what} off by {:.2} cells",
            s.nx,
            s.ny,
            e / h
        );
    }
    errors
}

/// The secant oracle inverts `q(p) = C[p] p`: it must increase up to well beyond
/// the pressures reached.
fn assert_secant_invertible(c: &dyn Fn(f64) -> f64, p_max: f64) {
    let n = 10_000;
    for k in 0..n {
        let (p1, p2) = (
            2.0 * p_max * k as f64 / n as f64,
            2.0 * p_max * (k + 1) as f64 / n as f64,
        );
        assert!(c(p2) * p2 > c(p1) * p1, "C p not increasing at {p1}");
    }
}

#[test]
fn linear_layer_on_a_rigid_base_matches_the_closed_form() {
    let reference = oracle_problem().solve(&Law::Linear {
        compliance: COMPLIANCE,
    });
    // For a constant compliance both integrations are the same law.
    for integration in [Integration::Exact, Integration::Secant] {
        let name = format!("linear, {integration:?}");
        compare_with_oracle(&name, layer(ComplianceLaw::Linear, integration), reference);
    }
}

/// Sigmoid with delta = 0.5 and p0 = 0.01: the compliance falls by a third over
/// the pressures of the contact (p_max ~ 0.015).
const SIGMOID: ComplianceLaw = ComplianceLaw::Sigmoid {
    delta: 0.5,
    p0: 0.01,
};

#[test]
fn sigmoid_layer_exact_integration_on_a_rigid_base_matches_the_row_ode() {
    let c = sigmoid(COMPLIANCE, 0.5, 0.01);
    let reference = oracle_problem().solve(&Law::Exact(&c));
    compare_with_oracle(
        "sigmoid, exact",
        layer(SIGMOID, Integration::Exact),
        reference,
    );
}

#[test]
fn sigmoid_layer_secant_integration_on_a_rigid_base_matches_the_row_ode() {
    let c = sigmoid(COMPLIANCE, 0.5, 0.01);
    let reference = oracle_problem().solve(&Law::Secant(&c));
    assert_secant_invertible(&c, reference.max_pressure);
    compare_with_oracle(
        "sigmoid, secant",
        layer(SIGMOID, Integration::Secant),
        reference,
    );
}

/// A measured-looking table: compliance falling by 45% up to p = 0.012, constant
/// beyond (the contact reaches p ~ 0.015, so the tail is used too). The oracle
/// takes the library's monotone interpolant of it as the definition of the law.
fn table_law() -> ComplianceLaw {
    let pressures = vec![0.0, 0.002, 0.005, 0.008, 0.012];
    let compliances = vec![0.02, 0.019, 0.015, 0.012, 0.011];
    ComplianceLaw::Table(Table::new(pressures, compliances).expect("a valid table"))
}

#[test]
fn table_layer_on_a_rigid_base_matches_the_row_ode() {
    for integration in [Integration::Exact, Integration::Secant] {
        let table = layer(table_law(), integration);
        let c = |p: f64| table.law_at(p).compliance;
        let reference = oracle_problem().solve(&match integration {
            Integration::Exact => Law::Exact(&c),
            Integration::Secant => Law::Secant(&c),
        });
        if integration == Integration::Secant {
            assert_secant_invertible(&c, reference.max_pressure);
        }
        compare_with_oracle(&format!("table, {integration:?}"), table.clone(), reference);
    }
}

/// The slow limit: creep lengths L = V T of a tenth and a hundredth of the fine
/// grid's cell, the load scaled (`Q = (4/3) L b0^3 / (2 R C0)`, the rows' slow
/// limit) so that the contact is the same near half disc of radius 0.04. The
/// pressure jumps at the leading edge (a boundary layer of width L inside the
/// first cell) and the flow's discrete relation between neighbouring cells has an
/// odd-even mode that decays only as `(r - 2) / (r + 2)` per cell, r = h / L;
/// before the flow's upwind correction and its located edges the mode rang across
/// the contact and the dissipated power came out 10-20 % off the friction. Now mu
/// and D are within 1 % of the oracle and the energy balance within 2e-3; the
/// peak, a centre value next to the jump, is still up to 12 % high, and the report
/// says that it is not resolved.
/// The slow limit: creep lengths V T from 0.3 to 0.01 of the cell (64 x 96), the
/// load scaled so that the contact stays the half disc b0 = 0.04. The pressure
/// rises over V T behind the leading edge, inside the entry cell, which the layer
/// models (`ContactEdge::rise`). Before, the entry cell's pressure jumped there and
/// the centre values next to it overshot the peak by 5.7 %, 12.2 % and 5.4 % at
/// V T = 0.3 h, h / 10 and h / 30 (15.8 % with the sigmoid law at h / 10), which
/// the report flagged as unresolved. Now the peak, mu and D are within 1 % of the
/// per-row closed form with no warning, and the energy balance within 1e-3. The
/// sigmoid law at V T = h / 5 has the edge of its peak row near a cell's centre,
/// where the rise is shortened (`rise_behind`).
#[test]
fn a_creep_length_far_below_the_cell_matches_the_oracle() {
    let b0: f64 = 0.04;
    let c = sigmoid(COMPLIANCE, 0.5, 0.01);
    let cell = 2.0 * WINDOW_HALF_WIDTH[0] / GRIDS[1][0] as f64;
    let cases = [
        (0.3, ComplianceLaw::Linear),
        (0.1, ComplianceLaw::Linear),
        (0.01, ComplianceLaw::Linear),
        (0.2, SIGMOID),
    ];
    for (share, law) in cases {
        let creep_length = share * cell;
        let load = 4.0 / 3.0 * creep_length * b0.powi(3) / (2.0 * RADIUS * COMPLIANCE);
        let oracle = RigidBase {
            radius: RADIUS,
            creep_length,
            load,
        };
        let reference = oracle.solve(&match law {
            ComplianceLaw::Linear => Law::Linear {
                compliance: COMPLIANCE,
            },
            _ => Law::Exact(&c),
        });
        let mut case = rigid_base_case(layer(law, Integration::Exact), GRIDS[1]);
        case.loading.normal_load = load;
        case.loading.velocity = Some(creep_length / RELAXATION_TIME);
        let name = format!("V T = {share} h");
        let errors = solve_and_compare(&name, &case, &reference);
        errors.assert_within(0.01, &name);
        let solution = thirdbody::solve(&case, &SolverParams::default()).unwrap();
        let warnings = thirdbody::report::model_warnings(&case, &solution);
        assert!(warnings.is_empty(), "{name}: {warnings:?}");
        let s = solution.summary();
        let balance = s.dissipation_friction_coefficient / s.friction_coefficient - 1.0;
        eprintln!("{name}: energy balance {balance:+.2e}");
        assert!(balance.abs() < 1e-3, "{name}: energy balance {balance:e}");
    }
}

#[test]
fn automatic_window_resolves_the_rigid_base_contact() {
    // The automatic window must find the layer-dominated contact (b0 ~ 0.04, some
    // 1700 times the Hertz radius of the stiff body alone) and, with 128 x 128
    // cells, resolve it to the same 1% and one cell as the fixed window.
    let reference = oracle_problem().solve(&Law::Linear {
        compliance: COMPLIANCE,
    });
    let mut case = rigid_base_case(layer(ComplianceLaw::Linear, Integration::Exact), [128, 128]);
    case.grid.half_width = None;
    case.grid.centre = None;
    let errors = solve_and_compare("linear, automatic window", &case, &reference);
    errors.assert_within(0.01, "linear, automatic window, 128 x 128");
}
