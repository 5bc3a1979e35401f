// Temporary: records the one-coating implementation's results (before it is replaced).
use thirdbody::stress::{Section, Side};
use thirdbody::{solve, Body, Case, Elastic, GridSpec, Layer, Loading, Slider, SolverParams, Units};

fn case(ratio: f64, thickness: f64, layer: Option<Layer>, velocity: Option<f64>) -> Case {
    Case {
        slider: Slider::Sphere { radius: 1.0 },
        body: Body::Coated {
            coating: Elastic { young: ratio, poisson: 0.25 },
            thickness,
            substrate: Elastic { young: 1.0, poisson: 0.3 },
        },
        layer,
        loading: Loading { normal_load: 5e-6, velocity },
        grid: GridSpec { cells: [32, 32], half_width: Some([0.06, 0.06]), centre: Some([0.0, 0.0]) },
        units: Units::Dimensionless,
    }
}

fn main() {
    let text = std::fs::read_to_string("../../examples/paper_fig12a_thin_coating.toml").unwrap();
    let file = thirdbody::case_file::parse_case_file(&text, &mut |_, _| unreachable!()).unwrap();
    let paper_layer = file.case.layer.clone();
    let cases = vec![
        ("stiff_thin", case(3.0, 0.002, None, None)),
        ("soft_thick", case(0.1, 0.05, None, None)),
        ("stiff_sub_cell", case(30.0, 0.0005, paper_layer.clone(), Some(1e-3))),
        ("paper_thick", case(3.0, 0.02, paper_layer, Some(1e-3))),
    ];
    let mut out = serde_json::Map::new();
    for (name, c) in cases {
        let s = solve(&c, &SolverParams::default()).unwrap();
        let h1 = match c.body { Body::Coated { thickness, .. } => thickness, _ => unreachable!() };
        let depths = vec![0.0, 0.5 * h1, h1, 1.5 * h1, 0.01, 0.03];
        let mut sections = serde_json::Map::new();
        for (label, sec) in [
            ("xz", Section::XzPlane { y: 0.0, depths: depths.clone() }),
            ("surface", Section::Plane { z: 0.0 }),
            ("interface_coating", Section::Interface { side: Side::Coating }),
            ("interface_substrate", Section::Interface { side: Side::Substrate }),
            ("plane_deep", Section::Plane { z: 0.02 }),
        ] {
            let f = s.stresses(&sec).unwrap();
            let rows: Vec<Vec<f64>> = if label == "xz" { f.components.to_vec() } else {
                f.components.iter().map(|c| c[16 * 32..18 * 32].to_vec()).collect()
            };
            sections.insert(label.into(), serde_json::json!(rows));
        }
        let summ = s.summary();
        out.insert(name.into(), serde_json::json!({
            "young_ratio": match c.body { Body::Coated { coating, .. } => coating.young, _ => 0.0 },
            "thickness": h1,
            "layered": c.layer.is_some(),
            "depths": depths,
            "approach": s.approach,
            "friction": summ.friction_coefficient,
            "pressure": s.pressure,
            "sections": sections,
        }));
    }
    std::fs::write("tests/data/coated_reference.json", serde_json::to_string(&out).unwrap()).unwrap();
}
