//! End-to-end tests of the `thirdbody` binary: every bad input of the
//! case file gives exit code 2, one stderr line naming the field and the allowed
//! range, and no file in the output folder; a successful solve writes every output
//! with the documented keys and shapes.

use crate::common;

use std::path::Path;

use common::{assert_no_output, read_summary, solve, SPHERE};

use ndarray::Array2;

/// The paper's Fig. 3 case on a small grid.
const LAYERED: &str = r#"
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

[loading]
normal_load = 5e-6
velocity = 1e-2

[grid]
cells = [32, 32]
"#;

/// Every key summary.json must hold (the required ones plus the extras documented).
const SUMMARY_KEYS: [&str; 25] = [
    "normal_load",
    "penetration",
    "max_pressure",
    "max_pressure_x",
    "max_pressure_y",
    "contact_area",
    "contact_x_min",
    "contact_x_max",
    "contact_y_min",
    "contact_y_max",
    "moment",
    "friction_coefficient",
    "tangential_force",
    "iterations",
    "residual",
    "nx",
    "ny",
    "cell_size",
    "solve_seconds",
    "linear_iterations",
    "windows",
    "window_x_min",
    "window_x_max",
    "window_y_min",
    "window_y_max",
];

/// Exit code 2, exactly one stderr line `error: ...` containing every `parts`,
/// and nothing in the output folder.
fn assert_bad_input(case: &str, files: &[(&str, &str)], parts: &[&str]) {
    let run = solve(case, files, &[]);
    let err = run.stderr();
    assert_eq!(run.code(), Some(2), "stderr: {err}");
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 1, "not one line: {err:?}");
    assert!(lines[0].starts_with("error: "), "{err}");
    for p in parts {
        assert!(lines[0].contains(p), "{err:?} does not mention {p:?}");
    }
    assert_no_output(&run.out_dir);
}

/// `text` with the line starting `key =` replaced by `new`.
fn with(text: &str, key: &str, new: &str) -> String {
    let mut out: Vec<String> = text.lines().map(str::to_string).collect();
    let k = out
        .iter()
        .position(|l| l.starts_with(&format!("{key} =")))
        .unwrap_or_else(|| panic!("no {key} in the case"));
    out[k] = new.to_string();
    out.join("\n")
}

#[test]
fn missing_section_is_named() {
    let case = SPHERE.replace("[substrate]\nyoung = 1.0\npoisson = 0.3\n", "");
    assert_bad_input(&case, &[], &["[substrate]", "young (> 0)", "poisson"]);
}

#[test]
fn unknown_key_is_named_with_the_allowed_keys() {
    let case = SPHERE.replace("radius = 1.0", "radius = 1.0\ncolour = \"red\"");
    assert_bad_input(
        &case,
        &[],
        &[
            "line 5",
            "slider.colour",
            "unknown field",
            "expected one of",
        ],
    );
}

#[test]
fn poisson_ratio_of_one_half_or_more() {
    for nu in ["0.5", "0.6"] {
        let case = with(SPHERE, "poisson", &format!("poisson = {nu}"));
        assert_bad_input(&case, &[], &["substrate.poisson", "-1 < poisson < 0.5"]);
    }
}

#[test]
fn young_modulus_not_positive() {
    for e in ["0.0", "-2.0"] {
        let case = with(SPHERE, "young", &format!("young = {e}"));
        assert_bad_input(&case, &[], &["substrate.young", "> 0"]);
    }
}

#[test]
fn normal_load_not_positive() {
    for q in ["0.0", "-5e-6"] {
        let case = with(SPHERE, "normal_load", &format!("normal_load = {q}"));
        assert_bad_input(&case, &[], &["loading.normal_load", "> 0"]);
    }
}

#[test]
fn delta_outside_zero_one() {
    for d in ["-0.1", "1.2"] {
        let case = with(LAYERED, "delta", &format!("delta = {d}"));
        assert_bad_input(&case, &[], &["layer.delta", "0 <= delta <= 1"]);
    }
}

