//! The paper's Fig. 10 case (Q' = 5e-6, V' = 1e-3, nu2 = 0.3, C' = 0.02,
//! p0' = 0.005, delta = 0.01 and 1, sigmoid law eq. 11, homogeneous half-space,
//! R = E2 = T = 1) under the readings the paper leaves open, for
//! docs/paper-discrepancies.md:
//! (a) tau1 = (s1 - s3)/2 (3-D principal stresses) or the in-plane principal shear of
//!     the XZ plane, sqrt(((sx - sz)/2)^2 + txz^2);
//! (b) resolution (64/128/256 cells a side) and a wider window at the same cell size;
//! (c) the sliding direction: the mirrored pressure (as if material entered at the
//!     smallest x) on a mirrored grid;
//! (d) the compliance that multiplies the creep: "exact" or "secant" integration.
//!
//! tau1 is taken on the plane y = 0 through the point of initial contact (paper,
//! section 4), at the cell-centre x's and at depths 0..3 L (L the contact's larger
//! half extent) in 120 steps, then refined to 1/40 of a step around the maximum.
//!
//! Run: `cargo run --release -p thirdbody --example fig10_readings`

use thirdbody::grid::Grid;
use thirdbody::stress::{self, Section, StressField};
use thirdbody::*;

/// The paper's published tau1_max / E2 (Fig. 10 caption, printed negative).
const PAPER: [(f64, f64); 2] = [(0.01, 0.000982), (1.0, 0.00132)];

/// Which maximum shear.
#[derive(Clone, Copy)]
enum Tau1 {
    /// (s1 - s3) / 2 of the 3-D tensor.
    Principal3d,
    /// sqrt(((sx - sz)/2)^2 + txz^2): the XZ plane's own principal shear.
    InPlaneXz,
}

fn tau1_values(field: &StressField, def: Tau1) -> Vec<f64> {
    match def {
        Tau1::Principal3d => field.tau1(),
        Tau1::InPlaneXz => {
            let [sx, _, sz, _, txz, _] = &field.components;
            (0..field.len())
                .map(|n| (0.25 * (sx[n] - sz[n]).powi(2) + txz[n].powi(2)).sqrt())
                .collect()
        }
    }
}

/// Largest tau1 on the plane y = 0 and its point: (tau1, x, z).
fn tau1_max(
    grid: &Grid,
    pressure: &[f64],
    body: &Body,
    reach: f64,
    def: Tau1,
) -> Result<(f64, f64, f64)> {
    let scan = |depths: Vec<f64>| -> Result<(f64, f64, f64)> {
        let field = stress::stresses(grid, pressure, body, &Section::XzPlane { y: 0.0, depths })?;
        let t = tau1_values(&field, def);
        let nx = field.xs.len();
        let (n, v) =
            t.iter().enumerate().fold(
                (0, f64::NEG_INFINITY),
                |b, (n, &v)| if v > b.1 { (n, v) } else { b },
            );
        Ok((v, field.xs[n % nx], field.zs[n / nx]))
    };
    let steps = 120;
    let dz = reach / steps as f64;
    let (_, _, z) = scan((0..=steps).map(|k| k as f64 * dz).collect())?;
    let lo = (z - dz).max(0.0);
    scan((0..=80).map(|k| lo + k as f64 * dz / 40.0).collect())
}

fn case(delta: f64, integration: Integration, cells: usize) -> Case {
    Case {
        slider: Slider::Sphere { radius: 1.0 },
        body: Body::Homogeneous(Elastic {
            young: 1.0,
            poisson: 0.3,
        }),
        layer: Some(Layer::maxwell(
            0.02,
            1.0,
            ComplianceLaw::Sigmoid { delta, p0: 0.005 },
            integration,
        )),
        loading: Loading {
            normal_load: 5e-6,
            velocity: Some(1e-3),
            reference_distance: None,
        },
        grid: GridSpec {
            cells: [cells, cells],
            half_width: None,
            centre: None,
        },
        units: Units::Dimensionless,
    }
}

/// The pressure mirrored in x (p'(x) = p(-x)) on the mirrored grid.
fn mirrored(grid: &Grid, pressure: &[f64]) -> Result<(Grid, Vec<f64>)> {
    let centre = [
        -(grid.x0() + 0.5 * grid.nx() as f64 * grid.cell()),
        grid.y0() + 0.5 * grid.ny() as f64 * grid.cell(),
    ];
    let g = Grid::centred(grid.nx(), grid.ny(), grid.cell(), centre)?;
    let mut p = vec![0.0; pressure.len()];
    for j in 0..grid.ny() {
        for i in 0..grid.nx() {
            p[j * grid.nx() + (grid.nx() - 1 - i)] = pressure[j * grid.nx() + i];
        }
    }
    Ok((g, p))
}

