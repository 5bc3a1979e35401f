//! `mu_vs_<key>.png`: the friction coefficient of the solved cases against the first
//! numeric axis of the sweep (the first axis whose values are all numbers, at least
//! two), one line per combination of the other axes' values (e.g. one per p0 and one
//! for the linear variant). The x axis is logarithmic when the values came from
//! log-spaced ranges or span two decades or more (all > 0). Failed cases are left out.
//! Axes and legends name the paper's symbols (V', C', p0', h1', ... for dimensionless
//! cases; V (m/s), C0 (m/Pa), ... for SI cases) with the case key beside them.

use std::path::{Path, PathBuf};

use anyhow::Result;
use serde_json::Value;

use super::folder::{Record, Status, SweepFile};
use crate::plot::{line_plot, Series};

/// The paper's symbol of a case key, with its unit for SI cases (section 4's primed
/// variables for dimensionless ones); `None` for keys without one.
fn symbol(key: &str, si: bool) -> Option<&'static str> {
    let (dimensionless, with_unit) = match key {
        "loading.velocity" => ("V'", "V (m/s)"),
        "loading.normal_load" => ("Q'", "Q (N)"),
        "layer.compliance" => ("C'", "C0 (m/Pa)"),
        "layer.p0" => ("p0'", "p0 (Pa)"),
        "layer.delta" => ("delta", "delta"),
        "layer.relaxation_time" => ("T'", "T (s)"),
        "coating.thickness" => ("h1'", "h1 (m)"),
        "coating.young" => ("E1'", "E1 (Pa)"),
        "coating.poisson" => ("nu1", "nu1"),
        "substrate.young" => ("E2'", "E2 (Pa)"),
        "substrate.poisson" => ("nu2", "nu2"),
        _ => return None,
    };
    Some(if si { with_unit } else { dimensionless })
}

/// `symbol (key)`, or the key alone.
fn axis_label(key: &str, si: bool) -> String {
    match symbol(key, si) {
        Some(s) => format!("{s} ({key})"),
        None => key.to_string(),
    }
}

/// Draws the plot into `dir`; `None` when there is no numeric axis or no solved case.
pub fn write_mu_plot(dir: &Path, file: &SweepFile, records: &[Record]) -> Result<Option<PathBuf>> {
    let Some(x_axis) = file
        .axes
        .iter()
        .position(|a| a.levels.len() >= 2 && a.levels.iter().all(|l| l.number().is_some()))
    else {
        return Ok(None);
    };
    let axis = &file.axes[x_axis];
    let si = records.iter().any(|r| {
        matches!(&r.summary, Some(Value::Object(m)) if m.get("units").and_then(Value::as_str) == Some("si"))
    });
    let mut series: Vec<(Vec<usize>, Series)> = Vec::new();
    for r in records {
        let Some(entry) = file.cases.get(r.index).filter(|e| e.case == r.case) else {
            continue;
        };
        let mu = match (&r.status, &r.summary) {
            (Status::Ok, Some(Value::Object(m))) => {
                m.get("friction_coefficient").and_then(Value::as_f64)
            }
            _ => None,
        };
        let (Some(mu), Some(x)) = (mu, axis.levels[entry.levels[x_axis]].number()) else {
            continue;
        };
        let others: Vec<usize> = entry
            .levels
            .iter()
            .enumerate()
            .filter(|&(a, _)| a != x_axis)
            .map(|(_, &l)| l)
            .collect();
        let k = match series.iter().position(|(o, _)| *o == others) {
            Some(k) => k,
            None => {
                let label = file
                    .axes
                    .iter()
                    .enumerate()
                    .filter(|&(a, _)| a != x_axis)
                    .map(|(a, ax)| {
                        let value = &ax.levels[entry.levels[a]].label;
                        if ax.name == super::spec::VARIANT_AXIS {
                            value.clone()
                        } else {
                            let name = symbol(&ax.name, si).unwrap_or(&ax.name);
                            format!("{name} = {value}")
                        }
                    })
                    .collect::<Vec<_>>()
                    .join(", ");
                series.push((
                    others,
                    Series {
                        label,
                        x: Vec::new(),
                        y: Vec::new(),
                        dashed: false,
                    },
                ));
                series.len() - 1
            }
        };
        series[k].1.x.push(x);
        series[k].1.y.push(mu);
    }
    let mut series: Vec<Series> = series.into_iter().map(|(_, s)| s).collect();
    if series.is_empty() {
        return Ok(None);
    }
    for s in &mut series {
        let mut points: Vec<(f64, f64)> = s.x.iter().copied().zip(s.y.iter().copied()).collect();
        points.sort_by(|a, b| a.0.total_cmp(&b.0));
        (s.x, s.y) = points.into_iter().unzip();
    }
    let xs: Vec<f64> = series.iter().flat_map(|s| s.x.iter().copied()).collect();
    let (lo, hi) = xs
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    let log_x = lo > 0.0 && (axis.log_spaced || hi / lo >= 100.0);
    let path = dir.join(format!("mu_vs_{}.png", axis.name));
    // line_plot writes atomically; its temporary is one the folder recognises.
    line_plot(
        &path,
        &series,
        &format!(
            "Friction coefficient against {}",
            symbol(&axis.name, si).unwrap_or(&axis.name)
        ),
        &axis_label(&axis.name, si),
        "mu",
        log_x,
    )?;
    Ok(Some(path))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_are_labelled_with_the_papers_symbols() {
        assert_eq!(
            axis_label("loading.velocity", false),
            "V' (loading.velocity)"
        );
        assert_eq!(
            axis_label("loading.velocity", true),
            "V (m/s) (loading.velocity)"
        );
        assert_eq!(
            axis_label("coating.thickness", false),
            "h1' (coating.thickness)"
        );
        assert_eq!(axis_label("grid.cells", false), "grid.cells");
        assert_eq!(symbol("layer.p0", false), Some("p0'"));
    }
}
