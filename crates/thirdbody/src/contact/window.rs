//! The automatic window and the initial pressure guesses. The contact's size is
//! estimated from three limits: Hertz (`a = (3 Q R / 4 E*)^(1/3)`, Johnson eq.
//! 4.22), a Winkler bed of compliance C0 (`a = (4 R C0 Q / pi)^(1/4)`), and the
//! creep-dominated rigid-base limit, where the pressure is `p ~ V T x / (C0 R)` on a
//! half disc ahead of the initial contact of radius `r = (3 Q C0 R / (2 V T))^(1/3)`
//! (docs/architecture.md (readings of the paper)). After a solve the window is enlarged if the contact reaches its
//! edge, and refitted once if the contact fills too little of it.

use rayon::prelude::*;

use crate::case::Case;
use crate::convolution::Parallelism;
use crate::error::{Error, Result};
use crate::grid::{Geometry, Grid};
use crate::layer::LayerEstimate;
use crate::passes::Passes;
use crate::solution::Solution;

/// Margin of the window around the estimated contact.
const MARGIN: f64 = 1.25;
/// Enlargement when the contact reaches the window's edge.
const ENLARGE: f64 = 1.6;
/// A refit is done when it makes the cells at least this much smaller.
const REFIT_GAIN: f64 = 0.8;
/// Fewest loaded cells across the contact for a meaningful solution.
const MIN_CELLS_ACROSS: usize = 3;

/// Size estimates of the contact of a case.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ContactEstimate {
    /// Radius of the symmetric (elastic or Winkler) contact.
    pub symmetric_radius: f64,
    /// Extent ahead of the initial contact point (>= symmetric radius).
    pub leading_extent: f64,
    /// Effective plane-strain modulus of the body.
    pub modulus: f64,
    /// The linear layer the guesses assume, if there is a layer.
    pub layer: Option<LayerEstimate>,
    /// Sliding velocity (infinite for none).
    pub velocity: f64,
}

impl ContactEstimate {
    /// The estimates of `case`. A line contact's (load Q per unit length) are the
    /// plane-strain ones: Hertz `a = (4 Q R / (pi E*))^(1/2)` (Johnson eq. 4.43),
    /// a Winkler bed `a = (3 Q R C0 / 2)^(1/3)`, and the creep-dominated limit
    /// `p ~ V T x / (C0 R)` ahead of the first contact, `r = (2 Q C0 R / (V T))^(1/2)`.
    pub fn of(case: &Case) -> Self {
        use std::f64::consts::PI;
        let r = case.slider.equivalent_radius();
        let q = case.loading.normal_load;
        let modulus = case.body.model().softest_modulus();
        let line = case.slider.is_line();
        let hertz = if line {
            (4.0 * q * r / (PI * modulus)).sqrt()
        } else {
            (3.0 * q * r / (4.0 * modulus)).cbrt()
        };
        let (mut symmetric, mut leading) = (hertz, hertz);
        let layer = case.layer.as_ref().map(|l| l.estimate());
        if let Some(layer) = &layer {
            let c0 = layer.compliance;
            let winkler = if line {
                (1.5 * q * r * c0).cbrt()
            } else {
                (4.0 * r * c0 * q / PI).powf(0.25)
            };
            symmetric = hertz.max(winkler);
            let vt = case.velocity() * layer.relaxation_time;
            // Creep matters when V T is small against the contact; the creep length
            // estimate is then the larger one.
            let creep = match (vt.is_finite(), line) {
                (false, _) => 0.0,
                (true, true) => (2.0 * q * c0 * r / vt).sqrt(),
                (true, false) => (3.0 * q * c0 * r / (2.0 * vt)).cbrt(),
            };
            leading = symmetric.max(creep);
        }
        ContactEstimate {
            symmetric_radius: symmetric,
            leading_extent: leading,
            modulus,
            layer,
            velocity: case.velocity(),
        }
    }
}