#[test]
fn p0_not_positive() {
    for p0 in ["0.0", "-1e-3"] {
        let case = with(LAYERED, "p0", &format!("p0 = {p0}"));
        assert_bad_input(&case, &[], &["layer.p0", "> 0"]);
    }
}

#[test]
fn height_map_with_nan() {
    let case = SPHERE.replace(
        "shape = \"sphere\"\nradius = 1.0",
        "shape = \"height_map\"\nfile = \"map.csv\"\ncell_size = 0.01",
    );
    let map = "0.5,0.2,0.5\n0.2,NaN,0.2\n0.5,0.2,0.5\n";
    assert_bad_input(
        &case,
        &[("map.csv", map)],
        &["slider.file", "NaN", "row 1, column 1", "finite heights"],
    );
}

#[test]
fn grid_of_fewer_than_8_cells() {
    let case = with(SPHERE, "cells", "cells = [32, 7]");
    assert_bad_input(&case, &[], &["grid.cells[1]", "at least 8"]);
}

#[test]
fn unreadable_files_are_bad_input() {
    let case = SPHERE.replace(
        "shape = \"sphere\"\nradius = 1.0",
        "shape = \"height_map\"\nfile = \"absent.npy\"\ncell_size = 0.01",
    );
    assert_bad_input(&case, &[], &["slider.file", "absent.npy"]);

    let root = tempfile::tempdir().unwrap();
    let out = root.path().join("out");
    let output = common::thirdbody(&[
        "solve".as_ref(),
        "no-such-case.toml".as_ref(),
        "--out".as_ref(),
        out.as_os_str(),
    ]);
    assert_eq!(output.status.code(), Some(2));
    let err = String::from_utf8_lossy(&output.stderr);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("no-such-case.toml"), "{err}");
    assert!(!root.path().join("out").exists());
}

