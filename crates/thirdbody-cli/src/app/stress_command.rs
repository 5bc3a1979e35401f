//! `thirdbody stress DIR`: subsurface stresses for a case already solved into DIR by
//! `thirdbody solve`. The problem is rebuilt from the folder's `case.toml` (a height
//! map is read from DIR, where `solve` copied it) and solved again, so the stresses
//! are computed on the case's own body and window; the pressure the folder holds
//! (`pressure.npy`, or `pressure.csv`) must be that solution's, or the folder does not
//! belong to its case and nothing is written. The request is the case's `[stress]`
//! section, or that of `--request FILE`, or the defaults. The stress files are
//! staged and renamed into DIR, and `summary.json` is replaced (atomically) by one
//! with the new `stress` object.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};

use crate::heightmap;
use anyhow::{Context, Result};
use clap::Args;
use ndarray::{Array1, Array2};
use serde_json::Value;
use thirdbody::case_file::parse_case_file;
use thirdbody::{Grid, KernelCache};

use crate::app::outputs::{self, Formats};
use crate::app::{progress, report, stress_outputs, BadInput};
use crate::atomic::Staging;

/// Arguments of `thirdbody stress`.
#[derive(Args)]
pub struct StressArgs {
    /// A folder written by `thirdbody solve`.
    dir: PathBuf,
    /// A TOML file with a `[stress]` section to use instead of the case's.
    #[arg(long, value_name = "FILE")]
    request: Option<PathBuf>,
    /// Data formats to write: a comma-separated list of npy, csv, vtk (default all).
    #[arg(long, value_name = "LIST", value_parser = outputs::parse_formats)]
    format: Option<Formats>,
    /// Print nothing but errors.
    #[arg(long)]
    quiet: bool,
}

/// How closely the folder's pressure must match the case's solution, relative to the
/// maximum pressure (a solve is deterministic; this allows for a CSV's rounding).
const PRESSURE_AGREEMENT: f64 = 1e-9;

fn bad(message: String) -> anyhow::Error {
    BadInput(message).into()
}

fn read_text(path: &Path, what: &str) -> Result<String> {
    std::fs::read_to_string(path).map_err(|e| {
        bad(format!(
            "cannot read {} ({what}): {e}; is this a folder written by thirdbody solve?",
            path.display()
        ))
    })
}

/// The case text with its `[stress]` table replaced by the request file's (or an
/// empty one, for the defaults, when neither has one).
fn case_with_request(case_text: &str, request: Option<&Path>) -> Result<String> {
    let mut case: toml::Table = case_text.parse().map_err(|e| {
        bad(format!(
            "case.toml of the solved folder does not parse: {e}"
        ))
    })?;
    if let Some(path) = request {
        let text = read_text(path, "the stress request")?;
        let mut table: toml::Table = text.parse().map_err(|e: toml::de::Error| {
            bad(format!(
                "{}: {}",
                path.display(),
                e.message().replace('\n', " ")
            ))
        })?;
        let stress = table.remove("stress").ok_or_else(|| {
            bad(format!(
                "{} has no [stress] section: give one (an empty one means the defaults)",
                path.display()
            ))
        })?;
        if let Some(other) = table.keys().next() {
            return Err(bad(format!(
                "{}: only a [stress] section is read from a request file, found {other}",
                path.display()
            )));
        }
        case.insert("stress".into(), stress);
    } else if !case.contains_key("stress") {
        case.insert("stress".into(), toml::Value::Table(toml::Table::new()));
    }
    Ok(toml::to_string(&case)?)
}

