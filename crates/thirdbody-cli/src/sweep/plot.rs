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
use thirdbody::Units;

use crate::plot::{line_plot, Series};
use crate::units::{from_name, key_symbol};

/// `symbol (key)`, or the key alone.
fn axis_label(key: &str, units: Units) -> String {
    match key_symbol(key, units) {
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
    // SI labels if any solved case is in SI units.
    let si = records.iter().any(|r| {
        matches!(&r.summary, Some(Value::Object(m))
            if m.get("units").and_then(Value::as_str).and_then(from_name) == Some(Units::Si))
    });
    let units = if si { Units::Si } else { Units::Dimensionless };
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
                            let name = key_symbol(&ax.name, units).unwrap_or(&ax.name);
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
            key_symbol(&axis.name, units).unwrap_or(&axis.name)
        ),
        &axis_label(&axis.name, units),
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
            axis_label("loading.velocity", Units::Dimensionless),
            "V' (loading.velocity)"
        );
        assert_eq!(
            axis_label("loading.velocity", Units::Si),
            "V (m/s) (loading.velocity)"
        );
        assert_eq!(
            axis_label("coating.thickness", Units::Dimensionless),
            "h1' (coating.thickness)"
        );
        assert_eq!(axis_label("grid.cells", Units::Dimensionless), "grid.cells");
        assert_eq!(key_symbol("layer.p0", Units::Dimensionless), Some("p0'"));
    }
}
