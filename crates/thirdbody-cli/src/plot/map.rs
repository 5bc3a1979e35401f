//! Colour maps of fields on rectilinear cells (a surface grid or a vertical section):
//! the raster of cell colours at the plot's pixel resolution, optional contour lines,
//! an outline, material interfaces, a marked extreme, the note of the sliding direction
//! under the map, and the colour bar.
//!
//! Nothing is written over the data but lines and the small cross of the extreme: the
//! extreme's value and the interfaces' legend go to a strip between the title and the
//! plotting area (the legend of a surface map's outline goes to the corner the contact
//! leaves emptiest). A section is drawn without padding: at equal scales when its depth
//! is between `SHORT_SIDE_MIN / LONG_SIDE` (about a third) and the inverse of that times
//! its width, else with the shorter extent stretched to that ratio (the ticks give each
//! axis its scale).

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
/// Height of one line of the strip above a section (the extreme's value, the
/// interfaces' legend), pixels.
const HEADER_LINE: u32 = 26;

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
    /// Horizontal lines across the map at these plot y (a section's material
    /// interfaces, at minus their depth), drawn dashed and named in the strip above.
    pub interfaces: Vec<f64>,
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
        let (w, h) = if self.y_negated {
            // A section: no padding; the shorter extent stretched when it is too short.
            if ratio <= 1.0 {
                (LONG_SIDE, (LONG_SIDE * ratio).max(SHORT_SIDE_MIN))
            } else {
                ((LONG_SIDE / ratio).max(SHORT_SIDE_MIN), LONG_SIDE)
            }
        } else if !self.equal_aspect {
            (LONG_SIDE, 0.68 * LONG_SIDE)
        } else if ratio <= 1.0 {
            (LONG_SIDE, (LONG_SIDE * ratio).max(SHORT_SIDE_MIN))
        } else {
            ((LONG_SIDE / ratio).max(SHORT_SIDE_MIN), LONG_SIDE)
        };
        let plot_px = (w.round() as u32, h.round() as u32);
        let (mut x_range, mut y_range) = ((x0, x1), (y0, y1));
        if self.equal_aspect && !self.y_negated {
            // Same data length per pixel on both axes: widen the axis that has less.
            let per_px = (rx / plot_px.0 as f64).max(ry / plot_px.1 as f64);
            let widen = |(a, b): (f64, f64), px: u32| {
                let half = 0.5 * per_px * px as f64;
                let mid = 0.5 * (a + b);
                (mid - half, mid + half)
            };
            x_range = widen(x_range, plot_px.0);
            y_range = widen(y_range, plot_px.1);
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

/// Dash and gap of an interface line, pixels.
const INTERFACE_DASH: (u32, u32) = (8, 5);
/// Length of the interface line's sample in the legend, pixels.
const INTERFACE_SAMPLE: i32 = 30;

/// Width of `s` in the tick labels' font, pixels (the font is registered before any
/// drawing; 0 if it cannot be measured).
fn text_width(s: &str) -> i32 {
    use plotters::style::IntoFont;
    (super::output::FAMILY, TICK_SIZE)
        .into_font()
        .layout_box(s)
        .map_or(0, |((x0, _), (x1, _))| x1 - x0)
}

impl MapFigure<'_> {
    /// Lines of the strip above the plotting area for a plotting area `width` pixels
    /// wide: none without a marker and interfaces, two when the marker's text and the
    /// interfaces' legend do not fit side by side.
    fn header_lines(&self, width: u32) -> u32 {
        let marker = self.marker.as_ref().map(|m| text_width(&m.text) + 24);
        let legend = (!self.interfaces.is_empty())
            .then(|| INTERFACE_SAMPLE + 8 + text_width(self.interface_label()));
        match (marker, legend) {
            (None, None) => 0,
            (Some(a), Some(b)) if a + b + 24 > width as i32 => 2,
            _ => 1,
        }
    }

    fn interface_label(&self) -> &'static str {
        if self.interfaces.len() > 1 {
            "interfaces between materials"
        } else {
            "interface between materials"
        }
    }
}

