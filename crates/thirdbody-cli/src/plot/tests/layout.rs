//! Layout of every plot kind the CLI writes: rendered to SVG through the
//! public functions, the SVG read back, and each text's box measured with the embedded
//! font and placed as plotters' bitmap backend places it (anchor, rotation). Checked: no
//! two texts overlap, every text lies on the canvas, and the legend box of a line plot
//! covers neither the largest nor the smallest point of any series (nor, on maps, the
//! marked extreme's label). For sections, also the depth range (it holds every drawn
//! contour line and not much more) and the contour lines (no speck, no sliver along the
//! surface).

use std::path::Path;

use plotters::style::IntoFont;

use super::*;
use crate::plot::{
    drawn_levels, line_plot, profile_plot, section_map, shown_depths, Series, LINE_FLOOR, LOBE_CORE,
};

mod data;

/// A pixel box `[x0, y0, x1, y1]`.
type PxBox = [f64; 4];

/// A series line's stroke colour and whether it is one polyline (solid).
type SeriesKey = (String, bool);

/// What the checks need of a rendered SVG.
struct Drawn {
    size: (f64, f64),
    /// Texts and their boxes.
    texts: Vec<(String, PxBox)>,
    /// Legend backgrounds (white at 85 % opacity; drawn by line plots and maps).
    legends: Vec<PxBox>,
    /// A map's plotting area (its first black frame), where every pixel is data.
    frame: Option<PxBox>,
    /// Points of the series' lines (stroke width 2, drawn before the legend), keyed by
    /// stroke colour and whether the line is one polyline (solid) or pieces (dashes).
    series: Vec<(SeriesKey, Vec<(f64, f64)>)>,
}

pub(super) fn attr<'a>(tag: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let start = tag.find(&key)? + key.len();
    let end = start + tag[start..].find('"')?;
    Some(&tag[start..end])
}

pub(super) fn num(tag: &str, name: &str) -> f64 {
    attr(tag, name)
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("attribute {name} in {tag}"))
}

fn unescape(s: &str) -> String {
    s.replace("&apos;", "'")
        .replace("&quot;", "\"")
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&amp;", "&")
}

/// The box of a `<text>` element, as the bitmap backend draws it: plotters-svg writes
/// the anchor as `text-anchor` and `dy` (0.76em top, 0.5ex centre, -0.5ex bottom), the
/// size divided by 1.24, and rotations as `rotate(a, x, y)`.
fn text_box(tag: &str, text: &str) -> PxBox {
    let (x, y) = (num(tag, "x"), num(tag, "y"));
    let size = num(tag, "font-size") * 1.24;
    let font = (super::super::output::FAMILY, size).into_font();
    let ((x0, y0), (x1, y1)) = font.layout_box(text).unwrap();
    let (w, h) = ((x1 - x0) as f64, (y1 - y0) as f64);
    let dx = match attr(tag, "text-anchor") {
        Some("middle") => -(w / 2.0).trunc(),
        Some("end") => -w,
        _ => 0.0,
    };
    let dy = match attr(tag, "dy") {
        Some("0.5ex") => -(h / 2.0).trunc(),
        Some("-0.5ex") => -h,
        _ => 0.0,
    };
    match attr(tag, "transform") {
        // plotters' Rotate270 maps an offset (u, v) to (v, -u); Rotate90 to (-v, u).
        Some(t) if t.starts_with("rotate(270") => [x + dy, y - dx - w, x + dy + h, y - dx],
        Some(t) if t.starts_with("rotate(90") => [x - dy - h, y + dx, x - dy, y + dx + w],
        _ => [x + dx, y + dy, x + dx + w, y + dy + h],
    }
}

