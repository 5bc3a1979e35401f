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
