//! The fractional Zener layer with its default branches (the order's rule) in
//! steady sliding: over six decades of speed around the peak, mu(V) has exactly
//! one maximum for orders 0.1, 0.2, 0.5 and 1 (the Zener layer), as the closed-form
//! complex compliance `C_g + C1 / (1 + (i omega tau)^alpha)` has one loss peak; with
//! branches two decades apart (24 at order 0.2, the former default) mu(V) had false
//! maxima. Sphere R = 1 on the paper's elastic half-space (E2 = 1), Q = 5e-6, linear
//! law, C_g = C1 = 0.01, tau = 1, 32 x 32 cells.

use crate::cases;

use cases::*;
use thirdbody::*;

fn fractional(order: f64, branch_count: Option<usize>) -> Rheology {
    Rheology::FractionalZener {
        glassy_compliance: 0.01,
        compliance: 0.01,
        retardation_time: 1.0,
        order,
        branch_count,
    }
}

/// mu at V for the layer.
fn friction(rheology: &Rheology, velocity: f64) -> f64 {
    let mut c = layered(
        5e-6,
        32,
        0.02,
        velocity,
        ComplianceLaw::Linear,
        Integration::Exact,
    );
    c.layer.as_mut().unwrap().rheology = rheology.clone();
    solve(&c, &SolverParams::default())
        .unwrap_or_else(|e| panic!("{rheology:?} at V = {velocity}: {e}"))
        .summary()
        .friction_coefficient
}

/// mu values for a message.
fn show(mus: &[f64]) -> String {
    let v: Vec<String> = mus.iter().map(|m| format!("{m:.4e}")).collect();
    v.join(", ")
}

/// The interior local maxima of a sequence.
fn local_maxima(values: &[f64]) -> Vec<usize> {
    (1..values.len() - 1)
        .filter(|&k| values[k] > values[k - 1] && values[k] > values[k + 1])
        .collect()
}

/// 13 speeds, half a decade apart, from 10^-4.5 to 10^1.5: the peak (creep length
/// V tau about the contact's length, 0.03) in the middle.
fn speeds() -> Vec<f64> {
    (0..13).map(|k| 10f64.powf(-4.5 + 0.5 * k as f64)).collect()
}

#[test]
fn friction_has_one_peak_for_every_order() {
    for order in [0.1, 0.2, 0.5, 1.0] {
        let rheology = fractional(order, None);
        let mus: Vec<f64> = speeds().iter().map(|&v| friction(&rheology, v)).collect();
        let maxima = local_maxima(&mus);
        eprintln!(
            "order {order} ({} branches): mu(V) = {}, maxima at V = {:?}",
            rheology.creep_form().branches.len(),
            show(&mus),
            maxima.iter().map(|&k| speeds()[k]).collect::<Vec<_>>()
        );
        assert_eq!(maxima.len(), 1, "order {order}: mu(V) = {mus:?}");
        assert!(mus.iter().all(|&m| m > 0.0), "order {order}");
    }
}

#[test]
fn branches_two_decades_apart_ripple_the_friction() {
    // The test above can fail: 24 branches at order 0.2 (about 1.8 decades apart).
    let rheology = fractional(0.2, Some(24));
    let mus: Vec<f64> = speeds().iter().map(|&v| friction(&rheology, v)).collect();
    eprintln!("order 0.2, 24 branches: mu(V) = {}", show(&mus));
    assert!(local_maxima(&mus).len() > 1, "{mus:?}");
}

#[test]
fn the_default_branches_loss_compliance_has_one_smooth_maximum() {
    // -Im C*(omega) of the branches, 20 frequencies a decade over 60 decades around
    // 1 / tau: one maximum, at omega tau = 1 (the closed form's, by its symmetry in
    // ln(omega tau)), for each order.
    for order in [0.1, 0.2, 0.5, 1.0] {
        let form = fractional(order, None).creep_form();
        let omegas: Vec<f64> = (-600..=600).map(|k| 10f64.powf(k as f64 / 20.0)).collect();
        let loss: Vec<f64> = omegas
            .iter()
            .map(|&w| -form.complex_compliance(w).1)
            .collect();
        let top = loss.iter().fold(0.0f64, |m, &x| m.max(x));
        let maxima: Vec<usize> = local_maxima(&loss)
            .into_iter()
            .filter(|&k| loss[k] > 0.01 * top)
            .collect();
        assert_eq!(maxima.len(), 1, "order {order}: maxima at {maxima:?}");
        assert!(
            (omegas[maxima[0]].log10()).abs() < 0.06,
            "order {order}: the maximum is at omega tau = {}",
            omegas[maxima[0]]
        );
    }
}
