//! `mu_vs_<key>.png`: the friction coefficient of the solved cases against the first
//! numeric axis of the sweep (the first axis whose values are all numbers, at least
//! two), one line per combination of the other axes' values (e.g. one per p0 and one
//! for the linear variant). The x axis is logarithmic when the values came from
//! log-spaced ranges or span two decades or more (all > 0). The mu axis follows
//! `[sweep] plot_scale` ([`PlotScale`]): by default logarithmic when every plotted mu
//! is positive and they span more than a factor [`AUTO_LOG_SPAN`], so that curves
//! decades apart (a Maxwell layer beside Kelvin–Voigt ones) all show. Failed cases are
//! left out; points of cases whose summary carries warnings are drawn hollow, and the
//! legend says so.
//! Axes and legends name the paper's symbols (V', C', p0', h1', ... for dimensionless
//! cases; V (m/s), C0 (m/Pa), ... for SI cases) with the case key beside them.

use std::path::{Path, PathBuf};

use anyhow::Result;
use serde_json::Value;

use super::folder::{Record, Status, SweepFile};
use thirdbody::Units;

use crate::plot::{line_plot_with, LineOptions, Series};
use crate::units::{from_name, key_symbol};

pub use thirdbody_engine::sweep::plot_scale::{PlotScale, AUTO_LOG_SPAN};

/// `symbol (key)`, or the key alone.
fn axis_label(key: &str, units: Units) -> String {
    match key_symbol(key, units) {
        Some(s) => format!("{s} ({key})"),
        None => key.to_string(),
    }
}

/// The legend's line for the points of warned cases.
pub const WARNING_NOTE: &str = "hollow: result carries a warning";

/// Whether a case's summary carries warnings (`warnings`, a non-empty list: the result
/// lies outside the model, docs/outputs.md).
pub fn carries_warning(summary: &Value) -> bool {
    summary
        .get("warnings")
        .and_then(Value::as_array)
        .is_some_and(|w| !w.is_empty())
}

