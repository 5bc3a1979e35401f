//! The short human summary printed after a solve.

use std::fmt::Write;

use thirdbody::grid::Geometry;
use thirdbody::{Case, Solution};

/// The first line of a summary: the method, iterations, residual and windows.
fn solve_line(solution: &Solution, solve_seconds: f64) -> String {
    let (s, info) = (solution.summary(), &solution.info);
    let method = serde_json::to_value(info.method)
        .ok()
        .and_then(|v| v.as_str().map(str::to_string))
        .unwrap_or_default();
    format!(
        "solved in {solve_seconds:.2} s: {method}, {} iterations, residual {:.1e}, {} window{}",
        s.iterations,
        s.residual,
        info.windows,
        if info.windows == 1 { "" } else { "s" }
    )
}

/// [`human_summary`] of a line contact (plane strain).
fn line_summary(case: &Case, solution: &Solution, solve_seconds: f64, datum: f64) -> String {
    let s = solution.summary();
    let l = crate::units::labels(case.units);
    let (len, stress) = (l.length_unit, l.stress_unit);
    let (force, moment) = (l.line_force_unit, l.line_moment_unit);
    let mut t = solve_line(solution, solve_seconds);
    let _ = writeln!(
        t,
        "\n  line contact  plane strain, loads per unit length, approach measured from \
         {datum:.4e}{len}"
    );
    let _ = writeln!(
        t,
        "  grid          {} cells of {:.4e}{len}",
        s.nx, s.cell_size
    );
    let _ = writeln!(
        t,
        "  load          Q = {:.4e}{force}, penetration D = {:.4e}{len}",
        s.normal_load, s.penetration
    );
    let _ = writeln!(
        t,
        "  max pressure  {:.4e}{stress} at x = {:.4e}{len}",
        s.max_pressure, s.max_pressure_x
    );
    let _ = writeln!(
        t,
        "  contact       width {:.4e}{len}, x from {:.4e} to {:.4e}{len}",
        s.contact_area, s.contact_x_min, s.contact_x_max
    );
    let _ = write!(
        t,
        "  friction      mu = {:.4e}, Q_T = {:.4e}{force}, moment M = {:.4e}{moment}",
        s.friction_coefficient, s.tangential_force, s.moment
    );
    t
}

/// A few lines: how the solve went, then D, the maximum pressure, the contact's
/// area and extent, and the friction. A line contact's say so, give its loads and
/// forces per unit length and its contact's width, and have no y.
pub fn human_summary(case: &Case, solution: &Solution, solve_seconds: f64) -> String {
    if let Geometry::Line { datum } = solution.grid.geometry() {
        return line_summary(case, solution, solve_seconds, datum);
    }
    let s = solution.summary();
    let l = crate::units::labels(case.units);
    let (len, area, force, stress, moment) = (
        l.length_unit,
        l.area_unit,
        l.force_unit,
        l.stress_unit,
        l.moment_unit,
    );
    let mut t = solve_line(solution, solve_seconds);
    t.push('\n');
    let _ = writeln!(
        t,
        "  grid          {} x {} cells of {:.4e}{len}",
        s.nx, s.ny, s.cell_size
    );
    let _ = writeln!(
        t,
        "  load          Q = {:.4e}{force}, penetration D = {:.4e}{len}",
        s.normal_load, s.penetration
    );
    let _ = writeln!(
        t,
        "  max pressure  {:.4e}{stress} at x = {:.4e}{len}, y = {:.4e}{len}",
        s.max_pressure, s.max_pressure_x, s.max_pressure_y
    );
    let _ = writeln!(
        t,
        "  contact       area {:.4e}{area}, x from {:.4e} to {:.4e}{len}, y from {:.4e} to \
         {:.4e}{len}",
        s.contact_area, s.contact_x_min, s.contact_x_max, s.contact_y_min, s.contact_y_max
    );
    let _ = write!(
        t,
        "  friction      mu = {:.4e}, Q_T = {:.4e}{force}, moment M = {:.4e}{moment}",
        s.friction_coefficient, s.tangential_force, s.moment
    );
    t
}

/// The stress lines printed after a solve or `thirdbody stress` (values in the
/// case's stress unit; only the ones the request produced).
pub fn stress_summary(s: &thirdbody::stress::StressSummary) -> String {
    let mut t = String::from("  stresses     ");
    let mut parts = Vec::new();
    if let (Some(v), Some(x), Some(z)) = (s.tau1_max, s.tau1_max_x, s.tau1_max_z) {
        parts.push(format!("tau1 max {v:.4e} at x = {x:.4e}, z = {z:.4e}"));
    }
    if let (Some(lo), Some(hi)) = (s.sigma_x_min, s.sigma_x_max) {
        parts.push(format!("surface sigma_x {lo:.4e} .. {hi:.4e}"));
    }
    for i in &s.interfaces {
        let side = |r: Option<thirdbody::stress::SigmaXRange>| {
            r.map_or("-".to_string(), |r| format!("{:.4e}", r.sigma_x_max))
        };
        parts.push(format!(
            "interface {} (z = {:.4e}) sigma_x max {} above, {} below",
            i.index,
            i.depth,
            side(i.above),
            side(i.below)
        ));
    }
    let mut text = parts.join("; ");
    for l in &s.layers {
        let name = if l.base {
            "base    ".to_string()
        } else {
            format!("layer {:<2}", l.index)
        };
        text.push_str(&format!(
            "\n  {name}      tau1 max {:.4e}, von Mises max {:.4e} (XZ section)",
            l.tau1_max, l.von_mises_max
        ));
    }
    t.push_str(&text);
    t
}
