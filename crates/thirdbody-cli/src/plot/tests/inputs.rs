//! Degenerate and invalid input, and sample figures for looking at.

use std::path::PathBuf;

use thirdbody::Grid;

use super::*;
use crate::plot::{field_map, line_plot, section_map, Series};

#[test]
fn bad_input_is_refused_and_leaves_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let grid = Grid::centred(8, 8, 1.0, [0.0, 0.0]).unwrap();
    let mut field = vec![1.0; 64];
    field[10] = f64::NAN;
    let err = |r: anyhow::Result<()>| format!("{:#}", r.unwrap_err());

    let e = err(field_map(
        &dir.path().join("a.png"),
        &grid,
        &field,
        "t",
        "x",
        "y",
        "p",
        None,
    ));
    assert!(e.contains("entry 10 is NaN"), "{e}");
    let ok = vec![1.0; 64];
    let e = err(field_map(
        &dir.path().join("b.svg"),
        &grid,
        &ok,
        "t",
        "x",
        "y",
        "p",
        Some(&field),
    ));
    assert!(e.contains("outline") && e.contains("NaN"), "{e}");
    let e = err(field_map(
        &dir.path().join("c.png"),
        &grid,
        &ok[..63],
        "t",
        "x",
        "y",
        "p",
        None,
    ));
    assert!(e.contains("63 values; expected 64"), "{e}");

    let e = err(section_map(
        &dir.path().join("d.png"),
        &[0.0, 1.0],
        &[0.0, 1.0],
        &[0.0, 1.0, f64::INFINITY, 2.0],
        "t",
        "x",
        "z",
        "s",
        3,
        &[],
    ));
    assert!(e.contains("entry 2 is inf"), "{e}");
    let e = err(section_map(
        &dir.path().join("e.png"),
        &[1.0, 0.0],
        &[0.0, 1.0],
        &[0.0; 4],
        "t",
        "x",
        "z",
        "s",
        3,
        &[],
    ));
    assert!(e.contains("strictly increasing"), "{e}");

    let e = err(line_plot(
        &dir.path().join("f.png"),
        &[],
        "t",
        "x",
        "y",
        false,
    ));
    assert!(e.contains("no series"), "{e}");
    let empty = Series {
        label: "s".into(),
        x: vec![],
        y: vec![],
        dashed: false,
    };
    let e = err(line_plot(
        &dir.path().join("g.png"),
        &[empty],
        "t",
        "x",
        "y",
        false,
    ));
    assert!(e.contains("is empty"), "{e}");
    let nan = Series {
        label: "s".into(),
        x: vec![1.0, 2.0],
        y: vec![0.0, f64::NAN],
        dashed: false,
    };
    let e = err(line_plot(
        &dir.path().join("h.png"),
        &[nan],
        "t",
        "x",
        "y",
        false,
    ));
    assert!(e.contains("y: entry 1 is NaN"), "{e}");
    let neg = Series {
        label: "s".into(),
        x: vec![0.0, 2.0],
        y: vec![0.0, 1.0],
        dashed: false,
    };
    let e = err(line_plot(
        &dir.path().join("i.png"),
        std::slice::from_ref(&neg),
        "t",
        "x",
        "y",
        true,
    ));
    assert!(e.contains("needs every x > 0"), "{e}");
    let e = err(line_plot(
        &dir.path().join("j.pdf"),
        std::slice::from_ref(&neg),
        "t",
        "x",
        "y",
        false,
    ));
    assert!(e.contains(".png or .svg"), "{e}");
    assert!(listing(dir.path()).is_empty(), "{:?}", listing(dir.path()));

    // A folder that does not exist: the error names the file and nothing is created.
    let missing = dir.path().join("no_such_dir").join("k.png");
    let e = err(line_plot(&missing, &[neg], "t", "x", "y", false));
    assert!(e.contains("k.png"), "{e}");
    assert!(listing(dir.path()).is_empty());
}

/// Writes one figure of each kind to $THIRDBODY_PLOT_SAMPLES for looking at them.
#[test]
#[ignore = "writes sample figures for visual inspection"]
fn write_samples() {
    let dir = PathBuf::from(std::env::var("THIRDBODY_PLOT_SAMPLES").unwrap());
    std::fs::create_dir_all(&dir).unwrap();
    for ext in ["png", "svg"] {
        render_field(&dir, &format!("field.{ext}"), true);
        // A Hertz-like subsurface shear stress, changing sign across x = 0.
        let xs: Vec<f64> = (0..120)
            .map(|i| -2.0 + 4.0 * (i as f64 + 0.5) / 120.0)
            .collect();
        let zs: Vec<f64> = (0..60).map(|k| 2.0 * (k as f64 + 0.5) / 60.0).collect();
        let field: Vec<f64> = zs
            .iter()
            .flat_map(|&z| {
                xs.iter()
                    .map(move |&x| -0.3 * x * z * (-(x * x + (z - 0.5).powi(2))).exp())
            })
            .collect();
        section_map(
            &dir.join(format!("section.{ext}")),
            &xs,
            &zs,
            &field,
            "Shear stress τxz under the contact",
            "x/a",
            "z/a",
            "τxz / p0",
            8,
            &[],
        )
        .unwrap();
        let vm: Vec<f64> = zs
            .iter()
            .flat_map(|&z| {
                xs.iter()
                    .map(move |&x| 0.62 * (-(x * x) - 2.0 * (z - 0.48).powi(2)).exp())
            })
            .collect();
        section_map(
            &dir.join(format!("vonmises.{ext}")),
            &xs,
            &zs,
            &vm,
            "Von Mises stress",
            "x/a",
            "z/a",
            "σvM / p0",
            6,
            &[],
        )
        .unwrap();
        let big = Grid::centred(1024, 512, 1.0 / 256.0, [0.0, 0.0]).unwrap();
        let field: Vec<f64> = (0..big.len())
            .map(|k| {
                let (x, y) = (big.x(k % big.nx()), big.y(k / big.nx()));
                (1.0 - (x - 0.3).powi(2) - y * y).max(0.0).sqrt()
            })
            .collect();
        let start = std::time::Instant::now();
        let path = dir.join(format!("big.{ext}"));
        field_map(
            &path,
            &big,
            &field,
            "1024 x 512",
            "x",
            "y",
            "p",
            Some(&field),
        )
        .unwrap();
        eprintln!("1024 x 512 field map to {ext}: {:?}", start.elapsed());
        line_plot(
            &dir.join(format!("lines.{ext}")),
            &two_series(),
            "Friction coefficient against sliding speed",
            "V' = VT/R",
            "μ",
            true,
        )
        .unwrap();
    }
}
