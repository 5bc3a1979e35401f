//! A coating is a stack of one layer on a half-space: the layered body must give
//! the results of the former one-coating implementation (its own Fourier solution,
//! Perriot & Barthel's surface factor and a six-coefficient potential solution for
//! the stresses, validated against published coated-contact results) to 1e-9 of the
//! peak. `tests/data/coated_reference.json` holds that implementation's results on
//! four cases on 32 x 32 cells, recorded before it was removed (the generator is
//! `examples/coated_fixture.rs` in the commit that added the file): thin stiff and
//! thick soft coatings without a layer, and a sub-cell stiff and a thick coating
//! under the paper's nonlinear layer; the pressure, approach, friction, the XZ
//! section at six depths (both sides of the interface and the coating's middle
//! included) and two rows of the surface, both interface sides and a plane below.
//!
//! The two cases under the layer were recorded with the layer's former row scheme
//! (the paper's Maxwell layer then had neither the flow's upwind correction nor its
//! leading edges located inside their cells), so their contact is no longer the
//! recorded one: for them the stresses, a property of the body alone, are computed
//! from the recorded pressure, and their contact results are not compared.

use serde_json::Value;
use thirdbody::stress::{Section, Side};
mod cases;

use thirdbody::{solve, Body, Case, Elastic, SolverParams};

fn case(ratio: f64, thickness: f64, layered: bool) -> Case {
    let coating = Elastic {
        young: ratio,
        poisson: 0.25,
    };
    let substrate = Elastic {
        young: 1.0,
        poisson: 0.3,
    };
    cases::on_fixed_window(Body::coated(coating, thickness, substrate), layered, 32)
}

fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

fn worst(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
}

#[test]
fn one_layer_stack_reproduces_the_recorded_coated_results() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/coated_reference.json"
    ))
    .unwrap();
    let reference: Value = serde_json::from_str(&text).unwrap();
    for (name, r) in reference.as_object().unwrap() {
        let c = case(
            r["young_ratio"].as_f64().unwrap(),
            r["thickness"].as_f64().unwrap(),
            r["layered"].as_bool().unwrap(),
        );
        let mut s = solve(&c, &SolverParams::default()).unwrap();
        let expected = numbers(&r["pressure"]);
        if r["layered"].as_bool().unwrap() {
            // The body's stresses under the recorded pressure (module docs).
            s.pressure = expected;
            s.contact_edges.clear();
        } else {
            let peak = expected.iter().fold(0.0f64, |m, &v| m.max(v));
            let dp = worst(&s.pressure, &expected) / peak;
            let dmu = (s.summary().friction_coefficient - r["friction"].as_f64().unwrap()).abs();
            let dd = (s.approach - r["approach"].as_f64().unwrap()).abs()
                / r["approach"].as_f64().unwrap().abs();
            eprintln!("{name}: pressure {dp:.1e} of the peak, mu {dmu:.1e}, approach {dd:.1e}");
            assert!(dp < 1e-9, "{name}: pressure off by {dp:.1e} of the peak");
            assert!(dmu < 1e-9, "{name}: friction off by {dmu:.1e}");
            assert!(dd < 1e-9, "{name}: approach off by {dd:.1e}");
        }
        let depths = numbers(&r["depths"]);
        let sections = r["sections"].as_object().unwrap();
        for (label, section) in [
            (
                "xz",
                Section::XzPlane {
                    y: 0.0,
                    depths: depths.clone(),
                },
            ),
            ("surface", Section::Plane { z: 0.0 }),
            (
                "interface_coating",
                Section::Interface {
                    index: 0,
                    side: Side::Above,
                },
            ),
            (
                "interface_substrate",
                Section::Interface {
                    index: 0,
                    side: Side::Below,
                },
            ),
            ("plane_deep", Section::Plane { z: 0.02 }),
        ] {
            let field = s.stresses(&section).unwrap();
            let recorded: Vec<Vec<f64>> = sections[label]
                .as_array()
                .unwrap()
                .iter()
                .map(numbers)
                .collect();
            let peak = recorded
                .iter()
                .flatten()
                .fold(0.0f64, |m, &v| m.max(v.abs()));
            let mut err = 0.0f64;
            for (c, rec) in recorded.iter().enumerate() {
                let got: Vec<f64> = if label == "xz" {
                    field.components[c].clone()
                } else {
                    field.components[c][16 * 32..18 * 32].to_vec()
                };
                err = err.max(worst(&got, rec) / peak);
            }
            eprintln!("{name} {label}: stresses {err:.1e} of the peak");
            assert!(
                err < 1e-9,
                "{name} {label}: stresses off by {err:.1e} of the peak"
            );
        }
    }
}