/// The first window: the case's fixed one, or one around the estimated contact.
pub(crate) fn initial_window(case: &Case) -> Result<Grid> {
    let [nx, ny] = case.grid.cells;
    let geometry = case.geometry();
    if let Some([wx, _]) = case.grid.half_width {
        let centre = case.grid.centre.unwrap_or([0.0, 0.0]);
        return window(geometry, nx, ny, 2.0 * wx / nx as f64, centre);
    }
    let e = ContactEstimate::of(case);
    for (extent, keys) in [
        (
            e.symmetric_radius,
            "slider radius, the moduli, loading.normal_load and layer.compliance",
        ),
        (
            e.leading_extent,
            "loading.velocity, layer.relaxation_time and layer.compliance",
        ),
    ] {
        let ok = extent.is_finite() && extent > 0.0;
        if !ok {
            return Err(Error::invalid(
                "case",
                format!("an estimated contact size of {extent:e}"),
                &format!(
                    "values whose contact estimate is a finite size > 0 (it is \
                     (3 Q R / 4 E*)^(1/3), or (4 R C0 Q / pi)^(1/4), or (3 Q C0 R / 2 V T)^(1/3) \
                     with a layer): check {keys}"
                ),
            ));
        }
    }
    let x_lo = -MARGIN * e.symmetric_radius;
    let x_hi = MARGIN * e.leading_extent;
    let half_y = match geometry {
        Geometry::Point => MARGIN * e.leading_extent,
        Geometry::Line { .. } => 0.0,
    };
    fit(geometry, nx, ny, [x_lo, x_hi], [-half_y, half_y])
}

/// The window of `geometry` of `nx x ny` cells (a line's: `nx`) of side `cell`
/// centred on `centre`.
fn window(geometry: Geometry, nx: usize, ny: usize, cell: f64, centre: [f64; 2]) -> Result<Grid> {
    match geometry {
        Geometry::Point => Grid::centred(nx, ny, cell, centre),
        Geometry::Line { datum } => Grid::line(nx, cell, centre[0], datum),
    }
}

/// The cell that fits lengths `lx x ly` into `nx x ny` cells with the margin and two
/// spare cells a side (a line contact: `lx` into `nx`).
fn refit_cell(grid_is_line: bool, nx: usize, ny: usize, lx: f64, ly: f64) -> f64 {
    let along_x = lx * 1.1 / (nx as f64 - 4.0);
    if grid_is_line {
        along_x
    } else {
        along_x.max(ly * 1.1 / (ny as f64 - 4.0))
    }
}

/// The grid of `nx x ny` square cells that holds the box `xs x ys`, centred on it.
fn fit(geometry: Geometry, nx: usize, ny: usize, xs: [f64; 2], ys: [f64; 2]) -> Result<Grid> {
    let cell = ((xs[1] - xs[0]) / nx as f64).max((ys[1] - ys[0]) / ny as f64);
    if !(cell.is_finite() && cell > 0.0) {
        return Err(Error::invalid(
            "grid",
            cell,
            "a window of finite positive size (check the load and moduli)",
        ));
    }
    window(
        geometry,
        nx,
        ny,
        cell,
        [(xs[0] + xs[1]) / 2.0, (ys[0] + ys[1]) / 2.0],
    )
}

/// Index ranges `[i_min, i_max] x [j_min, j_max]` of the loaded cells.
pub(crate) fn loaded_box(grid: &Grid, p: &[f64]) -> Option<[usize; 4]> {
    let mut b = [usize::MAX, 0, usize::MAX, 0];
    let mut any = false;
    for j in 0..grid.ny {
        for i in 0..grid.nx {
            if p[grid.index(i, j)] > 0.0 {
                any = true;
                b = [b[0].min(i), b[1].max(i), b[2].min(j), b[3].max(j)];
            }
        }
    }
    any.then_some(b)
}

/// The next window to try, or `None` when the solution on `grid` is acceptable.
pub(crate) fn next_window(grid: &Grid, p: &[f64], touches: bool) -> Option<Grid> {
    let b = loaded_box(grid, p)?;
    let h = grid.cell;
    let xs = [grid.x(b[0]) - 0.5 * h, grid.x(b[1]) + 0.5 * h];
    let ys = [grid.y(b[2]) - 0.5 * h, grid.y(b[3]) + 0.5 * h];
    let centre = [(xs[0] + xs[1]) / 2.0, (ys[0] + ys[1]) / 2.0];
    if touches {
        return grid.resized(grid.nx, grid.ny, ENLARGE * h, centre).ok();
    }
    // Cells that would hold the contact with the margin and two spare cells a side.
    let (lx, ly) = (xs[1] - xs[0], ys[1] - ys[0]);
    let cell = refit_cell(grid.is_line(), grid.nx, grid.ny, lx, ly);
    if cell < REFIT_GAIN * h {
        grid.resized(grid.nx, grid.ny, cell, centre).ok()
    } else {
        None
    }
}

