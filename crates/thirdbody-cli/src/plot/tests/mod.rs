//! Rendering tests: every figure kind to PNG and SVG, checked on the decoded pixels
//! (geometry of known shapes, orientation, colours) and on the SVG text; degenerate input.

use std::path::{Path, PathBuf};

use image::RgbImage;
use thirdbody::Grid;

use super::{field_map, Series};

mod inputs;
mod layout;
mod lines;
mod maps;

pub(super) const VIRIDIS_LOW: [u8; 3] = [68, 1, 84];
pub(super) const VIRIDIS_HIGH: [u8; 3] = [254, 232, 37];
/// Colour of the legend frame of line plots in SVG (no other element uses it).
pub(super) const LEGEND_FRAME: &str = "#A0A0A0";

/// Width and height from the IHDR chunk, after checking the PNG signature.
pub(super) fn png_size(path: &Path) -> (u32, u32) {
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
pub(super) fn decode(path: &Path) -> RgbImage {
    let size = png_size(path);
    let img = image::open(path).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), size);
    img
}

pub(super) fn distinct_colours(img: &RgbImage) -> usize {
    let mut set = std::collections::HashSet::new();
    for p in img.pixels() {
        set.insert(p.0);
    }
    set.len()
}

/// Bounding box (x0, y0, x1, y1 inclusive) of pixels left of `x_limit` that satisfy `f`.
pub(super) fn bbox(img: &RgbImage, x_limit: u32, f: impl Fn([u8; 3]) -> bool) -> Option<[u32; 4]> {
    let mut b: Option<[u32; 4]> = None;
    for (x, y, p) in img.enumerate_pixels() {
        if x < x_limit && f(p.0) {
            let e = b.get_or_insert([x, y, x, y]);
            *e = [e[0].min(x), e[1].min(y), e[2].max(x), e[3].max(y)];
        }
    }
    b
}

pub(super) fn close(p: [u8; 3], q: [u8; 3], tol: i32) -> bool {
    (0..3).all(|c| (p[c] as i32 - q[c] as i32).abs() <= tol)
}

/// Files in `dir` (names), sorted.
pub(super) fn listing(dir: &Path) -> Vec<String> {
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
pub(super) fn disc_case() -> (Grid, Vec<f64>, Vec<f64>) {
    let grid = Grid::centred(96, 48, 1.0 / 24.0, [0.0, 0.0]).unwrap();
    let mut indicator = vec![0.0; grid.len()];
    let mut hertz = vec![0.0; grid.len()];
    for j in 0..grid.ny() {
        for i in 0..grid.nx() {
            let r = ((grid.x(i) - 0.5).powi(2) + grid.y(j).powi(2)).sqrt() / 0.8;
            if r < 1.0 {
                indicator[j * grid.nx() + i] = 1.0;
                hertz[j * grid.nx() + i] = (1.0 - r * r).sqrt();
            }
        }
    }
    (grid, indicator, hertz)
}

pub(super) fn render_field(dir: &Path, name: &str, outline: bool) -> PathBuf {
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

pub(super) fn two_series() -> Vec<Series> {
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
