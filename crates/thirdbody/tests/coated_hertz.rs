//! Hertz-like contact of a rigid sphere on a coated body:
//! a coating much thinner than the contact radius gives the substrate's Hertz
//! solution, a coating much thicker gives the coating's, within 1 %, and the same
//! for stacks of three layers (on a half-space or a rigid base) (Hertz;
//! Johnson, Contact Mechanics, eq. 4.22-4.23: `a = (3 Q R / (4 E*))^(1/3)`,
//! `p0 = 3 Q / (2 pi a^2)`, `delta = a^2 / R`, `E* = E / (1 - nu^2)` for a rigid
//! sphere). The same grid solved on the homogeneous body separates the coating's
//! effect from the discretization error.

use std::f64::consts::PI;

use thirdbody::{
    solve, Body, Case, Elastic, GridSpec, Loading, Slider, SolverParams, Summary, Units,
};

struct Hertz {
    radius: f64,
    max_pressure: f64,
    approach: f64,
}

fn hertz(load: f64, material: Elastic) -> Hertz {
    let e_star = material.plane_strain_modulus();
    let a = (3.0 * load / (4.0 * e_star)).cbrt();
    Hertz {
        radius: a,
        max_pressure: 3.0 * load / (2.0 * PI * a * a),
        approach: a * a,
    }
}

fn solve_on(body: Body, load: f64, half_width: f64, cells: usize) -> Summary {
    let case = Case {
        slider: Slider::Sphere { radius: 1.0 },
        body,
        layer: None,
        loading: Loading {
            normal_load: load,
            velocity: None,
            reference_distance: None,
        },
        grid: GridSpec {
            cells: [cells, cells],
            half_width: Some([half_width, half_width]),
            centre: None,
        },
        units: Units::Dimensionless,
    };
    solve(&case, &SolverParams::default()).unwrap().summary()
}

fn relative(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

/// Compares a coated solve with Hertz for `limit` and with the homogeneous
/// solve of `limit` on the same grid.
fn check(coating: Elastic, thickness: f64, substrate: Elastic, limit: Elastic, what: &str) {
    check_body(Body::coated(coating, thickness, substrate), limit, what);
}

/// As [`check`] for any body.
fn check_body(body: Body, limit: Elastic, what: &str) {
    let load = 1e-5;
    let h = hertz(load, limit);
    let (half_width, cells) = (1.3 * h.radius, 64);
    let coated = solve_on(body, load, half_width, cells);
    let homogeneous = solve_on(Body::Homogeneous(limit), load, half_width, cells);
    // Equivalent contact radius from the contact area.
    let radius = (coated.contact_area / PI).sqrt();
    let errors = [
        ("approach", relative(coated.penetration, h.approach)),
        (
            "max pressure",
            relative(coated.max_pressure, h.max_pressure),
        ),
        ("contact radius", relative(radius, h.radius)),
    ];
    let same_grid = [
        relative(coated.penetration, homogeneous.penetration),
        relative(coated.max_pressure, homogeneous.max_pressure),
        relative(coated.contact_area, homogeneous.contact_area),
    ];
    eprintln!("{what}: vs Hertz {errors:?}; vs homogeneous on the same grid {same_grid:?}");
    for (name, e) in errors {
        assert!(e < 0.01, "{what}: {name} differs from Hertz by {e}");
    }
    for e in same_grid {
        assert!(
            e < 2e-3,
            "{what}: differs from the homogeneous solve by {e}"
        );
    }
}

#[test]
fn thin_coating_gives_the_substrate_hertz_solution() {
    let (coating, substrate) = (
        Elastic {
            young: 3.0,
            poisson: 0.3,
        },
        Elastic {
            young: 1.0,
            poisson: 0.25,
        },
    );
    let a = hertz(1e-5, substrate).radius;
    check(coating, 1e-3 * a, substrate, substrate, "thin coating");
}

#[test]
fn thick_coating_gives_the_coating_hertz_solution() {
    let (coating, substrate) = (
        Elastic {
            young: 0.3,
            poisson: 0.35,
        },
        Elastic {
            young: 1.0,
            poisson: 0.25,
        },
    );
    let a = hertz(1e-5, coating).radius;
    check(coating, 2e3 * a, substrate, coating, "thick coating");
}

fn elastic(young: f64, poisson: f64) -> Elastic {
    Elastic { young, poisson }
}

fn three_layers(thicknesses: [f64; 3], base: thirdbody::body::layered::Base) -> Body {
    use thirdbody::body::layered::{Ply, Stack};
    let materials = [elastic(0.3, 0.35), elastic(5.0, 0.2), elastic(0.05, 0.45)];
    Body::Layered(Stack {
        layers: materials
            .iter()
            .zip(thicknesses)
            .map(|(&material, thickness)| Ply {
                material,
                thickness,
            })
            .collect(),
        base,
    })
}

#[test]
fn a_stack_with_a_thick_top_layer_gives_the_top_layer_hertz_solution() {
    use thirdbody::body::layered::{Base, BaseContact};
    let top = elastic(0.3, 0.35);
    let a = hertz(1e-5, top).radius;
    for (base, name) in [
        (Base::HalfSpace(elastic(1.0, 0.25)), "half-space"),
        (Base::Rigid(BaseContact::Bonded), "bonded rigid base"),
        (
            Base::Rigid(BaseContact::Frictionless),
            "frictionless rigid base",
        ),
    ] {
        let body = three_layers([2e3 * a, 1e3 * a, 5e3 * a], base);
        check_body(body, top, &format!("three layers, thick top, {name}"));
    }
}

#[test]
fn a_stack_far_thinner_than_the_contact_gives_the_substrate_hertz_solution() {
    use thirdbody::body::layered::Base;
    let substrate = elastic(1.0, 0.25);
    let a = hertz(1e-5, substrate).radius;
    // The third layer is 20 times softer than the substrate: its compression adds
    // about h3 E2 / E3 to the approach, so the stack must be far thinner than 1e-3 a
    // (at 1e-3 a the contact area moved by 0.6 %).
    let body = three_layers([1e-5 * a, 7e-6 * a, 1.5e-5 * a], Base::HalfSpace(substrate));
    check_body(body, substrate, "three thin layers");
}
