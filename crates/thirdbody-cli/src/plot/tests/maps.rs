//! Colour maps: geometry, orientation and colours checked on the decoded pixels.

use image::RgbImage;
use thirdbody::Grid;

use super::*;
use crate::plot::{field_map, line_plot, section_map, Series};

#[test]
fn field_map_keeps_equal_aspect_and_places_the_disc() {
    let dir = tempfile::tempdir().unwrap();
    let (grid, indicator, _) = disc_case();
    let path = dir.path().join("disc.png");
    field_map(&path, &grid, &indicator, "Disc", "x'", "y'", "p'", None).unwrap();
    let img = decode(&path);
    let map_right = img.width() - crate::plot::colour::BAR_STRIP;
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
    use crate::plot::map::Corner;
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
    let map_right = plain.width() - crate::plot::colour::BAR_STRIP;
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
    section_map(&path, &xs, &zs, &field, "Depth", "x'", "z'", "z'", 4, &[]).unwrap();
    let img = decode(&path);
    let map_right = img.width() - crate::plot::colour::BAR_STRIP;
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
    section_map(&path, &xs, &zs, &field, "Sign", "x'", "z'", "σxx'", 0, &[]).unwrap();
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

    // A single peak of 1 at (0.525, 1.225) (grid points i = 40, k = 24): the cross sits
    // there, black at its centre, and the SVG names value and place.
    let peak: Vec<f64> = zs
        .iter()
        .flat_map(|&z| {
            xs.iter()
                .map(move |&x| (-((x - 0.525).powi(2) + (z - 1.225).powi(2)) / 0.1).exp())
        })
        .collect();
    let path = dir.path().join("peak.png");
    section_map(&path, &xs, &zs, &peak, "Peak", "x'", "z'", "s'", 0, &[]).unwrap();
    let img = decode(&path);
    let (ww, wh) = (ww as f64, wh as f64);
    let px = window[0] as f64 + (0.525 + 1.5) / 3.0 * ww;
    let py = window[1] as f64 + 1.225 / 2.0 * wh;
    let black_near = (-2..=2).any(|d: i32| {
        (-2..=2).any(|e: i32| {
            let p = img
                .get_pixel((px as i32 + d) as u32, (py as i32 + e) as u32)
                .0;
            close(p, [0, 0, 0], 40)
        })
    });
    assert!(black_near, "no cross at ({px}, {py})");
    let svg = dir.path().join("peak.svg");
    section_map(&svg, &xs, &zs, &peak, "Peak", "x'", "z'", "s'", 0, &[]).unwrap();
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.contains("1.00 at (0.525, 1.2"), "annotation missing");
    assert_eq!(
        listing(dir.path()),
        vec!["depth.png", "peak.png", "peak.svg", "sign.png"]
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
        let map_right = img.width() - crate::plot::colour::BAR_STRIP;
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
        &[],
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
fn sections_draw_their_interfaces_and_show_where_the_field_lives() {
    // A thin-coating sigma_x: compression in a layer 0.01 deep under a contact 0.06
    // long in a section 0.13 wide and 0.16 deep, the interface at 0.02.
    let dir = tempfile::tempdir().unwrap();
    let xs: Vec<f64> = (0..64)
        .map(|i| -0.043 + (i as f64 + 0.5) * 0.13 / 64.0)
        .collect();
    let zs: Vec<f64> = (0..64).map(|k| k as f64 * 0.0025).collect();
    let field: Vec<f64> = zs
        .iter()
        .flat_map(|&z| {
            xs.iter().map(move |&x| {
                let d = (-((x - 0.03) / 0.02).powi(2)).exp();
                -3e-3 * d * (-(z / 0.004)).exp()
            })
        })
        .collect();
    let interface = 0.02;
    let (lo, hi) = crate::plot::colour::min_max(&field);
    let frame_of = |img: &RgbImage| {
        // Rows of the map that are dark over half its width (an anti-aliased line of
        // width 1 is two rows of mid grey).
        let map_right = img.width() - crate::plot::colour::BAR_STRIP;
        let dark = |p: [u8; 3]| p.iter().all(|&c| c < 150);
        (0..img.height())
            .filter(|&y| {
                (0..map_right)
                    .filter(|&x| dark(img.get_pixel(x, y).0))
                    .count()
                    > 300
            })
            .collect::<Vec<u32>>()
    };
    for (name, interfaces) in [("with.png", vec![interface]), ("without.png", vec![])] {
        let path = dir.path().join(name);
        section_map(
            &path,
            &xs,
            &zs,
            &field,
            "s",
            "x'",
            "z'",
            "s",
            10,
            &interfaces,
        )
        .unwrap();
        let img = decode(&path);
        let rows = frame_of(&img);
        // Rows that are mostly dark: the frame's top and bottom, and the interface.
        let (top, bottom) = (rows[0], *rows.last().unwrap());
        let inner: Vec<u32> = rows
            .iter()
            .copied()
            .filter(|&y| y > top + 3 && y + 3 < bottom)
            .collect();
        let shown = crate::plot::shown_depths(
            &zs,
            xs.len(),
            &field,
            &crate::plot::drawn_levels(lo, hi, 10),
            &interfaces,
        );
        let (z_top, z_bottom) = (zs[0] - 0.00125, zs[shown - 1] + 0.00125);
        let expected =
            top as f64 + (interface - z_top) / (z_bottom - z_top) * (bottom - top) as f64;
        if interfaces.is_empty() {
            assert!(inner.is_empty(), "{name}: dark rows {inner:?}");
            // Where the field lives: its lowest drawn level is reached above z = 0.01;
            // the picture ends well above the section's bottom 0.16.
            assert!(z_bottom < 0.02, "{name}: shown to {z_bottom}");
        } else {
            assert!(
                inner.iter().any(|&y| (y as f64 - expected).abs() <= 2.0),
                "{name}: no interface line at pixel row {expected}: dark rows {inner:?}"
            );
            assert!(
                z_bottom >= interface && z_bottom < 0.03,
                "{name}: shown to {z_bottom}"
            );
        }
    }
}
