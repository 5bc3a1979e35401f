//! The DC-FFT + Newton/CG solver and the dense
//! direct reference (the paper's system 6 with LU and an active-set loop) give the
//! same discrete solution on a 24 x 24 grid.

use crate::cases;

use cases::*;
use thirdbody::*;

fn compare(case: &Case, label: &str) {
    let (dp, dd, loaded) = against_dense_reference(case, label);
    assert!(
        loaded > 60,
        "{label}: the contact must cover a fair part of the grid"
    );
    assert!(dp <= 1e-8, "{label}: {dp:.3e}");
    assert!(dd < 1e-8, "{label}: D");
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
    let winkler = winkler_bed(5e-6, 24);
    compare(&fixed_window(winkler, 0.026, [0.0, 0.0]), "winkler");
}