fn read_svg(path: &Path) -> Drawn {
    let svg = std::fs::read_to_string(path).unwrap();
    let svg_tag = &svg[svg.find("<svg").unwrap()..];
    let mut drawn = Drawn {
        size: (num(svg_tag, "width"), num(svg_tag, "height")),
        texts: Vec::new(),
        legends: Vec::new(),
        frame: None,
        series: Vec::new(),
    };
    for piece in svg.split('<').skip(1) {
        let (tag, rest) = piece.split_once('>').unwrap_or((piece, ""));
        let tag = format!(" {tag}");
        if tag.starts_with(" text ") {
            let text = unescape(rest.trim());
            if !text.trim().is_empty() {
                let b = text_box(&tag, &text);
                drawn.texts.push((text, b));
            }
        } else if tag.starts_with(" rect ")
            && attr(&tag, "fill") == Some("#FFFFFF")
            && attr(&tag, "opacity") == Some("0.85")
        {
            let (x, y) = (num(&tag, "x"), num(&tag, "y"));
            drawn
                .legends
                .push([x, y, x + num(&tag, "width"), y + num(&tag, "height")]);
        } else if drawn.frame.is_none()
            && tag.starts_with(" rect ")
            && attr(&tag, "fill") == Some("none")
            && attr(&tag, "stroke") == Some("#000000")
        {
            let (x, y) = (num(&tag, "x"), num(&tag, "y"));
            drawn.frame = Some([x, y, x + num(&tag, "width"), y + num(&tag, "height")]);
        } else if tag.starts_with(" polyline ")
            && attr(&tag, "stroke-width") == Some("2")
            && drawn.legends.is_empty()
        {
            let points: Vec<(f64, f64)> = attr(&tag, "points")
                .unwrap()
                .split_whitespace()
                .map(|p| {
                    let (a, b) = p.split_once(',').unwrap();
                    (a.parse().unwrap(), b.parse().unwrap())
                })
                .collect();
            let key = (attr(&tag, "stroke").unwrap().to_string(), points.len() > 2);
            match drawn.series.iter_mut().find(|(k, _)| *k == key) {
                Some((_, all)) => all.extend(points),
                None => drawn.series.push((key, points)),
            }
        }
    }
    drawn
}

fn overlap(a: &PxBox, b: &PxBox) -> bool {
    // One pixel of slack for the rounding of glyph boxes.
    a[0] + 1.0 < b[2] && b[0] + 1.0 < a[2] && a[1] + 1.0 < b[3] && b[1] + 1.0 < a[3]
}

/// Every layout defect found in the SVG at `path`, as readable lines.
pub(super) fn layout_defects(path: &Path) -> Vec<String> {
    let d = read_svg(path);
    let mut defects = Vec::new();
    for (k, (a, ba)) in d.texts.iter().enumerate() {
        if ba[0] < 0.0 || ba[1] < 0.0 || ba[2] > d.size.0 || ba[3] > d.size.1 {
            defects.push(format!("text '{a}' {ba:?} leaves the canvas {:?}", d.size));
        }
        for (b, bb) in &d.texts[k + 1..] {
            if overlap(ba, bb) {
                defects.push(format!("texts '{a}' {ba:?} and '{b}' {bb:?} overlap"));
            }
        }
    }
    // The extreme's label covers no data: it lies outside a map's plotting area.
    if let Some(frame) = &d.frame {
        for (text, b) in &d.texts {
            if text.contains(" at (") && overlap(b, frame) {
                defects.push(format!(
                    "the extreme's label '{text}' {b:?} covers the plotting area {frame:?}"
                ));
            }
        }
    }
    for legend in &d.legends {
        let inside = |p: &(f64, f64)| {
            p.0 >= legend[0] && p.0 <= legend[2] && p.1 >= legend[1] && p.1 <= legend[3]
        };
        for ((colour, solid), points) in &d.series {
            // Pixel y grows downward: the smallest y is the largest value.
            let top = points.iter().min_by(|a, b| a.1.total_cmp(&b.1)).unwrap();
            let bottom = points.iter().max_by(|a, b| a.1.total_cmp(&b.1)).unwrap();
            for (what, p) in [("largest", top), ("smallest", bottom)] {
                if inside(p) {
                    defects.push(format!(
                        "legend {legend:?} covers the {what} point {p:?} of the {} \
                         series drawn in {colour}",
                        if *solid { "solid" } else { "dashed" }
                    ));
                }
            }
        }
        for (text, b) in &d.texts {
            let centre = (0.5 * (b[0] + b[2]), 0.5 * (b[1] + b[3]));
            if text.contains(" at (") && inside(&centre) {
                defects.push(format!("legend {legend:?} covers the extreme's label"));
            }
        }
    }
    defects
}