fn read_npy(path: &Path) -> Array2<f64> {
    ndarray_npy::read_npy(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Checks the files every solve writes; returns the summary.
fn check_outputs(dir: &Path, layer: bool) -> serde_json::Map<String, serde_json::Value> {
    let summary = read_summary(dir);
    for key in SUMMARY_KEYS {
        let v = summary.get(key).unwrap_or_else(|| panic!("no {key}"));
        let x = v
            .as_f64()
            .unwrap_or_else(|| panic!("{key} = {v} is not a number"));
        assert!(x.is_finite(), "{key} = {x}");
    }
    assert_eq!(summary["units"], "dimensionless");
    assert!(summary["method"].is_string());
    let (nx, ny) = (
        summary["nx"].as_u64().unwrap() as usize,
        summary["ny"].as_u64().unwrap() as usize,
    );
    assert_eq!((nx, ny), (32, 32));
    let h = summary["cell_size"].as_f64().unwrap();

    let p = read_npy(&dir.join("pressure.npy"));
    assert_eq!(p.dim(), (ny, nx));
    assert!(p.iter().all(|&v| v.is_finite() && v >= 0.0));
    for name in ["body_displacement.npy", "gap.npy"] {
        assert_eq!(read_npy(&dir.join(name)).dim(), (ny, nx), "{name}");
    }
    assert_eq!(dir.join("compliance.npy").exists(), layer);
    assert_eq!(dir.join("layer_displacement.npy").exists(), layer);
    if layer {
        assert_eq!(read_npy(&dir.join("compliance.npy")).dim(), (ny, nx));
    }

    // The CSV holds the same pressures as the NPY, cell by cell with rows along y,
    // and its cell centres are h apart.
    let csv = std::fs::read_to_string(dir.join("pressure.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines[0], "x,y,pressure");
    assert_eq!(lines.len(), nx * ny + 1);
    let row = |k: usize| -> Vec<f64> {
        lines[k + 1]
            .split(',')
            .map(|s| s.parse().unwrap())
            .collect()
    };
    let (first, second, next_row) = (row(0), row(1), row(nx));
    assert!((second[0] - first[0] - h).abs() < 1e-9 * h);
    assert!((next_row[1] - first[1] - h).abs() < 1e-9 * h);
    let mut load = 0.0;
    for j in 0..ny {
        for i in 0..nx {
            let r = row(j * nx + i);
            assert_eq!(r[2], p[[j, i]]);
            load += r[2] * h * h;
        }
    }
    // Load balance: sum(p) h^2 = Q (the solver's load equation).
    let q = summary["normal_load"].as_f64().unwrap();
    assert!((load - q).abs() < 1e-6 * q, "{load} vs {q}");

    // No temporaries left.
    for entry in std::fs::read_dir(dir).unwrap() {
        let name = entry.unwrap().file_name().into_string().unwrap();
        assert!(!name.contains(".tmp-"), "{name}");
    }
    summary
}

#[test]
fn sphere_without_layer_writes_every_output_and_matches_hertz() {
    let run = solve(SPHERE, &[], &[]);
    assert_eq!(run.code(), Some(0), "stderr: {}", run.stderr());
    assert!(run.stderr().is_empty(), "{}", run.stderr());
    assert!(run.stdout().contains("mu ="), "{}", run.stdout());
    let s = check_outputs(&run.out_dir, false);
    // Hertz (Johnson, Contact Mechanics, section 4.2), E* = 1 / (1 - 0.09):
    // a = (3 Q R / 4 E*)^(1/3) = 0.015055, D = a^2 / R = 2.2666e-4,
    // p_max = 3 Q / (2 pi a^2) = 0.010532. Coarse grid: a few per cent.
    let d = s["penetration"].as_f64().unwrap();
    assert!((d / 2.2666e-4 - 1.0).abs() < 0.03, "D = {d}");
    let pmax = s["max_pressure"].as_f64().unwrap();
    assert!((pmax / 0.010532 - 1.0).abs() < 0.05, "p_max = {pmax}");
    // Symmetric contact: no friction from hysteresis.
    let mu = s["friction_coefficient"].as_f64().unwrap();
    assert!(mu.abs() < 1e-6, "mu = {mu}");
}

#[test]
fn height_map_of_a_paraboloid_solves_like_the_sphere() {
    // The sphere's shape sampled into a CSV map (201 x 201 samples, spacing
    // h = 0.001, half extent 0.1 = 6.6 Hertz radii). Bilinear interpolation errs by
    // at most e = h^2 / (8 R) = 1.25e-7 in height (0.06% of D) with slope kinks at
    // the sample lines, which perturb the pressure locally by about
    // E* e / h = E* h / 8 = 1.4e-4 (1.3% of p_max); the solves must agree within that.
    let (n, h) = (201, 0.001);
    let mut csv = String::new();
    for j in 0..n {
        let y = (j as f64 + 0.5 - n as f64 / 2.0) * h;
        let row: Vec<String> = (0..n)
            .map(|i| {
                let x = (i as f64 + 0.5 - n as f64 / 2.0) * h;
                format!("{}", (x * x + y * y) / 2.0)
            })
            .collect();
        csv.push_str(&row.join(","));
        csv.push('\n');
    }
    let case = SPHERE.replace(
        "shape = \"sphere\"\nradius = 1.0",
        "shape = \"height_map\"\nfile = \"ball.csv\"\ncell_size = 0.001",
    );
    let map = solve(&case, &[("ball.csv", &csv)], &["--quiet"]);
    assert_eq!(map.code(), Some(0), "stderr: {}", map.stderr());
    let sphere = solve(SPHERE, &[], &["--quiet"]);
    assert_eq!(sphere.code(), Some(0), "stderr: {}", sphere.stderr());
    let (a, b) = (read_summary(&map.out_dir), read_summary(&sphere.out_dir));
    // The area counts cells, so one cell in ~200 flipping at the edge is 0.5%.
    for (key, tol) in [
        ("penetration", 0.002),
        ("max_pressure", 0.02),
        ("contact_area", 0.02),
    ] {
        let (va, vb) = (a[key].as_f64().unwrap(), b[key].as_f64().unwrap());
        assert!((va / vb - 1.0).abs() < tol, "{key}: map {va}, sphere {vb}");
    }
}

#[test]
fn layered_case_writes_compliance_and_shifts_pressure_forward() {
    let run = solve(LAYERED, &[], &["--quiet", "--threads", "1"]);
    assert_eq!(run.code(), Some(0), "stderr: {}", run.stderr());
    assert!(run.stdout().is_empty(), "--quiet: {}", run.stdout());
    let s = check_outputs(&run.out_dir, true);
    // Creep moves the pressure towards the leading edge (+x): mu > 0 and the
    // contact reaches further ahead than behind (paper section 5, Fig. 3).
    assert!(s["friction_coefficient"].as_f64().unwrap() > 0.0);
    let (xmin, xmax) = (
        s["contact_x_min"].as_f64().unwrap(),
        s["contact_x_max"].as_f64().unwrap(),
    );
    assert!(xmax > -xmin, "contact from {xmin} to {xmax}");
    // Paper eq. 11 at p >= 0: C0 (1 - delta) < C[p] <= C0, with C0 where p = 0.
    let c = read_npy(&run.out_dir.join("compliance.npy"));
    let p = read_npy(&run.out_dir.join("pressure.npy"));
    for (&cv, &pv) in c.iter().zip(p.iter()) {
        assert!(
            cv > 0.01 && cv <= 0.02 * (1.0 + 1e-12),
            "C = {cv} at p = {pv}"
        );
        if pv == 0.0 {
            assert!((cv - 0.02).abs() < 1e-12, "C = {cv} at p = 0");
        }
    }
}

#[test]
fn plots_are_written() {
    let run = solve(LAYERED, &[], &["--quiet"]);
    assert_eq!(run.code(), Some(0), "stderr: {}", run.stderr());
    for name in ["pressure_map.png", "pressure_x.png", "compliance_map.png"] {
        let bytes = std::fs::read(run.out_dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "{name} is not a PNG");
    }
}

#[test]
fn a_window_too_small_exits_with_2_a_solver_failure_with_1_and_neither_writes() {
    // A fixed window of half width 0.005 cannot hold the Hertz contact of radius
    // 0.015: the contact reaches the edge, which the case's window causes (exit 2).
    let case = SPHERE.replace(
        "cells = [32, 32]",
        "cells = [32, 32]\nhalf_width = [0.005, 0.005]",
    );
    let run = solve(&case, &[], &[]);
    assert_eq!(run.code(), Some(2), "stderr: {}", run.stderr());
    assert_eq!(run.stderr().lines().count(), 1, "{}", run.stderr());
    assert!(
        run.stderr().contains("edge of the window"),
        "{}",
        run.stderr()
    );
    assert_no_output(&run.out_dir);
    // One iteration is not enough to converge.
    let case = format!("{SPHERE}\n[solver]\nmax_iterations = 1\n");
    let run = solve(&case, &[], &[]);
    assert_eq!(run.code(), Some(1), "stderr: {}", run.stderr());
    assert_eq!(run.stderr().lines().count(), 1, "{}", run.stderr());
    assert!(
        run.stderr().contains("did not converge"),
        "{}",
        run.stderr()
    );
    assert_no_output(&run.out_dir);
}

/// The shared list of bad case files (`tests/data/bad_inputs.json`, also run through
/// the Python package): each gives its exit code, one `error:` line that names what
/// is wrong, and no output.
#[test]
fn the_shared_bad_input_list_exits_cleanly_with_one_line() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let list: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(root.join("tests/data/bad_inputs.json")).unwrap(),
    )
    .unwrap();
    let cases = list["cases"].as_array().unwrap();
    assert!(cases.len() >= 30);
    for entry in cases {
        let name = entry["name"].as_str().unwrap();
        let example = entry["example"].as_str().unwrap();
        let mut text =
            std::fs::read_to_string(root.join(format!("../../examples/{example}.toml"))).unwrap();
        for pair in entry["replace"].as_array().unwrap() {
            let (old, new) = (pair[0].as_str().unwrap(), pair[1].as_str().unwrap());
            assert!(text.contains(old), "{name}: the example has no {old:?}");
            text = text.replacen(old, new, 1);
        }
        let run = solve(&text, &[], &["--format", "npy"]);
        let err = run.stderr();
        assert_eq!(
            run.code(),
            entry["exit"].as_i64().map(|c| c as i32),
            "{name}: {err}"
        );
        let lines: Vec<&str> = err.lines().collect();
        assert_eq!(lines.len(), 1, "{name}: not one line: {err:?}");
        assert!(lines[0].starts_with("error: "), "{name}: {err}");
        let expect = entry["expect"].as_str().unwrap();
        assert!(
            lines[0].contains(expect),
            "{name}: {err:?} lacks {expect:?}"
        );
        assert_no_output(&run.out_dir);
    }
}

/// A cylinder (plane strain) on 256 cells.
const CYLINDER: &str = "[slider]\nshape = \"cylinder\"\nradius = 1.0\n[substrate]\n\
                        young = 1.0\npoisson = 0.3\n[loading]\nnormal_load = 1e-3\n\
                        [grid]\ncells = 256\n";

#[test]
fn a_line_contact_writes_profiles_along_x_and_a_summary_without_y() {
    let run = solve(CYLINDER, &[], &[]);
    assert_eq!(run.code(), Some(0), "{}", run.stderr());
    let dir = &run.out_dir;
    for name in [
        "pressure.npy",
        "body_displacement.npy",
        "gap.npy",
        "shape.npy",
        "pressure.csv",
        "surface.vti",
        "pressure_x.png",
        "summary.json",
        "case.toml",
    ] {
        assert!(dir.join(name).is_file(), "{name} missing");
    }
    for name in ["pressure_map.png", "compliance_map.png"] {
        assert!(
            !dir.join(name).exists(),
            "{name} written for a line contact"
        );
    }
    for name in ["pressure", "gap", "body_displacement", "shape"] {
        let a: ndarray::Array1<f64> =
            ndarray_npy::read_npy(dir.join(format!("{name}.npy"))).unwrap();
        assert_eq!(a.len(), 256, "{name}");
    }
    let csv = std::fs::read_to_string(dir.join("pressure.csv")).unwrap();
    assert_eq!(csv.lines().next(), Some("x,pressure"));
    assert_eq!(csv.lines().count(), 257);
    let s = read_summary(dir);
    for key in [
        "contact_y_min",
        "contact_y_max",
        "max_pressure_y",
        "ny",
        "window_y_min",
        "window_y_max",
    ] {
        assert!(!s.contains_key(key), "{key} in a line contact's summary");
    }
    assert_eq!(s["contact"], "line");
    assert_eq!(s["reference_distance"], 1.0);
    // Q per unit length = sum(p) h.
    let p: ndarray::Array1<f64> = ndarray_npy::read_npy(dir.join("pressure.npy")).unwrap();
    let h = s["cell_size"].as_f64().unwrap();
    assert!((p.sum() * h / 1e-3 - 1.0).abs() < 1e-8);
    assert!(run.stdout().contains("line contact"), "{}", run.stdout());
    assert!(run.stdout().contains("width"), "{}", run.stdout());
}

#[test]
fn a_line_contact_refuses_a_point_contacts_stress_maps_naming_the_key() {
    assert_bad_input(
        &format!("{CYLINDER}[stress]\ny = 0.5\n"),
        &[],
        &["stress.y = 0.5", "line contact"],
    );
    assert_bad_input(
        &format!("{CYLINDER}[stress]\nsections = [\"xz\", \"block\"]\n"),
        &[],
        &["stress.sections = block", "line contact"],
    );
}
