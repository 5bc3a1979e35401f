//! The files a solve writes into its output folder (docs/outputs.md): the summary
//! (`summary.json`, always), a copy of the case file (`case.toml`, which
//! `thirdbody stress` reads back), grid fields as NPY arrays of shape (ny, nx) with
//! rows along y (`pressure.npy`, `body_displacement.npy`, `gap.npy`, and with a
//! layer `compliance.npy` and `layer_displacement.npy`), the pressure as CSV
//! (`x,y,pressure`, one line per cell), the surface fields as VTK image data
//! (`surface.vti`), the stresses asked for (see [`crate::app::stress_outputs`]) and the
//! plots. `--format` chooses among NPY, CSV and VTK. All are staged and renamed into
//! place together (see [`crate::atomic`]).
//!
//! A line contact (plane strain: one row of strips along x) writes the same files as
//! profiles along x: NPY arrays of shape (nx,), the pressure as `x,pressure`, the
//! slider's shape (`shape.npy`), a VTK image one point high, and the pressure
//! profile; no colour maps (there is no y to map).

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use ndarray::{Array1, Array2};
use serde_json::Value;
use thirdbody::stress::StressResults;
use thirdbody::{Case, Grid, Solution};

use crate::app::stress_outputs;
use crate::atomic::Staging;
use crate::plot::{self, Series};
use crate::units;
use crate::vtk;

/// Which data formats to write (`--format npy,csv,vtk`; all by default). The JSON
/// summary and the plots are always written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Formats {
    /// NPY arrays.
    pub npy: bool,
    /// CSV tables.
    pub csv: bool,
    /// VTK image data (`.vti`).
    pub vtk: bool,
}

impl Default for Formats {
    fn default() -> Self {
        Formats {
            npy: true,
            csv: true,
            vtk: true,
        }
    }
}

/// Parses `--format`: a comma-separated list of `npy`, `csv`, `vtk`.
pub fn parse_formats(text: &str) -> std::result::Result<Formats, String> {
    let mut f = Formats {
        npy: false,
        csv: false,
        vtk: false,
    };
    for word in text.split(',').map(str::trim) {
        match word.to_ascii_lowercase().as_str() {
            "npy" => f.npy = true,
            "csv" => f.csv = true,
            "vtk" | "vti" => f.vtk = true,
            _ => {
                return Err(format!(
                    "unknown format {word:?}: give a comma-separated list of npy, csv, vtk"
                ))
            }
        }
    }
    Ok(f)
}

/// Everything one solve writes.
pub struct SolveOutputs<'a> {
    /// The case file's text, saved as `case.toml`.
    pub case_text: &'a str,
    /// The slider's height-map file (its name in the case, its path), copied
    /// beside `case.toml`.
    pub height_map: Option<(&'a str, &'a Path)>,
    /// The case.
    pub case: &'a Case,
    /// Its solution.
    pub solution: &'a Solution,
    /// `summary.json`'s content.
    pub summary: &'a Value,
    /// Stresses, if the case asked for them.
    pub stress: Option<&'a StressResults>,
    /// Data formats to write.
    pub formats: Formats,
}

/// Whether `name` is one of the files a solve (or `thirdbody stress`) writes: a
/// height map of that name is not copied beside them, and a new solve into the
/// folder removes those of an earlier run that it does not write again. Only exact
/// names are matched, so a user's own files in the folder are never touched.
pub fn is_output_name(name: &str) -> bool {
    const FIXED: [&str; 15] = [
        "summary.json",
        "case.toml",
        "pressure.npy",
        "pressure.csv",
        "compliance.npy",
        "body_displacement.npy",
        "gap.npy",
        "layer_displacement.npy",
        "shape.npy",
        "surface.vti",
        "pressure_map.png",
        "pressure_x.png",
        "compliance_map.png",
        "stress_block.vti",
        "stress_sigma_x.png",
    ];
    if FIXED.contains(&name) {
        return true;
    }
    if let Some(what) = name
        .strip_prefix("stress_xz_")
        .and_then(|r| r.strip_suffix(".png"))
    {
        return what == "tau1" || what == "sigma_x";
    }
    let Some(section) = name
        .strip_prefix("stress_")
        .and_then(|r| r.strip_suffix(".npy").or_else(|| r.strip_suffix(".csv")))
    else {
        return false;
    };
    let number = |k: &str| !k.is_empty() && k.bytes().all(|b| b.is_ascii_digit());
    // `interface_coating` and `interface_substrate`: the names of earlier versions.
    matches!(
        section,
        "xz" | "surface" | "interface_coating" | "interface_substrate" | "block"
    ) || section.strip_prefix("plane_").is_some_and(number)
        || section.strip_prefix("interface_").is_some_and(|rest| {
            rest.strip_suffix("_above")
                .or_else(|| rest.strip_suffix("_below"))
                .is_some_and(number)
        })
}