/// Paper Fig. 7 at 3 points: mu against h1' on a log axis; the linear curve's last point
/// is its largest and lies in the upper right corner.
fn fig07() -> Vec<Series> {
    let x = vec![0.001, 0.007071067811865475, 0.05];
    vec![
        Series {
            label: "linear".into(),
            x: x.clone(),
            y: vec![0.029100853, 0.029278907, 0.029826113],
            dashed: true,
        },
        Series {
            label: "delta = 0.5, p0' = 0.005".into(),
            x,
            y: vec![0.028577227, 0.028770342, 0.029342581],
            dashed: false,
        },
    ]
}

/// Paper Fig. 12b at 32 cells: sigma_x on the surface and both sides of the interface,
/// nonlinear and linear; the interface curves peak in the upper right.
fn fig12b() -> Vec<Series> {
    data::FIG12B
        .iter()
        .map(|(label, dashed, y)| Series {
            label: label.to_string(),
            x: data::FIG12B_X.to_vec(),
            y: y.to_vec(),
            dashed: *dashed,
        })
        .collect()
}

/// A Hertz-like section: (xs, zs, tau1-like field of one sign with its peak under the
/// surface at x = 0.05, sigma_x-like field of both signs confined to z < 0.03).
fn sections() -> (Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>) {
    let xs: Vec<f64> = (0..64)
        .map(|i| -0.043 + (i as f64 + 0.5) * 0.13 / 64.0)
        .collect();
    let zs: Vec<f64> = (0..40).map(|k| (k as f64 + 0.5) * 0.004).collect();
    let mut tau = Vec::new();
    let mut sigma = Vec::new();
    for &z in &zs {
        for &x in &xs {
            let r2 = ((x - 0.03) / 0.03).powi(2) + ((z - 0.012) / 0.02).powi(2);
            tau.push(9e-4 / (1.0 + r2));
            let d = (-((x - 0.035) / 0.02).powi(2)).exp();
            sigma.push(
                -3e-3 * d * (-(z / 0.006)).exp() + 8e-4 * d * (-((z - 0.02) / 0.004).powi(2)).exp(),
            );
        }
    }
    (xs, zs, tau, sigma)
}

#[test]
fn no_plot_kind_overlaps_texts_or_covers_extremes_with_its_legend() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mut paths = Vec::new();
    let mut out = |name: &str| {
        let p = d.join(name);
        paths.push(p.clone());
        p
    };

    // Line plots: a study on a log axis, a profile along x with six curves, a linear
    // two-curve sweep, a single unlabelled curve.
    line_plot(
        &out("fig07.svg"),
        &fig07(),
        "Friction against coating thickness (Fig. 7)",
        "h1'",
        "mu",
        true,
    )
    .unwrap();
    profile_plot(
        &out("fig12b.svg"),
        &fig12b(),
        "sigma_x, h1' = 0.02 (Fig. 12b)",
        "x'",
        "sigma_x / E2",
        None,
    )
    .unwrap();
    line_plot(
        &out("sweep.svg"),
        &two_series(),
        "Friction sweep",
        "V'",
        "mu",
        true,
    )
    .unwrap();
    let mut linear = two_series();
    for s in &mut linear {
        s.x.iter_mut().for_each(|x| *x = x.log10());
    }
    line_plot(
        &out("linear.svg"),
        &linear,
        "Friction sweep",
        "log V'",
        "mu",
        false,
    )
    .unwrap();
    let single = [Series {
        label: String::new(),
        ..linear[0].clone()
    }];
    profile_plot(
        &out("pressure_x.svg"),
        &single,
        "Pressure along x through the centre",
        "x'",
        "p'",
        None,
    )
    .unwrap();

    // Maps: a surface field with the contact boundary, a tall narrow grid, sections of
    // one sign and of both signs.
    let _ = render_field(d, "pressure_map.svg", true);
    paths.push(d.join("pressure_map.svg"));
    let (grid, _, hertz) = disc_case();
    let tall = thirdbody::Grid::centred(grid.ny(), grid.nx(), grid.cell(), [0.0, 0.0]).unwrap();
    let transposed: Vec<f64> = (0..tall.len())
        .map(|k| hertz[(k % tall.nx()) * grid.nx() + k / tall.nx()])
        .collect();
    let p = d.join("tall.svg");
    crate::plot::field_map(
        &p,
        &tall,
        &transposed,
        "Layer compliance",
        "x'",
        "y'",
        "C'",
        Some(&transposed),
    )
    .unwrap();
    paths.push(p);
    let (xs, zs, tau, sigma) = sections();
    let p = d.join("tau1.svg");
    section_map(
        &p,
        &xs,
        &zs,
        &tau,
        "tau1, delta = 0.01 (Fig. 10a)",
        "x'",
        "z' (depth)",
        "tau1 / E2",
        10,
        &[],
    )
    .unwrap();
    paths.push(p);
    let p = d.join("sigma_x.svg");
    section_map(
        &p,
        &xs,
        &zs,
        &sigma,
        "sigma_x in the plane y = 0",
        "x'",
        "z' (depth)",
        "sigma_x / E2",
        10,
        &[0.02],
    )
    .unwrap();
    paths.push(p);

    let defects: Vec<String> = paths
        .iter()
        .flat_map(|p| {
            let name = p.file_name().unwrap().to_string_lossy().into_owned();
            layout_defects(p)
                .into_iter()
                .map(move |e| format!("{name}: {e}"))
        })
        .collect();
    assert!(defects.is_empty(), "{}", defects.join("\n"));
}

