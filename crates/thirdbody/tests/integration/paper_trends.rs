//! The paper's qualitative findings on its own parameters
//! (section 4: Q' = 5e-6, V' = 1e-3, nu2 = 0.3, C' = 0.02; Fig. 8: Q' = 25e-6).

use crate::cases;

use cases::*;
use thirdbody::*;

const N: usize = 64;

fn summary(law: ComplianceLaw, c0: f64, load: f64, velocity: f64) -> Summary {
    solve_to(
        &layered(load, N, c0, velocity, law, Integration::Exact),
        1e-9,
    )
    .summary()
}

#[test]
fn nonlinear_pressure_lies_between_the_two_linear_bounds() {
    // Fig. 4: the solid (nonlinear) curves lie between the linear ones with C0 and
    // C0 (1 - delta).
    let soft = summary(ComplianceLaw::Linear, 0.02, 5e-6, 1e-3).max_pressure;
    let stiff = summary(ComplianceLaw::Linear, 0.01, 5e-6, 1e-3).max_pressure;
    for p0 in [0.0025, 0.005, 0.05] {
        let p = summary(sigmoid(0.5, p0), 0.02, 5e-6, 1e-3).max_pressure;
        eprintln!("p0' = {p0}: {soft:.4e} < {p:.4e} < {stiff:.4e}");
        assert!(soft < p && p < stiff);
    }
}

#[test]
fn smaller_p0_gives_higher_pressure_and_smaller_contact() {
    // Fig. 4 text: "the smaller the value of p0, the greater the maximum contact
    // pressure and the smaller the size of the contact area".
    let runs: Vec<Summary> = [0.05, 0.005, 0.0025]
        .iter()
        .map(|&p0| summary(sigmoid(0.5, p0), 0.02, 5e-6, 1e-3))
        .collect();
    for w in runs.windows(2) {
        assert!(w[1].max_pressure > w[0].max_pressure);
        assert!(w[1].contact_area < w[0].contact_area);
    }
}

#[test]
fn larger_delta_gives_higher_pressure() {
    // Fig. 5: delta = 0.01, 0.5, 1 with p0' = 0.005.
    let p: Vec<f64> = [0.01, 0.5, 1.0]
        .iter()
        .map(|&d| summary(sigmoid(d, 0.005), 0.02, 5e-6, 1e-3).max_pressure)
        .collect();
    eprintln!("max pressure for delta 0.01, 0.5, 1: {p:?}");
    assert!(p[0] < p[1] && p[1] < p[2]);
}

#[test]
fn friction_falls_with_velocity_and_nonlinearity_lowers_it() {
    // Fig. 8a: mu decreases with V' for the Maxwell layer; mu(nonlinear) < mu(linear).
    let velocities = [1e-4, 1e-3, 1e-2, 1e-1];
    let laws = [
        ("linear", ComplianceLaw::Linear),
        ("p0'=0.0025", sigmoid(0.5, 0.0025)),
        ("p0'=0.005", sigmoid(0.5, 0.005)),
        ("p0'=0.0075", sigmoid(0.5, 0.0075)),
    ];
    let mut table = Vec::new();
    for (name, law) in &laws {
        let mu: Vec<f64> = velocities
            .iter()
            .map(|&v| summary(law.clone(), 0.02, 25e-6, v).friction_coefficient)
            .collect();
        eprintln!("{name}: mu(V') = {mu:.4?}");
        for w in mu.windows(2) {
            assert!(w[1] < w[0], "{name}: {mu:?}");
        }
        table.push(mu);
    }
    for mu in &table[1..] {
        for (k, m) in mu.iter().enumerate() {
            assert!(
                *m < table[0][k],
                "nonlinear below linear at V' = {}",
                velocities[k]
            );
        }
    }
}