/// The window of `nx x ny` cells that holds the contact `p` found on the coarser
/// `coarse` grid, widened by one coarse cell on every side (its edges are known to a
/// coarse cell) and by the margin [`next_window`]'s refits keep.
pub(crate) fn fit_to_contact(nx: usize, ny: usize, coarse: &Grid, p: &[f64]) -> Option<Grid> {
    let b = loaded_box(coarse, p)?;
    let h = coarse.cell;
    let xs = [coarse.x(b[0]) - 1.5 * h, coarse.x(b[1]) + 1.5 * h];
    let ys = [coarse.y(b[2]) - 1.5 * h, coarse.y(b[3]) + 1.5 * h];
    let centre = [(xs[0] + xs[1]) / 2.0, (ys[0] + ys[1]) / 2.0];
    let (lx, ly) = (xs[1] - xs[0], ys[1] - ys[0]);
    let cell = refit_cell(coarse.is_line(), nx, ny, lx, ly);
    coarse.resized(nx, ny, cell, centre).ok()
}

/// Whether the lowest cell of the slider's height `f` (the first cell to touch)
/// lies on the window's edge, ties included.
pub(crate) fn lowest_point_on_edge(grid: &Grid, f: &[f64]) -> bool {
    let lowest = f.iter().copied().fold(f64::INFINITY, f64::min);
    let mut edge = vec![0.0; f.len()];
    for (e, &v) in edge.iter_mut().zip(f) {
        *e = if v == lowest { 1.0 } else { 0.0 };
    }
    // Only the lowest cells are marked: they touch the edge iff one is on it.
    grid.touches_edge(&edge)
}

/// Rejects a fixed window whose cells are too coarse for the contact.
pub(crate) fn check_resolution(solution: &Solution) -> Result<()> {
    let g = &solution.grid;
    if let Some(b) = loaded_box(g, &solution.pressure) {
        let along_x = b[1] - b[0] + 1;
        let across = if g.is_line() {
            along_x
        } else {
            along_x.min(b[3] - b[2] + 1)
        };
        if across < MIN_CELLS_ACROSS {
            return Err(Error::invalid(
                "grid.half_width",
                format!("[{:e}, {:e}]", g.half_widths()[0], g.half_widths()[1]),
                &format!(
                    "a window in which the contact spans at least {MIN_CELLS_ACROSS} cells \
                     (it spans {across}); use a smaller window or more cells"
                ),
            ));
        }
    }
    Ok(())
}

/// Bilinear interpolation of a cell field from one grid to another (zero outside).
pub(crate) fn interpolate(
    old: &Grid,
    field: &[f64],
    new: &Grid,
    parallelism: Parallelism,
) -> Vec<f64> {
    let mut out = vec![0.0; new.len()];
    if old.is_line() {
        // One row: linear interpolation along x.
        for (i, o) in out.iter_mut().enumerate() {
            let u = (new.x(i) - old.x0) / old.cell - 0.5;
            if u < 0.0 || u > (old.nx - 1) as f64 {
                continue;
            }
            let i0 = (u as usize).min(old.nx - 2);
            let s = u - i0 as f64;
            *o = (1.0 - s) * field[i0] + s * field[i0 + 1];
        }
        return out;
    }
    out.par_chunks_mut(new.nx)
        .enumerate()
        .with_min_len(Passes::new(new.len(), parallelism).min_rows(new.nx))
        .for_each(|(j, row)| {
            let v = (new.y(j) - old.y0) / old.cell - 0.5;
            for (i, o) in row.iter_mut().enumerate() {
                let u = (new.x(i) - old.x0) / old.cell - 0.5;
                if u < 0.0 || v < 0.0 || u > (old.nx - 1) as f64 || v > (old.ny - 1) as f64 {
                    continue;
                }
                let (i0, j0) = ((u as usize).min(old.nx - 2), (v as usize).min(old.ny - 2));
                let (s, t) = (u - i0 as f64, v - j0 as f64);
                let at = |a: usize, b: usize| field[old.index(a, b)];
                *o = (1.0 - t) * ((1.0 - s) * at(i0, j0) + s * at(i0 + 1, j0))
                    + t * ((1.0 - s) * at(i0, j0 + 1) + s * at(i0 + 1, j0 + 1));
            }
        });
    out
}

