//! Line plots and the texts of SVG output.

use std::path::Path;

use super::*;
use crate::plot::line::log_keys;
use crate::plot::{
    line_plot, line_plot_with, profile_plot, section_map, LineOptions, Series, PROFILE_MARGIN,
};

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
        &[],
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

#[test]
fn a_log_y_axis_is_ticked_at_decades_and_hollow_points_are_explained() {
    let dir = tempfile::tempdir().unwrap();
    // Two curves three decades apart, as a Maxwell and a Kelvin-Voigt layer's mu.
    let x: Vec<f64> = (0..11).map(|k| 10f64.powf(-4.0 + 0.5 * k as f64)).collect();
    let high: Vec<f64> = x.iter().map(|v| 0.02 / (1.0 + v.sqrt())).collect();
    let low: Vec<f64> = x.iter().map(|v| 2e-3 * v / (1.0 + v * v)).collect();
    let series = [
        Series {
            label: "maxwell".into(),
            x: x.clone(),
            y: high,
            dashed: false,
        },
        Series {
            label: "kelvin_voigt".into(),
            x,
            y: low,
            dashed: false,
        },
    ];
    let mut hollow = vec![vec![false; 11], vec![false; 11]];
    hollow[1][0] = true;
    hollow[1][1] = true;
    hollow[0][10] = true;
    let options = LineOptions {
        log_x: true,
        log_y: true,
        hollow,
        hollow_note: "hollow: result carries a warning".into(),
    };
    let path = dir.path().join("mu.svg");
    line_plot_with(&path, &series, "Sweep", "V'", "mu", &options).unwrap();
    let svg = std::fs::read_to_string(&path).unwrap();
    // One ring per warned point and one in the legend; the other 19 points filled.
    let rings = svg
        .split("<circle")
        .skip(1)
        .filter(|c| c.split('>').next().unwrap().contains("fill=\"none\""))
        .count();
    assert_eq!(rings, 3 + 1, "{svg}");
    assert!(svg.contains("hollow: result carries a warning"));
    // The y axis (mu from 2e-7 to 0.02) is labelled at its decades only, as powers of
    // ten; the x axis (1e-4 to 10) too.
    let (x_ticks, y_ticks) = tick_labels(&svg);
    for (label, axis) in [
        ("10\u{207b}\u{2076}", &y_ticks),
        ("10\u{207b}\u{2075}", &y_ticks),
        ("10\u{207b}\u{2074}", &y_ticks),
        ("10\u{207b}\u{b3}", &y_ticks),
        ("10\u{207b}\u{b2}", &y_ticks),
        ("10\u{207b}\u{2074}", &x_ticks),
        ("10\u{b9}", &x_ticks),
    ] {
        assert!(axis.iter().any(|t| t == label), "tick {label} in {axis:?}");
    }
    assert!(!y_ticks.iter().any(|t| t.contains('\u{d7}')), "{y_ticks:?}");
    assert!(
        super::layout::layout_defects(&path).is_empty(),
        "{:?}",
        super::layout::layout_defects(&path)
    );
    // Without hollow points there is no note; a log y axis refuses y <= 0.
    let path = dir.path().join("plain.svg");
    let options = LineOptions {
        log_y: true,
        log_x: true,
        hollow_note: "hollow: result carries a warning".into(),
        ..LineOptions::default()
    };
    line_plot_with(&path, &series, "Sweep", "V'", "mu", &options).unwrap();
    let svg = std::fs::read_to_string(&path).unwrap();
    assert!(!svg.contains("hollow"));
    assert!(!svg.contains("r=\"5\""));
    let mut zero = series.clone();
    zero[1].y[3] = 0.0;
    let e = line_plot_with(&path, &zero, "Sweep", "V'", "mu", &options)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("has y = 0; a logarithmic y axis needs every y > 0"),
        "{e}"
    );
}

#[test]
fn log_ticks_are_decades_then_two_and_five_times_them_then_any() {
    let close = |a: &[f64], b: &[f64]| {
        a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-12 * y)
    };
    let k = log_keys(2e-7, 0.03);
    assert!(close(&k, &[1e-6, 1e-5, 1e-4, 1e-3, 1e-2]), "{k:?}");
    let k = log_keys(1.5e-5, 6e-4);
    assert!(close(&k, &[2e-5, 5e-5, 1e-4, 2e-4, 5e-4]), "{k:?}");
    let k = log_keys(0.25, 0.45);
    assert!(close(&k, &[0.3, 0.4]), "{k:?}");
    // Too narrow for any of those: a linear axis's ticks, inside the range.
    let k = log_keys(0.0285, 0.0299);
    assert!(
        k.len() >= 2 && k.iter().all(|v| (0.0285..=0.0299).contains(v)),
        "{k:?}"
    );
}

