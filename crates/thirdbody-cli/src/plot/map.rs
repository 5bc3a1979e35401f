//! Colour maps of fields on rectilinear cells (a surface grid or a vertical section):
//! the raster of cell colours at the plot's pixel resolution, optional contour lines,
//! an outline, a marked extreme, the note of the sliding direction under the map, and the
//! colour bar.

use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;

use super::colour::{draw_colour_bar, linear_ticks, ColourScale, BAR_STRIP};
use super::contours::Axis;
use super::output::{
    draw_err, draw_sliding_note, draw_title, text, Figure, LABEL_SIZE, TICK_SIZE, TITLE_STRIP,
};

/// Margin around the map, pixels.
const MARGIN: u32 = 14;
/// Height of the x tick labels and description below the map.
const BOTTOM_AREA: u32 = 62;
/// Width of the y tick labels and description left of the map.
const LEFT_AREA: u32 = 90;
/// Longer side of the map's plotting area, pixels.
const LONG_SIDE: f64 = 640.0;
/// Shortest side allowed (a very elongated window is padded to keep equal aspect; a
/// section only below, so that its surface stays at the top edge).
const SHORT_SIDE_MIN: f64 = 220.0;
/// Depth over width of the shallowest section drawn at equal scales without padding:
/// a section shallower than this is padded below (or, under a fifth, stretched).
pub(crate) const SECTION_FULL_RATIO: f64 = SHORT_SIDE_MIN / LONG_SIDE;

/// A line through points in plot coordinates.
pub(crate) type Polyline = Vec<(f64, f64)>;

/// Labelled ticks per axis, at most.
const AXIS_TICKS: usize = 8;

/// A point marked with a cross and a text.
pub(crate) struct Marker {
    pub at: (f64, f64),
    pub text: String,
}

/// One colour map figure. Rows of `values` run along the plot's y axis, upwards.
pub(crate) struct MapFigure<'a> {
    pub title: &'a str,
    pub x_label: &'a str,
    pub y_label: &'a str,
    pub colour_label: &'a str,
    pub cols: Axis,
    pub rows: Axis,
    /// Row-major, `values[row * cols.len() + col]`.
    pub values: Vec<f64>,
    pub scale: ColourScale,
    /// Plot y is minus the physical coordinate (depth drawn increasing downward).
    pub y_negated: bool,
    pub equal_aspect: bool,
    /// Thin lines (contours) drawn over the map.
    pub lines: Vec<Polyline>,
    /// A boundary drawn bold with a halo, and its legend entry.
    pub outline: Option<(Vec<Polyline>, &'a str)>,
    /// Corner of the legend (of the outline).
    pub legend_corner: Corner,
    pub marker: Option<Marker>,
}

/// A corner of the plotting area.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Corner {
    UpperRight,
    UpperLeft,
    LowerRight,
    LowerLeft,
}

impl Corner {
    /// The corner whose box (a third of the width, a sixth of the height) holds the
    /// fewest cells where `inside` is true; ties go in the order upper right, upper left,
    /// lower right, lower left.
    pub fn emptiest(nx: usize, ny: usize, inside: impl Fn(usize) -> bool) -> Self {
        let (bw, bh) = (nx.div_ceil(3), ny.div_ceil(6));
        let count = |cols: std::ops::Range<usize>, rows: std::ops::Range<usize>| {
            rows.flat_map(|j| cols.clone().map(move |i| j * nx + i))
                .filter(|&k| inside(k))
                .count()
        };
        // Rows run upwards: the upper corners hold the last rows.
        let candidates = [
            (Corner::UpperRight, count(nx - bw..nx, ny - bh..ny)),
            (Corner::UpperLeft, count(0..bw, ny - bh..ny)),
            (Corner::LowerRight, count(nx - bw..nx, 0..bh)),
            (Corner::LowerLeft, count(0..bw, 0..bh)),
        ];
        candidates
            .iter()
            .min_by_key(|c| c.1)
            .map_or(Corner::UpperRight, |c| c.0)
    }
}

/// Pixel size of the plotting area and the data ranges shown in it.
struct Layout {
    plot_px: (u32, u32),
    x_range: (f64, f64),
    y_range: (f64, f64),
}

