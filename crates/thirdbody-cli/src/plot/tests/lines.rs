//! Line plots and the texts of SVG output.

use std::path::Path;

use super::*;
use crate::plot::{line_plot, section_map, Series};

#[test]
fn svg_files_carry_the_texts_and_the_raster() {
    let dir = tempfile::tempdir().unwrap();
    let svg = |p: &Path| std::fs::read_to_string(p).unwrap();

    let path = render_field(dir.path(), "field.svg", true);
    let s = svg(&path);
    // The dimensionless mark is drawn as the prime.
    for t in [
        "Pressure, V\u{2032} = 0.1",
        "x\u{2032}",
        "p\u{2032}",
        "contact boundary",
        "<image",
    ] {
        assert!(s.contains(t), "missing {t}");
    }

    let xs = [0.0, 1.0, 2.0, 3.0];
    let zs = [0.5, 1.0, 2.0];
    let field: Vec<f64> = (0..12).map(|k| (k as f64 - 5.0) * 0.1).collect();
    let path = dir.path().join("section.svg");
    section_map(
        &path,
        &xs,
        &zs,
        &field,
        "Sxx section",
        "x [mm]",
        "z [mm]",
        "Sxx [MPa]",
        3,
    )
    .unwrap();
    let s = svg(&path);
    for t in [
        "Sxx section",
        "x [mm]",
        "z [mm]",
        "Sxx [MPa]",
        "data:image/png;base64,",
    ] {
        assert!(s.contains(t), "missing {t}");
    }

    let path = dir.path().join("lines.svg");
    line_plot(&path, &two_series(), "Friction sweep", "V'", "mu", true).unwrap();
    let s = svg(&path);
    // The ASCII spelling of a symbol is drawn as the symbol.
    for t in ["Friction sweep", "\u{3bc}", "exact", "secant"] {
        assert!(s.contains(t), "missing {t}");
    }
    assert!(s.contains("stroke-dasharray") || s.matches("<polyline").count() > 2);
    assert_eq!(
        listing(dir.path()),
        vec!["field.svg", "lines.svg", "section.svg"]
    );
}

#[test]
fn line_plot_renders_linear_and_log_axes() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("log.png");
    line_plot(&path, &two_series(), "Friction sweep", "V'", "μ", true).unwrap();
    let img = decode(&path);
    assert_eq!(img.dimensions(), (900, 620));
    // Both line colours are present (tab10 blue and orange).
    let has = |c: [u8; 3]| img.pixels().any(|p| p.0 == c);
    assert!(has([31, 119, 180]) && has([255, 127, 14]));

    // One unlabelled series, linear axis, few points (markers): no legend needed.
    let path = dir.path().join("single.PNG");
    let s = Series {
        label: String::new(),
        x: vec![0.0, 1.0, 2.0],
        y: vec![1.0, 3.0, 2.0],
        dashed: false,
    };
    line_plot(
        &path,
        std::slice::from_ref(&s),
        "Profile",
        "x'",
        "p'",
        false,
    )
    .unwrap();
    let img = decode(&path);
    assert!(distinct_colours(&img) > 10);
    assert!(img.pixels().any(|p| p.0 == [31, 119, 180]));
    // The legend frame is grey 160 (#A0A0A0): present with labels, absent without.
    let svg = dir.path().join("single.svg");
    line_plot(&svg, std::slice::from_ref(&s), "Profile", "x'", "p'", false).unwrap();
    assert!(!std::fs::read_to_string(&svg)
        .unwrap()
        .contains(LEGEND_FRAME));
    let svg2 = dir.path().join("two.svg");
    line_plot(&svg2, &two_series(), "Sweep", "V'", "mu", false).unwrap();
    assert!(std::fs::read_to_string(&svg2)
        .unwrap()
        .contains(LEGEND_FRAME));
    assert_eq!(
        listing(dir.path()),
        vec!["log.png", "single.PNG", "single.svg", "two.svg"]
    );
}
