//! Figures for reports and papers: colour maps of surface fields (pressure, gap, layer
//! creep) with the contact boundary, colour maps of vertical sections (subsurface
//! stresses) with contour lines, and line plots of sweeps and profiles.
//!
//! Every figure has a title, labelled axes and, for maps, a labelled colour bar; maps of
//! the surface keep equal scales on x and y. The format follows the file extension:
//! `.svg` (vector; the colour raster is embedded as PNG) or `.png` (that SVG rasterised,
//! RGB, anti-aliased lines and kerned text, so both formats show one picture). Text
//! uses the embedded DejaVu Sans, so no system font is needed. Files are written
//! atomically: rendered to `<stem>.tmp-<pid>.<ext>` next to the target, then renamed.
//!
//! Conventions (docs/architecture.md, conventions): grid fields are row-major with rows along y,
//! `field[j * nx + i]` at `x = x0 + (i + 1/2) h`, `y = y0 + (j + 1/2) h`; sections are
//! row-major with rows along depth z, drawn increasing downward (z points into the body).
//!
//! Texts are drawn with the paper's symbols: the ASCII spellings `mu`, `delta`, `tau1`,
//! `sigma_x`, `E2`, ... in titles, labels and legends become μ, δ, τ₁, σₓ, E₂
//! (`output::pretty`; CSV columns keep the ASCII names). Maps and profiles along x
//! note the sliding direction ("slider moves +x →"). Sections show depths down to the
//! deepest drawn contour line, and draw no line at levels below [`LINE_FLOOR`] of the
//! peak (see [`section_map`]); the layout rules of line plots (legend
//! clear of the data, thinned tick labels, one colour per curve) are in `line`.
//!
//! Input with NaN or infinite values, empty series or mismatched lengths is refused with
//! an error naming the offending argument, and no file is left behind.

mod colour;
mod contours;
mod line;
mod map;
mod output;
#[cfg(test)]
mod tests;

use std::path::Path;

use anyhow::{bail, Result};

use colour::{min_max, ColourScale};
use contours::{contour_lines, Axis};
use map::{Corner, MapFigure, Marker};
use output::pretty;

/// One curve of a line plot.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend entry; an empty label leaves the series out of the legend.
    pub label: String,
    /// Abscissae.
    pub x: Vec<f64>,
    /// Ordinates, same length as `x`.
    pub y: Vec<f64>,
    /// Draw dashed instead of solid.
    pub dashed: bool,
}

/// How [`line_plot_with`] draws beyond [`line_plot`]: the scales of the axes and which
/// points get a hollow marker.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LineOptions {
    /// Logarithmic x axis (every x must be > 0).
    pub log_x: bool,
    /// Logarithmic y axis (every y must be > 0), with the x axis's log tick labels.
    pub log_y: bool,
    /// Per series, per point: draw the point as a hollow marker (a ring in the series'
    /// colour), whatever the number of points. Empty, or shorter than the series, for
    /// none.
    pub hollow: Vec<Vec<bool>>,
    /// The legend's line that says what a hollow marker means, shown when one is drawn.
    pub hollow_note: String,
}

/// Refuses non-finite entries, naming the argument and the first bad index.
fn check_finite(what: &str, values: &[f64]) -> Result<()> {
    if let Some((k, v)) = values.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        bail!("{what}: entry {k} is {v}; every value must be finite (no NaN or infinity)");
    }
    Ok(())
}

/// Refuses a length other than `expected`.
fn check_len(what: &str, len: usize, expected: usize, why: &str) -> Result<()> {
    if len != expected {
        bail!("{what} has {len} values; expected {expected} ({why})");
    }
    Ok(())
}

/// Refuses axis positions that are not finite and strictly increasing (at least two).
fn check_axis(what: &str, values: &[f64]) -> Result<()> {
    if values.len() < 2 {
        bail!("{what} has {} values; at least 2 are needed", values.len());
    }
    check_finite(what, values)?;
    if let Some(k) = values.windows(2).position(|w| w[1] <= w[0]) {
        bail!(
            "{what} must be strictly increasing, but entry {} ({}) <= entry {k} ({})",
            k + 1,
            values[k + 1],
            values[k]
        );
    }
    Ok(())
}