impl MapFigure<'_> {
    fn layout(&self) -> Layout {
        let (x0, x1) = (self.cols.first_edge, self.cols.last_edge);
        let (y0, y1) = (self.rows.first_edge, self.rows.last_edge);
        let (rx, ry) = (x1 - x0, y1 - y0);
        let ratio = ry / rx;
        let (w, h) = if !self.equal_aspect {
            (LONG_SIDE, 0.68 * LONG_SIDE)
        } else if ratio <= 1.0 {
            (LONG_SIDE, (LONG_SIDE * ratio).max(SHORT_SIDE_MIN))
        } else {
            ((LONG_SIDE / ratio).max(SHORT_SIDE_MIN), LONG_SIDE)
        };
        let plot_px = (w.round() as u32, h.round() as u32);
        let (mut x_range, mut y_range) = ((x0, x1), (y0, y1));
        if self.equal_aspect {
            // Same data length per pixel on both axes: widen the axis that has less.
            let per_px = (rx / plot_px.0 as f64).max(ry / plot_px.1 as f64);
            let widen = |(a, b): (f64, f64), px: u32| {
                let half = 0.5 * per_px * px as f64;
                let mid = 0.5 * (a + b);
                (mid - half, mid + half)
            };
            x_range = widen(x_range, plot_px.0);
            y_range = if self.y_negated {
                // A section keeps its surface (the top) at the top edge: pad below.
                let extra = per_px * plot_px.1 as f64 - ry;
                (y0 - extra, y1)
            } else {
                widen(y_range, plot_px.1)
            };
        }
        Layout {
            plot_px,
            x_range,
            y_range,
        }
    }

    /// RGB pixels of the plotting area (row 0 at the top); white outside the cells.
    fn raster(&self, layout: &Layout) -> Vec<u8> {
        let (w, h) = layout.plot_px;
        let (x0, x1) = layout.x_range;
        let (y0, y1) = layout.y_range;
        let col_of: Vec<Option<usize>> = (0..w)
            .map(|px| {
                self.cols
                    .cell_of(x0 + (px as f64 + 0.5) / w as f64 * (x1 - x0))
            })
            .collect();
        let row_of: Vec<Option<usize>> = (0..h)
            .map(|py| {
                self.rows
                    .cell_of(y1 - (py as f64 + 0.5) / h as f64 * (y1 - y0))
            })
            .collect();
        let nx = self.cols.len();
        let mut buf = Vec::with_capacity(3 * (w * h) as usize);
        for row in &row_of {
            for col in &col_of {
                let RGBColor(r, g, b) = match (row, col) {
                    (Some(j), Some(i)) => self.scale.colour(self.values[j * nx + i]),
                    _ => WHITE,
                };
                buf.extend_from_slice(&[r, g, b]);
            }
        }
        buf
    }
}

