//! `thirdbody reproduce` at a coarse resolution: every figure
//! of the paper (2 to 12) is written as PNG, SVG and CSV, every number in the data
//! and in the report is finite, and the report names every figure with the paper's
//! printed numbers beside ours.

use crate::common;

use std::collections::BTreeMap;
use std::path::Path;

use common::thirdbody;

/// Parses a CSV of numbers (quoted first columns are series labels).
fn csv_rows(path: &Path) -> Vec<(String, Vec<f64>)> {
    let text = std::fs::read_to_string(path).unwrap();
    text.lines()
        .skip(1)
        .map(|line| {
            let mut cells: Vec<&str> = line.split(',').collect();
            let label = if cells[0].starts_with('"') {
                // A label may itself hold commas: join up to the closing quote.
                let end = cells.iter().position(|c| c.ends_with('"')).unwrap();
                let label = cells[..=end].join(",");
                cells.drain(..=end);
                label
            } else {
                String::new()
            };
            let values = cells
                .iter()
                .map(|c| {
                    c.parse::<f64>()
                        .unwrap_or_else(|_| panic!("{}: {c:?} is not a number", path.display()))
                })
                .collect();
            (label, values)
        })
        .collect()
}

#[test]
fn every_figure_is_written_with_finite_data_and_a_report() {
    let root = tempfile::tempdir().unwrap();
    let dir = root.path().join("paper");
    let out = thirdbody(&[
        "reproduce".as_ref(),
        "--out".as_ref(),
        dir.as_os_str(),
        "--cells".as_ref(),
        "32".as_ref(),
        "--points".as_ref(),
        "3".as_ref(),
        "--quiet".as_ref(),
    ]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // The numbers are those recorded before the assembly stage.
    common::recorded::check_reproduce_data(&dir);
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    assert!(!names.iter().any(|n| n.contains(".tmp-")), "{names:?}");

    // Every figure has a plot in both formats and its data.
    for fig in 2..=12 {
        let prefix = format!("fig{fig:02}");
        for ext in ["png", "svg", "csv"] {
            assert!(
                names
                    .iter()
                    .any(|n| n.starts_with(&prefix) && n.ends_with(ext)),
                "no {ext} for Fig. {fig}: {names:?}"
            );
        }
    }
    // PNGs decode to real images; SVGs are SVG.
    for name in names.iter().filter(|n| n.ends_with(".png")) {
        let img = image::open(dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(img.width() >= 400 && img.height() >= 300, "{name}");
        let svg = std::fs::read_to_string(dir.join(name.replace(".png", ".svg"))).unwrap();
        assert!(svg.contains("<svg"), "{name}");
    }
    // Plot texts write the paper's symbols: no ASCII spelling of a Greek letter or a
    // subscript (mu, delta, tau1, sigma_x) is left in a title, label or legend.
    for name in names.iter().filter(|n| n.ends_with(".svg")) {
        let svg = std::fs::read_to_string(dir.join(name)).unwrap();
        for text in svg.split("<text").skip(1) {
            let text = text.split_once('>').unwrap().1.split('<').next().unwrap();
            let words: Vec<&str> = text
                .split(|c: char| !(c.is_alphanumeric() || c == '_'))
                .collect();
            assert!(
                !words.iter().any(|w| {
                    w.contains('_')
                        || ["mu", "delta", "tau", "tau1", "sigma", "nu", "E1", "E2"].contains(w)
                }),
                "{name}: {text:?}"
            );
        }
    }
    // Every number in every CSV is finite, and curves have points.
    let mut curves: BTreeMap<String, Vec<(String, Vec<f64>)>> = BTreeMap::new();
    for name in names.iter().filter(|n| n.ends_with(".csv")) {
        let rows = csv_rows(&dir.join(name));
        assert!(!rows.is_empty(), "{name} is empty");
        for (label, values) in &rows {
            assert!(
                values.iter().all(|v| v.is_finite()),
                "{name}, {label}: {values:?}"
            );
        }
        curves.insert(name.clone(), rows);
    }

    // The report: every figure, the paper's printed numbers beside ours, all finite.
    let report = std::fs::read_to_string(dir.join("report.md")).unwrap();
    for fig in 2..=12 {
        assert!(
            report.contains(&format!("## Fig. {fig}:")),
            "Fig. {fig} missing"
        );
    }
    for paper in ["0.0009820", "0.001320", "34.42", "| 12.00 |", "| 16.00 |"] {
        assert!(
            report.contains(paper),
            "the paper's {paper} is not in the report"
        );
    }
    for line in report
        .lines()
        .filter(|l| l.starts_with("| ") && !l.starts_with("| quantity"))
    {
        let ours = line.split('|').nth(2).unwrap().trim();
        let v: f64 = ours.parse().unwrap_or_else(|_| panic!("{line}"));
        assert!(v.is_finite(), "{line}");
    }

    // Fig. 8 physics (here on a coarse grid): mu falls with V'
    // on every curve, and the nonlinear curves lie below the linear one.
    let fig8 = &curves["fig08a_mu_vs_velocity.csv"];
    let mut by_series: BTreeMap<&str, Vec<(f64, f64)>> = BTreeMap::new();
    for (label, v) in fig8 {
        by_series
            .entry(label.as_str())
            .or_default()
            .push((v[0], v[1]));
    }
    let linear = by_series["\"linear\""].clone();
    assert_eq!(linear.len(), 3);
    for (label, points) in &by_series {
        for w in points.windows(2) {
            assert!(w[1].0 > w[0].0 && w[1].1 < w[0].1, "{label}: {points:?}");
        }
        if *label != "\"linear\"" {
            for (v, m) in points {
                let (_, m_lin) = linear.iter().find(|(w, _)| w == v).unwrap();
                assert!(m < m_lin, "{label} at V' = {v}: {m} not below {m_lin}");
            }
        }
    }
}

#[test]
fn bad_resolutions_are_refused() {
    let root = tempfile::tempdir().unwrap();
    let dir = root.path().join("paper");
    for (flag, value) in [("--cells", "4"), ("--points", "1")] {
        let out = thirdbody(&[
            "reproduce".as_ref(),
            "--out".as_ref(),
            dir.as_os_str(),
            flag.as_ref(),
            value.as_ref(),
        ]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(err.contains(flag) && err.contains(value), "{err}");
        assert!(!dir.exists());
    }
}
