//! Plots (stubs: the real implementation is written in parallel and replaces
//! this file at merge).

use std::path::Path;

/// One curve of a line plot.
pub struct Series {
    /// Legend entry.
    pub label: String,
    /// Abscissae.
    pub x: Vec<f64>,
    /// Ordinates.
    pub y: Vec<f64>,
    /// Dashed line.
    pub dashed: bool,
}

/// Colour map of a grid field with colour bar; `outline`: draw the contour where
/// this field (e.g. pressure) becomes > 0. PNG or SVG by extension; atomic write.
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
) -> anyhow::Result<()> {
    let _ = (
        path,
        grid,
        field,
        title,
        x_label,
        y_label,
        colour_label,
        outline,
    );
    Ok(())
}

/// Line plot of several series. PNG or SVG by extension; atomic write.
pub fn line_plot(
    path: &Path,
    series: &[Series],
    title: &str,
    x_label: &str,
    y_label: &str,
    log_x: bool,
) -> anyhow::Result<()> {
    let _ = (path, title, x_label, y_label, log_x);
    for s in series {
        let _ = (&s.label, &s.x, &s.y, s.dashed);
    }
    Ok(())
}
