//! The summary of a solve as `summary.json` writes it (docs/outputs.md): the
//! library's [`thirdbody::Summary`] plus the solver report, the wall time of kernel
//! set-up and solve, the units and the window. `thirdbody solve` writes it once per
//! case; `thirdbody sweep` keeps it per case and turns its keys into the columns of
//! `results.csv`, so both commands report exactly the same quantities.

use anyhow::Result;
use serde_json::{json, Map, Value};
use thirdbody::{Case, Solution};

/// The summary of a solve as written to `summary.json`: the library's
/// [`thirdbody::Summary`] plus the solver report, the wall time of kernel set-up
/// and solve, the units and the window.
pub fn summary_json(case: &Case, solution: &Solution, solve_seconds: f64) -> Result<Value> {
    let Value::Object(mut map) = serde_json::to_value(solution.summary())? else {
        anyhow::bail!("the summary did not serialise to an object");
    };
    let g = &solution.grid;
    let [wx, wy] = g.half_widths();
    let [cx, cy] = g.centre();
    let info = &solution.info;
    let extra: Map<String, Value> = json!({
        "solve_seconds": solve_seconds,
        "units": crate::units::labels(case.units).name,
        "method": info.method,
        "linear_iterations": info.linear_iterations,
        "windows": info.windows,
        "window_x_min": cx - wx,
        "window_x_max": cx + wx,
        "window_y_min": cy - wy,
        "window_y_max": cy + wy,
    })
    .as_object()
    .cloned()
    .unwrap_or_default();
    map.extend(extra);
    Ok(Value::Object(map))
}
