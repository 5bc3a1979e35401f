//! Rendering shared by the figures: line plots with their CSV, colour maps of an XZ
//! section with theirs, the rows the paper plots (pressure and sigma_x along x
//! through y = 0), the parameter-study curves, and the report's entries.

use crate::plot::{self, Series};
use anyhow::Result;
use thirdbody::stress::StressField;
use thirdbody::Solution;

use crate::units::{self, Labels};
use thirdbody::Units;

use super::catalogue::Study;
use super::solutions::Solutions;
use super::{FigureFiles, FigureReport, KeyNumber};
use crate::app::outputs::row_nearest_y0;
use crate::app::stress_outputs::nearest;

/// The paper's dimensionless labels of plot axes, colour bars and CSV columns.
pub const L: &Labels = units::labels(Units::Dimensionless);

/// `sigma_x / E2` etc.
pub fn stress_label(name: &str) -> String {
    format!("{name} {}", L.stress_scale)
}

/// A report entry without numbers yet.
pub fn report(id: &str, title: &str, parameters: String) -> FigureReport {
    FigureReport {
        id: id.into(),
        title: title.into(),
        parameters,
        files: Vec::new(),
        numbers: Vec::new(),
        notes: Vec::new(),
    }
}

/// A key number of the report.
pub fn number(name: impl Into<String>, ours: f64, paper: Option<f64>) -> KeyNumber {
    KeyNumber {
        name: name.into(),
        ours,
        paper,
    }
}

/// The largest contact pressure.
pub fn max_pressure(s: &Solution) -> f64 {
    s.summary().max_pressure
}

/// Stages a line plot (PNG + SVG) and its CSV (all points); a plot along x (linear) is
/// a profile that notes the sliding direction and, given the `contact`'s extent along
/// x, frames it.
pub fn line_figure(
    files: &mut FigureFiles,
    stem: &str,
    series: &[Series],
    title: &str,
    [x_label, y_label]: [&str; 2],
    (log_x, contact): (bool, Option<(f64, f64)>),
) -> Result<()> {
    files.series_csv(&format!("{stem}.csv"), ["series", x_label, y_label], series)?;
    files.plot(stem, |p| {
        if x_label == L.x && !log_x {
            // A profile along the sliding direction.
            plot::profile_plot(p, series, title, x_label, y_label, contact)
        } else {
            plot::line_plot(p, series, title, x_label, y_label, log_x)
        }
    })
}

/// The extent along x of the union of the solutions' contacts (cell edges).
pub fn contact_x<'a, S>(solutions: impl IntoIterator<Item = &'a S>) -> Option<(f64, f64)>
where
    S: std::ops::Deref<Target = Solution> + 'a,
{
    solutions
        .into_iter()
        .map(|s| s.summary())
        .filter(|s| s.contact_area > 0.0)
        .map(|s| (s.contact_x_min, s.contact_x_max))
        .reduce(|a, b| (a.0.min(b.0), a.1.max(b.1)))
}

/// Pressure along x at the centres of the cell row nearest y = 0 (behind a rising
/// leading edge, the pressure at the entry cell's centre).
pub fn pressure_row(s: &Solution, label: String, dashed: bool) -> Series {
    let g = &s.grid;
    let j = row_nearest_y0(g);
    Series {
        label,
        x: (0..g.nx()).map(|i| g.x(i)).collect(),
        y: s.centre_pressure()[j * g.nx()..(j + 1) * g.nx()].to_vec(),
        dashed,
    }
}

/// sigma_x along x on the row of a plane section (surface, interface) nearest y = 0.
pub fn sigma_x_row(f: &StressField, label: String, dashed: bool) -> Series {
    let j = nearest(&f.ys, 0.0).unwrap_or(0);
    Series {
        label,
        x: f.xs.clone(),
        y: (0..f.xs.len())
            .map(|i| f.components[0][f.index(i, j, 0)])
            .collect(),
        dashed,
    }
}

/// Stages the colour map (PNG + SVG) of `values` on the XZ section `f` of a body with
/// material interfaces at depths `interfaces`, and its data as `stem.csv` with columns
/// `x', z', name`.
pub fn xz_map(
    files: &mut FigureFiles,
    stem: &str,
    (f, interfaces): (&StressField, &[f64]),
    values: &[f64],
    name: &str,
    title: &str,
) -> Result<()> {
    files.plot(stem, |p| {
        plot::section_map(
            p,
            &f.xs,
            &f.zs,
            values,
            title,
            L.x,
            L.depth,
            &stress_label(name),
            10,
            interfaces,
        )
    })?;
    let rows: Vec<Vec<f64>> = (0..f.zs.len())
        .flat_map(|k| (0..f.xs.len()).map(move |i| (i, k)))
        .map(|(i, k)| vec![f.xs[i], f.zs[k], values[f.index(i, 0, k)]])
        .collect();
    files.table_csv(&format!("{stem}.csv"), &[L.x, "z'", name], &rows)
}

/// A parameter study: `mu` of each curve's case at each value; points whose solve
/// fails are left out of the curve and named in the notes.
pub fn mu_curves(solutions: &mut Solutions, study: &Study, notes: &mut Vec<String>) -> Vec<Series> {
    study
        .curves
        .iter()
        .map(|curve| {
            let (mut x, mut y) = (Vec::new(), Vec::new());
            for (v, s) in study.values.iter().zip(solutions.solve(&curve.cases)) {
                match s {
                    Ok(s) => {
                        x.push(*v);
                        y.push(s.summary().friction_coefficient);
                    }
                    Err(e) => notes.push(format!(
                        "{}, {} = {v:.4e}: not solved ({e})",
                        curve.label, study.key
                    )),
                }
            }
            Series {
                label: curve.label.to_string(),
                x,
                y,
                dashed: curve.dashed,
            }
        })
        .collect()
}

/// mu at both ends of each curve.
pub fn push_curve_ends(rep: &mut FigureReport, series: &[Series], key: &str) {
    for s in series {
        if let (Some(x0), Some(y0), Some(x1), Some(y1)) =
            (s.x.first(), s.y.first(), s.x.last(), s.y.last())
        {
            rep.numbers.push(number(
                format!("mu, {}, {key} = {x0:.3e}", s.label),
                *y0,
                None,
            ));
            rep.numbers.push(number(
                format!("mu, {}, {key} = {x1:.3e}", s.label),
                *y1,
                None,
            ));
        }
    }
}