#[test]
fn the_checks_see_overlapping_labels_and_a_covering_legend() {
    // Hand-made SVG in plotters' format: two tick labels one on the other, and a legend
    // over a series' top point.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.svg");
    let t = |x: i32, s: &str| {
        format!(
            "<text x=\"{x}\" y=\"550\" dy=\"0.76em\" text-anchor=\"middle\" \
             font-family=\"sans-serif\" font-size=\"13.709677419354838\" opacity=\"1\" \
             fill=\"#000000\">{s}</text>"
        )
    };
    let svg = format!(
        "<svg width=\"900\" height=\"620\" viewBox=\"0 0 900 620\" \
         xmlns=\"http://www.w3.org/2000/svg\">\n{}\n{}\n\
         <polyline fill=\"none\" opacity=\"1\" stroke=\"#1F77B4\" stroke-width=\"2\" \
         points=\"100,300 500,200 860,70 \"/>\n\
         <rect x=\"613\" y=\"50\" width=\"266\" height=\"60\" opacity=\"0.85\" \
         fill=\"#FFFFFF\" stroke=\"none\"/>\n\
         <rect x=\"100\" y=\"40\" width=\"700\" height=\"400\" fill=\"none\" \
         stroke=\"#000000\"/>\n{}\n</svg>",
        t(400, "0.005"),
        t(420, "0.006"),
        t(300, "-0.00383 at (0.0468, 0)").replace("y=\"550\"", "y=\"38\"")
    );
    std::fs::write(&path, svg).unwrap();
    // The font is registered by any rendering.
    let _ = render_field(dir.path(), "f.svg", false);
    let defects = layout_defects(&path);
    assert!(defects.iter().any(|e| e.contains("overlap")), "{defects:?}");
    assert!(
        defects.iter().any(|e| e.contains("largest point")),
        "{defects:?}"
    );
    assert!(
        !defects.iter().any(|e| e.contains("smallest point")),
        "{defects:?}"
    );
    assert!(
        defects
            .iter()
            .any(|e| e.contains("label '-0.00383 at (0.0468, 0)'") && e.contains("covers")),
        "{defects:?}"
    );
}

/// Checks the SVG figures of a `thirdbody reproduce` or `solve` output folder named by
/// THIRDBODY_LAYOUT_DIR (skipped without it).
#[test]
#[ignore = "needs THIRDBODY_LAYOUT_DIR"]
fn figures_in_a_folder_are_laid_out_cleanly() {
    let Ok(dir) = std::env::var("THIRDBODY_LAYOUT_DIR") else {
        return;
    };
    let scratch = tempfile::tempdir().unwrap();
    let _ = render_field(scratch.path(), "font.svg", false);
    let mut report = Vec::new();
    for name in listing(Path::new(&dir)) {
        if name.ends_with(".svg") {
            for e in layout_defects(&Path::new(&dir).join(&name)) {
                report.push(format!("{name}: {e}"));
            }
        }
    }
    assert!(report.is_empty(), "{}", report.join("\n"));
}