/// Colour map of a grid field (`thirdbody::Grid`: `nx`, `ny`, `cell`, `x0`, `y0`; `field`
/// row-major, rows along y, `field[j*nx+i]` at `x = x0+(i+0.5)cell`,
/// `y = y0+(j+0.5)cell`) with a colour bar and its label; `outline`: also draw the
/// contour line where that field (e.g. pressure) becomes > 0 (the contact boundary,
/// drawn on the cell edges between cells with value > 0 and cells without). Equal aspect
/// ratio of x and y.
#[allow(clippy::too_many_arguments)]
pub fn field_map(
    path: &Path,
    grid: &thirdbody::Grid,
    field: &[f64],
    title: &str,
    x_label: &str,
    y_label: &str,
    colour_label: &str,
    outline: Option<&[f64]>,
) -> Result<()> {
    let (nx, ny) = (grid.nx(), grid.ny());
    if nx < 2 || ny < 2 || !(grid.cell().is_finite() && grid.cell() > 0.0) {
        bail!(
            "field map grid of {nx} x {ny} cells of side {}: needs at least 2 x 2 cells of \
             finite positive side",
            grid.cell()
        );
    }
    if !(grid.x0().is_finite() && grid.y0().is_finite()) {
        bail!(
            "field map grid origin ({}, {}) must be finite",
            grid.x0(),
            grid.y0()
        );
    }
    check_len("field map field", field.len(), nx * ny, "grid nx * ny")?;
    check_finite("field map field", field)?;
    let cols = Axis::uniform(nx, grid.x0(), grid.cell());
    let rows = Axis::uniform(ny, grid.y0(), grid.cell());
    let legend_corner = match outline {
        Some(o) if o.len() == nx * ny => Corner::emptiest(nx, ny, |k| o[k] > 0.0),
        _ => Corner::UpperRight,
    };
    let outline = match outline {
        Some(o) => {
            check_len("field map outline", o.len(), nx * ny, "grid nx * ny")?;
            check_finite("field map outline", o)?;
            // Cells with a value > 0 are inside; the unsmoothed contour at a threshold
            // between 0 and the smallest positive value lies on the cell edges.
            let smallest_positive = o
                .iter()
                .copied()
                .filter(|&v| v > 0.0)
                .fold(f64::INFINITY, f64::min);
            let lines = if smallest_positive.is_finite() {
                contour_lines(o, &cols, &rows, &[0.5 * smallest_positive], false, 0.0)?
            } else {
                Vec::new()
            };
            Some((lines, "contact boundary"))
        }
        None => None,
    };
    let (title, x_label, y_label, colour_label) = (
        pretty(title),
        pretty(x_label),
        pretty(y_label),
        pretty(colour_label),
    );
    let figure = MapFigure {
        title: &title,
        x_label: &x_label,
        y_label: &y_label,
        colour_label: &colour_label,
        scale: ColourScale::for_values(field),
        cols,
        rows,
        values: field.to_vec(),
        y_negated: false,
        equal_aspect: true,
        lines: Vec::new(),
        outline,
        legend_corner,
        marker: None,
        interfaces: Vec::new(),
    };
    output::write_figure(path, &figure)
}

/// Line plot of several series with a legend (skipped if a single series has an empty
/// label; series with empty labels are left out of it); `log_x`: logarithmic x axis (all
/// x must then be > 0). Series of at most 30 points also mark each point.
pub fn line_plot(
    path: &Path,
    series: &[Series],
    title: &str,
    x_label: &str,
    y_label: &str,
    log_x: bool,
) -> Result<()> {
    let options = LineOptions {
        log_x,
        ..LineOptions::default()
    };
    line_figure(path, series, title, x_label, y_label, &options, false)
}

/// [`line_plot`] with the axes' scales and hollow markers of `options`.
pub fn line_plot_with(
    path: &Path,
    series: &[Series],
    title: &str,
    x_label: &str,
    y_label: &str,
    options: &LineOptions,
) -> Result<()> {
    line_figure(path, series, title, x_label, y_label, options, false)
}

