//! Line plots of several series (sweeps, profiles, convergence histories) with a legend,
//! optional logarithmic x and y axes, and optional hollow markers for chosen points.
//!
//! Layout rules shared by every line plot: tick labels that would run into each other
//! are thinned (on a logarithmic axis decades are kept first, then 2 and 5 times a
//! decade, then the rest, each only if it clears the labels already kept); the legend
//! goes to the first place (corners first, then the middles of the edges) where it
//! covers no drawn point of any series, and if there is none the y axis gets headroom
//! above the data for it. Series are coloured by the "tab10" cycle, except that a dashed
//! and a solid series whose labels differ only after their last ", " (e.g.
//! "surface, linear" and "surface, nonlinear") share a colour. A profile along the
//! sliding direction (x) notes it under the plot. A logarithmic axis (x or y) is
//! labelled at its decades (and at 2 and 5 times them when it spans fewer than three),
//! all its labels in one format (plain decimals between 1e-3 and 1e4, else powers of
//! ten, `10⁻⁴`, `2×10⁻⁴`); minor grid lines are at most [`LINEAR_MINOR`] between labelled
//! ticks of a linear axis and, on a logarithmic one, at the multiples of a decade only
//! where they stay [`MINOR_GAP`] apart. Hollow markers (a ring in the series' colour) are
//! explained by a last legend line.

use anyhow::Result;
use plotters::coord::combinators::BindKeyPoints;
use plotters::coord::ranged1d::{AsRangedCoord, Ranged, ValueFormatter};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;

use super::colour::{linear_ticks, log_ticks, min_max, tick_values};
use super::output::{
    draw_err, draw_sliding_note, draw_title, text, Figure, LABEL_SIZE, TICK_SIZE, TITLE_STRIP,
};
use super::Series;

/// Distinct line colours (the "tab10" cycle of matplotlib / Tableau).
pub(crate) const CYCLE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// Labelled ticks on the x and y axes, at most.
const X_TICKS: usize = 10;
const Y_TICKS: usize = 8;

/// Series with at most this many points also get a marker at each point.
const MARKED_POINTS: usize = 30;
/// Radius of a hollow marker, pixels (a filled one has 3).
const HOLLOW_RADIUS: i32 = 5;

/// Legend geometry (plotters' series-label box): sample line area and inner margin.
const LEGEND_SAMPLE: i32 = 30;
const LEGEND_MARGIN: i32 = 10;
/// Inset of plotters' legend positions from the plotting area's border, pixels.
const LEGEND_INSET: i32 = 5;
/// Clearance kept between the legend box and drawn data, pixels.
const LEGEND_CLEARANCE: i32 = 5;
/// Margin right of the plotting area: room for half the last x tick label.
const RIGHT_MARGIN: u32 = 32;
/// Smallest gap between neighbouring tick labels, pixels.
const TICK_GAP: i32 = 8;

pub(crate) struct LineFigure<'a> {
    pub series: &'a [Series],
    pub title: &'a str,
    pub x_label: &'a str,
    pub y_label: &'a str,
    pub log_x: bool,
    pub log_y: bool,
    /// Per series, per point: a hollow marker (missing entries: none).
    pub hollow: &'a [Vec<bool>],
    /// The legend line for hollow markers.
    pub hollow_note: &'a str,
    /// Note the sliding direction (+x) under the plot: the x axis is the position x.
    pub sliding_note: bool,
}

/// `[lo, hi]` padded by 5 % of the span, or by a unit-ish amount around a single value.
fn padded(lo: f64, hi: f64) -> (f64, f64) {
    if hi > lo {
        let pad = 0.05 * (hi - lo);
        (lo - pad, hi + pad)
    } else {
        let pad = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
        (lo - pad, hi + pad)
    }
}

/// `[lo, hi]` widened by 5 % of its decades on each side (a factor 2 around one value).
fn padded_log(lo: f64, hi: f64) -> (f64, f64) {
    let pad = if hi > lo { (hi / lo).powf(0.05) } else { 2.0 };
    (lo / pad, hi * pad)
}