/// Stages `summary.json` (pretty-printed).
pub fn write_summary(out: &mut Staging, summary: &Value) -> Result<()> {
    out.write("summary.json", |path| {
        let mut text = serde_json::to_string_pretty(summary)?;
        text.push('\n');
        Ok(std::fs::write(path, text)?)
    })
}

/// Writes every output of a solve into `dir`; nothing is left there on failure.
pub fn write_all(dir: &Path, o: &SolveOutputs) -> Result<Vec<PathBuf>> {
    let (case, solution) = (o.case, o.solution);
    let g = &solution.grid;
    // What each cell carries on average: the centre value but where a contact's edge
    // cuts the cell (the load, the friction and the stresses integrate this).
    let mean = solution.mean_pressure();
    let p: &[f64] = &mean;
    let mut out = Staging::new(dir)?;
    write_summary(&mut out, o.summary)?;
    out.write("case.toml", |path| Ok(std::fs::write(path, o.case_text)?))?;
    if let Some((name, source)) = o.height_map {
        out.write(name, |path| {
            std::fs::copy(source, path)?;
            Ok(())
        })?;
    }
    let mut fields: Vec<(&str, &[f64])> = vec![
        ("pressure", p),
        ("body_displacement", &solution.body_displacement),
        ("gap", &solution.gap),
    ];
    if let Some(c) = &solution.compliance {
        fields.push(("compliance", c));
    }
    if let Some(w3) = &solution.layer_displacement {
        fields.push(("layer_displacement", w3));
    }
    if g.is_line() {
        fields.push(("shape", &solution.shape));
    }
    if o.formats.npy {
        for (name, field) in &fields {
            out.write(&format!("{name}.npy"), |path| {
                write_field_npy(path, g, field)
            })?;
        }
    }
    if o.formats.csv {
        out.write("pressure.csv", |path| write_pressure_csv(path, g, p))?;
    }
    if o.formats.vtk {
        out.write("surface.vti", |path| {
            let xs: Vec<f64> = (0..g.nx()).map(|i| g.x(i)).collect();
            let ys: Vec<f64> = (0..g.ny()).map(|j| g.y(j)).collect();
            let lattice = vtk::Lattice::from_axes([&xs, &ys, &[0.0]], g.cell())?;
            vtk::write_image_data(path, &lattice, &fields)
        })?;
    }
    if let Some(results) = o.stress {
        stress_outputs::write_stress(
            &mut out,
            results,
            case,
            (contact_x(solution), plot_units(case, solution)),
            o.formats,
        )?;
    }

    let u = plot_units(case, solution);
    let (x_label, y_label, p_label) = (u.x(), u.y(), u.pressure());
    if g.is_line() {
        let x: Vec<f64> = (0..g.nx()).map(|i| u.length(g.x(i))).collect();
        out.write("pressure_x.png", |path| {
            plot::profile_plot(
                path,
                &[Series {
                    label: "line contact".to_string(),
                    x,
                    y: p.iter().map(|&v| u.stress(v)).collect(),
                    dashed: false,
                }],
                "Pressure along x (line contact)",
                &x_label,
                &p_label,
                contact_x(solution).map(|(a, b)| (u.length(a), u.length(b))),
            )
        })?;
        return out.commit_replacing(is_output_name);
    }
    let scaled = Grid::new(
        g.nx(),
        g.ny(),
        u.length(g.cell()),
        [u.length(g.x0()), u.length(g.y0())],
    )?;
    let p_shown: Vec<f64> = p.iter().map(|&v| u.stress(v)).collect();
    out.write("pressure_map.png", |path| {
        plot::field_map(
            path,
            &scaled,
            &p_shown,
            "Contact pressure",
            &x_label,
            &y_label,
            &p_label,
            Some(p),
        )
    })?;
    out.write("pressure_x.png", |path| {
        let j = row_nearest_y0(g);
        let series = [Series {
            label: format!("y = {}", u.length_text(g.y(j))),
            x: (0..g.nx()).map(|i| scaled.x(i)).collect(),
            y: p_shown[j * g.nx()..(j + 1) * g.nx()].to_vec(),
            dashed: false,
        }];
        plot::profile_plot(
            path,
            &series,
            "Pressure along x through the centre",
            &x_label,
            &p_label,
            contact_x(solution).map(|(a, b)| (u.length(a), u.length(b))),
        )
    })?;
    if let Some(c) = &solution.compliance {
        let l = units::labels(case.units);
        out.write("compliance_map.png", |path| {
            plot::field_map(
                path,
                &scaled,
                c,
                "Layer compliance",
                &x_label,
                &y_label,
                l.compliance,
                Some(p),
            )
        })?;
    }
    out.commit_replacing(is_output_name)
}

/// How the plots of `case` write lengths and stresses: for an SI case, units chosen
/// for its window and its largest pressure.
pub fn plot_units(case: &Case, solution: &Solution) -> units::PlotUnits {
    let g = &solution.grid;
    let x_max = g.x0() + g.nx() as f64 * g.cell();
    let window = if g.is_line() {
        vec![g.x0(), x_max]
    } else {
        vec![g.x0(), g.y0(), x_max, g.y0() + g.ny() as f64 * g.cell()]
    }
    .iter()
    .fold(0.0f64, |m, v| m.max(v.abs()));
    units::PlotUnits::new(case.units, window, solution.summary().max_pressure)
}

