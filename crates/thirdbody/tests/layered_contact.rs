//! Consistency of layered bodies through the whole solve (surface kernel, solver,
//! summary): a stack of layers of the substrate's material is the homogeneous body;
//! a layer split into two of the same material changes nothing; a layer whose
//! thickness goes to 0 disappears, its effect falling linearly with the thickness.
//! Each on a fixed 32 x 32 window, with and without the paper's nonlinear layer.

use thirdbody::body::layered::{Base, Ply, Stack};
mod cases;

use thirdbody::{solve, Body, Case, Elastic, Solution, SolverParams};

const SUBSTRATE: Elastic = Elastic {
    young: 1.0,
    poisson: 0.3,
};

fn case(body: Body, layered: bool) -> Case {
    cases::on_fixed_window(body, layered, 32)
}

fn stack(layers: &[(Elastic, f64)]) -> Body {
    Body::Layered(Stack {
        layers: layers
            .iter()
            .map(|&(material, thickness)| Ply {
                material,
                thickness,
            })
            .collect(),
        base: Base::HalfSpace(SUBSTRATE),
    })
}

fn solved(body: Body, layered: bool) -> Solution {
    solve(&case(body, layered), &SolverParams::default()).unwrap()
}

/// The largest pressure difference over the peak, and the friction's difference.
fn difference(a: &Solution, b: &Solution) -> (f64, f64) {
    let peak = b.pressure.iter().fold(0.0f64, |m, &v| m.max(v));
    let dp = a
        .pressure
        .iter()
        .zip(&b.pressure)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    let dmu = (a.summary().friction_coefficient - b.summary().friction_coefficient).abs();
    (dp / peak, dmu)
}

#[test]
fn layers_of_the_substrate_material_are_the_homogeneous_body() {
    for layered in [false, true] {
        let homogeneous = solved(Body::Homogeneous(SUBSTRATE), layered);
        let layers = solved(
            stack(&[(SUBSTRATE, 0.003), (SUBSTRATE, 0.01), (SUBSTRATE, 0.5)]),
            layered,
        );
        let (dp, dmu) = difference(&layers, &homogeneous);
        eprintln!("identical layers, layer {layered}: pressure {dp:.1e}, mu {dmu:.1e}");
        assert!(dp < 1e-12 && dmu < 1e-12, "{dp:.1e} {dmu:.1e}");
    }
}

#[test]
fn splitting_a_layer_into_two_of_its_material_changes_nothing() {
    let (a, b) = (
        Elastic {
            young: 3.0,
            poisson: 0.25,
        },
        Elastic {
            young: 0.4,
            poisson: 0.45,
        },
    );
    for layered in [false, true] {
        let whole = solved(stack(&[(a, 0.01), (b, 0.005)]), layered);
        let split = solved(stack(&[(a, 0.004), (a, 0.006), (b, 0.005)]), layered);
        let (dp, dmu) = difference(&split, &whole);
        eprintln!("split layer, layer {layered}: pressure {dp:.1e}, mu {dmu:.1e}");
        assert!(dp < 1e-10 && dmu < 1e-10, "{dp:.1e} {dmu:.1e}");
    }
}

#[test]
fn a_vanishing_layer_disappears_linearly() {
    let (stiff, soft) = (
        Elastic {
            young: 10.0,
            poisson: 0.2,
        },
        Elastic {
            young: 0.5,
            poisson: 0.4,
        },
    );
    // The difference is linear in t with a second-order term (the stiff film's
    // membrane length, 20 t, against the contact): the ratio of successive halvings
    // must approach 2, its distance from 2 halving with t.
    let without = solved(stack(&[(soft, 0.005)]), true);
    let mut last: Option<f64> = None;
    let mut gaps = Vec::new();
    for t in [8e-6, 4e-6, 2e-6, 1e-6] {
        let with = solved(stack(&[(stiff, t), (soft, 0.005)]), true);
        let (dp, _) = difference(&with, &without);
        eprintln!("top layer {t:e} thick: pressure {dp:.3e} of the peak");
        if let Some(previous) = last {
            let ratio = previous / dp;
            eprintln!("  ratio {ratio:.4}");
            gaps.push((ratio - 2.0).abs());
        }
        last = Some(dp);
    }
    assert!(gaps.windows(2).all(|g| g[1] < 0.7 * g[0]), "{gaps:?}");
    assert!(gaps[gaps.len() - 1] < 0.05, "{gaps:?}");
}