/// Ticks of a logarithmic axis over `[lo, hi]`: its decades, with 2 and 5 times each
/// decade when there are fewer than three, and every integer times a decade when that
/// still gives fewer than three; a range too narrow for two of those gets a linear
/// axis's ticks.
pub(crate) fn log_keys(lo: f64, hi: f64) -> Vec<f64> {
    let (first, last) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    let within = |mantissas: &[f64]| -> Vec<f64> {
        (first..=last)
            .flat_map(|e| mantissas.iter().map(move |m| m * 10f64.powi(e)))
            .filter(|v| (lo..=hi).contains(v))
            .collect()
    };
    for mantissas in [
        &[1.0][..],
        &[1.0, 2.0, 5.0],
        &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0],
    ] {
        let keys = within(mantissas);
        if keys.len() >= 3 {
            return keys;
        }
    }
    let keys = within(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]);
    if keys.len() >= 2 {
        keys
    } else {
        tick_values(lo, hi, Y_TICKS)
    }
}

/// About the plotting area's width and height, pixels (the minor grid's spacing).
const PLOT_WIDTH: f64 = 740.0;
const PLOT_HEIGHT: f64 = 480.0;
/// Smallest spacing of minor grid lines, pixels: closer ones read as a grey band.
pub(crate) const MINOR_GAP: f64 = 8.0;
/// Minor lines between labelled ticks of a linear axis, at most.
pub(crate) const LINEAR_MINOR: usize = 4;

/// Minor grid lines of a logarithmic axis over `[lo, hi]` drawn `px` pixels long: the
/// integer multiples 2..9 of each decade when the closest two (9 and 10 times a decade)
/// are [`MINOR_GAP`] apart, else 2 and 5 times each decade when those are, else none.
pub(crate) fn log_minor(lo: f64, hi: f64, px: f64) -> Vec<f64> {
    let per_decade = px / (hi / lo).log10().max(1e-12);
    let (first, last) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    let mantissas: &[f64] = if per_decade * (10.0f64 / 9.0).log10() >= MINOR_GAP {
        &[2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]
    } else if per_decade * 2.0f64.log10() >= MINOR_GAP {
        &[2.0, 5.0]
    } else {
        &[]
    };
    (first..=last)
        .flat_map(|e| mantissas.iter().map(move |m| m * 10f64.powi(e)))
        .filter(|v| (lo..=hi).contains(v))
        .collect()
}

/// Whether point `k` of series `s` is drawn hollow.
fn is_hollow(hollow: &[Vec<bool>], s: usize, k: usize) -> bool {
    hollow
        .get(s)
        .and_then(|h| h.get(k))
        .copied()
        .unwrap_or(false)
}

/// Index into [`CYCLE`] of each series: a new colour per series, except that a series
/// whose label equals a solid/dashed counterpart's up to the last ", " takes that
/// counterpart's colour (one colour per curve, solid vs dashed per model).
pub(crate) fn colour_indices(series: &[Series]) -> Vec<usize> {
    let stem = |s: &Series| s.label.rsplit_once(", ").map(|(a, _)| a.to_string());
    let mut out: Vec<usize> = Vec::with_capacity(series.len());
    let mut next = 0;
    for (k, s) in series.iter().enumerate() {
        let partner = stem(s).and_then(|st| {
            (0..k).find(|&m| {
                series[m].dashed != s.dashed
                    && stem(&series[m]).as_deref() == Some(st.as_str())
                    // Each earlier series pairs with one later series at most.
                    && !(m + 1..k).any(|q| out[q] == out[m])
            })
        });
        match partner {
            Some(m) => out.push(out[m]),
            None => {
                out.push(next);
                next += 1;
            }
        }
    }
    out
}

/// Of tick labels at pixel positions `centres` (along the axis) with text extents
/// `sizes` (along the axis) and priorities `rank` (0 first), which ones to keep so that
/// no two kept ones come closer than [`TICK_GAP`]: higher priority first, then in order.
pub(crate) fn thin_labels(centres: &[i32], sizes: &[i32], rank: &[u8]) -> Vec<bool> {
    let mut keep = vec![false; centres.len()];
    let mut order: Vec<usize> = (0..centres.len()).collect();
    order.sort_by_key(|&k| rank[k]);
    for k in order {
        let (a0, a1) = (centres[k] - sizes[k] / 2, centres[k] + sizes[k] / 2);
        let clear = (0..centres.len()).filter(|&m| keep[m]).all(|m| {
            let (b0, b1) = (centres[m] - sizes[m] / 2, centres[m] + sizes[m] / 2);
            a1 + TICK_GAP <= b0 || b1 + TICK_GAP <= a0
        });
        keep[k] = clear;
    }
    keep
}

