//! Issue 2, acceptance 3 (first half): the DC-FFT + Newton/CG solver and the dense
//! direct reference (the paper's system 6 with LU and an active-set loop) give the
//! same discrete solution on a 24 x 24 grid.

mod cases;

use cases::*;
use thirdbody::reference::solve_dense;
use thirdbody::*;

fn compare(case: &Case, label: &str) {
    let fast = solve_to(case, 1e-13);
    let dense = solve_dense(case, &fast.grid, 1e-13).unwrap_or_else(|e| panic!("{label}: {e}"));
    let pmax = dense.pressure.iter().fold(0.0f64, |m, v| m.max(*v));
    let diff = fast
        .pressure
        .iter()
        .zip(&dense.pressure)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    let loaded = fast.pressure.iter().filter(|&&p| p > 0.0).count();
    eprintln!(
        "{label}: max|dp|/max p = {:.2e}, D {:.3e} vs {:.3e}, {loaded} loaded cells, {:?}",
        diff / pmax,
        fast.approach,
        dense.approach,
        fast.info.method
    );
    assert!(
        loaded > 60,
        "{label}: the contact must cover a fair part of the grid"
    );
    assert!(diff <= 1e-8 * pmax, "{label}: {:.3e}", diff / pmax);
    assert!(rel(fast.approach, dense.approach) < 1e-8, "{label}: D");
}

#[test]
fn all_laws_and_integrations_agree_with_the_dense_reference() {
    // V' = 1e-2 gives a creep-dominated contact of radius ~0.025 R.
    let laws = [
        ("linear", ComplianceLaw::Linear),
        ("sigmoid", sigmoid(0.5, 0.001)),
        ("table", stiffening_table()),
    ];
    for (name, law) in laws {
        for integration in [Integration::Exact, Integration::Secant] {
            let case = fixed_window(
                layered(5e-6, 24, 0.02, 1e-2, law.clone(), integration),
                0.034,
                [0.008, 0.0],
            );
            compare(&case, &format!("{name}/{integration:?}"));
        }
    }
}

#[test]
fn layer_free_and_creep_free_cases_agree_with_the_dense_reference() {
    compare(&fixed_window(sphere(5e-6, 24), 0.02, [0.0, 0.0]), "hertz");
    // Linear layer at infinite velocity: a Winkler bed on the half-space (PK path).
    let winkler = layered(
        5e-6,
        24,
        0.02,
        f64::INFINITY,
        ComplianceLaw::Linear,
        Integration::Exact,
    );
    compare(&fixed_window(winkler, 0.026, [0.0, 0.0]), "winkler");
}