impl Figure for MapFigure<'_> {
    fn size(&self) -> (u32, u32) {
        let (w, h) = self.layout().plot_px;
        (
            w + LEFT_AREA + 2 * MARGIN + BAR_STRIP,
            h + BOTTOM_AREA + 2 * MARGIN + TITLE_STRIP,
        )
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let layout = self.layout();
        let (width, _) = self.size();
        let (title_area, body) = root.split_vertically(TITLE_STRIP);
        draw_title(&title_area, self.title)?;
        let (main, bar) = body.split_horizontally(width - BAR_STRIP);
        let (x0, x1) = layout.x_range;
        let (y0, y1) = layout.y_range;
        let mut chart = ChartBuilder::on(&main)
            .margin(MARGIN)
            .x_label_area_size(BOTTOM_AREA)
            .y_label_area_size(LEFT_AREA)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(draw_err)?;

        let (w, h) = layout.plot_px;
        let image = BitMapElement::with_owned_buffer((x0, y1), (w, h), self.raster(&layout))
            .ok_or_else(|| anyhow::anyhow!("raster of {w} x {h} pixels has the wrong length"))?;
        chart
            .draw_series(std::iter::once(image))
            .map_err(draw_err)?;

        let y_ticks = linear_ticks(y0, y1, AXIS_TICKS);
        let y_format = |v: &f64| {
            if self.y_negated {
                y_ticks(&-v)
            } else {
                y_ticks(v)
            }
        };
        chart
            .configure_mesh()
            .disable_mesh()
            .x_labels(AXIS_TICKS)
            .y_labels(AXIS_TICKS)
            .x_label_formatter(&linear_ticks(x0, x1, AXIS_TICKS))
            .y_label_formatter(&y_format)
            .x_desc(self.x_label)
            .y_desc(self.y_label)
            .label_style(text(TICK_SIZE))
            .axis_desc_style(text(LABEL_SIZE))
            .draw()
            .map_err(draw_err)?;

        let thin = BLACK.mix(0.75).stroke_width(1);
        chart
            .draw_series(self.lines.iter().map(|l| PathElement::new(l.clone(), thin)))
            .map_err(draw_err)?;

        // Frame of the plotting area.
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(x0, y0), (x1, y1)],
                BLACK.stroke_width(1),
            )))
            .map_err(draw_err)?;

        if let Some((lines, label)) = &self.outline {
            chart
                .draw_series(
                    lines
                        .iter()
                        .map(|l| PathElement::new(l.clone(), BLACK.stroke_width(4))),
                )
                .map_err(draw_err)?;
            chart
                .draw_series(
                    lines
                        .iter()
                        .map(|l| PathElement::new(l.clone(), WHITE.stroke_width(2))),
                )
                .map_err(draw_err)?
                .label(*label)
                .legend(|(x, y)| {
                    EmptyElement::at((x, y))
                        + PathElement::new(vec![(0, 0), (24, 0)], BLACK.stroke_width(4))
                        + PathElement::new(vec![(0, 0), (24, 0)], WHITE.stroke_width(2))
                });
            chart
                .configure_series_labels()
                .position(match self.legend_corner {
                    Corner::UpperRight => SeriesLabelPosition::UpperRight,
                    Corner::UpperLeft => SeriesLabelPosition::UpperLeft,
                    Corner::LowerRight => SeriesLabelPosition::LowerRight,
                    Corner::LowerLeft => SeriesLabelPosition::LowerLeft,
                })
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .label_font(text(TICK_SIZE))
                .draw()
                .map_err(draw_err)?;
        }

        if let Some(marker) = &self.marker {
            let right_half = marker.at.0 > 0.5 * (x0 + x1);
            let anchor = plotters::style::text_anchor::Pos::new(
                if right_half {
                    plotters::style::text_anchor::HPos::Right
                } else {
                    plotters::style::text_anchor::HPos::Left
                },
                plotters::style::text_anchor::VPos::Center,
            );
            let dx = if right_half { -12 } else { 12 };
            let cross = |style: ShapeStyle| {
                EmptyElement::at(marker.at)
                    + PathElement::new(vec![(-7, -7), (7, 7)], style)
                    + PathElement::new(vec![(-7, 7), (7, -7)], style)
            };
            chart
                .draw_series([cross(WHITE.stroke_width(5)), cross(BLACK.stroke_width(2))])
                .map_err(draw_err)?;
            // The text on a light box so that it reads on any colour.
            let style = text(TICK_SIZE).pos(anchor).color(&BLACK);
            let (tw, th) = main
                .estimate_text_size(&marker.text, &style)
                .map_err(draw_err)?;
            let (tw, th) = (tw as i32, th as i32);
            let (left, right) = if right_half {
                (dx - tw - 6, dx + 6)
            } else {
                (dx - 6, dx + tw + 6)
            };
            let label = EmptyElement::at(marker.at)
                + Rectangle::new(
                    [(left, -th / 2 - 4), (right, th / 2 + 4)],
                    WHITE.mix(0.8).filled(),
                )
                + Text::new(marker.text.clone(), (dx, 0), style);
            chart
                .draw_series(std::iter::once(label))
                .map_err(draw_err)?;
        }

        // Under the map, right-aligned, level with the x description.
        let (px, py) = chart.plotting_area().get_pixel_range();
        draw_sliding_note(&main, px, py.end, 44, self.x_label)?;

        draw_colour_bar(
            &bar,
            &self.scale,
            self.colour_label,
            MARGIN,
            MARGIN + BOTTOM_AREA,
        )
    }
}