/// Priority of a tick on a logarithmic axis: 0 for a decade, 1 for 2 or 5 times one,
/// 2 otherwise.
fn log_rank(v: f64) -> u8 {
    let mantissa = v / 10f64.powf(v.log10().floor());
    let near = |m: f64| (mantissa - m).abs() < 1e-6 * m || (mantissa - 10.0 * m).abs() < 1e-5;
    if near(1.0) {
        0
    } else if near(2.0) || near(5.0) {
        1
    } else {
        2
    }
}

/// How a tick's value is written.
type TickFormat = Box<dyn Fn(&f64) -> String>;

/// A rectangle in pixels, `[x0, y0, x1, y1]`.
type PixelBox = [i32; 4];

/// The candidate legend positions, in order of preference.
const LEGEND_PLACES: [SeriesLabelPosition; 8] = [
    SeriesLabelPosition::UpperRight,
    SeriesLabelPosition::UpperLeft,
    SeriesLabelPosition::LowerRight,
    SeriesLabelPosition::LowerLeft,
    SeriesLabelPosition::UpperMiddle,
    SeriesLabelPosition::LowerMiddle,
    SeriesLabelPosition::MiddleRight,
    SeriesLabelPosition::MiddleLeft,
];

/// The legend box at `place` in an area of `area` pixels (plotters' layout rule).
fn legend_box(place: &SeriesLabelPosition, (w, h): (i32, i32), area: (i32, i32)) -> PixelBox {
    use SeriesLabelPosition::*;
    let x = match place {
        UpperLeft | MiddleLeft | LowerLeft => LEGEND_INSET,
        UpperMiddle | MiddleMiddle | LowerMiddle => (area.0 - w) / 2,
        _ => area.0 - w - LEGEND_INSET,
    };
    let y = match place {
        UpperLeft | UpperMiddle | UpperRight => LEGEND_INSET,
        MiddleLeft | MiddleMiddle | MiddleRight => (area.1 - h) / 2,
        _ => area.1 - h - LEGEND_INSET,
    };
    [x, y, x + w, y + h]
}

/// Whether the pixel `p` lies in `b` grown by [`LEGEND_CLEARANCE`].
fn near_box(b: &PixelBox, p: (i32, i32)) -> bool {
    let c = LEGEND_CLEARANCE;
    p.0 >= b[0] - c && p.0 <= b[2] + c && p.1 >= b[1] - c && p.1 <= b[3] + c
}