#[test]
fn png_lines_are_anti_aliased() {
    // One steep and one shallow straight line: drawn anti-aliased, their edges hold
    // intermediate shades between the line colour (tab10 blue) and the white
    // background; a line drawn in whole pixels has only the two.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("aa.png");
    let series = [Series {
        label: String::new(),
        x: (0..=100).map(|k| k as f64).collect(),
        y: (0..=100)
            .map(|k| {
                if k < 50 {
                    3.0 * k as f64
                } else {
                    150.0 + 0.2 * (k - 50) as f64
                }
            })
            .collect(),
        dashed: false,
    }];
    line_plot(&path, &series, "Line", "x", "y", false).unwrap();
    let img = decode(&path);
    let blue = [31.0, 119.0, 180.0];
    // A pixel that is white * (1 - a) + blue * a with 0.15 < a < 0.85 (within 3 levels).
    let shade = |p: [u8; 3]| {
        let a = (255.0 - p[0] as f64) / (255.0 - blue[0]);
        (0.15..0.85).contains(&a)
            && (0..3).all(|c| {
                let want = 255.0 * (1.0 - a) + blue[c] * a;
                (p[c] as f64 - want).abs() <= 3.0
            })
    };
    let full = img
        .pixels()
        .filter(|p| close(p.0, [31, 119, 180], 3))
        .count();
    let partial = img.pixels().filter(|p| shade(p.0)).count();
    assert!(full > 200, "{full} pixels in the line colour");
    assert!(
        partial * 2 > full,
        "{partial} edge pixels of intermediate shade beside {full} of the line colour"
    );
}

/// The tick labels of a line plot's SVG: (x axis, y axis). Tick labels are the texts in
/// the tick font; those of x are centred under their tick, those of y end at it.
fn tick_labels(svg: &str) -> (Vec<String>, Vec<String>) {
    let size = format!("font-size=\"{}\"", crate::plot::output::TICK_SIZE / 1.24);
    let (mut x, mut y) = (Vec::new(), Vec::new());
    for piece in svg.split("<text").skip(1) {
        let Some((tag, rest)) = piece.split_once('>') else {
            continue;
        };
        let text = rest.split('<').next().unwrap().trim().to_string();
        if !tag.contains(&size) || tag.contains("transform") || text.is_empty() {
            continue;
        }
        if tag.contains("text-anchor=\"middle\"") && tag.contains("dy=\"0.76em\"") {
            x.push(text);
        } else if tag.contains("text-anchor=\"end\"") && tag.contains("dy=\"0.5ex\"") {
            y.push(text);
        }
    }
    (x, y)
}

/// Whether every label of an axis is written one way: all plain decimals or all
/// powers of ten.
fn one_format(labels: &[String]) -> bool {
    let power = |t: &String| {
        t.contains("10")
            && t.chars().any(|c| {
                "\u{207b}\u{2070}\u{b9}\u{b2}\u{b3}\u{2074}\u{2075}\u{2076}\u{2077}\u{2078}\u{2079}"
                    .contains(c)
            })
    };
    let plain = |t: &String| t.parse::<f64>().is_ok();
    labels.iter().all(plain) || labels.iter().all(power)
}

