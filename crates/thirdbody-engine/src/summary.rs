//! The summary of a solve as `summary.json` writes it (docs/outputs.md): the
//! library's [`thirdbody::Report`] as JSON. `thirdbody solve` writes it once per case;
//! `thirdbody sweep` keeps it per case and turns its keys into the columns of
//! `results.csv`, so both commands report exactly the same quantities.

use anyhow::Result;
use serde_json::Value;
use thirdbody::stress::StressResults;
use thirdbody::{Case, Report, Solution};

/// The summary of a solve as written to `summary.json` (see [`thirdbody::Report`]),
/// with the `stress` object when stresses were computed.
pub fn summary_json(
    case: &Case,
    solution: &Solution,
    solve_seconds: f64,
    stress: Option<&StressResults>,
) -> Result<Value> {
    Ok(serde_json::to_value(Report::new(
        case,
        solution,
        solve_seconds,
        stress,
    ))?)
}