/// The curves of mu against axis `x_axis` (one per combination of the other axes'
/// values, points in increasing x) and, per curve and point, whether its case carries
/// warnings.
fn mu_curves(
    file: &SweepFile,
    records: &[Record],
    x_axis: usize,
    units: Units,
) -> (Vec<Series>, Vec<Vec<bool>>) {
    let axis = &file.axes[x_axis];
    // Per series: the levels of the other axes, the curve, and per point a warning.
    let mut series: Vec<(Vec<usize>, Series, Vec<bool>)> = Vec::new();
    for r in records {
        let Some(entry) = file.cases.get(r.index).filter(|e| e.case == r.case) else {
            continue;
        };
        let (mu, warned) = match (&r.status, &r.summary) {
            (Status::Ok, Some(summary @ Value::Object(m))) => (
                m.get("friction_coefficient").and_then(Value::as_f64),
                carries_warning(summary),
            ),
            _ => (None, false),
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
        let k = match series.iter().position(|(o, _, _)| *o == others) {
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
                    Vec::new(),
                ));
                series.len() - 1
            }
        };
        series[k].1.x.push(x);
        series[k].1.y.push(mu);
        series[k].2.push(warned);
    }
    let mut hollow = Vec::with_capacity(series.len());
    let curves = series
        .into_iter()
        .map(|(_, mut s, warned)| {
            let mut points: Vec<(f64, f64, bool)> = (0..s.x.len())
                .map(|k| (s.x[k], s.y[k], warned[k]))
                .collect();
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            s.x = points.iter().map(|p| p.0).collect();
            s.y = points.iter().map(|p| p.1).collect();
            hollow.push(points.iter().map(|p| p.2).collect());
            s
        })
        .collect();
    (curves, hollow)
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
    let (series, hollow) = mu_curves(file, records, x_axis, units);
    if series.is_empty() {
        return Ok(None);
    }
    let xs: Vec<f64> = series.iter().flat_map(|s| s.x.iter().copied()).collect();
    let (lo, hi) = xs
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    let log_x = lo > 0.0 && (axis.log_spaced || hi / lo >= 100.0);
    let mu: Vec<f64> = series.iter().flat_map(|s| s.y.iter().copied()).collect();
    let options = LineOptions {
        log_x,
        log_y: file.plot_scale.log_axis(&mu),
        hollow,
        hollow_note: WARNING_NOTE.to_string(),
    };
    let path = dir.join(format!("mu_vs_{}.png", axis.name));
    // line_plot writes atomically; its temporary is one the folder recognises.
    line_plot_with(
        &path,
        &series,
        &format!(
            "Friction coefficient against {}",
            key_symbol(&axis.name, units).unwrap_or(&axis.name)
        ),
        &axis_label(&axis.name, units),
        "mu",
        &options,
    )?;
    Ok(Some(path))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_mu_axis_is_logarithmic_for_positive_values_spanning_decades() {
        use PlotScale::*;
        // Auto: log when all > 0 and the span exceeds a factor 30.
        assert!(Auto.log_axis(&[1e-5, 3e-4, 2e-3]));
        assert!(Auto.log_axis(&[1.0, 30.01]));
        assert!(!Auto.log_axis(&[1.0, 30.0]));
        // A narrow range (the paper's Fig. 7: mu from 0.0286 to 0.0298) stays linear.
        assert!(!Auto.log_axis(&[0.0286, 0.0291, 0.0298]));
        // The paper's Fig. 8 spans a factor of about 100 (its file asks for linear).
        assert!(Auto.log_axis(&[0.00104, 0.0212, 0.115]));
        // A zero or a negative value keeps the axis linear.
        assert!(!Auto.log_axis(&[0.0, 1e-4, 1e-1]));
        assert!(!Auto.log_axis(&[-1e-5, 1e-4, 1e-1]));
        assert!(!Auto.log_axis(&[]));
        // The user's choice, except that a log axis cannot show mu <= 0.
        assert!(!Linear.log_axis(&[1e-5, 2e-3]));
        assert!(Log.log_axis(&[0.004, 0.031]));
        assert!(!Log.log_axis(&[0.0, 0.031]));
        assert_eq!(PlotScale::default(), Auto);
        for name in PlotScale::NAMES {
            assert!(PlotScale::from_name(name).is_some(), "{name}");
        }
        assert_eq!(PlotScale::from_name("logarithmic"), None);
    }

    #[test]
    fn a_case_carries_a_warning_when_its_summary_lists_one() {
        use serde_json::json;
        assert!(carries_warning(&json!({"warnings": ["mu > 1"]})));
        assert!(!carries_warning(&json!({"warnings": []})));
        assert!(!carries_warning(&json!({"friction_coefficient": 0.1})));
    }

    #[test]
    fn points_of_warned_cases_are_hollow_and_stay_with_their_points() {
        use super::super::folder::{AxisEntry, CaseEntry, LevelEntry};
        use serde_json::json;
        let level = |key: &str, label: &str, v: Value| LevelEntry {
            label: label.into(),
            set: vec![(key.into(), v)],
        };
        // Axes: variant (a, b), then velocity (1e-3, 1e-2, 1e-1); the first numeric axis
        // is the velocity.
        let file = SweepFile {
            format: "f".into(),
            base_case: String::new(),
            axes: vec![
                AxisEntry {
                    name: "variant".into(),
                    log_spaced: false,
                    levels: vec![
                        LevelEntry {
                            label: "a".into(),
                            set: vec![],
                        },
                        LevelEntry {
                            label: "b".into(),
                            set: vec![],
                        },
                    ],
                },
                AxisEntry {
                    name: "loading.velocity".into(),
                    log_spaced: true,
                    levels: ["0.001", "0.01", "0.1"]
                        .iter()
                        .map(|l| level("loading.velocity", l, json!(l.parse::<f64>().unwrap())))
                        .collect(),
                },
            ],
            cases: (0..6)
                .map(|k| CaseEntry {
                    case: format!("{k:04}"),
                    levels: vec![k / 3, k % 3],
                })
                .collect(),
            plot_scale: PlotScale::Auto,
        };
        let record = |k: usize, mu: f64, warnings: &[&str]| Record {
            case: format!("{k:04}"),
            index: k,
            settings: vec![],
            status: Status::Ok,
            error: None,
            summary: Some(if warnings.is_empty() {
                json!({"friction_coefficient": mu})
            } else {
                json!({"friction_coefficient": mu, "warnings": warnings})
            }),
            solve_seconds: 0.0,
        };
        // Out of order, so that the points must be sorted with their flags.
        let records = [
            record(2, 1e-5, &[]),
            record(0, 3e-2, &["the contact reaches 0.11 R"]),
            record(1, 1e-2, &[]),
            record(5, 2e-3, &[]),
            record(3, 4e-5, &["the energy balance is off by 84 %"]),
            record(4, 1e-3, &[]),
        ];
        let (curves, hollow) = mu_curves(&file, &records, 1, Units::Dimensionless);
        assert_eq!(curves.len(), 2);
        assert_eq!(curves[0].label, "a");
        assert_eq!(curves[0].x, [1e-3, 1e-2, 1e-1]);
        assert_eq!(curves[0].y, [3e-2, 1e-2, 1e-5]);
        assert_eq!(hollow[0], [true, false, false]);
        assert_eq!(curves[1].y, [4e-5, 1e-3, 2e-3]);
        assert_eq!(hollow[1], [true, false, false]);
        // The plot itself: drawn (log mu: 1e-5 to 3e-2).
        let dir = tempfile::tempdir().unwrap();
        let path = write_mu_plot(dir.path(), &file, &records).unwrap().unwrap();
        assert!(path.ends_with("mu_vs_loading.velocity.png"));
    }

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
