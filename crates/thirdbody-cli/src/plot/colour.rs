//! Colour scales of the maps and their colour bar, and the tick-label formats shared by
//! all figures.
//!
//! A field that changes sign gets a diverging map symmetric about zero (ColorBrewer
//! "RdBu", C. Brewer & M. Harrower, colorbrewer2.org, reversed: blue negative, i.e.
//! compressive for tension-positive stresses; white zero; red positive). A field of one
//! sign gets the perceptually uniform sequential map viridis (van der Walt & Smith,
//! matplotlib; plotters' `ViridisRGB`). A constant field maps to the middle colour of a
//! range around its value.

use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::output::{draw_err, text, LABEL_SIZE, TICK_SIZE};

/// ColorBrewer RdBu, 11 classes, from strongly negative (dark blue) to strongly positive
/// (dark red).
const DIVERGING: [(u8, u8, u8); 11] = [
    (5, 48, 97),
    (33, 102, 172),
    (67, 147, 195),
    (146, 197, 222),
    (209, 229, 240),
    (247, 247, 247),
    (253, 219, 199),
    (244, 165, 130),
    (214, 96, 77),
    (178, 24, 43),
    (103, 0, 31),
];

/// Which family of colour map a scale uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Palette {
    /// viridis, for fields of one sign.
    Sequential,
    /// RdBu centred on zero, for fields that change sign.
    Diverging,
}

/// Maps values in `[lo, hi]` to colours (values outside are clamped).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ColourScale {
    pub lo: f64,
    pub hi: f64,
    pub palette: Palette,
}

impl ColourScale {
    /// The scale for a field of finite values (at least one): diverging and symmetric
    /// about zero when the field has both signs beyond round-off (1e-9 of its largest
    /// magnitude), sequential from its minimum to its maximum otherwise; a constant
    /// field gets a range around its value so that it maps to the middle colour.
    pub fn for_values(values: &[f64]) -> Self {
        let (min, max) = min_max(values);
        let magnitude = min.abs().max(max.abs());
        let round_off = 1e-9 * magnitude;
        if min < -round_off && max > round_off {
            return ColourScale {
                lo: -magnitude,
                hi: magnitude,
                palette: Palette::Diverging,
            };
        }
        if max - min <= 1e-12 * magnitude || max == min {
            let half = if magnitude > 0.0 {
                0.5 * magnitude
            } else {
                1.0
            };
            let mid = 0.5 * (min + max);
            return ColourScale {
                lo: mid - half,
                hi: mid + half,
                palette: Palette::Sequential,
            };
        }
        ColourScale {
            lo: min,
            hi: max,
            palette: Palette::Sequential,
        }
    }

    /// Colour of value `v`.
    pub fn colour(&self, v: f64) -> RGBColor {
        let t = ((v - self.lo) / (self.hi - self.lo)).clamp(0.0, 1.0);
        match self.palette {
            Palette::Sequential => ViridisRGB::get_color_normalized(t, 0.0, 1.0),
            Palette::Diverging => interpolate(&DIVERGING, t),
        }
    }
}

/// Linear interpolation in a table of evenly spaced anchor colours, `t` in [0, 1].
fn interpolate(anchors: &[(u8, u8, u8)], t: f64) -> RGBColor {
    let s = t * (anchors.len() - 1) as f64;
    let k = (s.floor() as usize).min(anchors.len() - 2);
    let f = s - k as f64;
    let mix = |a: u8, b: u8| (a as f64 + f * (b as f64 - a as f64)).round() as u8;
    let (a, b) = (anchors[k], anchors[k + 1]);
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// Smallest and largest of finite values.
pub(crate) fn min_max(values: &[f64]) -> (f64, f64) {
    values
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        })
}

/// Positions plotters chooses for at most `count` labelled ticks on a linear axis
/// `[lo, hi]`.
pub(crate) fn tick_values(lo: f64, hi: f64, count: usize) -> Vec<f64> {
    let range: plotters::coord::types::RangedCoordf64 = (lo..hi).into();
    range.key_points(count)
}

/// Formatter of the tick labels of a linear axis `[lo, hi]` with at most `count` labelled
/// ticks: the fewest decimals that show every tick exactly, the same for all of them;
/// scientific notation (`1.5e-4`) when the values are large or small in magnitude.
pub(crate) fn linear_ticks(lo: f64, hi: f64, count: usize) -> impl Fn(&f64) -> String {
    let ticks = tick_values(lo, hi, count);
    let magnitude = lo.abs().max(hi.abs());
    let span = (hi - lo).abs().max(f64::MIN_POSITIVE);
    let scientific = magnitude >= 1e5 || (magnitude < 1e-3 && magnitude > 0.0);
    let format = move |v: f64, digits: usize| {
        if v.abs() <= 1e-9 * span {
            // Zero (also a tick at round-off from zero) without a minus sign.
            if scientific {
                "0".to_string()
            } else {
                format!("{:.*}", digits, 0.0)
            }
        } else if scientific {
            format!("{v:.digits$e}")
        } else {
            format!("{v:.digits$}")
        }
    };
    let exact = |digits: usize| {
        ticks.iter().all(|&t| {
            format(t, digits)
                .parse::<f64>()
                .is_ok_and(|p| (p - t).abs() <= 1e-6 * span)
        })
    };
    let digits = (0..=8).find(|&d| exact(d)).unwrap_or(8);
    move |&v: &f64| format(v, digits)
}