impl Figure for MapFigure<'_> {
    fn size(&self) -> (u32, u32) {
        let (w, h) = self.layout().plot_px;
        (
            w + LEFT_AREA + 2 * MARGIN + BAR_STRIP,
            h + BOTTOM_AREA + 2 * MARGIN + TITLE_STRIP + self.header_lines(w) * HEADER_LINE,
        )
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let layout = self.layout();
        let (width, _) = self.size();
        let (title_area, body) = root.split_vertically(TITLE_STRIP);
        draw_title(&title_area, self.title)?;
        let header_lines = self.header_lines(layout.plot_px.0);
        let (_, body) = body.split_vertically(header_lines * HEADER_LINE);
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

        // Interfaces: dashed black over a light halo, so they read on any colour.
        for &y in &self.interfaces {
            let across = [(x0, y), (x1, y)];
            chart
                .draw_series(std::iter::once(PathElement::new(
                    across.to_vec(),
                    WHITE.mix(0.7).stroke_width(4),
                )))
                .map_err(draw_err)?;
            chart
                .draw_series(DashedLineSeries::new(
                    across,
                    INTERFACE_DASH.0,
                    INTERFACE_DASH.1,
                    BLACK.stroke_width(2),
                ))
                .map_err(draw_err)?;
        }

        if let Some(marker) = &self.marker {
            let cross = |style: ShapeStyle| {
                EmptyElement::at(marker.at)
                    + PathElement::new(vec![(-7, -7), (7, 7)], style)
                    + PathElement::new(vec![(-7, 7), (7, -7)], style)
            };
            chart
                .draw_series([cross(WHITE.stroke_width(5)), cross(BLACK.stroke_width(2))])
                .map_err(draw_err)?;
        }
        // The strip above the plotting area: the extreme's cross and value at its right,
        // the interfaces' legend at its left (on a second line when both do not fit).
        let (px, py) = chart.plotting_area().get_pixel_range();
        let line_centre = |line: u32| {
            py.start - MARGIN as i32 - ((header_lines - line) * HEADER_LINE) as i32
                + HEADER_LINE as i32 / 2
        };
        if let Some(marker) = &self.marker {
            let style = text(TICK_SIZE).pos(plotters::style::text_anchor::Pos::new(
                plotters::style::text_anchor::HPos::Right,
                plotters::style::text_anchor::VPos::Center,
            ));
            let y = line_centre(0);
            root.draw_text(&marker.text, &style, (px.end, y))
                .map_err(draw_err)?;
            let w = text_width(&marker.text);
            let at = (px.end - w - 14, y);
            root.draw(
                &(EmptyElement::at(at)
                    + PathElement::new(vec![(-5, -5), (5, 5)], BLACK.stroke_width(2))
                    + PathElement::new(vec![(-5, 5), (5, -5)], BLACK.stroke_width(2))),
            )
            .map_err(draw_err)?;
        }
        if !self.interfaces.is_empty() {
            let line = if header_lines > 1 || self.marker.is_none() {
                header_lines - 1
            } else {
                0
            };
            let y = line_centre(line);
            let x = px.start;
            let mut dash = 0;
            while dash < INTERFACE_SAMPLE {
                let end = (dash + INTERFACE_DASH.0 as i32).min(INTERFACE_SAMPLE);
                root.draw(&PathElement::new(
                    vec![(x + dash, y), (x + end, y)],
                    BLACK.stroke_width(2),
                ))
                .map_err(draw_err)?;
                dash = end + INTERFACE_DASH.1 as i32;
            }
            let style = text(TICK_SIZE).pos(plotters::style::text_anchor::Pos::new(
                plotters::style::text_anchor::HPos::Left,
                plotters::style::text_anchor::VPos::Center,
            ));
            root.draw_text(
                self.interface_label(),
                &style,
                (x + INTERFACE_SAMPLE + 8, y),
            )
            .map_err(draw_err)?;
        }

        // Under the map, right-aligned, level with the x description.
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
