//! Friction from a height-map slider: the slope in the friction sum
//! `mu = sum(p df/dx) h^2 / Q` was the one-sided slope of the bilinear interpolant at
//! a node, which biased mu by hm / (2R) when the map's nodes fall on the cell centres.
//! A sphere written as a map (NPY and CSV, read through the CLI as a user's file is),
//! with its nodes on the cell centres, on the cell corners and at an unrelated
//! spacing (0.37 h), must give the mu of the same sphere given as `shape = "sphere"`
//! (an independent path: the closed-form slope x / R) to 1e-4, and
//! `friction_coefficient` must equal `moment / (R Q)` (paper eq. 12) to 1e-4.

use crate::common;

use std::path::Path;

use common::read_summary;
use ndarray::Array2;

/// The paper's Fig. 3 layer on a fixed window centred on the origin (128 cells of
/// h = 0.112 / 128), so that map nodes can be laid on the cell centres or corners.
fn case(slider: &str) -> String {
    format!(
        "[slider]\n{slider}\n\n[substrate]\nyoung = 1.0\npoisson = 0.3\n\n[layer]\n\
         compliance = 0.02\nrelaxation_time = 1.0\nlaw = \"sigmoid\"\ndelta = 0.5\n\
         p0 = 0.001\n\n[loading]\nnormal_load = 5e-6\nvelocity = 1e-3\n\n[grid]\n\
         cells = [128, 128]\nhalf_width = [0.056, 0.056]\n"
    )
}

const CELL: f64 = 0.112 / 128.0;

/// `(x^2 + y^2) / 2` on `n x n` nodes at `(i + 1/2 - n/2) spacing` (the map layout).
fn sphere_map(n: usize, spacing: f64) -> Array2<f64> {
    Array2::from_shape_fn((n, n), |(j, i)| {
        let x = (i as f64 + 0.5 - n as f64 / 2.0) * spacing;
        let y = (j as f64 + 0.5 - n as f64 / 2.0) * spacing;
        (x * x + y * y) / 2.0
    })
}

fn write_csv(path: &Path, a: &Array2<f64>) {
    let text: String = a
        .rows()
        .into_iter()
        .map(|r| {
            let row: Vec<String> = r.iter().map(|v| format!("{v}")).collect();
            row.join(",") + "\n"
        })
        .collect();
    std::fs::write(path, text).unwrap();
}

fn solve_in(dir: &Path, slider: &str) -> serde_json::Map<String, serde_json::Value> {
    let case_path = dir.join("case.toml");
    std::fs::write(&case_path, case(slider)).unwrap();
    let out = dir.join("out");
    let run = common::thirdbody(&[
        "solve".as_ref(),
        case_path.as_os_str(),
        "--out".as_ref(),
        out.as_os_str(),
        "--quiet".as_ref(),
        "--format".as_ref(),
        "npy".as_ref(),
    ]);
    assert_eq!(
        run.status.code(),
        Some(0),
        "{slider}: {}",
        String::from_utf8_lossy(&run.stderr)
    );
    read_summary(&out)
}

fn number(s: &serde_json::Map<String, serde_json::Value>, key: &str) -> f64 {
    s[key].as_f64().unwrap()
}

#[test]
fn a_sphere_given_as_a_map_has_the_spheres_friction() {
    let root = tempfile::tempdir().unwrap();
    let sphere = solve_in(root.path(), "shape = \"sphere\"\nradius = 1.0");
    let mu_sphere = number(&sphere, "friction_coefficient");
    // Layouts: nodes on the cell centres (an even count at the cell size), on the
    // corners (an odd count), and at 0.37 h; each map reaches past the window.
    for (layout, n, spacing) in [
        ("centres", 140, CELL),
        ("corners", 141, CELL),
        ("0.37 h", 372, 0.37 * CELL),
    ] {
        let map = sphere_map(n, spacing);
        for format in ["npy", "csv"] {
            let dir = root
                .path()
                .join(format!("{format}_{}", layout.replace(' ', "_")));
            std::fs::create_dir_all(&dir).unwrap();
            let file = dir.join(format!("ball.{format}"));
            if format == "npy" {
                ndarray_npy::write_npy(&file, &map).unwrap();
            } else {
                write_csv(&file, &map);
            }
            let s = solve_in(
                &dir,
                &format!(
                    "shape = \"height_map\"\nfile = \"ball.{format}\"\ncell_size = {spacing:e}"
                ),
            );
            let mu = number(&s, "friction_coefficient");
            let eq12 = number(&s, "moment") / (1.0 * 5e-6);
            let error = (mu / mu_sphere - 1.0).abs();
            eprintln!(
                "{layout}, {format}: mu {mu:.10e} (sphere {mu_sphere:.10e}, relative {error:.1e}); \
                 M/(RQ) relative {:.1e}",
                (mu / eq12 - 1.0).abs()
            );
            assert!(error < 1e-4, "{layout}, {format}: mu {mu} vs {mu_sphere}");
            assert!(
                (mu / eq12 - 1.0).abs() < 1e-4,
                "{layout}, {format}: mu {mu} vs M/(RQ) {eq12}"
            );
        }
    }
}
