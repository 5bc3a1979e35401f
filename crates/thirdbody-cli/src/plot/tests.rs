//! Rendering tests: every figure kind to PNG and SVG, checked on the decoded pixels
//! (geometry of known shapes, orientation, colours) and on the SVG text; degenerate input.

use std::path::{Path, PathBuf};

use image::RgbImage;
use thirdbody::Grid;

use super::{field_map, line_plot, section_map, Series};

const VIRIDIS_LOW: [u8; 3] = [68, 1, 84];
const VIRIDIS_HIGH: [u8; 3] = [254, 232, 37];
/// Colour of the legend frame of line plots in SVG (no other element uses it).
const LEGEND_FRAME: &str = "#A0A0A0";

/// Width and height from the IHDR chunk, after checking the PNG signature.
fn png_size(path: &Path) -> (u32, u32) {
    let bytes = std::fs::read(path).unwrap();
    assert_eq!(
        &bytes[..8],
        &[137, 80, 78, 71, 13, 10, 26, 10],
        "PNG signature"
    );
    assert_eq!(&bytes[12..16], b"IHDR");
    let be = |k: usize| u32::from_be_bytes(bytes[k..k + 4].try_into().unwrap());
    (be(16), be(20))
}

/// Decodes a PNG with the `image` crate and checks it against the IHDR size.
fn decode(path: &Path) -> RgbImage {
    let size = png_size(path);
    let img = image::open(path).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), size);
    img
}

fn distinct_colours(img: &RgbImage) -> usize {
    let mut set = std::collections::HashSet::new();
    for p in img.pixels() {
        set.insert(p.0);
    }
    set.len()
}

/// Bounding box (x0, y0, x1, y1 inclusive) of pixels left of `x_limit` that satisfy `f`.
fn bbox(img: &RgbImage, x_limit: u32, f: impl Fn([u8; 3]) -> bool) -> Option<[u32; 4]> {
    let mut b: Option<[u32; 4]> = None;
    for (x, y, p) in img.enumerate_pixels() {
        if x < x_limit && f(p.0) {
            let e = b.get_or_insert([x, y, x, y]);
            *e = [e[0].min(x), e[1].min(y), e[2].max(x), e[3].max(y)];
        }
    }
    b
}

fn close(p: [u8; 3], q: [u8; 3], tol: i32) -> bool {
    (0..3).all(|c| (p[c] as i32 - q[c] as i32).abs() <= tol)
}

/// Files in `dir` (names), sorted.
fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// Grid of 96 x 48 cells of side 1/24 (window 4 x 2 centred on the origin) and a field
/// equal to 1 on the disc of radius 0.8 centred at (0.5, 0), 0 elsewhere; also the
/// Hertz-like pressure sqrt(1 - (r/0.8)^2) on that disc.
fn disc_case() -> (Grid, Vec<f64>, Vec<f64>) {
    let grid = Grid::centred(96, 48, 1.0 / 24.0, [0.0, 0.0]).unwrap();
    let mut indicator = vec![0.0; grid.len()];
    let mut hertz = vec![0.0; grid.len()];
    for j in 0..grid.ny {
        for i in 0..grid.nx {
            let r = ((grid.x(i) - 0.5).powi(2) + grid.y(j).powi(2)).sqrt() / 0.8;
            if r < 1.0 {
                indicator[j * grid.nx + i] = 1.0;
                hertz[j * grid.nx + i] = (1.0 - r * r).sqrt();
            }
        }
    }
    (grid, indicator, hertz)
}

fn render_field(dir: &Path, name: &str, outline: bool) -> PathBuf {
    let (grid, _, hertz) = disc_case();
    let path = dir.join(name);
    field_map(
        &path,
        &grid,
        &hertz,
        "Pressure, V' = 0.1",
        "x'",
        "y'",
        "p'",
        outline.then_some(hertz.as_slice()),
    )
    .unwrap();
    path
}

#[test]
fn field_map_keeps_equal_aspect_and_places_the_disc() {
    let dir = tempfile::tempdir().unwrap();
    let (grid, indicator, _) = disc_case();
    let path = dir.path().join("disc.png");
    field_map(&path, &grid, &indicator, "Disc", "x'", "y'", "p'", None).unwrap();
    let img = decode(&path);
    let map_right = img.width() - super::colour::BAR_STRIP;
    // The window (dark purple outside the disc, yellow inside) and the disc, in pixels.
    let window = bbox(&img, map_right, |p| {
        close(p, VIRIDIS_LOW, 2) || close(p, VIRIDIS_HIGH, 2)
    })
    .unwrap();
    let disc = bbox(&img, map_right, |p| close(p, VIRIDIS_HIGH, 2)).unwrap();
    let (ww, wh) = (window[2] - window[0] + 1, window[3] - window[1] + 1);
    let (dw, dh) = (disc[2] - disc[0] + 1, disc[3] - disc[1] + 1);
    // Window 4 x 2: aspect 2 within a pixel or two.
    assert!(((ww as f64 / wh as f64) - 2.0).abs() < 0.02, "{ww} x {wh}");
    // Disc of diameter 1.6 in a window 4 wide: 40 % of it, round (equal scales).
    assert!(((dw as f64 / ww as f64) - 0.4).abs() < 0.02, "{dw} / {ww}");
    assert!(((dw as f64 / dh as f64) - 1.0).abs() < 0.03, "{dw} x {dh}");
    // Centre at x = 0.5 (5/8 of the window from its left edge), y = 0 (half height).
    let cx = 0.5 * (disc[0] + disc[2]) as f64 - window[0] as f64;
    let cy = 0.5 * (disc[1] + disc[3]) as f64 - window[1] as f64;
    assert!((cx / ww as f64 - 0.625).abs() < 0.01, "cx = {cx}");
    assert!((cy / wh as f64 - 0.5).abs() < 0.01, "cy = {cy}");
    assert_eq!(listing(dir.path()), vec!["disc.png"]);
}