impl LineFigure<'_> {
    fn ranges(&self) -> ((f64, f64), (f64, f64)) {
        let xs: Vec<f64> = self
            .series
            .iter()
            .flat_map(|s| s.x.iter().copied())
            .collect();
        let ys: Vec<f64> = self
            .series
            .iter()
            .flat_map(|s| s.y.iter().copied())
            .collect();
        let (x_lo, x_hi) = min_max(&xs);
        let (y_lo, y_hi) = min_max(&ys);
        let y_range = if self.log_y {
            padded_log(y_lo, y_hi)
        } else {
            padded(y_lo, y_hi)
        };
        let x_range = if self.log_x {
            // 2 % of the decades on each side, so that a decade at the end gets its label.
            let pad = if x_hi > x_lo {
                (x_hi / x_lo).powf(0.02)
            } else {
                2.0
            };
            (x_lo / pad, x_hi * pad)
        } else if x_hi > x_lo {
            (x_lo, x_hi)
        } else {
            padded(x_lo, x_hi)
        };
        (x_range, y_range)
    }

    /// Whether any point is drawn hollow (the legend then explains it).
    fn any_hollow(&self) -> bool {
        self.hollow.iter().flatten().any(|&h| h)
    }

    /// The labelled ticks of the y axis over `y` and their format.
    fn y_ticks(&self, y: (f64, f64)) -> (Vec<f64>, TickFormat) {
        if self.log_y {
            let keys = log_keys(y.0, y.1);
            let format = Box::new(log_ticks(&keys));
            (keys, format)
        } else {
            (
                tick_values(y.0, y.1, Y_TICKS),
                Box::new(linear_ticks(y.0, y.1, Y_TICKS)),
            )
        }
    }

    fn labelled(&self) -> impl Iterator<Item = &Series> {
        self.series.iter().filter(|s| !s.label.is_empty())
    }

    #[allow(clippy::too_many_arguments)]
    fn draw_on<DB, X, Y>(
        &self,
        area: &DrawingArea<DB, Shift>,
        x_axis: impl Fn() -> X,
        y_axis: impl Fn((f64, f64)) -> Y,
        x_keys: &[f64],
        x_rank: &dyn Fn(f64) -> u8,
        x_format: &dyn Fn(&f64) -> String,
        mut y_range: (f64, f64),
    ) -> Result<()>
    where
        DB: DrawingBackend,
        X: AsRangedCoord<Value = f64>,
        X::CoordDescType: ValueFormatter<f64>,
        Y: AsRangedCoord<Value = f64>,
        Y::CoordDescType: ValueFormatter<f64>,
    {
        let (title_area, body) = area.split_vertically(TITLE_STRIP);
        draw_title(&title_area, self.title)?;
        // The y label area fits the widest tick label, a gap and the rotated description.
        let y_area = |y: (f64, f64)| -> Result<u32> {
            let (keys, format) = self.y_ticks(y);
            let mut widest = 0;
            for v in keys {
                let (w, _) = area
                    .estimate_text_size(&format(&v), &text(TICK_SIZE))
                    .map_err(draw_err)?;
                widest = widest.max(w);
            }
            Ok((widest + 22 + LABEL_SIZE as u32 + 8).max(80))
        };
        let build = |y: (f64, f64)| -> Result<_> {
            ChartBuilder::on(&body)
                .margin(16)
                .margin_top(4)
                .margin_right(RIGHT_MARGIN)
                .x_label_area_size(62)
                .y_label_area_size(y_area(y)?)
                .build_cartesian_2d(x_axis(), y_axis(y))
                .map_err(draw_err)
        };

        // Legend size (plotters' series-label layout), then its place: the first that
        // covers no data; if none, headroom above the data, and try again.
        let mut legend_text = MultiLineText::<_, &str>::new((0, 0), text(TICK_SIZE));
        for s in self.labelled() {
            legend_text.push_line(s.label.as_str());
        }
        let note = self.any_hollow() && !self.hollow_note.is_empty();
        if note {
            legend_text.push_line(self.hollow_note);
        }
        let any_label = self.labelled().next().is_some() || note;
        let legend_dim = legend_text
            .estimate_dimension()
            .map(|(w, h)| (w + LEGEND_SAMPLE + 2 * LEGEND_MARGIN, h + 2 * LEGEND_MARGIN))
            .map_err(|e| anyhow::anyhow!("measuring the legend: {e:?}"))?;
        let mut legend_place = SeriesLabelPosition::UpperRight;
        let mut chart = build(y_range)?;
        for attempt in 0..4 {
            if !any_label {
                break;
            }
            let (px, py) = chart.plotting_area().get_pixel_range();
            let dim = (px.end - px.start, py.end - py.start);
            let samples = self.pixel_samples(|p| {
                let (x, y) = chart.backend_coord(&p);
                (x - px.start, y - py.start)
            });
            let free = LEGEND_PLACES.iter().find(|place| {
                let b = legend_box(place, legend_dim, dim);
                !samples.iter().any(|&p| near_box(&b, p))
            });
            if let Some(place) = free {
                legend_place = place.clone();
                break;
            }
            if attempt == 3 {
                break;
            }
            // Reserve the legend's height (and clearance) at the top.
            let r = ((legend_dim.1 + 2 * LEGEND_INSET + 2 * LEGEND_CLEARANCE) as f64
                / dim.1.max(1) as f64)
                .min(0.6);
            if self.log_y {
                y_range.1 *= (y_range.1 / y_range.0).powf(r / (1.0 - r));
            } else {
                y_range.1 += (y_range.1 - y_range.0) * r / (1.0 - r);
            }
            chart = build(y_range)?;
        }

        // Tick labels of x that clear each other.
        let mut centres = Vec::new();
        let mut widths = Vec::new();
        let mut ranks = Vec::new();
        for &v in x_keys {
            let (w, _) = area
                .estimate_text_size(&x_format(&v), &text(TICK_SIZE))
                .map_err(draw_err)?;
            centres.push(chart.backend_coord(&(v, y_range.0)).0);
            widths.push(w as i32);
            ranks.push(x_rank(v));
        }
        let keep = thin_labels(&centres, &widths, &ranks);
        let kept: Vec<f64> = x_keys
            .iter()
            .zip(&keep)
            .filter(|(_, &k)| k)
            .map(|(&v, _)| v)
            .collect();
        // plotters asks for the labels of the same key points (compared exactly), and
        // may list one twice (log axes at a decade): label each value once.
        let labelled = std::cell::RefCell::new(Vec::<f64>::new());
        let x_labels = |v: &f64| {
            if kept.contains(v) && !labelled.borrow().contains(v) {
                labelled.borrow_mut().push(*v);
                x_format(v)
            } else {
                String::new()
            }
        };

        // Tick labels of y: on a logarithmic axis, those that clear each other (decades
        // first); a linear axis's are spaced by plotters.
        let (y_keys, y_format) = self.y_ticks(y_range);
        let y_kept: Vec<f64> = if self.log_y {
            let x_any = x_keys.first().copied().unwrap_or(1.0);
            let mut centres = Vec::new();
            let mut heights = Vec::new();
            for &v in &y_keys {
                let (_, h) = area
                    .estimate_text_size(&y_format(&v), &text(TICK_SIZE))
                    .map_err(draw_err)?;
                centres.push(chart.backend_coord(&(x_any, v)).1);
                heights.push(h as i32);
            }
            let ranks: Vec<u8> = y_keys.iter().map(|&v| log_rank(v)).collect();
            let keep = thin_labels(&centres, &heights, &ranks);
            y_keys
                .iter()
                .zip(&keep)
                .filter(|(_, &k)| k)
                .map(|(&v, _)| v)
                .collect()
        } else {
            y_keys
        };
        let y_labels = |v: &f64| {
            if !self.log_y || y_kept.contains(v) {
                y_format(v)
            } else {
                String::new()
            }
        };

        chart
            .configure_mesh()
            .light_line_style(RGBColor(235, 235, 235))
            .bold_line_style(RGBColor(205, 205, 205))
            .x_max_light_lines(LINEAR_MINOR)
            .y_max_light_lines(LINEAR_MINOR)
            .x_labels(X_TICKS)
            .y_labels(Y_TICKS)
            .x_label_formatter(&x_labels)
            .y_label_formatter(&y_labels)
            .x_desc(self.x_label)
            .y_desc(self.y_label)
            .label_style(text(TICK_SIZE))
            .axis_desc_style(text(LABEL_SIZE))
            .draw()
            .map_err(draw_err)?;

        let colours = colour_indices(self.series);
        for (k, (s, &c)) in self.series.iter().zip(&colours).enumerate() {
            let colour = CYCLE[c % CYCLE.len()];
            let style = colour.stroke_width(2);
            let points = s.x.iter().copied().zip(s.y.iter().copied());
            let annotation = if s.dashed {
                chart
                    .draw_series(DashedLineSeries::new(points.clone(), 9, 6, style))
                    .map_err(draw_err)?
            } else {
                chart
                    .draw_series(LineSeries::new(points.clone(), style))
                    .map_err(draw_err)?
            };
            if !s.label.is_empty() {
                // A dashed legend line shows a gap; a solid one is two touching pieces.
                let gap = if s.dashed { 6 } else { 0 };
                annotation.label(s.label.as_str()).legend(move |(x, y)| {
                    EmptyElement::at((x, y))
                        + PathElement::new(vec![(0, 0), (9, 0)], style)
                        + PathElement::new(vec![(9 + gap, 0), (24, 0)], style)
                });
            }
            let filled = s.x.len() <= MARKED_POINTS;
            for (m, p) in points.enumerate() {
                if is_hollow(self.hollow, k, m) {
                    chart
                        .draw_series([
                            Circle::new(p, HOLLOW_RADIUS, WHITE.filled()),
                            Circle::new(p, HOLLOW_RADIUS, colour.stroke_width(2)),
                        ])
                        .map_err(draw_err)?;
                } else if filled {
                    chart
                        .draw_series([Circle::new(p, 3, colour.filled())])
                        .map_err(draw_err)?;
                }
            }
        }
        if note {
            // A legend line of its own: a hollow marker in grey, no line.
            let grey = RGBColor(90, 90, 90);
            chart
                .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())
                .map_err(draw_err)?
                .label(self.hollow_note)
                .legend(move |(x, y)| {
                    EmptyElement::at((x, y))
                        + Circle::new((12, 0), HOLLOW_RADIUS, grey.stroke_width(2))
                });
        }
        if any_label {
            chart
                .configure_series_labels()
                .position(legend_place)
                .margin(LEGEND_MARGIN)
                .legend_area_size(LEGEND_SAMPLE)
                .background_style(WHITE.mix(0.85))
                .border_style(RGBColor(160, 160, 160))
                .label_font(text(TICK_SIZE))
                .draw()
                .map_err(draw_err)?;
        }
        if self.sliding_note {
            // Under the plotting area, right-aligned, level with the x description.
            let (px, py) = chart.plotting_area().get_pixel_range();
            draw_sliding_note(area, px, py.end, 44, self.x_label)?;
        }
        Ok(())
    }

    /// Pixels (plotting-area coordinates, via `to_px`) along every series' polyline,
    /// about every 2 pixels, and its points.
    fn pixel_samples(&self, to_px: impl Fn((f64, f64)) -> (i32, i32)) -> Vec<(i32, i32)> {
        let mut out = Vec::new();
        for s in self.series {
            let pts: Vec<(i32, i32)> = s.x.iter().zip(&s.y).map(|(&x, &y)| to_px((x, y))).collect();
            out.extend_from_slice(&pts);
            for w in pts.windows(2) {
                let (a, b) = (w[0], w[1]);
                let n = ((b.0 - a.0).abs().max((b.1 - a.1).abs()) / 2).max(1);
                for t in 1..n {
                    out.push((a.0 + (b.0 - a.0) * t / n, a.1 + (b.1 - a.1) * t / n));
                }
            }
        }
        out
    }
}