/// [`line_plot`] of profiles along the sliding direction x (linear x axis), with the note
/// "slider moves +x →" under the plot. `contact`: the contact's extent along x
/// (`x_min`, `x_max`); the plot then shows it and a margin of [`PROFILE_MARGIN`] of its
/// length on each side (as far as the series reach), not the whole window, where the
/// pressure is mostly zero.
pub fn profile_plot(
    path: &Path,
    series: &[Series],
    title: &str,
    x_label: &str,
    y_label: &str,
    contact: Option<(f64, f64)>,
) -> Result<()> {
    let framed: Vec<Series>;
    let series = match contact {
        Some((lo, hi)) if lo.is_finite() && hi.is_finite() && hi > lo => {
            let margin = PROFILE_MARGIN * (hi - lo);
            let shown = (lo - margin)..=(hi + margin);
            framed = series
                .iter()
                .map(|s| {
                    let (x, y) =
                        s.x.iter()
                            .zip(&s.y)
                            .filter(|(x, _)| shown.contains(x))
                            .unzip();
                    Series { x, y, ..s.clone() }
                })
                .filter(|s: &Series| !s.x.is_empty())
                .collect();
            if framed.is_empty() {
                series
            } else {
                &framed
            }
        }
        _ => series,
    };
    line_figure(
        path,
        series,
        title,
        x_label,
        y_label,
        &LineOptions::default(),
        true,
    )
}

/// Margin beyond the contact on each side of a profile, as a fraction of the contact's
/// length.
pub const PROFILE_MARGIN: f64 = 0.15;

fn line_figure(
    path: &Path,
    series: &[Series],
    title: &str,
    x_label: &str,
    y_label: &str,
    options: &LineOptions,
    sliding_note: bool,
) -> Result<()> {
    if series.is_empty() {
        bail!("line plot '{title}': no series to draw");
    }
    for (k, s) in series.iter().enumerate() {
        let name = format!("line plot series {k} ('{}')", s.label);
        if s.x.is_empty() {
            bail!("{name} is empty");
        }
        check_len(&format!("{name} y"), s.y.len(), s.x.len(), "one y per x")?;
        check_finite(&format!("{name} x"), &s.x)?;
        check_finite(&format!("{name} y"), &s.y)?;
        if options.log_x {
            if let Some(v) = s.x.iter().find(|&&v| v <= 0.0) {
                bail!("{name} has x = {v}; a logarithmic x axis needs every x > 0");
            }
        }
        if options.log_y {
            if let Some(v) = s.y.iter().find(|&&v| v <= 0.0) {
                bail!("{name} has y = {v}; a logarithmic y axis needs every y > 0");
            }
        }
    }
    let series: Vec<Series> = series
        .iter()
        .map(|s| Series {
            label: pretty(&s.label),
            ..s.clone()
        })
        .collect();
    let figure = line::LineFigure {
        series: &series,
        title: &pretty(title),
        x_label: &pretty(x_label),
        y_label: &pretty(y_label),
        log_x: options.log_x,
        log_y: options.log_y,
        hollow: &options.hollow,
        hollow_note: &pretty(&options.hollow_note),
        sliding_note,
    };
    output::write_figure(path, &figure)
}

