//! End-to-end tests of the stress outputs: `[stress]` in a case file makes
//! `thirdbody solve` write the sections, plots, VTK block and the `stress` summary;
//! `thirdbody stress DIR` computes the same from a solved folder; bad requests are
//! refused with exit code 2, naming the key, and leave no file behind.

mod common;

use std::ffi::OsStr;
use std::path::Path;

use common::{assert_no_output, read_summary, solve, thirdbody};
use ndarray::Array4;

/// The paper's Fig. 10a case (delta = 0.01) on a small grid.
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
delta = 0.01
p0 = 0.005

[loading]
normal_load = 5e-6
velocity = 1e-3

[grid]
cells = [32, 32]
"#;

const COATING: &str = "\n[coating]\nyoung = 3.0\npoisson = 0.25\nthickness = 0.01\n";

fn read4(path: &Path) -> Array4<f64> {
    ndarray_npy::read_npy(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn files(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    names
}

fn stress_of(summary: &serde_json::Map<String, serde_json::Value>, key: &str) -> f64 {
    summary["stress"][key]
        .as_f64()
        .unwrap_or_else(|| panic!("stress.{key} missing: {:?}", summary["stress"]))
}

#[test]
fn an_empty_stress_section_writes_the_default_sections() {
    let run = solve(&format!("{LAYERED}\n[stress]\n"), &[], &[]);
    assert_eq!(run.code(), Some(0), "{}", run.stderr());
    let dir = &run.out_dir;
    let summary = read_summary(dir);
    for key in [
        "tau1_max",
        "tau1_max_x",
        "tau1_max_z",
        "sigma_x_min",
        "sigma_x_max",
    ] {
        assert!(stress_of(&summary, key).is_finite(), "{key}");
    }
    assert!(summary["stress"]
        .get("interface_sigma_x_max_coating")
        .is_none());
    // tau1 lies below the surface, under the contact; sigma_x is compressive under
    // the load and tensile somewhere on the surface.
    let (x_min, x_max) = (
        summary["contact_x_min"].as_f64().unwrap(),
        summary["contact_x_max"].as_f64().unwrap(),
    );
    let x = stress_of(&summary, "tau1_max_x");
    assert!(x > x_min && x < x_max, "{x}");
    assert!(stress_of(&summary, "tau1_max_z") > 0.0);
    assert!(stress_of(&summary, "sigma_x_min") < 0.0 && stress_of(&summary, "sigma_x_max") > 0.0);
    // The XZ section: (11, 64, 1, nx), down to three contact half-lengths.
    let xz = read4(&dir.join("stress_xz.npy"));
    assert_eq!(xz.dim(), (11, 64, 1, 32));
    assert!(xz.iter().all(|v| v.is_finite()));
    let depths = summary["stress"]["sections"][0]["depths"]
        .as_array()
        .unwrap();
    assert_eq!(depths.len(), 64);
    let half = 0.5
        * (x_max - x_min).max(
            summary["contact_y_max"].as_f64().unwrap() - summary["contact_y_min"].as_f64().unwrap(),
        );
    assert!((depths[63].as_f64().unwrap() - 3.0 * half).abs() < 1e-12);
    // tau1 (field 9) is (s1 - s3)/2 (fields 6, 8), and its maximum is the summary's.
    let mut best = 0.0f64;
    for v in xz.index_axis(ndarray::Axis(0), 9).iter() {
        best = best.max(*v);
    }
    assert_eq!(best, stress_of(&summary, "tau1_max"));
    for k in 0..64 {
        for i in 0..32 {
            let t = 0.5 * (xz[[6, k, 0, i]] - xz[[8, k, 0, i]]);
            assert!((t - xz[[9, k, 0, i]]).abs() <= 1e-15 + 1e-12 * t.abs());
        }
    }
    // The surface: sigma_z = -p at every cell centre.
    let surface = read4(&dir.join("stress_surface.npy"));
    assert_eq!(surface.dim(), (11, 1, 32, 32));
    let p: ndarray::Array2<f64> = ndarray_npy::read_npy(dir.join("pressure.npy")).unwrap();
    for j in 0..32 {
        for i in 0..32 {
            assert!((surface[[2, 0, j, i]] + p[[j, i]]).abs() < 1e-12);
        }
    }
    // CSV: a header and one line per point, the same values as the NPY.
    let csv = std::fs::read_to_string(dir.join("stress_xz.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert!(lines[0].starts_with("x,y,z,sigma_x,sigma_y,sigma_z,tau_xy,tau_xz,tau_yz,s1"));
    assert_eq!(lines.len(), 64 * 32 + 1);
    let last: Vec<f64> = lines[64 * 32]
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    assert_eq!(last[3..], xz.slice(ndarray::s![.., 63, 0, 31]).to_vec()[..]);
    let names = files(dir);
    for name in [
        "case.toml",
        "stress_xz_tau1.png",
        "stress_xz_sigma_x.png",
        "stress_sigma_x.png",
        "stress_surface.csv",
        "surface.vti",
    ] {
        assert!(
            names.contains(&name.to_string()),
            "{name} missing: {names:?}"
        );
    }
    assert!(!names.iter().any(|n| n.contains(".tmp-")));
}

#[test]
fn a_coated_body_reports_both_sides_of_the_interface_and_a_block_as_vtk() {
    let case = format!(
        "{LAYERED}{COATING}\n[stress]\nsections = [\"interface\", \"block\"]\n\
         max_depth = 0.03\ndepth_points = 4\n"
    );
    let run = solve(&case, &[], &["--format", "npy,vtk"]);
    assert_eq!(run.code(), Some(0), "{}", run.stderr());
    let dir = &run.out_dir;
    let summary = read_summary(dir);
    let coating = stress_of(&summary, "interface_sigma_x_max_coating");
    let substrate = stress_of(&summary, "interface_sigma_x_max_substrate");
    assert!(coating != substrate, "sigma_x jumps across the interface");
    // The same, per interface by index.
    let interface = &summary["stress"]["interfaces"][0];
    assert_eq!(interface["index"], 0);
    assert_eq!(interface["above"]["sigma_x_max"].as_f64(), Some(coating));
    assert_eq!(interface["below"]["sigma_x_max"].as_f64(), Some(substrate));
    let c = read4(&dir.join("stress_interface_0_above.npy"));
    let s = read4(&dir.join("stress_interface_0_below.npy"));
    assert_eq!(c.dim(), (11, 1, 32, 32));
    // sigma_z, tau_xz and tau_yz are continuous across the interface.
    for field in [2, 4, 5] {
        for j in 0..32 {
            for i in 0..32 {
                let (a, b) = (c[[field, 0, j, i]], s[[field, 0, j, i]]);
                assert!((a - b).abs() < 1e-9 * 3e-3, "field {field}: {a} vs {b}");
            }
        }
    }
    let block = read4(&dir.join("stress_block.npy"));
    assert_eq!(block.dim(), (11, 4, 32, 32));
    // The VTK file: an image-data header with the block's extent, and the first
    // array (sigma_x) at offset 0 of the appended data equal to the NPY's.
    let bytes = std::fs::read(dir.join("stress_block.vti")).unwrap();
    let text = String::from_utf8_lossy(&bytes);
    assert!(text.contains("type=\"ImageData\""));
    assert!(
        text.contains("WholeExtent=\"0 31 0 31 0 3\""),
        "{}",
        &text[..400]
    );
    assert!(text.contains("Spacing=") && text.contains(" 0.01\""));
    let marker = b"<AppendedData encoding=\"raw\">";
    let at = bytes
        .windows(marker.len())
        .position(|w| w == marker)
        .unwrap();
    let start = at + bytes[at..].iter().position(|&b| b == b'_').unwrap() + 1;
    let count = u64::from_le_bytes(bytes[start..start + 8].try_into().unwrap()) as usize;
    assert_eq!(count, 8 * 4 * 32 * 32);
    let first = f64::from_le_bytes(bytes[start + 8..start + 16].try_into().unwrap());
    assert_eq!(first, block[[0, 0, 0, 0]]);
    // --format npy,vtk: no CSV.
    assert!(!files(dir).iter().any(|n| n.ends_with(".csv")));
}

#[test]
fn the_stress_command_reproduces_the_solve_stresses_from_the_folder() {
    // Solve without stresses, then ask the folder for the defaults.
    let run = solve(LAYERED, &[], &[]);
    assert_eq!(run.code(), Some(0), "{}", run.stderr());
    let dir = &run.out_dir;
    assert!(!dir.join("stress_xz.npy").exists());
    assert!(read_summary(dir).get("stress").is_none());
    let out = thirdbody(&["stress".as_ref(), dir.as_os_str()]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let later = read_summary(dir);
    // The same as a solve that asked for them.
    let direct = solve(&format!("{LAYERED}\n[stress]\n"), &[], &[]);
    let first = read_summary(&direct.out_dir);
    for key in [
        "tau1_max",
        "tau1_max_x",
        "tau1_max_z",
        "sigma_x_min",
        "sigma_x_max",
    ] {
        assert_eq!(stress_of(&later, key), stress_of(&first, key), "{key}");
    }
    assert_eq!(
        read4(&dir.join("stress_xz.npy")),
        read4(&direct.out_dir.join("stress_xz.npy"))
    );
    // The rest of the summary is kept.
    assert_eq!(later["friction_coefficient"], first["friction_coefficient"]);

    // A request file replaces the case's request.
    let request = run.root.path().join("request.toml");
    std::fs::write(
        &request,
        "[stress]\nsections = [\"block\"]\nmax_depth = 0.02\ndepth_points = 3\n",
    )
    .unwrap();
    let out = thirdbody(&[
        "stress".as_ref(),
        dir.as_os_str(),
        "--request".as_ref(),
        request.as_os_str(),
    ]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(read4(&dir.join("stress_block.npy")).dim(), (11, 3, 32, 32));
    let s = read_summary(dir);
    assert!(
        s["stress"].get("tau1_max").is_none(),
        "no XZ section was asked for"
    );
    assert_eq!(s["stress"]["sections"][0]["name"], "block");
}

/// `thirdbody stress` with `args`: exit code 2, one line naming every `parts`, and
/// the folder exactly as it was.
fn assert_stress_refused(dir: &Path, args: &[&OsStr], parts: &[&str]) {
    let before: Vec<(String, Vec<u8>)> = files(dir)
        .into_iter()
        .map(|n| (n.clone(), std::fs::read(dir.join(&n)).unwrap()))
        .collect();
    let mut all = vec!["stress".as_ref(), dir.as_os_str()];
    all.extend_from_slice(args);
    let out = thirdbody(&all);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    for p in parts {
        assert!(err.contains(p), "{err:?} does not mention {p:?}");
    }
    let after: Vec<(String, Vec<u8>)> = files(dir)
        .into_iter()
        .map(|n| (n.clone(), std::fs::read(dir.join(&n)).unwrap()))
        .collect();
    assert!(before == after, "the folder changed");
}

#[test]
fn bad_stress_requests_are_refused_and_write_nothing() {
    for (lines, parts) in [
        (
            "depth_points = 0",
            &["stress.depth_points", "at least 2"][..],
        ),
        ("max_depth = -1.0", &["stress.max_depth", "> 0"]),
        ("planes = [-0.1]", &["stress.planes[0]", ">= 0"]),
        (
            "sections = [\"interface\"]",
            &["stress.sections", "[coating]"],
        ),
    ] {
        let run = solve(&format!("{LAYERED}\n[stress]\n{lines}\n"), &[], &[]);
        let err = run.stderr();
        assert_eq!(run.code(), Some(2), "{err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        for p in parts {
            assert!(err.contains(p), "{err:?} does not mention {p:?}");
        }
        assert_no_output(&run.out_dir);
    }

    let run = solve(LAYERED, &[], &[]);
    let dir = &run.out_dir;
    let request = run.root.path().join("request.toml");
    std::fs::write(&request, "[stress]\ndepth_points = 0\n").unwrap();
    assert_stress_refused(
        dir,
        &["--request".as_ref(), request.as_os_str()],
        &["stress.depth_points"],
    );
    std::fs::write(&request, "[stres]\n").unwrap();
    assert_stress_refused(
        dir,
        &["--request".as_ref(), request.as_os_str()],
        &["no [stress] section"],
    );
    // An unknown format is refused by the argument parser (exit 2, its own usage hint).
    let out = thirdbody(&[
        "stress".as_ref(),
        dir.as_os_str(),
        "--format".as_ref(),
        "npy,png".as_ref(),
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.lines()
            .next()
            .unwrap()
            .contains("unknown format \"png\""),
        "{err}"
    );
    // A folder that was not written by thirdbody solve.
    let empty = run.root.path().join("empty");
    std::fs::create_dir(&empty).unwrap();
    assert_stress_refused(&empty, &[], &["case.toml", "thirdbody solve"]);
}

#[test]
fn the_stress_command_rebuilds_a_height_map_case_from_the_folder() {
    // A paraboloid written as a height map (nodes on a 0.002 lattice): `solve` copies
    // the map beside case.toml, so the folder alone rebuilds the case, wherever the
    // original map was.
    let (n, h) = (101, 0.002);
    let mut csv = String::new();
    for j in 0..n {
        let y = (j as f64 - (n - 1) as f64 / 2.0) * h;
        let row: Vec<String> = (0..n)
            .map(|i| {
                let x = (i as f64 - (n - 1) as f64 / 2.0) * h;
                format!("{}", (x * x + y * y) / 2.0)
            })
            .collect();
        csv.push_str(&row.join(","));
        csv.push('\n');
    }
    let case = LAYERED.replace(
        "shape = \"sphere\"\nradius = 1.0",
        "shape = \"height_map\"\nfile = \"ball.csv\"\ncell_size = 0.002",
    );
    let direct = solve(&format!("{case}\n[stress]\n"), &[("ball.csv", &csv)], &[]);
    assert_eq!(direct.code(), Some(0), "{}", direct.stderr());
    let run = solve(&case, &[("ball.csv", &csv)], &[]);
    assert_eq!(run.code(), Some(0), "{}", run.stderr());
    assert!(
        run.out_dir.join("ball.csv").exists(),
        "the map is not copied"
    );
    std::fs::remove_file(run.root.path().join("ball.csv")).unwrap();
    let out = thirdbody(&["stress".as_ref(), run.out_dir.as_os_str()]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        read4(&run.out_dir.join("stress_xz.npy")),
        read4(&direct.out_dir.join("stress_xz.npy"))
    );
}

#[test]
fn a_folder_whose_pressure_is_not_its_cases_solution_is_refused() {
    // The problem is rebuilt from case.toml; a pressure from another case (here the
    // same case at twice the load) does not belong to it, and nothing is written.
    let run = solve(LAYERED, &[], &[]);
    assert_eq!(run.code(), Some(0), "{}", run.stderr());
    let other = solve(
        &LAYERED.replace("normal_load = 5e-6", "normal_load = 1e-5"),
        &[],
        &[],
    );
    assert_eq!(other.code(), Some(0), "{}", other.stderr());
    std::fs::copy(
        other.out_dir.join("pressure.npy"),
        run.out_dir.join("pressure.npy"),
    )
    .unwrap();
    assert_stress_refused(
        &run.out_dir,
        &[],
        &["pressure", "not the solution of its case.toml"],
    );
}