/// The contact's extent along x (cell edges), if there is a contact.
pub fn contact_x(solution: &Solution) -> Option<(f64, f64)> {
    let s = solution.summary();
    (s.contact_area > 0.0).then_some((s.contact_x_min, s.contact_x_max))
}

/// The row whose centre is nearest y = 0 (the first of two equally near).
pub fn row_nearest_y0(g: &Grid) -> usize {
    (0..g.ny())
        .min_by(|&a, &b| g.y(a).abs().total_cmp(&g.y(b).abs()))
        .unwrap_or(0)
}

/// A grid field as a float64 NPY array of shape (ny, nx), or (nx,) for a line
/// contact.
fn write_field_npy(path: &Path, g: &Grid, field: &[f64]) -> Result<()> {
    if g.is_line() {
        anyhow::ensure!(field.len() == g.nx(), "field size does not match the grid");
        ndarray_npy::write_npy(path, &Array1::from_vec(field.to_vec()))?;
        return Ok(());
    }
    let array = Array2::from_shape_vec((g.ny(), g.nx()), field.to_vec())
        .context("field size does not match the grid")?;
    ndarray_npy::write_npy(path, &array)?;
    Ok(())
}

/// `x,y,pressure` per cell, rows along y (y outer, x inner), shortest round-trip
/// decimal form; `x,pressure` for a line contact.
fn write_pressure_csv(path: &Path, g: &Grid, p: &[f64]) -> Result<()> {
    let mut w = BufWriter::new(File::create(path)?);
    if g.is_line() {
        writeln!(w, "x,pressure")?;
        for (i, v) in p.iter().enumerate() {
            writeln!(w, "{},{}", g.x(i), v)?;
        }
        w.flush()?;
        return Ok(());
    }
    writeln!(w, "x,y,pressure")?;
    for j in 0..g.ny() {
        let y = g.y(j);
        for i in 0..g.nx() {
            writeln!(w, "{},{},{}", g.x(i), y, p[g.index(i, j)])?;
        }
    }
    w.flush()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_centre_row_is_found_for_even_and_odd_rows() {
        // 9 rows centred on 0: the middle row (j = 4) has y = 0 exactly.
        let g = Grid::centred(8, 9, 1.0, [0.0, 0.0]).unwrap();
        assert_eq!(row_nearest_y0(&g), 4);
        // Window centred at y = 1.2 with cells of 1: rows at ... -0.3, 0.7 ...
        let g = Grid::centred(8, 8, 1.0, [0.0, 1.2]).unwrap();
        let j = row_nearest_y0(&g);
        assert!((g.y(j) - -0.3).abs() < 1e-12, "{}", g.y(j));
    }

    #[test]
    fn csv_and_npy_are_laid_out_with_rows_along_y() {
        let dir = tempfile::tempdir().unwrap();
        let g = Grid::centred(8, 8, 0.5, [0.0, 0.0]).unwrap();
        let field: Vec<f64> = (0..64).map(|k| k as f64).collect();
        write_field_npy(&dir.path().join("f.npy"), &g, &field).unwrap();
        let a: Array2<f64> = ndarray_npy::read_npy(dir.path().join("f.npy")).unwrap();
        // Cell (i = 3, j = 5) holds index j * nx + i = 43.
        assert_eq!(a[[5, 3]], 43.0);
        write_pressure_csv(&dir.path().join("p.csv"), &g, &field).unwrap();
        let text = std::fs::read_to_string(dir.path().join("p.csv")).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 65);
        assert_eq!(lines[0], "x,y,pressure");
        // Line 1 + 43: x_3 = -2 + 3.5 * 0.5 = -0.25, y_5 = -2 + 5.5 * 0.5 = 0.75.
        assert_eq!(lines[44], "-0.25,0.75,43");
    }

    #[test]
    fn a_line_contact_writes_profiles_along_x() {
        let dir = tempfile::tempdir().unwrap();
        let g = Grid::line(8, 0.5, 0.0, 1.0).unwrap();
        let field: Vec<f64> = (0..8).map(|k| k as f64).collect();
        write_field_npy(&dir.path().join("f.npy"), &g, &field).unwrap();
        let a: Array1<f64> = ndarray_npy::read_npy(dir.path().join("f.npy")).unwrap();
        assert_eq!(a.len(), 8);
        assert_eq!(a[3], 3.0);
        write_pressure_csv(&dir.path().join("p.csv"), &g, &field).unwrap();
        let text = std::fs::read_to_string(dir.path().join("p.csv")).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 9);
        assert_eq!(lines[0], "x,pressure");
        // x_3 = -2 + 3.5 * 0.5 = -0.25.
        assert_eq!(lines[4], "-0.25,3");
        assert!(write_field_npy(&dir.path().join("g.npy"), &g, &field[..7]).is_err());
    }
}
