//! The stress files of a solve or of `thirdbody stress` (docs/outputs.md): per
//! section `stress_<name>.npy` (float64, shape (11, nz, ny, nx): the six components
//! `sigma_x, sigma_y, sigma_z, tau_xy, tau_xz, tau_yz`, the principal stresses
//! `s1 >= s2 >= s3`, `tau1 = (s1 - s3)/2` and von Mises) and `stress_<name>.csv`
//! (`x,y,z` and the same eleven columns); the block also as `stress_block.vti`
//! (VTK image data); colour maps of tau1 and sigma_x in the XZ plane with contour
//! lines (paper Figs. 10-11); sigma_x along x on the surface and on both sides of
//! the interface (Figs. 9 and 12). The JSON `stress` object of `summary.json` holds
//! the library's [`thirdbody::stress::StressSummary`] and what each section covers.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

use crate::plot::{self, Series};
use crate::vtk;
use anyhow::{Context, Result};
use ndarray::Array4;
use serde_json::Value;
use thirdbody::report::StressReport;
use thirdbody::stress::{Side, StressField, StressResults};
use thirdbody::Case;

use crate::units::PlotUnits;

use crate::app::outputs::Formats;
use crate::app::section::{self, SectionId, SectionLabels};
use crate::atomic::Staging;

/// Names of the eleven stored fields, in storage order (the library's).
pub use thirdbody::stress::STORED_FIELD_NAMES as FIELD_NAMES;

/// The eleven fields of a section, in [`FIELD_NAMES`] order.
fn all_fields(f: &StressField) -> Vec<Vec<f64>> {
    f.stored_fields()
}

/// The `stress` object of `summary.json`.
pub fn summary_json(results: &StressResults) -> Result<Value> {
    Ok(serde_json::to_value(StressReport::of(results))?)
}

/// Stages every stress file of `case`'s `results` into `out`; `contact`: the contact's
/// extent along x, which the sigma_x profile of a homogeneous body frames (a coated
/// body's interface stresses reach beyond it); `u`: the plots' units.
pub fn write_stress(
    out: &mut Staging,
    results: &StressResults,
    case: &Case,
    (contact, u): (Option<(f64, f64)>, PlotUnits),
    formats: Formats,
) -> Result<()> {
    let interfaces: Vec<f64> = case
        .body
        .model()
        .interface_depths()
        .iter()
        .map(|&z| u.length(z))
        .collect();
    let lengths = |v: &[f64]| -> Vec<f64> { v.iter().map(|&z| u.length(z)).collect() };
    let stresses = |v: &[f64]| -> Vec<f64> { v.iter().map(|&s| u.stress(s)).collect() };
    let sections = section::sections(results)?;
    for &(id, f) in &sections {
        let name = id.name();
        let fields = all_fields(f);
        if formats.npy {
            out.write(&format!("stress_{name}.npy"), |p| write_npy(p, f, &fields))?;
        }
        if formats.csv {
            out.write(&format!("stress_{name}.csv"), |p| write_csv(p, f, &fields))?;
        }
        if formats.vtk && id == SectionId::Block {
            out.write("stress_block.vti", |p| {
                let spacing = f.xs.get(1).map_or(1.0, |x1| x1 - f.xs[0]);
                let lattice = vtk::Lattice::from_axes([&f.xs, &f.ys, &f.zs], spacing)?;
                let named: Vec<(&str, &[f64])> = FIELD_NAMES
                    .iter()
                    .zip(&fields)
                    .map(|(n, v)| (*n, v.as_slice()))
                    .collect();
                vtk::write_image_data(p, &lattice, &named)
            })?;
        }
        if id == SectionId::Xz && f.xs.len() >= 2 && f.zs.len() >= 2 {
            let y = f.ys[0];
            for (field, what) in [(9, "tau1"), (0, "sigma_x")] {
                out.write(&format!("stress_xz_{what}.png"), |p| {
                    plot::section_map(
                        p,
                        &lengths(&f.xs),
                        &lengths(&f.zs),
                        &stresses(&fields[field]),
                        &format!("{what} in the plane y = {}", u.length_text(y)),
                        &u.x(),
                        &u.depth(),
                        &u.stress_label(what),
                        10,
                        &interfaces,
                    )
                })?;
            }
        }
    }
    // sigma_x along x through y = 0 (or the XZ section's y) on the surface and the
    // interface (paper Figs. 9 and 12).
    let y_line = section::find(results, SectionId::Xz).map_or(0.0, |f| f.ys[0]);
    let mut row_y = y_line;
    let series: Vec<Series> = sections
        .iter()
        .filter_map(|&(id, f)| {
            let label = id.sigma_x_row_label()?;
            let j = nearest(&f.ys, y_line)?;
            row_y = f.ys[j];
            Some(Series {
                label,
                x: lengths(&f.xs),
                y: (0..f.xs.len())
                    .map(|i| u.stress(f.components[0][f.index(i, j, 0)]))
                    .collect(),
                dashed: matches!(
                    id,
                    SectionId::Interface {
                        side: Side::Below,
                        ..
                    }
                ),
            })
        })
        .collect();
    if !series.is_empty() {
        out.write("stress_sigma_x.png", |p| {
            plot::profile_plot(
                p,
                &series,
                &format!(
                    "sigma_x along x on the cell row y = {}",
                    u.length_text(row_y)
                ),
                &u.x(),
                &u.stress_label("sigma_x"),
                contact
                    .filter(|_| interfaces.is_empty())
                    .map(|(a, b)| (u.length(a), u.length(b))),
            )
        })?;
    }
    Ok(())
}

/// Index of the value nearest `y` (the first of two equally near).
pub fn nearest(ys: &[f64], y: f64) -> Option<usize> {
    (0..ys.len()).min_by(|&a, &b| (ys[a] - y).abs().total_cmp(&(ys[b] - y).abs()))
}

/// The eleven fields as a float64 NPY array of shape (11, nz, ny, nx).
fn write_npy(path: &Path, f: &StressField, fields: &[Vec<f64>]) -> Result<()> {
    let shape = (fields.len(), f.zs.len(), f.ys.len(), f.xs.len());
    let array = Array4::from_shape_vec(shape, fields.concat())
        .context("stress field size does not match its axes")?;
    ndarray_npy::write_npy(path, &array)?;
    Ok(())
}

/// `x,y,z` and the eleven fields, one line per point (x fastest, then y, then z).
fn write_csv(path: &Path, f: &StressField, fields: &[Vec<f64>]) -> Result<()> {
    let mut w = BufWriter::new(File::create(path)?);
    writeln!(w, "x,y,z,{}", FIELD_NAMES.join(","))?;
    for (k, z) in f.zs.iter().enumerate() {
        for (j, y) in f.ys.iter().enumerate() {
            for (i, x) in f.xs.iter().enumerate() {
                let n = f.index(i, j, k);
                write!(w, "{x},{y},{z}")?;
                for field in fields {
                    write!(w, ",{}", field[n])?;
                }
                writeln!(w)?;
            }
        }
    }
    w.flush()?;
    Ok(())
}