#[test]
fn log_axes_have_one_label_format_enough_labels_and_a_sparse_minor_grid() {
    let dir = tempfile::tempdir().unwrap();
    let curve = |lo: f64, hi: f64| {
        let x: Vec<f64> = (0..8)
            .map(|k| lo * (hi / lo).powf(k as f64 / 7.0))
            .collect();
        let y: Vec<f64> = x.iter().map(|v| 0.01 + v.sqrt()).collect();
        vec![Series {
            label: "curve".into(),
            x,
            y,
            dashed: false,
        }]
    };
    // Paper Figs. 8 (V' from 1e-4 to 0.1), 6 (C' from 0.002 to 0.2), 7 (h1' from 0.001
    // to 0.05), and a sweep over six decades with a logarithmic mu.
    let cases = [
        ("fig08.svg", curve(1e-4, 0.1), false),
        ("fig06.svg", curve(0.002, 0.2), false),
        ("fig07.svg", curve(0.001, 0.05), false),
        ("wide.svg", curve(1e-6, 1.0), true),
    ];
    for (name, series, log_y) in cases {
        let path = dir.path().join(name);
        let options = LineOptions {
            log_x: true,
            log_y,
            ..LineOptions::default()
        };
        line_plot_with(&path, &series, "Sweep", "V'", "mu", &options).unwrap();
        let svg = std::fs::read_to_string(&path).unwrap();
        let (x, y) = tick_labels(&svg);
        assert!(x.len() >= 3, "{name}: x labels {x:?}");
        assert!(one_format(&x), "{name}: x labels {x:?}");
        if log_y {
            assert!(y.len() >= 3, "{name}: y labels {y:?}");
            assert!(one_format(&y), "{name}: y labels {y:?}");
        }
        // Minor grid lines (light grey) never closer than MINOR_GAP (1 px of rounding).
        let mut vertical = Vec::new();
        let mut horizontal = Vec::new();
        for piece in svg.split("<line").skip(1) {
            let tag = format!(" {}", piece.split('>').next().unwrap());
            if super::layout::attr(&tag, "stroke") != Some("#EBEBEB") {
                continue;
            }
            let n = |k: &str| super::layout::num(&tag, k);
            if n("x1") == n("x2") {
                vertical.push(n("x1"));
            } else {
                horizontal.push(n("y1"));
            }
        }
        for (axis, mut lines) in [("vertical", vertical), ("horizontal", horizontal)] {
            lines.sort_by(f64::total_cmp);
            lines.dedup();
            assert!(lines.len() >= 3, "{name}: {axis} minor lines {lines:?}");
            let gap = lines
                .windows(2)
                .map(|w| w[1] - w[0])
                .fold(f64::INFINITY, f64::min);
            assert!(
                gap >= crate::plot::line::MINOR_GAP - 1.0,
                "{name}: {axis} minor lines {gap} px apart: {lines:?}"
            );
        }
    }
    assert_eq!(
        tick_labels(&std::fs::read_to_string(dir.path().join("fig06.svg")).unwrap()).0,
        ["0.002", "0.005", "0.01", "0.02", "0.05", "0.1", "0.2"]
    );
}

#[test]
fn a_profile_frames_the_contact_with_a_margin() {
    // A pressure profile on a window from -1 to 3, in contact from 0 to 1.
    let dir = tempfile::tempdir().unwrap();
    let x: Vec<f64> = (0..400).map(|i| -1.0 + (i as f64 + 0.5) * 0.01).collect();
    let p: Vec<f64> = x
        .iter()
        .map(|&x| {
            if (0.0..1.0).contains(&x) {
                (x * (1.0 - x)).sqrt()
            } else {
                0.0
            }
        })
        .collect();
    let series = [Series {
        label: String::new(),
        x,
        y: p,
        dashed: false,
    }];
    let ticks = |contact: Option<(f64, f64)>| {
        let path = dir.path().join("p.svg");
        profile_plot(&path, &series, "Pressure", "x'", "p'", contact).unwrap();
        let svg = std::fs::read_to_string(&path).unwrap();
        let values: Vec<f64> = tick_labels(&svg)
            .0
            .iter()
            .map(|t| t.parse().unwrap())
            .collect();
        values
    };
    let framed = ticks(Some((0.0, 1.0)));
    let whole = ticks(None);
    let m = PROFILE_MARGIN;
    assert!(
        framed
            .iter()
            .all(|&v| v >= -m - 1e-9 && v <= 1.0 + m + 1e-9),
        "{framed:?}"
    );
    assert!(framed.contains(&0.0) && framed.contains(&1.0), "{framed:?}");
    assert!(whole.iter().any(|&v| v >= 2.0), "{whole:?}");
}

#[test]
fn digits_are_evenly_spaced() {
    // A title of ten equal digits: each glyph's centre of ink lies one advance after the
    // previous, to a fraction of a pixel. Glyphs placed at whole pixels (an advance of
    // 12.3 px drawn as 12 or 13) are off by up to half a pixel.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("digits.png");
    line_plot(&path, &two_series(), "0000000000", "x", "y", false).unwrap();
    let img = decode(&path);
    let strip = crate::plot::output::TITLE_STRIP;
    let ink: Vec<f64> = (0..img.width())
        .map(|x| {
            (0..strip)
                .map(|y| 255.0 - img.get_pixel(x, y).0[0] as f64)
                .sum()
        })
        .collect();
    // Glyphs: runs of columns with ink, and the centre of ink of each.
    let mut centres = Vec::new();
    let mut x = 0;
    while x < ink.len() {
        if ink[x] > 1.0 {
            let start = x;
            while x < ink.len() && ink[x] > 1.0 {
                x += 1;
            }
            let mass: f64 = ink[start..x].iter().sum();
            let moment: f64 = (start..x).map(|k| k as f64 * ink[k]).sum();
            centres.push(moment / mass);
        }
        x += 1;
    }
    assert_eq!(centres.len(), 10, "{centres:?}");
    let steps: Vec<f64> = centres.windows(2).map(|w| w[1] - w[0]).collect();
    let mean = steps.iter().sum::<f64>() / steps.len() as f64;
    assert!(
        steps.iter().all(|s| (s - mean).abs() < 0.2),
        "digit spacing {steps:?}"
    );
}