/// The pressure, row-major with rows along y, from `pressure.npy` or `pressure.csv`.
fn read_pressure(dir: &Path, grid: &Grid) -> Result<Vec<f64>> {
    let npy = dir.join("pressure.npy");
    let csv = dir.join("pressure.csv");
    let p = if npy.exists() {
        if grid.is_line() {
            let a: Array1<f64> = ndarray_npy::read_npy(&npy).map_err(|e| {
                bad(format!(
                    "cannot read {} as a line contact's profile of shape ({},): {e}",
                    npy.display(),
                    grid.nx()
                ))
            })?;
            if a.len() != grid.nx() {
                return Err(bad(format!(
                    "{} has {} points; its case.toml solves to ({},)",
                    npy.display(),
                    a.len(),
                    grid.nx()
                )));
            }
            return Ok(a.to_vec());
        }
        let a: Array2<f64> = ndarray_npy::read_npy(&npy)
            .map_err(|e| bad(format!("cannot read {}: {e}", npy.display())))?;
        if a.dim() != (grid.ny(), grid.nx()) {
            return Err(bad(format!(
                "{} has shape {:?}; its case.toml solves to ({}, {})",
                npy.display(),
                a.dim(),
                grid.ny(),
                grid.nx()
            )));
        }
        a.iter().copied().collect()
    } else if csv.exists() {
        let text = read_text(&csv, "the pressure")?;
        let p: Vec<f64> = text
            .lines()
            .skip(1)
            .map(|l| l.rsplit(',').next().and_then(|v| v.parse().ok()))
            .collect::<Option<_>>()
            .ok_or_else(|| {
                bad(format!(
                    "{} has a line that does not end in the pressure",
                    csv.display()
                ))
            })?;
        if p.len() != grid.len() {
            return Err(bad(format!(
                "{} has {} cells; its case.toml solves to {}",
                csv.display(),
                p.len(),
                grid.len()
            )));
        }
        p
    } else {
        return Err(bad(format!(
            "{} has neither pressure.npy nor pressure.csv: solve with --format including npy \
             or csv",
            dir.display()
        )));
    };
    Ok(p)
}

/// Runs `thirdbody stress`.
pub fn run(args: &StressArgs) -> Result<()> {
    let dir = &args.dir;
    if !dir.is_dir() {
        return Err(bad(format!("{} is not a folder", dir.display())));
    }
    let case_text = read_text(&dir.join("case.toml"), "the solved case")?;
    let text = case_with_request(&case_text, args.request.as_deref())?;
    let file = parse_case_file(&text, &mut |map, cell_size| {
        heightmap::load(dir, map, cell_size)
    })?;
    let request = file
        .stress
        .context("the stress request vanished while parsing")?;
    let summary_path = dir.join("summary.json");
    let mut summary: Value = serde_json::from_str(&read_text(&summary_path, "the summary")?)
        .map_err(|e| bad(format!("{}: {e}", summary_path.display())))?;
    thirdbody_engine::geometry::check(&file.case, Some(&request)).map_err(bad)?;
    crate::memory::check(
        &file.case,
        Some(&request),
        1,
        crate::memory::available_bytes(),
    )
    .map_err(bad)?;
    let solution = thirdbody::solve_with(
        &file.case,
        &file.solver,
        &mut KernelCache::new(),
        &mut |_| std::ops::ControlFlow::Continue(()),
    )?;
    let pressure = read_pressure(dir, &solution.grid)?;
    let mean = solution.mean_pressure();
    let scale = mean.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let worst = pressure
        .iter()
        .zip(mean.iter())
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    let agrees = worst <= PRESSURE_AGREEMENT * scale;
    if !agrees {
        return Err(bad(format!(
            "the pressure in {} is not the solution of its case.toml (they differ by {:.3e} \
             of the maximum pressure): solve the case again into the folder",
            dir.display(),
            worst / scale
        )));
    }
    let bar = progress::StressBar::new(!args.quiet && std::io::stderr().is_terminal());
    let results = solution.stress_results_observed(&request, &|e| bar.observe(e));
    bar.finish();
    let results = results?;

    let mut out = Staging::new(dir)?;
    stress_outputs::write_stress(
        &mut out,
        &results,
        &file.case,
        (
            outputs::contact_x(&solution),
            outputs::plot_units(&file.case, &solution),
        ),
        args.format.unwrap_or_default(),
    )?;
    summary["stress"] = stress_outputs::summary_json(&results)?;
    outputs::write_summary(&mut out, &summary)?;
    out.commit()?;
    if !args.quiet {
        crate::say!("{}", report::stress_summary(&results.summary));
        crate::say!("stresses in {}", dir.display());
    }
    Ok(())
}