/// Hertz-shaped start for conjugate gradients: `sqrt(1 - f / f_a)` inside the
/// estimated contact, where `f_a` is the shape's height at its edge.
pub(crate) fn hertz_like_guess(grid: &Grid, f: &[f64], e: &ContactEstimate) -> Vec<f64> {
    let mut fa = f64::INFINITY;
    // Height of the shape at the estimated radius along x, from the sampled f.
    for i in 0..grid.nx {
        let x = grid.x(i);
        if x >= e.symmetric_radius {
            let j = (0..grid.ny)
                .min_by(|&a, &b| grid.y(a).abs().total_cmp(&grid.y(b).abs()))
                .unwrap_or(0);
            fa = f[grid.index(i, j)];
            break;
        }
    }
    let fmin = f.iter().copied().fold(f64::INFINITY, f64::min);
    let mut p: Vec<f64> = f
        .iter()
        .map(|&v| (1.0 - (v - fmin) / (fa - fmin)).max(0.0).sqrt())
        .collect();
    if p.iter().filter(|&&v| v > 0.0).count() < 4 {
        p.iter_mut().for_each(|v| *v = 1.0);
    }
    p
}

/// Start for the layered solver: the contact of a rigid-like bed where each cell has
/// the body's effective compliance `pi a / (2 E*)` (Hertz centre displacement over
/// peak pressure) plus the linear layer of compliance C0 with its creep, solved row
/// by row from the leading edge; D is found by bisection on the load.
pub(crate) fn rigid_base_guess(
    grid: &Grid,
    f: &[f64],
    e: &ContactEstimate,
    load: f64,
    row_response: Option<(f64, f64)>,
    parallelism: Parallelism,
) -> Vec<f64> {
    let (c0, relaxation_time) = e
        .layer
        .map_or((0.0, f64::INFINITY), |l| (l.compliance, l.relaxation_time));
    let kc = if e.velocity.is_infinite() {
        0.0
    } else {
        grid.cell / (e.velocity * relaxation_time)
    };
    let body = std::f64::consts::PI * e.symmetric_radius / (2.0 * e.modulus);
    // The layer's own response and its reach to the next cell downstream: the
    // estimate's (a spring of the relaxed compliance creeping at the flow's rate),
    // or the layer's own at zero pressure where that estimate has no creep and the
    // layer does (retarded branches: at speed they creep over the contact as flow
    // does, and their relaxed compliance is far from what the contact sees).
    let (own, reach) = row_response.unwrap_or((c0 * (1.0 + 0.5 * kc), kc * c0));
    let diag = body + own;
    let nx = grid.nx;
    let mut p = vec![0.0; f.len()];
    // Rows are independent; their loads are added in row order, so the guess is the
    // same on any number of threads.
    let rows_per_task = crate::passes::Passes::new(f.len(), parallelism).min_rows(nx);
    let sweep = |d: f64, p: &mut [f64]| -> f64 {
        let row_loads: Vec<f64> = f
            .par_chunks(nx)
            .zip(p.par_chunks_mut(nx))
            .with_min_len(rows_per_task)
            .map(|(frow, prow)| {
                let mut upstream = 0.0;
                let mut total = 0.0;
                for i in (0..nx).rev() {
                    let v = ((d - frow[i] - reach * upstream) / diag).max(0.0);
                    prow[i] = v;
                    upstream += v;
                    total += v;
                }
                total
            })
            .collect();
        row_loads.iter().sum::<f64>() * grid.cell_measure()
    };
    let fmin = f.iter().copied().fold(f64::INFINITY, f64::min);
    let (mut lo, mut hi) = (fmin, fmin + diag * load / grid.cell_measure());
    // Expand until the bed carries the load (always reached: load grows without bound).
    for _ in 0..200 {
        if sweep(hi, &mut p) >= load {
            break;
        }
        let w = hi - lo;
        lo = hi;
        hi += 2.0 * w;
    }
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            // lo and hi are adjacent doubles: no further step changes them.
            break;
        }
        if sweep(mid, &mut p) < load {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    sweep(hi, &mut p);
    p
}