impl Figure for LineFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (900, 620)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let ((x0, x1), y_range) = self.ranges();
        // A logarithmic axis: plotters' log scale, labelled at `log_keys`, with a minor
        // grid line at the integer multiples of each decade only where they stay apart.
        let log_y = |y: (f64, f64)| {
            (y.0..y.1)
                .log_scale()
                .with_key_points(log_keys(y.0, y.1))
                .with_light_points(log_minor(y.0, y.1, PLOT_HEIGHT))
        };
        let linear_y = |y: (f64, f64)| y.0..y.1;
        if self.log_x {
            let keys = log_keys(x0, x1);
            let format = log_ticks(&keys);
            let x_axis = || {
                (x0..x1)
                    .log_scale()
                    .with_key_points(keys.clone())
                    .with_light_points(log_minor(x0, x1, PLOT_WIDTH))
            };
            if self.log_y {
                self.draw_on(root, x_axis, log_y, &keys, &log_rank, &format, y_range)
            } else {
                self.draw_on(root, x_axis, linear_y, &keys, &log_rank, &format, y_range)
            }
        } else {
            let coord: RangedCoordf64 = (x0..x1).into();
            let keys = coord.key_points(X_TICKS);
            let format = linear_ticks(x0, x1, X_TICKS);
            let x_axis = || x0..x1;
            if self.log_y {
                self.draw_on(root, x_axis, log_y, &keys, &|_| 0, &format, y_range)
            } else {
                self.draw_on(root, x_axis, linear_y, &keys, &|_| 0, &format, y_range)
            }
        }
    }
}