struct Row {
    delta: f64,
    integration: &'static str,
    label: String,
    solution: Solution,
    body: Body,
}

fn report(row: &Row, results: &mut Vec<(f64, &'static str, String, f64)>) -> Result<()> {
    let s = row.solution.summary();
    let reach =
        3.0 * (s.contact_x_max - s.contact_x_min).max(0.5 * (s.contact_y_max - s.contact_y_min));
    let g = &row.solution.grid;
    let p = &row.solution.pressure;
    let paper = PAPER
        .iter()
        .find(|(d, _)| *d == row.delta)
        .map_or(f64::NAN, |q| q.1);
    for (name, def) in [("3d", Tau1::Principal3d), ("xz", Tau1::InPlaneXz)] {
        let (t, x, z) = tau1_max(g, p, &row.body, reach, def)?;
        println!(
            "| {} | {} | {} | {} | {:.6} | {:+.2}% | {:.5} | {:.5} | {:.6} | {:.5} | [{:.4}, {:.4}] | [{:.4}, {:.4}] | {:.4} |",
            row.delta,
            row.integration,
            row.label,
            name,
            t,
            100.0 * (t / paper - 1.0),
            x,
            z,
            s.max_pressure,
            s.max_pressure_x,
            s.contact_x_min,
            s.contact_x_max,
            s.contact_y_min,
            s.contact_y_max,
            s.friction_coefficient,
        );
        results.push((
            row.delta,
            row.integration,
            format!("{} {name}", row.label),
            t,
        ));
    }
    if row.label.starts_with("128") && row.integration == "exact" {
        let (gm, pm) = mirrored(g, p)?;
        let (t, x, z) = tau1_max(&gm, &pm, &row.body, reach, Tau1::Principal3d)?;
        println!(
            "| {} | {} | {} mirrored | 3d | {:.6} | {:+.2}% | {:.5} | {:.5} | | | | | |",
            row.delta,
            row.integration,
            row.label,
            t,
            100.0 * (t / paper - 1.0),
            x,
            z
        );
    }
    Ok(())
}

/// (b') Coarse grids such as a dense direct solve (the paper's method) affords: the
/// leading-edge boundary layer (width ~ V T = 0.001) is then below one cell.
fn coarse(params: &SolverParams) -> Result<()> {
    println!();
    println!("Coarse grids (auto window), tau1 = (s1 - s3)/2: cells, integration, h, tau1_max(0.01), tau1_max(1), ratio, p_max(0.01), p_max(1)");
    for cells in [24, 32, 40, 48] {
        for (integration, name) in [
            (Integration::Exact, "exact"),
            (Integration::Secant, "secant"),
        ] {
            let mut t = [0.0; 2];
            let mut pm = [0.0; 2];
            let mut h = 0.0;
            for (k, (delta, _)) in PAPER.iter().enumerate() {
                let c = case(*delta, integration, cells);
                let sol = solve(&c, params)?;
                let s = sol.summary();
                let reach = 3.0
                    * (s.contact_x_max - s.contact_x_min)
                        .max(0.5 * (s.contact_y_max - s.contact_y_min));
                t[k] = tau1_max(&sol.grid, &sol.pressure, &c.body, reach, Tau1::Principal3d)?.0;
                pm[k] = s.max_pressure;
                h = s.cell_size;
            }
            println!(
                "  {cells} | {name} | {h:.5} | {:.6} ({:+.1}%) | {:.6} ({:+.1}%) | {:.3} | {:.6} | {:.6}",
                t[0],
                100.0 * (t[0] / PAPER[0].1 - 1.0),
                t[1],
                100.0 * (t[1] / PAPER[1].1 - 1.0),
                t[1] / t[0],
                pm[0],
                pm[1]
            );
        }
    }
    Ok(())
}

/// (e) Is the largest tau1 of the whole body on the plane y = 0? Block of all cell
/// centres at depths 0..0.015 (about 3 times the depth of the plane's maximum).
fn global_maxima(params: &SolverParams) -> Result<()> {
    println!();
    println!("Global maximum of tau1 = (s1 - s3)/2 over all cell centres (128 cells, exact):");
    for (delta, _) in PAPER {
        let c = case(delta, Integration::Exact, 128);
        let sol = solve(&c, params)?;
        let depths: Vec<f64> = (0..=60).map(|k| k as f64 * 0.00025).collect();
        let field = sol.stresses(&Section::Block { depths })?;
        let t = field.tau1();
        let (n, v) =
            t.iter().enumerate().fold(
                (0, f64::NEG_INFINITY),
                |b, (n, &v)| if v > b.1 { (n, v) } else { b },
            );
        let (nx, ny) = (field.xs.len(), field.ys.len());
        println!(
            "  delta = {delta}: {v:.6} at x = {:.5}, y = {:.5}, z = {:.5}",
            field.xs[n % nx],
            field.ys[(n / nx) % ny],
            field.zs[n / (nx * ny)]
        );
    }
    Ok(())
}

/// Diagnosis only (not a reading of the paper): how far V', C' would have to move
/// for tau1_max to reach the published values (128 cells, exact, 3-D tau1).
fn sensitivity(params: &SolverParams) -> Result<()> {
    println!();
    println!("Sensitivity (128 cells, exact, tau1 = (s1 - s3)/2): delta, V', C', tau1_max, p_max");
    for (delta, _) in PAPER {
        for (v, c0) in [
            (1e-3, 0.02),
            (1.5e-3, 0.02),
            (2e-3, 0.02),
            (2.5e-3, 0.02),
            (4e-3, 0.02),
            (1e-3, 0.01),
            (1e-3, 0.005),
        ] {
            let mut c = case(delta, Integration::Exact, 128);
            c.loading.velocity = Some(v);
            if let Some(layer) = c.layer.as_mut() {
                layer.rheology = thirdbody::Rheology::Maxwell {
                    compliance: c0,
                    relaxation_time: 1.0,
                };
            }
            let sol = solve(&c, params)?;
            let s = sol.summary();
            let reach = 3.0
                * (s.contact_x_max - s.contact_x_min)
                    .max(0.5 * (s.contact_y_max - s.contact_y_min));
            let (t, _, _) = tau1_max(&sol.grid, &sol.pressure, &c.body, reach, Tau1::Principal3d)?;
            println!("  {delta} | {v:e} | {c0} | {t:.6} | {:.6}", s.max_pressure);
        }
    }
    Ok(())
}

fn main() -> Result<()> {
    let params = SolverParams::default();
    let mut results = Vec::new();
    println!(
        "| delta | integration | grid | tau1 | tau1_max/E2 | vs paper | x | z | p_max | x(p_max) | contact x | contact y | mu |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for (integration, name) in [
        (Integration::Exact, "exact"),
        (Integration::Secant, "secant"),
    ] {
        for cells in [32, 64, 128, 256] {
            for (delta, _) in PAPER {
                let c = case(delta, integration, cells);
                let solution = solve(&c, &params)?;
                let g = solution.grid;
                let label = format!(
                    "{cells} (h = {:.5}, half width {:.4})",
                    g.cell(),
                    0.5 * g.nx() as f64 * g.cell()
                );
                let row = Row {
                    delta,
                    integration: name,
                    label,
                    solution,
                    body: c.body.clone(),
                };
                report(&row, &mut results)?;
                if cells == 128 && name == "exact" {
                    // The same cell size on a window 1.5 times wider (192 cells).
                    let mut wide = case(delta, integration, 192);
                    wide.grid.half_width = Some([0.75 * g.nx() as f64 * g.cell(); 2]);
                    wide.grid.centre = Some([g.x0() + 0.5 * g.nx() as f64 * g.cell(), 0.0]);
                    let solution = solve(&wide, &params)?;
                    let row = Row {
                        delta,
                        integration: name,
                        label: format!(
                            "192 wide (h = {:.5}, half width {:.4})",
                            g.cell(),
                            0.75 * g.nx() as f64 * g.cell()
                        ),
                        solution,
                        body: c.body,
                    };
                    report(&row, &mut results)?;
                }
            }
        }
    }
    coarse(&params)?;
    global_maxima(&params)?;
    sensitivity(&params)?;
    println!();
    println!(
        "Ratio tau1_max(delta = 1) / tau1_max(delta = 0.01) (paper: 0.00132 / 0.000982 = {:.4}):",
        PAPER[1].1 / PAPER[0].1
    );
    let lows: Vec<_> = results.iter().filter(|r| r.0 == 0.01).collect();
    for low in lows {
        if let Some(high) = results
            .iter()
            .find(|r| r.0 == 1.0 && r.1 == low.1 && r.2 == low.2)
        {
            println!("  {} {}: {:.4}", low.1, low.2, high.3 / low.3);
        }
    }
    Ok(())
}
