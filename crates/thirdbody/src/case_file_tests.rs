//! Tests of the case-file parser: every schema branch against a hand-built
//! [`Case`], and every bad input against an error that names the field and the
//! allowed range in one line.

use super::*;
use crate::test_cases::HERTZ;

/// The paper's Fig. 3 case, as the case file states it.
const FIG3: &str = r#"
[slider]
shape = "sphere"
radius = 1.0

[substrate]
young = 1.0
poisson = 0.3

[layer]
compliance = 0.02
relaxation_time = 1.0
law = "sigmoid"
delta = 0.5
p0 = 0.001
integration = "exact"

[loading]
normal_load = 5e-6
velocity = 1e-3

[grid]
cells = [128, 128]
"#;

fn no_map(_: &str, _: f64) -> Result<HeightMap> {
    panic!("no height map expected")
}

fn parse(text: &str) -> Result<CaseFile> {
    parse_case_file(text, &mut no_map)
}

/// Replaces the first line starting with `key =` (after trimming) by `new`.
fn with(text: &str, key: &str, new: &str) -> String {
    let mut done = false;
    text.lines()
        .map(|l| {
            if !done && l.trim_start().starts_with(&format!("{key} =")) {
                done = true;
                new.to_string()
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// Inserts `line` right after the header `[section]`.
fn add(text: &str, section: &str, line: &str) -> String {
    text.replacen(
        &format!("[{section}]\n"),
        &format!("[{section}]\n{line}\n"),
        1,
    )
}

/// The error message, checked to be a single line containing every `parts`.
fn error_naming(text: &str, parts: &[&str]) -> Error {
    let e = parse(text).expect_err("this case must be rejected");
    let msg = e.to_string();
    assert!(!msg.contains('\n'), "multi-line message: {msg}");
    for p in parts {
        assert!(msg.contains(p), "{msg:?} does not mention {p:?}");
    }
    e
}

#[test]
fn paper_fig3_parses_into_the_hand_built_case() {
    let file = parse(FIG3).unwrap();
    let expected = Case {
        slider: Slider::Sphere { radius: 1.0 },
        body: Body::Homogeneous(Elastic {
            young: 1.0,
            poisson: 0.3,
        }),
        layer: Some(Layer::maxwell(
            0.02,
            1.0,
            ComplianceLaw::Sigmoid {
                delta: 0.5,
                p0: 0.001,
            },
            Integration::Exact,
        )),
        loading: Loading {
            normal_load: 5e-6,
            velocity: Some(1e-3),
            reference_distance: None,
        },
        grid: GridSpec {
            cells: [128, 128],
            half_width: None,
            centre: None,
        },
        units: Units::Dimensionless,
    };
    assert_eq!(file.case, expected);
    assert_eq!(file.solver, SolverParams::default());
}

#[test]
fn shipped_examples_parse() {
    // examples/paper_fig3.toml is this text exactly.
    let fig3 = include_str!("../../../examples/paper_fig3.toml");
    assert_eq!(fig3.trim(), FIG3.trim());
    let hertz = parse(include_str!("../../../examples/hertz.toml")).unwrap();
    assert!(hertz.case.layer.is_none());
    assert_eq!(hertz.case.grid.cells, [128, 128]);
    let ellipsoid = parse(include_str!("../../../examples/ellipsoid_si.toml")).unwrap();
    assert_eq!(ellipsoid.case.units, Units::Si);
    assert!(matches!(ellipsoid.case.slider, Slider::Ellipsoid { .. }));
}

#[test]
fn no_layer_needs_no_velocity_and_accepts_integers_for_reals() {
    let text = with(HERTZ, "young", "young = 2");
    let file = parse(&text).unwrap();
    assert!(file.case.layer.is_none());
    assert_eq!(file.case.loading.velocity, None);
    assert_eq!(file.case.body.half_space().unwrap().young, 2.0);
}

#[test]
fn linear_layer_defaults_to_exact_integration_and_accepts_infinite_velocity() {
    let text = HERTZ.replace(
        "[loading]\nnormal_load = 5e-6",
        "[layer]\ncompliance = 0.1\nrelaxation_time = 2.0\n[loading]\nnormal_load = 5e-6\nvelocity = inf",
    );
    let file = parse(&text).unwrap();
    let layer = file.case.layer.unwrap();
    assert_eq!(layer.law, ComplianceLaw::Linear);
    assert_eq!(layer.integration, Integration::Exact);
    assert_eq!(
        layer.rheology,
        Rheology::Maxwell {
            compliance: 0.1,
            relaxation_time: 2.0
        }
    );
    assert_eq!(file.case.loading.velocity, Some(f64::INFINITY));
}

#[test]
fn secant_integration_and_table_law() {
    let text = FIG3
        .replace(
            "compliance = 0.02\n",
            "pressures = [0.0, 0.01, 0.02]\ncompliances = [0.02, 0.015, 0.01]\n",
        )
        .replace(
            "law = \"sigmoid\"\ndelta = 0.5\np0 = 0.001\n",
            "law = \"table\"\n",
        )
        .replace("\"exact\"", "\"secant\"");
    let layer = parse(&text).unwrap().case.layer.unwrap();
    assert_eq!(layer.integration, Integration::Secant);
    let ComplianceLaw::Table(t) = &layer.law else {
        panic!("{:?}", layer.law)
    };
    assert_eq!(t.pressures(), &[0.0, 0.01, 0.02]);
    assert_eq!(t.compliances(), &[0.02, 0.015, 0.01]);
    // The table's first compliance is C0.
    assert_eq!(layer.reference_compliance(), 0.02);
}

#[test]
fn ellipsoid_coating_units_window_and_solver_sections() {
    let text = r#"
units = "si"
[slider]
shape = "ellipsoid"
radius_x = 0.02
radius_y = 0.01
[substrate]
young = 210e9
poisson = 0.3
[coating]
young = 70e9
poisson = 0.25
thickness = 1e-5
[loading]
normal_load = 10.0
[grid]
cells = [64, 32]
half_width = [2e-4, 1e-4]
centre = [1e-5, 0.0]
[solver]
tolerance = 1e-8
max_iterations = 50
max_windows = 2
"#;
    let file = parse(text).unwrap();
    let c = &file.case;
    assert_eq!(c.units, Units::Si);
    assert_eq!(
        c.slider,
        Slider::Ellipsoid {
            radius_x: 0.02,
            radius_y: 0.01
        }
    );
    assert_eq!(
        c.body,
        Body::coated(
            Elastic {
                young: 70e9,
                poisson: 0.25
            },
            1e-5,
            Elastic {
                young: 210e9,
                poisson: 0.3
            },
        )
    );
    assert_eq!(c.grid.half_width, Some([2e-4, 1e-4]));
    assert_eq!(c.grid.centre, Some([1e-5, 0.0]));
    assert_eq!(file.solver.tolerance, 1e-8);
    assert_eq!(file.solver.max_iterations, 50);
    assert_eq!(file.solver.max_windows, 2);
}

fn height_map_case(file: &str) -> String {
    HERTZ.replace(
        "shape = \"sphere\"\nradius = 1.0",
        &format!("shape = \"height_map\"\nfile = \"{file}\"\ncell_size = 0.25"),
    )
}

#[test]
fn height_map_is_loaded_by_the_callback() {
    let mut seen = Vec::new();
    let mut load = |file: &str, cell: f64| {
        seen.push((file.to_string(), cell));
        Ok(HeightMap {
            nx: 3,
            ny: 2,
            cell_size: cell,
            heights: vec![1.0, 0.0, 1.0, 1.5, 0.5, 1.5],
        })
    };
    let file = parse_case_file(&height_map_case("maps/bump.csv"), &mut load).unwrap();
    assert_eq!(seen, vec![("maps/bump.csv".to_string(), 0.25)]);
    let Slider::HeightMap(m) = &file.case.slider else {
        panic!()
    };
    assert_eq!((m.nx, m.ny, m.cell_size), (3, 2, 0.25));
}

#[test]
fn height_map_with_nan_is_named() {
    let mut load = |_: &str, cell: f64| {
        Ok(HeightMap {
            nx: 2,
            ny: 2,
            cell_size: cell,
            heights: vec![0.0, 1.0, f64::NAN, 1.0],
        })
    };
    let e = parse_case_file(&height_map_case("m.csv"), &mut load).unwrap_err();
    let msg = e.to_string();
    assert!(msg.contains("slider.file") && msg.contains("NaN"), "{msg}");
    assert!(msg.contains("finite heights"), "{msg}");
}

#[test]
fn a_loader_error_is_passed_through() {
    let mut load = |file: &str, _: f64| {
        Err(Error::invalid(
            "slider.file",
            file,
            "a readable CSV or NPY file",
        ))
    };
    let e = parse_case_file(&height_map_case("gone.npy"), &mut load).unwrap_err();
    assert!(e.to_string().contains("gone.npy"), "{e}");
}

#[test]
fn unknown_key_gives_its_line_section_and_name() {
    let text = add(FIG3, "slider", "radiuss = 2.0");
    let e = error_naming(&text, &["line 3 (slider.radiuss)", "radiuss"]);
    assert!(matches!(e, Error::Parse(_)), "{e:?}");
    // Unknown section.
    let e = error_naming(&format!("{FIG3}\n[lubricant]\nx = 1\n"), &["lubricant"]);
    assert!(matches!(e, Error::Parse(_)), "{e:?}");
}

#[test]
fn wrong_type_and_bad_syntax_are_one_line_parse_errors() {
    let text = with(FIG3, "young", "young = \"steel\"");
    let e = error_naming(&text, &["line 7 (substrate.young)", "string"]);
    assert!(matches!(e, Error::Parse(_)), "{e:?}");
    error_naming(&with(FIG3, "law", "law = \"cubic\""), &["cubic", "sigmoid"]);
    error_naming(&with(FIG3, "poisson", "poisson = "), &["line 8"]);
    error_naming(
        &with(FIG3, "cells", "cells = [128]"),
        &[
            "grid.cells = [128]",
            "exactly two values [x, y] for a point contact",
        ],
    );
    error_naming(
        &with(FIG3, "cells", "cells = 128"),
        &["grid.cells = 128", "exactly two values", "cylinder"],
    );
    // A third element is not dropped silently.
    error_naming(
        &with(FIG3, "cells", "cells = [128, 128, 128]"),
        &["grid.cells = [128, 128, 128]", "exactly two"],
    );
    error_naming(
        &add(FIG3, "grid", "half_width = [0.06, 0.06, 5.0]"),
        &["grid.half_width = [0.06, 0.06, 5]", "exactly two"],
    );
    error_naming(&with(FIG3, "cells", "cells = \"many\""), &["line 23"]);
}

/// A line contact (a cylinder) takes one value per grid key, a point contact's
/// pairs are refused with the key named, and its datum is a line contact's only.
#[test]
fn a_line_contact_has_one_axis() {
    let line = "[slider]\nshape = \"cylinder\"\nradius = 2.0\n[substrate]\nyoung = 1.0\n\
                poisson = 0.3\n[loading]\nnormal_load = 1e-3\n[grid]\ncells = 256\n";
    let case = parse(line).unwrap().case;
    assert_eq!(case.grid.cells, [256, 1]);
    assert_eq!(case.slider, Slider::Cylinder { radius: 2.0 });
    assert_eq!(case.geometry(), crate::grid::Geometry::Line { datum: 2.0 });
    let fixed = parse(&format!("{line}half_width = 0.1\ncentre = [0.02]\n"))
        .unwrap()
        .case;
    assert_eq!(fixed.grid.half_width, Some([0.1, 0.0]));
    assert_eq!(fixed.grid.centre, Some([0.02, 0.0]));
    let datum = add(line, "loading", "reference_distance = 7.5");
    let with_datum = parse(&datum).unwrap().case;
    assert_eq!(
        with_datum.geometry(),
        crate::grid::Geometry::Line { datum: 7.5 }
    );
    // The datum is part of the case's identity; an unset one leaves the debug form
    // (and the hash of every point contact) as it was.
    assert_ne!(
        crate::provenance::case_hash(&with_datum),
        crate::provenance::case_hash(&case)
    );
    assert!(!format!("{:?}", case.loading).contains("reference_distance"));
    error_naming(
        &with(line, "cells", "cells = [256, 256]"),
        &[
            "grid.cells = [256, 256]",
            "one value along x for a line contact",
        ],
    );
    error_naming(
        &format!("{line}half_width = [0.1, 0.1]\n"),
        &["grid.half_width = [0.1, 0.1]", "one value along x"],
    );
    error_naming(&with(line, "cells", "cells = 4"), &["grid.cells", "8 to"]);
    error_naming(
        &add(line, "loading", "reference_distance = -1.0"),
        &["loading.reference_distance", "> 0"],
    );
    error_naming(
        &add(FIG3, "loading", "reference_distance = 1.0"),
        &["loading.reference_distance", "line contact's datum"],
    );
    error_naming(
        &add(line, "slider", "radius_x = 1.0"),
        &["slider.radius_x", "only a radius"],
    );
}

#[test]
fn missing_sections_are_named() {
    for name in ["slider", "substrate", "loading", "grid"] {
        let text = FIG3.replace(&format!("[{name}]"), "[dummy]");
        // `[dummy]` is itself unknown: the parse error names it.
        error_naming(&text, &["dummy"]);
        let start = FIG3.find(&format!("[{name}]")).unwrap();
        let end = FIG3[start + 1..]
            .find("\n[")
            .map_or(FIG3.len(), |k| start + 1 + k);
        let text = format!("{}{}", &FIG3[..start], &FIG3[end..]);
        let e = error_naming(&text, &[&format!("[{name}]")]);
        assert!(matches!(e, Error::MissingField { .. }), "{e:?}");
    }
}

#[test]
fn out_of_range_values_name_the_field_and_the_range() {
    let cases: [(&str, &str, &[&str]); 11] = [
        ("poisson", "poisson = 0.5", &["substrate.poisson", "< 0.5"]),
        ("poisson", "poisson = 0.7", &["substrate.poisson", "< 0.5"]),
        ("young", "young = 0.0", &["substrate.young", "> 0"]),
        ("young", "young = -3.0", &["substrate.young", "> 0"]),
        (
            "normal_load",
            "normal_load = 0.0",
            &["loading.normal_load", "> 0"],
        ),
        (
            "normal_load",
            "normal_load = -1e-6",
            &["loading.normal_load", "> 0"],
        ),
        ("delta", "delta = 1.5", &["layer.delta", "0 <= delta <= 1"]),
        ("delta", "delta = -0.1", &["layer.delta", "0 <= delta <= 1"]),
        ("p0", "p0 = 0.0", &["layer.p0", "> 0"]),
        (
            "cells",
            "cells = [7, 128]",
            &["grid.cells[0]", "at least 8"],
        ),
        (
            "cells",
            "cells = [128, 4]",
            &["grid.cells[1]", "at least 8"],
        ),
    ];
    for (key, line, parts) in cases {
        let e = error_naming(&with(FIG3, key, line), parts);
        assert!(matches!(e, Error::InvalidValue { .. }), "{e:?}");
    }
    error_naming(&with(FIG3, "p0", "p0 = nan"), &["layer.p0", "> 0"]);
    error_naming(
        &with(FIG3, "compliance", "compliance = -0.02"),
        &["layer.compliance", "> 0"],
    );
    error_naming(
        &with(FIG3, "velocity", "velocity = 0.0"),
        &["loading.velocity", "> 0"],
    );
    error_naming(
        &format!("{FIG3}\n[solver]\ntolerance = 2.0\n"),
        &["solver.tolerance", "0 < tolerance < 1"],
    );
}

#[test]
fn fields_the_options_do_not_use_are_errors() {
    let linear = with(FIG3, "law", "law = \"linear\"");
    let e = error_naming(&linear, &["layer.delta", "sigmoid"]);
    assert!(matches!(e, Error::UnusedField { .. }), "{e:?}");
    let e = error_naming(&add(FIG3, "slider", "radius_x = 1.0"), &["slider.radius_x"]);
    assert!(matches!(e, Error::UnusedField { .. }), "{e:?}");
    let ellipsoid = with(FIG3, "shape", "shape = \"ellipsoid\"");
    error_naming(&ellipsoid, &["slider.radius", "radius_x"]);
    let table = with(FIG3, "law", "law = \"table\"");
    error_naming(&table, &["layer.compliance", "table"]);
    error_naming(
        &add(FIG3, "layer", "pressures = [0.0, 1.0]"),
        &["layer.pressures", "table"],
    );
}

#[test]
fn fields_the_options_need_are_named_when_missing() {
    let e = error_naming(
        &with(FIG3, "delta", ""),
        &["layer.delta", "0 <= delta <= 1"],
    );
    assert!(matches!(e, Error::MissingField { .. }), "{e:?}");
    error_naming(&with(FIG3, "velocity", ""), &["loading.velocity"]);
    error_naming(&with(FIG3, "radius", ""), &["slider.radius", "> 0"]);
    error_naming(
        &with(FIG3, "relaxation_time", ""),
        &["layer.relaxation_time"],
    );
    error_naming(&with(FIG3, "cells", ""), &["grid.cells", ">= 8"]);
    error_naming(&with(FIG3, "shape", ""), &["slider.shape", "ellipsoid"]);
    let coated = format!("{FIG3}\n[coating]\nyoung = 2.0\npoisson = 0.3\n");
    error_naming(&coated, &["coating.thickness", "> 0"]);
    let bad_table = with(FIG3, "law", "law = \"table\"")
        .replace("compliance = 0.02\n", "")
        .replace("delta = 0.5\np0 = 0.001\n", "pressures = [0.0, 1.0]\n");
    error_naming(&bad_table, &["layer.compliances"]);
}

/// HERTZ with a coating.
fn coated() -> String {
    format!("{HERTZ}\n[coating]\nyoung = 3.0\npoisson = 0.3\nthickness = 0.01\n")
}

#[test]
fn no_stress_section_means_no_stresses_and_an_empty_one_the_defaults() {
    assert_eq!(parse(HERTZ).unwrap().stress, None);
    let file = parse(&format!("{HERTZ}\n[stress]\n")).unwrap();
    let request = file.stress.unwrap();
    assert_eq!(request, StressRequest::default());
    let body = file.case.body;
    assert_eq!(
        request.kinds(&body),
        [SectionKind::Xz, SectionKind::Surface]
    );
    // A coated body adds both sides of the interface by default.
    let file = parse(&format!("{}\n[stress]\n", coated())).unwrap();
    assert_eq!(
        file.stress.unwrap().kinds(&file.case.body),
        [
            SectionKind::Xz,
            SectionKind::Surface,
            SectionKind::Interface
        ]
    );
}

#[test]
fn stress_section_keys_are_read() {
    let text = format!(
        "{}\n[stress]\nsections = [\"block\", \"interface\", \"xz\"]\ny = 0.01\n\
         max_depth = 0.2\ndepth_points = 9\nplanes = [0.0, 0.05]\n",
        coated()
    );
    let request = parse(&text).unwrap().stress.unwrap();
    assert_eq!(
        request,
        StressRequest {
            sections: Some(vec![
                SectionKind::Block,
                SectionKind::Interface,
                SectionKind::Xz
            ]),
            y: 0.01,
            max_depth: Some(0.2),
            depth_points: 9,
            planes: vec![0.0, 0.05],
        }
    );
    // Evenly spaced from the surface to max_depth, both included.
    let d = request.depths(1.0);
    assert_eq!(d.len(), 9);
    assert_eq!((d[0], d[8]), (0.0, 0.2));
    assert!((d[1] - 0.025).abs() < 1e-15);
}

#[test]
fn bad_stress_requests_name_the_key() {
    let stress = |lines: &str| format!("{HERTZ}\n[stress]\n{lines}\n");
    for (lines, parts) in [
        (
            "depth_points = 0",
            &["stress.depth_points", "at least 2"][..],
        ),
        ("depth_points = 1", &["stress.depth_points", "at least 2"]),
        ("max_depth = -0.1", &["stress.max_depth", "> 0"]),
        ("max_depth = 0.0", &["stress.max_depth", "> 0"]),
        ("max_depth = nan", &["stress.max_depth", "finite"]),
        ("planes = [0.1, -0.2]", &["stress.planes[1]", ">= 0"]),
        ("y = inf", &["stress.y", "finite"]),
        (
            "sections = [\"xy\"]",
            &["stress.sections", "\"xy\"", "\"block\""],
        ),
        ("sections = []", &["stress.sections", "at least one"]),
        ("sections = [\"xz\", \"xz\"]", &["stress.sections", "once"]),
        (
            "sections = [\"interface\"]",
            &["stress.sections", "interface", "[coating]"],
        ),
        ("depth = 3", &["line", "stress.depth", "unknown field"]),
        ("depth_points = -3", &["stress.depth_points"]),
    ] {
        error_naming(&stress(lines), parts);
    }
}

/// FIG3 with its `[layer]` section replaced by `layer` (lines of keys).
fn with_layer(layer: &str) -> String {
    let start = FIG3.find("[layer]").unwrap();
    let end = FIG3.find("[loading]").unwrap();
    format!("{}[layer]\n{layer}\n\n{}", &FIG3[..start], &FIG3[end..])
}

fn layer_of(text: &str) -> Layer {
    parse(text).unwrap().case.layer.unwrap()
}

#[test]
fn every_rheology_preset_parses_into_its_parameters() {
    let kv = layer_of(&with_layer(
        "rheology = \"kelvin_voigt\"\ncompliance = 0.02\nretardation_time = 3.0",
    ));
    assert_eq!(
        kv.rheology,
        Rheology::KelvinVoigt {
            compliance: 0.02,
            retardation_time: 3.0
        }
    );
    let z = layer_of(&with_layer(
        "rheology = \"zener\"\nglassy_compliance = 0.01\ncompliance = 0.02\n\
         retardation_time = 3.0\nlaw = \"sigmoid\"\ndelta = 0.5\np0 = 0.001",
    ));
    assert_eq!(
        z.rheology,
        Rheology::Zener {
            glassy_compliance: 0.01,
            compliance: 0.02,
            retardation_time: 3.0
        }
    );
    assert_eq!(
        z.law,
        ComplianceLaw::Sigmoid {
            delta: 0.5,
            p0: 0.001
        }
    );
    let b = layer_of(&with_layer(
        "rheology = \"burgers\"\nglassy_compliance = 0.01\nrelaxation_time = 5\n\
         compliance = 0.02\nretardation_time = 3.0",
    ));
    assert_eq!(b.rheology.creep_form().flow.unwrap().time, 5.0);
    let p = layer_of(&with_layer(
        "rheology = \"prony\"\nglassy_compliance = 0.0\nbranch_compliances = [0.01, 0.02]\n\
         branch_times = [0.1, 10]\nviscosity = 50.0",
    ));
    let form = p.rheology.creep_form();
    assert_eq!(form.branches.len(), 2);
    assert_eq!(form.branches[1].time, 10.0);
    assert_eq!(form.flow.unwrap().time, 50.0);
    let r = layer_of(&with_layer(
        "rheology = \"relaxation_prony\"\nequilibrium_stiffness = 0.0\n\
         branch_stiffnesses = [100.0]\nbranch_times = [2.0]",
    ));
    // One Maxwell branch and no equilibrium stiffness: a Maxwell fluid, C_g = 1/K,
    // eta = K rho.
    let form = r.rheology.creep_form();
    assert!(form.branches.is_empty());
    assert!((form.glassy - 0.01).abs() < 1e-15);
    assert!((form.flow.unwrap().time - 200.0).abs() < 1e-12);
    let f = layer_of(&with_layer(
        "rheology = \"fractional_zener\"\nglassy_compliance = 0.01\ncompliance = 0.02\n\
         retardation_time = 3.0\norder = 0.5",
    ));
    // Without branch_count the order chooses: for alpha = 0.5 the span holding all
    // but 1e-4 of the spectrum is 4 ln(4e4 / pi) = 37.8 in ln(time), the spacing
    // min(1, pi / 2) = 1, so 38 branches, made odd: 39.
    assert_eq!(
        f.rheology,
        Rheology::FractionalZener {
            glassy_compliance: 0.01,
            compliance: 0.02,
            retardation_time: 3.0,
            order: 0.5,
            branch_count: None
        }
    );
    assert_eq!(f.rheology.creep_form().branches.len(), 39);
    // Maxwell is the default and the table law gives a Kelvin–Voigt layer its
    // compliance.
    let t = layer_of(&with_layer(
        "rheology = \"kelvin_voigt\"\nretardation_time = 1.0\nlaw = \"table\"\n\
         pressures = [0.0, 0.01]\ncompliances = [0.03, 0.02]",
    ));
    assert_eq!(t.reference_compliance(), 0.03);
    assert_eq!(
        t.rheology,
        Rheology::KelvinVoigt {
            compliance: 0.03,
            retardation_time: 1.0
        }
    );
}

#[test]
fn bad_rheology_parameters_are_errors_naming_the_key() {
    // A preset given a key it does not use.
    let e = error_naming(
        &with_layer("rheology = \"kelvin_voigt\"\ncompliance = 0.02\nretardation_time = 1\nrelaxation_time = 1"),
        &["layer.relaxation_time", "kelvin_voigt", "retardation_time"],
    );
    assert!(matches!(e, Error::UnusedField { .. }), "{e:?}");
    error_naming(
        &with_layer("compliance = 0.02\nrelaxation_time = 1\nglassy_compliance = 0.01"),
        &["layer.glassy_compliance", "maxwell"],
    );
    // Missing keys.
    error_naming(
        &with_layer("rheology = \"zener\"\ncompliance = 0.02\nretardation_time = 1"),
        &["layer.glassy_compliance"],
    );
    error_naming(
        &with_layer("rheology = \"prony\"\nglassy_compliance = 0.01\nbranch_compliances = [0.01]"),
        &["layer.branch_times"],
    );
    // Zero or negative times, empty or mismatched lists.
    error_naming(
        &with_layer("rheology = \"kelvin_voigt\"\ncompliance = 0.02\nretardation_time = 0"),
        &["layer.retardation_time", "> 0"],
    );
    error_naming(
        &with_layer(
            "rheology = \"prony\"\nglassy_compliance = 0.01\nbranch_compliances = [0.01, 0.02]\n\
             branch_times = [1.0, -2.0]",
        ),
        &["layer.branch_times[1]", "> 0"],
    );
    error_naming(
        &with_layer(
            "rheology = \"prony\"\nglassy_compliance = 0.01\nbranch_compliances = []\n\
             branch_times = []",
        ),
        &["layer.branch_compliances", "from 1 to"],
    );
    error_naming(
        &with_layer(
            "rheology = \"prony\"\nglassy_compliance = 0.01\nbranch_compliances = [0.01]\n\
             branch_times = [1.0, 2.0]",
        ),
        &["layer.branch_times", "one time per entry"],
    );
    error_naming(
        &with_layer(
            "rheology = \"prony\"\nglassy_compliance = -0.01\nbranch_compliances = [0.01]\n\
             branch_times = [1.0]",
        ),
        &["layer.glassy_compliance", ">= 0"],
    );
    error_naming(
        &with_layer(
            "rheology = \"fractional_zener\"\nglassy_compliance = 0.01\ncompliance = 0.02\n\
             retardation_time = 3.0\norder = 1.5",
        ),
        &["layer.order", "0 < order <= 1"],
    );
    error_naming(
        &with_layer(
            "rheology = \"fractional_zener\"\nglassy_compliance = 0.01\ncompliance = 0.02\n\
             retardation_time = 3.0\norder = 0.5\nbranch_count = 1",
        ),
        &["layer.branch_count", "from 2"],
    );
    error_naming(
        &with_layer("rheology = \"plastic\"\ncompliance = 0.02"),
        &["rheology", "kelvin_voigt"],
    );
}

#[test]
fn a_box_spectrum_parses_and_rejects_the_keys_it_does_not_take() {
    let b = layer_of(&with_layer(
        "rheology = \"box_spectrum\"\nglassy_compliance = 0.01\ncompliance = 0.02\n\
         shortest_time = 0.1\nlongest_time = 100",
    ));
    assert_eq!(
        b.rheology,
        Rheology::BoxSpectrum {
            glassy_compliance: 0.01,
            compliance: 0.02,
            shortest_time: 0.1,
            longest_time: 100.0
        }
    );
    let e = error_naming(
        &with_layer(
            "rheology = \"box_spectrum\"\nglassy_compliance = 0.01\ncompliance = 0.02\n\
             shortest_time = 0.1\nlongest_time = 100\nretardation_time = 1",
        ),
        &[
            "layer.retardation_time",
            "box_spectrum",
            "shortest_time, longest_time",
        ],
    );
    assert!(matches!(e, Error::UnusedField { .. }), "{e:?}");
    error_naming(
        &with_layer(
            "rheology = \"box_spectrum\"\nglassy_compliance = 0.01\ncompliance = 0.02\n\
             shortest_time = 0.1",
        ),
        &["layer.longest_time", "box_spectrum"],
    );
    error_naming(
        &with_layer(
            "rheology = \"box_spectrum\"\nglassy_compliance = 0.01\ncompliance = 0.02\n\
             shortest_time = 10\nlongest_time = 1",
        ),
        &["layer.longest_time", "shortest_time <= longest_time"],
    );
    // Another preset's key is unused for a Zener layer, and a key of no preset is
    // unknown at its line.
    error_naming(
        &with_layer(
            "rheology = \"zener\"\nglassy_compliance = 0.01\ncompliance = 0.02\n\
             retardation_time = 1\nlongest_time = 3",
        ),
        &["layer.longest_time", "zener"],
    );
    let e = error_naming(
        &with_layer("rheology = \"zener\"\nglassy_compliance = 0.01\nlongest_tme = 3"),
        &[
            "(layer.longest_tme)",
            "unknown field",
            "`longest_time`",
            "`integration`",
        ],
    );
    assert!(matches!(e, Error::Parse(_)), "{e:?}");
}

/// Hertz's case with its `[substrate]` replaced by `body`.
fn with_body(body: &str) -> String {
    let substrate = "[substrate]\nyoung = 1.0\npoisson = 0.3\n";
    assert!(HERTZ.contains(substrate), "the shared case changed");
    HERTZ.replace(substrate, body)
}

const TWO_LAYERS: &str = "[[body.layers]]\nyoung = 3.0\npoisson = 0.25\nthickness = 0.01\n\
                          [[body.layers]]\nyoung = 0.5\npoisson = 0.45\nthickness = 0.02\n";

#[test]
fn stacks_parse_on_a_half_space_and_on_a_rigid_base() {
    use crate::body::layered::{Base, BaseContact, Ply, Stack};
    let layers = vec![
        Ply {
            material: Elastic {
                young: 3.0,
                poisson: 0.25,
            },
            thickness: 0.01,
        },
        Ply {
            material: Elastic {
                young: 0.5,
                poisson: 0.45,
            },
            thickness: 0.02,
        },
    ];
    let on_half_space = parse(&with_body(&format!(
        "[substrate]\nyoung = 1.0\npoisson = 0.3\n{TWO_LAYERS}"
    )))
    .unwrap();
    assert_eq!(
        on_half_space.case.body,
        Body::Layered(Stack {
            layers: layers.clone(),
            base: Base::HalfSpace(Elastic {
                young: 1.0,
                poisson: 0.3
            }),
        })
    );
    for (word, contact) in [
        ("bonded", BaseContact::Bonded),
        ("frictionless", BaseContact::Frictionless),
    ] {
        let rigid = parse(&with_body(&format!(
            "[body]\nbase = \"rigid\"\nbonding = \"{word}\"\n{TWO_LAYERS}"
        )))
        .unwrap();
        assert_eq!(
            rigid.case.body,
            Body::Layered(Stack {
                layers: layers.clone(),
                base: Base::Rigid(contact),
            })
        );
    }
    for example in [
        include_str!("../../../examples/three_layer_coating.toml"),
        include_str!("../../../examples/polymer_liner_rigid.toml"),
    ] {
        assert!(matches!(
            parse(example).unwrap().case.body,
            Body::Layered(_)
        ));
    }
}

#[test]
fn bad_stacks_name_the_field_in_one_line() {
    let substrate = "[substrate]\nyoung = 1.0\npoisson = 0.3\n";
    let rigid = "[body]\nbase = \"rigid\"\nbonding = \"bonded\"\n";
    for (body, parts) in [
        // No layers.
        (
            "[body]\nbase = \"rigid\"\nbonding = \"bonded\"\n".to_string(),
            &["body.layers", "at least one"][..],
        ),
        (format!("{substrate}[body]\n"), &["body.layers"][..]),
        // A non-positive thickness, a missing one, nu out of range, a bad modulus.
        (
            format!(
                "{rigid}{}",
                TWO_LAYERS.replace("thickness = 0.02", "thickness = 0")
            ),
            &["body.layers[1].thickness", "> 0"][..],
        ),
        (
            format!("{rigid}{}", TWO_LAYERS.replace("thickness = 0.02\n", "")),
            &["body.layers[1].thickness"][..],
        ),
        (
            format!(
                "{rigid}{}",
                TWO_LAYERS.replace("poisson = 0.45", "poisson = 0.5")
            ),
            &["body.layers[1].poisson", "poisson < 0.5"][..],
        ),
        (
            format!(
                "{rigid}{}",
                TWO_LAYERS.replace("young = 3.0", "young = -3.0")
            ),
            &["body.layers[0].young"][..],
        ),
        // A rigid base needs its bonding and has no substrate; a half-space has no
        // bonding; a [coating] is not given alongside [[body.layers]].
        (
            format!("[body]\nbase = \"rigid\"\n{TWO_LAYERS}"),
            &["body.bonding", "bonded", "frictionless"][..],
        ),
        (
            format!("{substrate}{rigid}{TWO_LAYERS}"),
            &["substrate", "rigid base"][..],
        ),
        (
            format!("{substrate}[body]\nbonding = \"bonded\"\n{TWO_LAYERS}"),
            &["body.bonding"][..],
        ),
        (
            format!(
                "{substrate}[coating]\nyoung = 3.0\npoisson = 0.3\nthickness = 0.01\n{TWO_LAYERS}"
            ),
            &["coating", "[[body.layers]]"][..],
        ),
        // A base that is not a base.
        (
            format!("[body]\nbase = \"granite\"\nbonding = \"bonded\"\n{TWO_LAYERS}"),
            &["base"][..],
        ),
        // A rigid layer (an infinite modulus) on a rigid base.
        (
            format!(
                "{rigid}{}",
                TWO_LAYERS.replace("young = 3.0", "young = inf")
            ),
            &["body.layers[0].young", "finite"][..],
        ),
    ] {
        error_naming(&with_body(&body), parts);
    }
    // A coating keeps its own names.
    error_naming(
        &with_body(&format!(
            "{substrate}[coating]\nyoung = 3.0\npoisson = 0.3\nthickness = 0\n"
        )),
        &["coating.thickness"],
    );
}

/// A Zener substrate under the sphere of [`HERTZ`].
const ZENER: &str = "[slider]\nshape = \"sphere\"\nradius = 1.0\n[substrate]\n\
                     rheology = \"zener\"\nglassy_modulus = 10.0\nrelaxed_modulus = 1.0\n\
                     relaxation_time = 0.5\npoisson = 0.3\n[loading]\nnormal_load = 5e-6\n\
                     velocity = 0.01\n[grid]\ncells = [32, 32]\n";

#[test]
fn viscoelastic_substrates_parse_into_their_rheologies() {
    use crate::body::{SolidRheology, ViscoelasticHalfSpace};
    let zener = |text: &str| parse(text).unwrap().case.body;
    assert_eq!(
        zener(ZENER),
        Body::Viscoelastic(ViscoelasticHalfSpace {
            rheology: SolidRheology::Zener {
                glassy_modulus: 10.0,
                relaxed_modulus: 1.0,
                relaxation_time: 0.5,
            },
            poisson: 0.3,
        })
    );
    let fractional = with(ZENER, "rheology", "rheology = \"fractional_zener\"");
    let fractional = add(&fractional, "substrate", "order = 0.4\nbranch_count = 21");
    assert_eq!(
        zener(&fractional),
        Body::Viscoelastic(ViscoelasticHalfSpace {
            rheology: SolidRheology::FractionalZener {
                glassy_modulus: 10.0,
                relaxed_modulus: 1.0,
                relaxation_time: 0.5,
                order: 0.4,
                branch_count: Some(21),
            },
            poisson: 0.3,
        })
    );
    let prony = "[slider]\nshape = \"sphere\"\nradius = 1.0\n[substrate]\nrheology = \"prony\"\n\
                 glassy_compliance = 0.1\nbranch_compliances = [0.5, 0.4]\n\
                 branch_times = [0.1, 10]\npoisson = 0.45\n[loading]\nnormal_load = 5e-6\n\
                 velocity = 0.01\n[grid]\ncells = [32, 32]\n";
    assert_eq!(
        zener(prony),
        Body::Viscoelastic(ViscoelasticHalfSpace {
            rheology: SolidRheology::Prony {
                glassy_compliance: 0.1,
                branch_compliances: vec![0.5, 0.4],
                branch_times: vec![0.1, 10.0],
            },
            poisson: 0.45,
        })
    );
    let relaxation = prony
        .replace("\"prony\"", "\"relaxation_prony\"")
        .replace("glassy_compliance = 0.1", "equilibrium_modulus = 1.0")
        .replace("branch_compliances", "branch_moduli");
    assert_eq!(
        zener(&relaxation),
        Body::Viscoelastic(ViscoelasticHalfSpace {
            rheology: SolidRheology::RelaxationProny {
                equilibrium_modulus: 1.0,
                branch_moduli: vec![0.5, 0.4],
                branch_times: vec![0.1, 10.0],
            },
            poisson: 0.45,
        })
    );
    // rheology = "elastic" is the default.
    let elastic = add(HERTZ, "substrate", "rheology = \"elastic\"");
    assert_eq!(zener(&elastic), parse(HERTZ).unwrap().case.body);
}

#[test]
fn bad_viscoelastic_substrates_name_the_key() {
    error_naming(
        &with(ZENER, "glassy_modulus", "glassy_modulus = 0.5"),
        &["substrate.glassy_modulus", "relaxed"],
    );
    error_naming(
        &with(ZENER, "relaxation_time", "relaxation_time = -1.0"),
        &["substrate.relaxation_time"],
    );
    error_naming(
        &with(ZENER, "relaxed_modulus", "order = 0.5"),
        &["substrate.order", "zener"],
    );
    error_naming(
        &with(ZENER, "relaxed_modulus", "young = 1.0"),
        &["substrate.young", "zener"],
    );
    error_naming(
        &with(ZENER, "relaxed_modulus", "branch_times = [1.0]"),
        &["substrate.branch_times"],
    );
    error_naming(
        &with(ZENER, "relaxed_modulus", ""),
        &["substrate.relaxed_modulus"],
    );
    error_naming(
        &with(ZENER, "rheology", "rheology = \"maxwell\""),
        &["substrate", "rheology"],
    );
    error_naming(&with(ZENER, "velocity", ""), &["loading.velocity"]);
    error_naming(
        &add(ZENER, "substrate", "").replace(
            "[loading]",
            "[coating]\nyoung = 2.0\npoisson = 0.3\nthickness = 0.01\n[loading]",
        ),
        &["coating", "viscoelastic"],
    );
    error_naming(
        &with(HERTZ, "young", "young = 1.0\nglassy_modulus = 3.0"),
        &["substrate.glassy_modulus", "rheology"],
    );
    let fractional = with(ZENER, "rheology", "rheology = \"fractional_zener\"");
    error_naming(&fractional, &["substrate.order"]);
    error_naming(
        &add(&fractional, "substrate", "order = 1.2"),
        &["substrate.order", "0 < order <= 1"],
    );
    error_naming(
        &add(&fractional, "substrate", "order = 0.5\nbranch_count = 1"),
        &["substrate.branch_count"],
    );
    let prony = "[slider]\nshape = \"sphere\"\nradius = 1.0\n[substrate]\nrheology = \"prony\"\n\
                 glassy_compliance = 0.1\nbranch_compliances = [0.5, -0.4]\n\
                 branch_times = [0.1, 10]\npoisson = 0.45\n[loading]\nnormal_load = 5e-6\n\
                 velocity = 0.01\n[grid]\ncells = [32, 32]\n";
    error_naming(prony, &["substrate.branch_compliances[1]"]);
    error_naming(
        &prony.replace("[0.1, 10]", "[0.1]").replace("-0.4", "0.4"),
        &["substrate.branch_times", "one time per entry"],
    );
    let fluid = prony
        .replace("\"prony\"", "\"relaxation_prony\"")
        .replace("glassy_compliance = 0.1", "equilibrium_modulus = 0.0")
        .replace(
            "branch_compliances = [0.5, -0.4]",
            "branch_moduli = [0.5, 0.4]",
        );
    error_naming(&fluid, &["substrate.equilibrium_modulus", "fluid"]);
}

/// `shape = "profile"` reads one row (or column) of heights through the map loader
/// and makes a line contact; a 2-D map is refused for it, and one row is refused as
/// a `height_map`, each naming the key and the other shape.
#[test]
fn a_profile_is_one_row_of_heights() {
    let text = "[slider]\nshape = \"profile\"\nfile = \"p.csv\"\ncell_size = 0.5\n\
                [substrate]\nyoung = 1.0\npoisson = 0.3\n[loading]\nnormal_load = 1e-3\n\
                [grid]\ncells = 64\n";
    let loader = |rows: usize, cols: usize| {
        move |_: &str, cell_size: f64| -> Result<HeightMap> {
            Ok(HeightMap {
                nx: cols,
                ny: rows,
                cell_size,
                heights: (0..rows * cols).map(|k| (k as f64 - 3.0).powi(2)).collect(),
            })
        }
    };
    for (rows, cols) in [(1, 7), (7, 1)] {
        let case = parse_case_file(text, &mut loader(rows, cols)).unwrap().case;
        let Slider::Profile(p) = &case.slider else {
            panic!("{:?}", case.slider)
        };
        assert_eq!((p.cell_size, p.heights.len()), (0.5, 7));
        assert!(case.slider.is_line());
        assert_eq!(case.grid.cells, [64, 1]);
    }
    let e = parse_case_file(text, &mut loader(3, 4))
        .unwrap_err()
        .to_string();
    assert!(e.contains("slider.file") && e.contains("height_map"), "{e}");
    let map = text
        .replace("\"profile\"", "\"height_map\"")
        .replace("cells = 64", "cells = [64, 64]");
    let e = parse_case_file(&map, &mut loader(1, 7))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("slider.file") && e.contains("\"profile\""),
        "{e}"
    );
    let e = parse_case_file(
        &text.replace("cell_size = 0.5\n", "radius = 1.0\n"),
        &mut loader(1, 7),
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("slider.radius"), "{e}");
}