#[test]
fn legend_goes_to_the_emptiest_corner() {
    use super::map::Corner;
    // 12 x 12 cells; rows run upwards, so row 11 is the top.
    let upper_right_full = |k: usize| k % 12 >= 8 && k / 12 >= 10;
    assert_eq!(
        Corner::emptiest(12, 12, upper_right_full),
        Corner::UpperLeft
    );
    let upper_full = |k: usize| k / 12 >= 10;
    assert_eq!(Corner::emptiest(12, 12, upper_full), Corner::LowerRight);
    assert_eq!(Corner::emptiest(12, 12, |_| false), Corner::UpperRight);
}

#[test]
fn field_map_outline_lies_on_the_contact_edge() {
    let dir = tempfile::tempdir().unwrap();
    let plain = decode(&render_field(dir.path(), "plain.png", false));
    let outlined = decode(&render_field(dir.path(), "outlined.png", true));
    assert_eq!(plain.dimensions(), outlined.dimensions());
    assert!(
        distinct_colours(&plain) > 100,
        "a smooth map has many colours"
    );
    let map_right = plain.width() - super::colour::BAR_STRIP;
    let window = bbox(&plain, map_right, |p| close(p, VIRIDIS_LOW, 2)).unwrap();
    let ww = (window[2] - window[0] + 1) as f64;
    let px_per_unit = ww / 4.0;
    let inside = |x: u32, y: u32| {
        x > window[0] + 3 && x + 3 < window[2] && y > window[1] + 3 && y + 3 < window[3]
    };
    // The legend box: 85 % white over the dark purple.
    let legend = bbox(&outlined, map_right, |p| close(p, [227, 217, 229], 3)).unwrap();
    let in_legend = |x: u32, y: u32| {
        (legend[0]..=legend[2]).contains(&x) && (legend[1]..=legend[3]).contains(&y)
    };
    // Pure white never occurs in viridis: inside the window it is the outline only.
    let white = |img: &RgbImage| -> Vec<(u32, u32)> {
        img.enumerate_pixels()
            .filter(|&(x, y, p)| inside(x, y) && !in_legend(x, y) && p.0 == [255, 255, 255])
            .map(|(x, y, _)| (x, y))
            .collect()
    };
    assert!(white(&plain).is_empty());
    let line = white(&outlined);
    assert!(line.len() > 200, "{} outline pixels", line.len());
    // Every outline pixel lies within about a cell of the circle r = 0.8 around (0.5, 0).
    let centre_x = window[0] as f64 + 0.5 + 2.5 * px_per_unit;
    let centre_y = window[1] as f64 + 0.5 * (window[3] - window[1] + 1) as f64;
    for &(x, y) in &line {
        let r = ((x as f64 + 0.5 - centre_x).hypot(y as f64 + 0.5 - centre_y)) / px_per_unit;
        assert!(
            (r - 0.8).abs() < 1.5 / 24.0 + 0.02,
            "outline pixel at r = {r}"
        );
    }
}

