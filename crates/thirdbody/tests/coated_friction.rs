//! On a stiff coating (E1/E2 = 3) the hysteresis friction
//! grows with the coating's thickness (paper Fig. 7: Q' = 5e-6, V' = 1e-3,
//! nu1 = nu2 = 0.3, C' = 0.02, delta = 0.5; linear and p0' = 0.005): a thicker stiff
//! coating makes the body stiffer, so the layer's creep carries more of the contact.

mod cases;

use cases::*;
use thirdbody::*;

fn coated(case: Case, thickness: f64) -> Case {
    Case {
        body: Body::coated(
            Elastic {
                young: 3.0,
                poisson: 0.3,
            },
            thickness,
            Elastic {
                young: 1.0,
                poisson: 0.3,
            },
        ),
        ..case
    }
}

#[test]
fn friction_grows_with_the_thickness_of_a_stiff_coating() {
    let thicknesses = [0.001, 0.005, 0.02, 0.05];
    for (name, law) in [
        ("linear", ComplianceLaw::Linear),
        ("p0'=0.005", sigmoid(0.5, 0.005)),
    ] {
        let base = layered(5e-6, 64, 0.02, 1e-3, law, Integration::Exact);
        let mu: Vec<f64> = thicknesses
            .iter()
            .map(|&h1| {
                solve_to(&coated(base.clone(), h1), 1e-9)
                    .summary()
                    .friction_coefficient
            })
            .collect();
        let bare = solve_to(&base, 1e-9).summary().friction_coefficient;
        let stiff = {
            let mut c = base.clone();
            c.body = Body::Homogeneous(Elastic {
                young: 3.0,
                poisson: 0.3,
            });
            solve_to(&c, 1e-9).summary().friction_coefficient
        };
        eprintln!("{name}: mu(h1' = {thicknesses:?}) = {mu:.5?}; substrate only {bare:.5}, coating only {stiff:.5}");
        for w in mu.windows(2) {
            assert!(w[1] > w[0], "{name}: {mu:?}");
        }
        // Between the two homogeneous limits.
        assert!(
            bare < mu[0] && mu[3] < stiff,
            "{name}: {bare} {mu:?} {stiff}"
        );
    }
}