/// The frame of a map's plotting area and its contour lines (pixel points per piece) in
/// an SVG written by `section_map`.
fn frame_and_contours(path: &Path) -> (PxBox, Vec<Vec<(f64, f64)>>) {
    let svg = std::fs::read_to_string(path).unwrap();
    let mut frame = None;
    let mut pieces = Vec::new();
    for piece in svg.split('<').skip(1) {
        let tag = format!(" {}", piece.split_once('>').map_or(piece, |t| t.0));
        // The first frame is the plotting area's (the colour bar's comes later).
        if frame.is_none()
            && tag.starts_with(" rect ")
            && attr(&tag, "fill") == Some("none")
            && attr(&tag, "stroke") == Some("#000000")
        {
            let (x, y) = (num(&tag, "x"), num(&tag, "y"));
            frame = Some([x, y, x + num(&tag, "width"), y + num(&tag, "height")]);
        } else if tag.starts_with(" polyline ") && attr(&tag, "opacity") == Some("0.75") {
            pieces.push(
                attr(&tag, "points")
                    .unwrap()
                    .split_whitespace()
                    .map(|p| {
                        let (a, b) = p.split_once(',').unwrap();
                        (a.parse().unwrap(), b.parse().unwrap())
                    })
                    .collect(),
            );
        }
    }
    (frame.expect("no frame"), pieces)
}

/// The XZ section of tau1 under the paper's Fig. 10a case at 64 cells (the example
/// file's case with a coarser grid): (xs, zs, tau1).
fn fig10a_tau1() -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let text = include_str!("../../../../../examples/paper_fig10a.toml")
        .replace("cells = [128, 128]", "cells = [64, 64]");
    let file = thirdbody::case_file::parse_case_file(&text, &mut |_, _| unreachable!()).unwrap();
    let solution = thirdbody::solve(&file.case, &file.solver).unwrap();
    let request = thirdbody::stress::StressRequest {
        sections: Some(vec![thirdbody::stress::SectionKind::Xz]),
        ..Default::default()
    };
    let results = request
        .compute(&file.case.body, &solution.grid, &solution.pressure)
        .unwrap();
    let f = &results.sections[0].1;
    (f.xs.clone(), f.zs.clone(), f.tau1())
}

#[test]
fn a_paper_section_shows_its_lines_without_specks_or_slivers_and_little_more() {
    // Paper Fig. 10a: tau1 fades slowly with depth (8 % of its peak at the section's
    // bottom, three contact half-lengths), while its structure is near the surface.
    let (xs, zs, tau) = fig10a_tau1();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("fig10a.svg");
    section_map(
        &path,
        &xs,
        &zs,
        &tau,
        "tau1",
        "x'",
        "z' (depth)",
        "tau1 / E2",
        10,
        &[],
    )
    .unwrap();
    let (frame, pieces) = frame_and_contours(&path);
    let (nx, nz) = (xs.len(), zs.len());
    let (lo, hi) = crate::plot::colour::min_max(&tau);
    let shown = shown_depths(&zs, nx, &tau, &drawn_levels(lo, hi, 10), &[]);
    assert!(shown < nz * 3 / 4, "{shown} of {nz} depths shown");
    let (cell_px, row_px) = (
        (frame[2] - frame[0]) / nx as f64,
        (frame[3] - frame[1]) / shown as f64,
    );
    assert!(!pieces.is_empty());
    let deepest = pieces.iter().flatten().map(|p| p.1).fold(0.0, f64::max);
    let below = frame[3] - deepest;
    assert!(
        below > 0.0 && below < 0.2 * (frame[3] - frame[1]),
        "the deepest contour point is {below} px above the panel's bottom {frame:?}"
    );
    for piece in &pieces {
        let span = |c: fn(&(f64, f64)) -> f64| {
            let (a, b) = piece
                .iter()
                .map(c)
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                    (a.min(v), b.max(v))
                });
            (a, b - a)
        };
        let ((_, w), (top, h)) = (span(|p| p.0), span(|p| p.1));
        assert!(
            w >= 2.5 * cell_px || h >= 2.5 * row_px,
            "a speck of {w} x {h} px at the top {top}"
        );
        assert!(
            top + h > frame[1] + 1.5 * row_px,
            "a sliver along the surface: {w} px long, {h} px deep"
        );
    }
}