#[test]
fn a_near_incompressible_layer_on_a_rigid_base_carries_the_load_to_the_base() {
    // Equilibrium: every plane z = const carries the whole load, the integral of
    // sigma_z over it is -Q. A layer of nu 0.45, 0.49 and 0.499 bonded (or sliding
    // without friction) on a rigid base, the contact radius about the layer's
    // thickness. A bonded layer spreads the load on the base over several
    // thicknesses (one cell's sigma_z there sums to 1 - 3.7e-3 over +-6 h, 1 - 3.5e-5
    // over +-12 h), so the window reaches 15 h.
    use thirdbody::body::layered::BaseContact;
    use thirdbody::stress::Section;
    for poisson in [0.45, 0.49, 0.499] {
        for contact in [BaseContact::Bonded, BaseContact::Frictionless] {
            let body = Body::Layered(Stack {
                layers: vec![Ply {
                    material: Elastic {
                        young: 1.0,
                        poisson,
                    },
                    thickness: 0.02,
                }],
                base: Base::Rigid(contact),
            });
            let mut c = case(body, false);
            c.loading.normal_load = 2e-5;
            c.grid.half_width = Some([0.3, 0.3]);
            c.grid.cells = [64, 64];
            let s = solve(&c, &SolverParams::default()).unwrap();
            let area = s.grid.cell() * s.grid.cell();
            for z in [0.0, 0.01, 0.02] {
                let f = s.stresses(&Section::Plane { z }).unwrap();
                let force: f64 = f.components[2].iter().sum::<f64>() * area;
                let e = (force / -2e-5 - 1.0).abs();
                eprintln!("nu {poisson}, {contact:?}, z = {z}: load carried {e:.1e}");
                assert!(f.components.iter().flatten().all(|v| v.is_finite()));
                assert!(e < 2e-4, "nu {poisson}, {contact:?}, z = {z}: {e:.1e}");
            }
        }
    }
}

/// A sphere on two bonded coatings over a half-space, against the tri-layered
/// contacts of Yu, Wang & Wang (Mech. Mater. 76, 102-120, 2014, section 3.3 and
/// Fig. 6): R = 200 a0, coatings 0.5 a0 thick each, every Poisson ratio 0.3, a0 and
/// P0 the Hertz radius and peak of the uncoated substrate. The paper's values, as
/// quoted in the tests of another contact code (github.com/FrictionTribologyEnigma/
/// slippy, commit 723b9332, `slippy/contact/tests/test_multilayer_material.py`; the
/// paper itself was not reachable here): compliant coatings (E1 = 0.25, E2 = 0.5 E_sub)
/// contact radius 1.373 a0 and peak 0.582 P0; stiff coatings (E1 = 4, E2 = 2 E_sub)
/// contact radius 0.695 a0, the peak "almost doubled". The radius is read from the
/// contact area, `sqrt(A / pi)`, on 128^2 cells (the default grid).
#[test]
fn two_coatings_under_a_sphere_match_yu_wang_and_wang() {
    let a0: f64 = 0.005;
    let radius = 200.0 * a0;
    let e_star = SUBSTRATE.young / (1.0 - SUBSTRATE.poisson * SUBSTRATE.poisson);
    let load = 4.0 * e_star * a0.powi(3) / (3.0 * radius);
    let p0 = 3.0 * load / (2.0 * std::f64::consts::PI * a0 * a0);
    let coating = |young: f64| Elastic {
        young,
        poisson: 0.3,
    };
    for (name, e1, e2, published_radius, published_peak) in [
        ("compliant", 0.25, 0.5, 1.373, Some(0.582)),
        ("stiff", 4.0, 2.0, 0.695, None),
    ] {
        let mut case = cases::sphere(load, 128);
        case.slider = thirdbody::Slider::Sphere { radius };
        case.body = stack(&[(coating(e1), 0.5 * a0), (coating(e2), 0.5 * a0)]);
        let m = solve(&case, &SolverParams::default()).unwrap().summary();
        let contact_radius = (m.contact_area / std::f64::consts::PI).sqrt() / a0;
        let peak = m.max_pressure / p0;
        eprintln!("{name}: contact radius {contact_radius:.4} a0, peak {peak:.4} P0");
        // Measured: 1.3775 and 0.5817 P0 (compliant), 0.6973 and 1.94 P0 (stiff);
        // on 256^2 1.3758 and 0.6966.
        let error = contact_radius / published_radius - 1.0;
        assert!(error.abs() < 5e-3, "{name}: contact radius {error:+.2e}");
        match published_peak {
            Some(published) => {
                let error = peak / published - 1.0;
                assert!(error.abs() < 2e-3, "{name}: peak {error:+.2e}");
            }
            None => assert!((1.8..2.2).contains(&peak), "{name}: peak {peak} P0"),
        }
    }
}