/// Formatter of the tick labels of a logarithmic axis labelled at `keys`: one format
/// for the whole axis, plain decimals (`0.002`, `0.05`, `100`) when every key lies
/// between 1e-3 and 1e4, else powers of ten (`10⁻⁴`, `2×10⁻⁴`). At most 6 significant
/// digits.
pub(crate) fn log_ticks(keys: &[f64]) -> impl Fn(&f64) -> String {
    let plain = keys.iter().all(|v| (1e-3..1e4).contains(&v.abs()));
    move |&v: &f64| {
        if v == 0.0 || !v.is_finite() {
            return format!("{v}");
        }
        let rounded = significant(v, 6);
        if plain {
            format!("{rounded}")
        } else {
            power_of_ten(rounded)
        }
    }
}

/// `v` rounded to `digits` significant digits.
fn significant(v: f64, digits: i32) -> f64 {
    let shift = digits - 1 - v.abs().log10().floor() as i32;
    if shift >= 0 {
        let f = 10f64.powi(shift);
        (v * f).round() / f
    } else {
        v
    }
}

/// `v` (non-zero, finite) as `m×10ⁿ` with superscript digits, `10ⁿ` when m is 1.
fn power_of_ten(v: f64) -> String {
    let mut exponent = v.abs().log10().floor() as i32;
    let mut mantissa = significant(v / 10f64.powi(exponent), 6);
    if mantissa.abs() >= 10.0 {
        exponent += 1;
        mantissa /= 10.0;
    }
    let superscript: String = exponent
        .to_string()
        .chars()
        .map(|c| match c {
            '-' => '\u{207b}',
            '0' => '\u{2070}',
            '1' => '\u{b9}',
            '2' => '\u{b2}',
            '3' => '\u{b3}',
            d => char::from_u32(0x2070 + d.to_digit(10).unwrap_or(0)).unwrap_or(d),
        })
        .collect();
    if mantissa == 1.0 {
        format!("10{superscript}")
    } else if mantissa == -1.0 {
        format!("\u{2212}10{superscript}")
    } else {
        format!("{mantissa}\u{d7}10{superscript}")
    }
}

/// Draws a vertical colour bar of `scale` in `area`, with tick labels and the rotated
/// description `label` on its right. `top`/`bottom` are the pixel margins that align the
/// bar with the plotting area of the map next to it.
pub(crate) fn draw_colour_bar<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    scale: &ColourScale,
    label: &str,
    top: u32,
    bottom: u32,
) -> Result<()> {
    let mut chart = ChartBuilder::on(area)
        .margin_top(top)
        .margin_bottom(bottom)
        .margin_left(14)
        .margin_right(6)
        .set_label_area_size(LabelAreaPosition::Right, BAR_LABEL_AREA)
        .build_cartesian_2d(0.0..1.0, scale.lo..scale.hi)
        .map_err(draw_err)?;
    const STEPS: usize = 256;
    let dv = (scale.hi - scale.lo) / STEPS as f64;
    chart
        .draw_series((0..STEPS).map(|k| {
            let v0 = scale.lo + k as f64 * dv;
            let colour = scale.colour(v0 + 0.5 * dv);
            // Overlap the next step slightly so no background line shows between them.
            let v1 = (v0 + 1.5 * dv).min(scale.hi);
            Rectangle::new([(0.0, v0), (1.0, v1)], colour.filled())
        }))
        .map_err(draw_err)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .set_tick_mark_size(LabelAreaPosition::Right, 6)
        .x_labels(0)
        .y_labels(BAR_TICKS)
        .y_label_formatter(&linear_ticks(scale.lo, scale.hi, BAR_TICKS))
        .label_style(text(TICK_SIZE))
        .axis_desc_style(text(LABEL_SIZE))
        .draw()
        .map_err(draw_err)?;
    chart
        .draw_series(std::iter::once(Rectangle::new(
            [(0.0, scale.lo), (1.0, scale.hi)],
            BLACK.stroke_width(1),
        )))
        .map_err(draw_err)?;

    // The description, reading upwards, a gap right of the widest tick label (plotters
    // starts the labels LABEL_OFFSET right of the bar).
    let format = linear_ticks(scale.lo, scale.hi, BAR_TICKS);
    let widest = tick_values(scale.lo, scale.hi, BAR_TICKS)
        .iter()
        .map(|v| area.estimate_text_size(&format(v), &text(TICK_SIZE)))
        .collect::<std::result::Result<Vec<_>, _>>()
        .map_err(draw_err)?
        .into_iter()
        .map(|(w, _)| w)
        .max()
        .unwrap_or(0);
    let (x_px, y_px) = chart.plotting_area().get_pixel_range();
    let (area_x, area_y) = (area.get_base_pixel().0, area.get_base_pixel().1);
    let (_, label_height) = area
        .estimate_text_size(label, &text(LABEL_SIZE))
        .map_err(draw_err)?;
    let x = x_px.end - area_x + LABEL_OFFSET + widest as i32 + 10 + label_height as i32 / 2;
    let y = (y_px.start + y_px.end) / 2 - area_y;
    let style = text(LABEL_SIZE)
        .transform(FontTransform::Rotate270)
        .pos(Pos::new(HPos::Center, VPos::Center));
    area.draw_text(label, &style, (x, y)).map_err(draw_err)?;
    Ok(())
}