#[test]
fn section_depths_hold_the_drawn_levels_and_deeper_maxima() {
    let (xs, zs, tau, sigma) = sections();
    let (nx, nz) = (xs.len(), zs.len());
    let row_reaches = |field: &[f64], k: usize, l: f64| {
        let row = &field[k * nx..(k + 1) * nx];
        if l > 0.0 {
            row.iter().any(|&v| v >= l)
        } else {
            row.iter().any(|&v| v <= l)
        }
    };
    for (name, field) in [("tau1", &tau), ("sigma_x", &sigma)] {
        let (lo, hi) = crate::plot::colour::min_max(field);
        let levels = drawn_levels(lo, hi, 10);
        let peak = lo.abs().max(hi.abs());
        assert!(!levels.is_empty());
        // Low levels go, but a weaker lobe of the other sign keeps its core.
        let extreme = |l: f64| if l > 0.0 { hi } else { lo };
        assert!(
            levels
                .iter()
                .all(|&l| l.abs() >= LINE_FLOOR * peak || l / extreme(l) >= LOBE_CORE),
            "{levels:?}"
        );
        assert!(levels.iter().all(|l| l.abs() >= 0.1 * peak), "{levels:?}");
        let shown = shown_depths(&zs, nx, field, &levels, &[]);
        // Every row where a drawn level is reached is shown, with the next row.
        let deepest = (0..nz)
            .filter(|&k| levels.iter().any(|&l| row_reaches(field, k, l)))
            .max()
            .unwrap();
        assert!(
            shown >= deepest + 2,
            "{name}: {shown} rows, level reached at {deepest}"
        );
        // Not much more: the margin (a tenth of the depth, two rows).
        let z_end = 1.1 * zs[deepest] + 2.0 * (zs[1] - zs[0]);
        assert!(
            zs[shown - 1] <= z_end,
            "{name}: {shown} rows to z = {}",
            zs[shown - 1]
        );
        assert!(shown < nz, "{name}: all {nz} rows shown");
    }
    // sigma_x: the tension at z = 0.02 (a quarter of the peak) has its own line.
    let (lo, hi) = crate::plot::colour::min_max(&sigma);
    assert!(drawn_levels(lo, hi, 10).iter().any(|&l| l > 0.0));

    // A deeper maximum below the floor (10 % of the peak at z = 0.12) stays in the
    // picture, though no line is drawn around it.
    let mut deep = tau.clone();
    for (k, &z) in zs.iter().enumerate() {
        for i in 0..nx {
            deep[k * nx + i] += 9e-5 * (-((z - 0.12) / 0.01).powi(2)).exp();
        }
    }
    let (lo, hi) = crate::plot::colour::min_max(&deep);
    let shown = shown_depths(&zs, nx, &deep, &drawn_levels(lo, hi, 10), &[]);
    assert!(zs[shown - 1] > 0.12, "{shown} rows");

    // An interface below where the field lives is shown, with the margin below it.
    let (lo, hi) = crate::plot::colour::min_max(&sigma);
    let levels = drawn_levels(lo, hi, 10);
    let without = shown_depths(&zs, nx, &sigma, &levels, &[]);
    let shown = shown_depths(&zs, nx, &sigma, &levels, &[0.1]);
    assert!(zs[without - 1] < 0.1, "{without} rows");
    assert!(zs[shown - 1] >= 0.1, "{shown} rows");
    assert!(
        zs[shown - 1] <= 0.11 + 2.0 * (zs[1] - zs[0]),
        "{shown} rows"
    );

    // A field still growing at the bottom keeps every row; a field confined to the
    // surface row shows three rows (no blank rows below it); a zero field keeps every
    // row.
    let growing: Vec<f64> = zs.iter().flat_map(|&z| xs.iter().map(move |_| z)).collect();
    let (lo, hi) = crate::plot::colour::min_max(&growing);
    assert_eq!(
        shown_depths(&zs, nx, &growing, &drawn_levels(lo, hi, 10), &[]),
        nz
    );
    let surface: Vec<f64> = (0..nz * nx)
        .map(|n| if n < nx { -1.0 } else { 0.0 })
        .collect();
    assert_eq!(
        shown_depths(&zs, nx, &surface, &drawn_levels(-1.0, 0.0, 10), &[]),
        3
    );
    assert_eq!(shown_depths(&zs, nx, &vec![0.0; nz * nx], &[], &[]), nz);
}
