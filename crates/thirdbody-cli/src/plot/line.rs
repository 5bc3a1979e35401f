//! Line plots of several series (sweeps, profiles, convergence histories) with a legend
//! and an optional logarithmic x axis.

use anyhow::Result;
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::coord::Shift;
use plotters::prelude::*;

use super::colour::{linear_ticks, log_tick, min_max};
use super::output::{draw_err, text, Figure, LABEL_SIZE, TICK_SIZE, TITLE_SIZE};
use super::Series;

/// Distinct line colours (the "tab10" cycle of matplotlib / Tableau).
const CYCLE: [RGBColor; 10] = [
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

pub(crate) struct LineFigure<'a> {
    pub series: &'a [Series],
    pub title: &'a str,
    pub x_label: &'a str,
    pub y_label: &'a str,
    pub log_x: bool,
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
        (x_range, padded(y_lo, y_hi))
    }

    fn draw_on<DB, X>(
        &self,
        area: &DrawingArea<DB, Shift>,
        x_axis: X,
        x_format: &dyn Fn(&f64) -> String,
        y_range: (f64, f64),
    ) -> Result<()>
    where
        DB: DrawingBackend,
        X: AsRangedCoord<Value = f64>,
        X::CoordDescType: ValueFormatter<f64>,
    {
        let mut chart = ChartBuilder::on(area)
            .caption(self.title, text(TITLE_SIZE))
            .margin(16)
            .x_label_area_size(62)
            .y_label_area_size(80)
            .build_cartesian_2d(x_axis, y_range.0..y_range.1)
            .map_err(draw_err)?;
        chart
            .configure_mesh()
            .light_line_style(RGBColor(235, 235, 235))
            .bold_line_style(RGBColor(205, 205, 205))
            .x_labels(X_TICKS)
            .y_labels(Y_TICKS)
            .x_label_formatter(x_format)
            .y_label_formatter(&linear_ticks(y_range.0, y_range.1, Y_TICKS))
            .x_desc(self.x_label)
            .y_desc(self.y_label)
            .label_style(text(TICK_SIZE))
            .axis_desc_style(text(LABEL_SIZE))
            .draw()
            .map_err(draw_err)?;

        let mut any_label = false;
        for (k, s) in self.series.iter().enumerate() {
            let colour = CYCLE[k % CYCLE.len()];
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
                any_label = true;
                // A dashed legend line shows a gap; a solid one is two touching pieces.
                let gap = if s.dashed { 6 } else { 0 };
                annotation.label(s.label.as_str()).legend(move |(x, y)| {
                    EmptyElement::at((x, y))
                        + PathElement::new(vec![(0, 0), (9, 0)], style)
                        + PathElement::new(vec![(9 + gap, 0), (24, 0)], style)
                });
            }
            if s.x.len() <= MARKED_POINTS {
                chart
                    .draw_series(points.map(|p| Circle::new(p, 3, colour.filled())))
                    .map_err(draw_err)?;
            }
        }
        if any_label {
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperRight)
                .background_style(WHITE.mix(0.85))
                .border_style(RGBColor(160, 160, 160))
                .label_font(text(TICK_SIZE))
                .draw()
                .map_err(draw_err)?;
        }
        Ok(())
    }
}

impl Figure for LineFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (900, 620)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let ((x0, x1), y_range) = self.ranges();
        if self.log_x {
            self.draw_on(root, (x0..x1).log_scale(), &log_tick, y_range)
        } else {
            self.draw_on(root, x0..x1, &linear_ticks(x0, x1, X_TICKS), y_range)
        }
    }
}