/// Distance from the bar's right edge to the start of its tick labels (tick mark and
/// plotters' gap), pixels.
const LABEL_OFFSET: i32 = 12;

/// Labelled ticks on the colour bar, at most.
const BAR_TICKS: usize = 8;

/// Width in pixels of the colour bar's label area (tick labels and description).
pub(crate) const BAR_LABEL_AREA: u32 = 110;
/// Total width in pixels of the strip holding the colour bar.
pub(crate) const BAR_STRIP: u32 = 14 + 26 + BAR_LABEL_AREA + 6;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scale_choice_follows_the_sign_of_the_field() {
        let one_sign = ColourScale::for_values(&[0.0, 0.5, 2.0]);
        assert_eq!(one_sign.palette, Palette::Sequential);
        assert_eq!((one_sign.lo, one_sign.hi), (0.0, 2.0));
        let both = ColourScale::for_values(&[-1.0, 0.5, 3.0]);
        assert_eq!(both.palette, Palette::Diverging);
        assert_eq!((both.lo, both.hi), (-3.0, 3.0));
        // Zero maps to the white centre of the diverging map.
        assert_eq!(both.colour(0.0), RGBColor(247, 247, 247));
        // Round-off below zero does not switch to the diverging map.
        let nearly = ColourScale::for_values(&[-1e-18, 1.0]);
        assert_eq!(nearly.palette, Palette::Sequential);
    }

    #[test]
    fn constant_fields_map_to_the_middle_colour() {
        for v in [0.0, 3.0, -2e9] {
            let scale = ColourScale::for_values(&[v; 5]);
            assert!(scale.lo < v && v < scale.hi, "{scale:?}");
            assert!(((v - scale.lo) - (scale.hi - v)).abs() <= 1e-9 * scale.hi.abs().max(1.0));
        }
    }

    #[test]
    fn diverging_ends_are_the_table_ends() {
        let scale = ColourScale::for_values(&[-2.0, 2.0]);
        assert_eq!(scale.colour(-5.0), RGBColor(5, 48, 97));
        assert_eq!(scale.colour(2.0), RGBColor(103, 0, 31));
    }

    #[test]
    fn tick_labels_are_short_and_exact() {
        // Ticks 0, 0.2, ..., 2 (plotters' choice, checked here): one decimal for all.
        assert_eq!(tick_values(0.0, 2.0, 11).len(), 11);
        let f = linear_ticks(0.0, 2.0, 11);
        assert_eq!(f(&0.4), "0.4");
        assert_eq!(f(&2.0), "2.0");
        assert_eq!(f(&-1e-17), "0.0");
        // Ticks at whole numbers: no decimals.
        let w = linear_ticks(-2.0, 2.0, 5);
        assert_eq!(tick_values(-2.0, 2.0, 5), vec![-2.0, -1.0, 0.0, 1.0, 2.0]);
        assert_eq!((w(&-2.0), w(&0.0)), ("-2".to_string(), "0".to_string()));
        let g = linear_ticks(-3.0e9, 3.0e9, 13);
        assert_eq!(g(&1.5e9), "1.5e9");
        assert_eq!(g(&-0.0), "0");
        let h = linear_ticks(0.0, 2.0e-4, 5);
        assert_eq!(h(&5.0e-5), "5.0e-5");
        // A logarithmic axis: plain decimals or powers of ten, one for all its ticks.
        let plain = log_ticks(&[0.001, 0.01, 0.1]);
        assert_eq!(
            (plain(&0.001), plain(&0.002)),
            ("0.001".into(), "0.002".into())
        );
        let powers = log_ticks(&[1e-4, 1e-3, 1e-2, 0.1]);
        assert_eq!(powers(&1e-4), "10\u{207b}\u{2074}");
        assert_eq!(powers(&0.001), "10\u{207b}\u{b3}");
        assert_eq!(powers(&0.1), "10\u{207b}\u{b9}");
        assert_eq!(powers(&2e-5), "2\u{d7}10\u{207b}\u{2075}");
        assert_eq!(powers(&1.0e6), "10\u{2076}");
        assert_eq!(powers(&1.0), "10\u{2070}");
    }
}