/// Colour map of a vertical section (e.g. a stress component in the XZ plane): `xs`
/// (len nx), `zs` (len nz, depth, drawn increasing DOWNWARD), `field[k*nx+i]` at
/// `(xs[i], zs[k])`, both strictly increasing; colour bar; contour lines (below); the
/// material `interfaces` (depths, in the units of `zs`) as dashed lines; and the extreme
/// (the value of largest magnitude) marked by a small cross, its value and position
/// written in a strip above the picture (no label covers the field). Diverging colour
/// map when the field changes sign, sequential otherwise. Equal scales on x and z unless
/// the shown depth is under about a third of the width (or the width under a third of
/// the depth): the shorter extent is then stretched, never padded.
///
/// Contour lines: `contours` evenly spaced levels dividing the field's range into
/// `contours + 1` equal parts (0 for none), of which only those whose magnitude reaches
/// [`LINE_FLOOR`] of the field's largest magnitude are drawn, and no piece of line that
/// spans fewer than [`SPECK_SPAN`] samples along both axes (see `drawn_levels`).
///
/// Depths shown (see `shown_depths`): from the first row down to the deepest row where
/// the field reaches a drawn level, or a depth of [`LINE_FLOOR`] of the peak without
/// lines, to any deeper maximum (of either sign, over the rows) that reaches [`FADED`]
/// of the peak, and to the deepest interface; then a margin of a tenth of that depth
/// (at least two rows). Deeper rows are left out of the picture (the caller's data
/// files keep them).
#[allow(clippy::too_many_arguments)]
pub fn section_map(
    path: &Path,
    xs: &[f64],
    zs: &[f64],
    field: &[f64],
    title: &str,
    x_label: &str,
    z_label: &str,
    colour_label: &str,
    contours: usize,
    interfaces: &[f64],
) -> Result<()> {
    check_axis("section xs", xs)?;
    check_finite("section interfaces", interfaces)?;
    check_axis("section zs", zs)?;
    let (nx, nz) = (xs.len(), zs.len());
    check_len("section field", field.len(), nx * nz, "xs.len() * zs.len()")?;
    check_finite("section field", field)?;
    let (lo, hi) = min_max(field);
    let levels = drawn_levels(lo, hi, contours);
    let nz = shown_depths(zs, nx, field, &levels, interfaces);
    let (zs, field) = (&zs[..nz], &field[..nz * nx]);
    let (title, x_label, z_label, colour_label) = (
        pretty(title),
        pretty(x_label),
        pretty(z_label),
        pretty(colour_label),
    );

    // Plot y = -z, rows upward: row r holds depth index k = nz - 1 - r.
    let cols = Axis::from_centres(xs);
    let rows = Axis::from_centres(zs).negated();
    let values: Vec<f64> = (0..nz)
        .flat_map(|r| {
            let k = nz - 1 - r;
            field[k * nx..(k + 1) * nx].iter().copied()
        })
        .collect();

    let lines = if levels.is_empty() {
        Vec::new()
    } else {
        contour_lines(&values, &cols, &rows, &levels, true, SPECK_SPAN)?
    };

    let (k_max, &extreme) = field
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
        .ok_or_else(|| anyhow::anyhow!("section field is empty"))?;
    let (x_max, z_max) = (xs[k_max % nx], zs[k_max / nx]);
    let marker = (extreme != 0.0).then(|| Marker {
        at: (x_max, -z_max),
        text: format!("{} at ({}, {})", short(extreme), short(x_max), short(z_max)),
    });

    let z_shown = -rows.first_edge;
    let figure = MapFigure {
        title: &title,
        x_label: &x_label,
        y_label: &z_label,
        colour_label: &colour_label,
        scale: ColourScale::for_values(field),
        cols,
        rows,
        values,
        y_negated: true,
        equal_aspect: true,
        lines,
        outline: None,
        legend_corner: Corner::UpperRight,
        marker,
        interfaces: interfaces
            .iter()
            .filter(|&&z| z > zs[0] && z < z_shown)
            .map(|z| -z)
            .collect(),
    };
    output::write_figure(path, &figure)
}

/// Fraction of a section's largest magnitude below which a deeper maximum (over the
/// rows) is not kept in the picture.
pub const FADED: f64 = 0.05;

/// Fraction of a section's largest magnitude below which no contour line is drawn,
/// unless the level lies in the core of a weaker lobe of the other sign ([`LOBE_CORE`]).
///
/// Why: near the surface outside the contact the low levels of tau1 and sigma_x cross
/// the first two depth rows only (the surface row holds the surface stresses, the next
/// row already the decay below it), so they come out as slivers hugging the surface
/// behind or ahead of the contact, where the field is a small fraction of its peak; they
/// are real values but read as stray fragments and say nothing about the structure under
/// the contact. The colour map still shows those values, and the summary and the data
/// files give them. Of the alternatives, dropping small pieces alone misses slivers that
/// are long but one row thin, and colour bands without lines for the low levels need a
/// banded colour bar; small pieces are dropped as well ([`SPECK_SPAN`]).
pub const LINE_FLOOR: f64 = 0.15;

/// A level of the sign opposite to the field's largest magnitude is drawn, below
/// [`LINE_FLOOR`], when it reaches this fraction of that sign's extreme and that extreme
/// reaches [`FADED`] of the peak: a weaker lobe of the other sign (the tension at a
/// coating's interface, paper Fig. 11b, a quarter of the compressive peak) keeps the
/// line around its core, while the low levels of the surface's tension outside the
/// contact (slivers) go.
pub const LOBE_CORE: f64 = 0.5;

/// Pieces of contour line spanning fewer sample spacings than this along both axes are
/// not drawn (specks around one or two samples, e.g. at the surface cell where the
/// pressure jumps at the contact's leading edge: a shape the grid does not resolve).
pub const SPECK_SPAN: f64 = 3.0;