#[test]
fn section_map_draws_depth_downward_and_marks_the_extreme() {
    let dir = tempfile::tempdir().unwrap();
    let xs: Vec<f64> = (0..60)
        .map(|i| -1.5 + 3.0 * (i as f64 + 0.5) / 60.0)
        .collect();
    let zs: Vec<f64> = (0..40).map(|k| 2.0 * (k as f64 + 0.5) / 40.0).collect();
    // One sign, growing with depth: dark at the surface (top), bright at depth (bottom).
    let field: Vec<f64> = zs.iter().flat_map(|&z| xs.iter().map(move |_| z)).collect();
    let path = dir.path().join("depth.png");
    section_map(&path, &xs, &zs, &field, "Depth", "x'", "z'", "z'", 4).unwrap();
    let img = decode(&path);
    let map_right = img.width() - super::colour::BAR_STRIP;
    let window = bbox(&img, map_right, |p| {
        close(p, VIRIDIS_LOW, 12) || close(p, VIRIDIS_HIGH, 12)
    })
    .unwrap();
    let mid_x = (window[0] + window[2]) / 2 - 40;
    let top = img.get_pixel(mid_x, window[1] + 1).0;
    let bottom = img.get_pixel(mid_x, window[3] - 1).0;
    assert!(close(top, VIRIDIS_LOW, 12), "top {top:?}");
    assert!(close(bottom, VIRIDIS_HIGH, 12), "bottom {bottom:?}");
    // Window 3 wide, 2 deep: equal scales.
    let (ww, wh) = (window[2] - window[0] + 1, window[3] - window[1] + 1);
    assert!(((ww as f64 / wh as f64) - 1.5).abs() < 0.03, "{ww} x {wh}");

    // A field that changes sign (x): diverging map, blue on the left, red on the right,
    // white in the middle.
    let field: Vec<f64> = zs.iter().flat_map(|_| xs.iter().copied()).collect();
    let path = dir.path().join("sign.png");
    section_map(&path, &xs, &zs, &field, "Sign", "x'", "z'", "σxx'", 0).unwrap();
    let img = decode(&path);
    let y = (window[1] + window[3]) / 2 + 30;
    let left = img.get_pixel(window[0] + 2, y).0;
    let right = img.get_pixel(window[2] - 2, y).0;
    assert!(
        left[2] as i32 > left[0] as i32 + 40,
        "left {left:?} is blue"
    );
    assert!(
        right[0] as i32 > right[2] as i32 + 40,
        "right {right:?} is red"
    );
    assert_eq!(
        listing(dir.path()),
        vec!["depth.png".to_string(), "sign.png".to_string()]
    );
}

#[test]
fn svg_files_carry_the_texts_and_the_raster() {
    let dir = tempfile::tempdir().unwrap();
    let svg = |p: &Path| std::fs::read_to_string(p).unwrap();

    let path = render_field(dir.path(), "field.svg", true);
    let s = svg(&path);
    for t in [
        "Pressure, V&apos; = 0.1",
        "x&apos;",
        "p&apos;",
        "contact boundary",
        "<image",
    ] {
        assert!(
            s.contains(t) || s.contains(&t.replace("&apos;", "'")),
            "missing {t}"
        );
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
    for t in ["Friction sweep", "mu", "exact", "secant"] {
        assert!(s.contains(t), "missing {t}");
    }
    assert!(s.contains("stroke-dasharray") || s.matches("<polyline").count() > 2);
    assert_eq!(
        listing(dir.path()),
        vec!["field.svg", "lines.svg", "section.svg"]
    );
}

fn two_series() -> Vec<Series> {
    let x: Vec<f64> = (0..41)
        .map(|k| 10f64.powf(-2.0 + k as f64 / 10.0))
        .collect();
    let y1: Vec<f64> = x.iter().map(|v| v / (1.0 + v * v)).collect();
    let y2: Vec<f64> = x.iter().map(|v| 0.8 * v / (1.0 + 0.5 * v * v)).collect();
    vec![
        Series {
            label: "exact".into(),
            x: x.clone(),
            y: y1,
            dashed: false,
        },
        Series {
            label: "secant".into(),
            x,
            y: y2,
            dashed: true,
        },
    ]
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
fn constant_and_zero_fields_draw_one_flat_colour() {
    let dir = tempfile::tempdir().unwrap();
    let grid = Grid::centred(16, 16, 0.25, [0.0, 0.0]).unwrap();
    for (name, v) in [("zero.png", 0.0), ("const.png", 2.5)] {
        let path = dir.path().join(name);
        let field = vec![v; grid.len()];
        field_map(&path, &grid, &field, "Flat", "x", "y", "p", Some(&field)).unwrap();
        let img = decode(&path);
        let map_right = img.width() - super::colour::BAR_STRIP;
        // The centre of the map has the middle colour of viridis throughout.
        let teal = |p: [u8; 3]| p[1] as i32 > p[0] as i32 + 40 && p[2] as i32 > p[0] as i32 + 40;
        let window = bbox(&img, map_right, teal).unwrap();
        let c = img
            .get_pixel((window[0] + window[2]) / 2, (window[1] + window[3]) / 2)
            .0;
        for x in window[0] + 5..window[2] - 5 {
            assert_eq!(
                img.get_pixel(x, (window[1] + window[3]) / 2).0,
                c,
                "{name} {window:?} x {x}"
            );
        }
    }
    // A constant section and a constant series are fine too.
    let path = dir.path().join("flat_section.svg");
    section_map(
        &path,
        &[0.0, 1.0],
        &[0.0, 1.0],
        &[3.0; 4],
        "Flat",
        "x",
        "z",
        "s",
        5,
    )
    .unwrap();
    let path = dir.path().join("flat_line.png");
    let s = Series {
        label: "c".into(),
        x: vec![1.0, 1.0],
        y: vec![2.0, 2.0],
        dashed: false,
    };
    line_plot(&path, &[s], "Flat", "x", "y", true).unwrap();
    assert_eq!(listing(dir.path()).len(), 4);
}

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
        )
        .unwrap();
        let big = Grid::centred(1024, 512, 1.0 / 256.0, [0.0, 0.0]).unwrap();
        let field: Vec<f64> = (0..big.len())
            .map(|k| {
                let (x, y) = (big.x(k % big.nx), big.y(k / big.nx));
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