/// The contour levels drawn for a field ranging over `lo..=hi`: `contours` levels
/// dividing the range into `contours + 1` equal parts, of which those whose magnitude
/// reaches [`LINE_FLOOR`] of `max(|lo|, |hi|)`, or [`LOBE_CORE`] of their own sign's
/// extreme when that sign is the weaker one and not faded. Empty for a flat field or no
/// contours.
fn drawn_levels(lo: f64, hi: f64, contours: usize) -> Vec<f64> {
    if contours == 0 || hi <= lo {
        return Vec::new();
    }
    let peak = lo.abs().max(hi.abs());
    let step = (hi - lo) / (contours + 1) as f64;
    let core = |l: f64| {
        let extreme = if l > 0.0 { hi } else { lo };
        extreme.abs() >= FADED * peak && l / extreme >= LOBE_CORE
    };
    (1..=contours)
        .map(|m| lo + m as f64 * step)
        .filter(|&l| l.abs() >= LINE_FLOOR * peak || core(l))
        .collect()
}

/// How many of the first depth rows of a section (`zs.len()` rows of `nx` values) to
/// show: where the field lives, and the material `interfaces` (depths). The deepest row
/// that matters is the deepest where the field reaches one of the drawn contour
/// `levels` (every drawn line is then in the picture; without levels, where its
/// magnitude reaches [`LINE_FLOOR`] of the peak), a deeper maximum over the rows of the
/// field's positive or negative part that reaches [`FADED`] of the peak (e.g. the
/// tension at a coating's interface), or the first row at or below the deepest
/// interface. Below it: a margin of a tenth of the depth down to there, and at least
/// two rows.
fn shown_depths(zs: &[f64], nx: usize, field: &[f64], levels: &[f64], interfaces: &[f64]) -> usize {
    let nz = zs.len();
    let row = |k: usize| &field[k * nx..(k + 1) * nx];
    let row_hi: Vec<f64> = (0..nz)
        .map(|k| row(k).iter().fold(f64::NEG_INFINITY, |m, &v| m.max(v)))
        .collect();
    let row_lo: Vec<f64> = (0..nz)
        .map(|k| row(k).iter().fold(f64::INFINITY, |m, &v| m.min(v)))
        .collect();
    let peak = (0..nz).fold(0.0f64, |m, k| m.max(row_hi[k].abs()).max(row_lo[k].abs()));
    if peak == 0.0 {
        return nz;
    }
    let reaches = |k: usize| {
        if levels.is_empty() {
            row_hi[k].abs().max(row_lo[k].abs()) >= LINE_FLOOR * peak
        } else {
            levels
                .iter()
                .any(|&l| (l > 0.0 && row_hi[k] >= l) || (l < 0.0 && row_lo[k] <= l))
        }
    };
    let mut deepest = (0..nz).rev().find(|&k| reaches(k)).unwrap_or(nz - 1);
    // Maxima over the rows of each sign's magnitude, deeper than that (the last row
    // counts when it is larger than the one above: the field grows out of the section).
    for part in [
        row_hi.iter().map(|v| v.max(0.0)).collect::<Vec<f64>>(),
        row_lo.iter().map(|v| (-v).max(0.0)).collect(),
    ] {
        let is_max = |k: usize| {
            part[k] >= FADED * peak
                && part[k] >= part[k - 1]
                && (k + 1 == nz || part[k] > part[k + 1])
        };
        if let Some(k) = (deepest + 1..nz).rev().find(|&k| is_max(k)) {
            deepest = k;
        }
    }
    if let Some(z) = interfaces.iter().copied().reduce(f64::max) {
        let below = zs.iter().position(|&d| d >= z).unwrap_or(nz - 1);
        deepest = deepest.max(below);
    }
    let z_end = zs[deepest] + MARGIN * (zs[deepest] - zs[0]);
    let by_margin = zs.iter().take_while(|&&z| z <= z_end).count();
    by_margin.max(deepest + 3).min(nz)
}

/// Margin below the deepest row that matters, as a fraction of its depth.
const MARGIN: f64 = 0.1;

/// A number with 3 significant digits for annotations.
fn short(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let magnitude = v.abs().log10().floor() as i32;
    if (-3..5).contains(&magnitude) {
        let decimals = (2 - magnitude).max(0) as usize;
        format!("{v:.decimals$}")
    } else {
        format!("{v:.2e}")
    }
}
