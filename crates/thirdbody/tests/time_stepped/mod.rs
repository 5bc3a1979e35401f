//! An independent time-stepped simulation of a rigid paraboloid `f = r^2 / (2 R)`
//! under a constant normal load sliding from rest over a linear viscoelastic
//! half-space, for `viscoelastic_time_stepped.rs`. It uses none of the production
//! viscoelastic kernel or contact solvers: only Love's closed form for a uniformly
//! loaded rectangle (`thirdbody::body::homogeneous::rectangle_inverse_distance_integral`,
//! Johnson, Contact Mechanics, eq. 3.25), rustfft, and its own projected
//! conjugate-gradient contact solver (Polonsky and Keer, Wear 231, 1999).
//!
//! # Model
//!
//! Frame fixed to the slider (x the sliding direction, the slider moves in +x, body
//! material flows through the contact in -x), `w > 0` into the body, `p >= 0`. With
//! a constant Poisson ratio, a material point's surface displacement is
//! `w = J_g W + sum_k w_k` with `W = L[p]` Love's displacement per unit plane-strain
//! compliance at the point's current place, and per branch the Kelvin-Voigt law
//! `tau_k dw_k/dt + w_k = J_k W` along the point's path: the creep compliance
//! `J(t) = J_g + sum_k J_k (1 - exp(-t / tau_k))`.
//!
//! # Scheme
//!
//! * The contact window is `n x n` square cells of side h centred on the slider.
//!   The material lines are the rows of cell centres; along each, material points
//!   sit `h / m` apart (a lattice `xi_q = x_0 + q h / m`, x_0 the first cell
//!   centre), from the window's first column to `upstream` beyond its last one.
//!   Every point carries its branch displacements `w_k`.
//! * A step is `dt = h / (m V)`: each point moves one lattice spacing in -x, so the
//!   fields shift by exactly one slot (no interpolation); the point leaving the
//!   window's first centre is dropped, a fresh point (`w_k = 0`) enters upstream.
//!   Every `m`-th slot is a cell centre, where the contact conditions are posed.
//! * Over a step each branch is integrated exactly for `W` linear in time between
//!   its values at the step's ends (exponential integrator, second order):
//!   `w_k(t + dt) = e_k w_k(t) + J_k (b0_k W(t) + b1_k W(t + dt))` with
//!   `r = dt / tau_k`, `e_k = exp(-r)`, `b1_k = 1 - (1 - e_k) / r`,
//!   `b0_k = (1 - e_k) / r - e_k`.
//! * The unknown `W(t + dt)` enters the displacement at the cell centres as
//!   `(J_g + sum_k J_k b1_k) L[p] + H` with the history `H` known, so each step is
//!   an elastic-like contact problem (symmetric positive definite), solved by
//!   projected conjugate gradients with the load constraint.
//! * `W` on the lattice comes from one FFT convolution of the pressure with Love's
//!   kernel of a cell, sampled at the lattice offsets.
//!
//! The simulation starts at rest either on a fresh (unloaded) body, the load being
//! applied at t = 0 (the response is then glassy), or on a body fully relaxed
//! under the load (`w_k = J_k W` of the relaxed static contact everywhere on the
//! lattice). The only truncation is that material entering the lattice upstream is
//! fresh: its missing displacement, at most `J_k W` there, decays by
//! `exp(-distance / (V tau_k))` before reaching the window.
#![allow(dead_code)]

use rustfft::num_complex::Complex64;
use rustfft::Fft;
use std::f64::consts::PI;
use std::sync::Arc;
use thirdbody::body::homogeneous::rectangle_inverse_distance_integral;
use thirdbody::body::viscoelastic::CreepSeries;
use thirdbody_reference::fft;

/// Love's normal surface displacement per unit plane-strain compliance at `(x, y)`
/// under a unit pressure on `|x| <= a, |y| <= b`.
pub fn love(x: f64, y: f64, a: f64, b: f64) -> f64 {
    rectangle_inverse_distance_integral(x, y, a, b) / PI
}

/// The smallest `2^a 3^b 5^c` at least `n`.
fn good_size(n: usize) -> usize {
    (n..)
        .find(|&k| {
            let mut k = k;
            for f in [2, 3, 5] {
                while k % f == 0 {
                    k /= f;
                }
            }
            k == 1
        })
        .unwrap()
}

/// A linear (non-circular) 2-D convolution by FFT:
/// `target[ty][tx] = sum_{sx, sy} kernel(tx - sx, ty - sy) source[sy][sx]`
/// for a `source` of `sx x sy` and a `target` of `tx x ty` values (row-major, rows
/// along y), zero padding to at least `sx + tx - 1` by `sy + ty - 1`.
pub struct Convolution {
    source: [usize; 2],
    target: [usize; 2],
    pad: [usize; 2],
    /// The kernel's spectrum, transposed (`[x * py + y]`), divided by `px py`.
    spectrum: Vec<Complex64>,
    row_fwd: Arc<dyn Fft<f64>>,
    row_inv: Arc<dyn Fft<f64>>,
    col_fwd: Arc<dyn Fft<f64>>,
    col_inv: Arc<dyn Fft<f64>>,
    rows: Vec<Complex64>,
    cols: Vec<Complex64>,
}

impl Convolution {
    /// Plans the convolution and transforms the kernel.
    pub fn new(source: [usize; 2], target: [usize; 2], kernel: impl Fn(i64, i64) -> f64) -> Self {
        let span = [source[0] + target[0] - 1, source[1] + target[1] - 1];
        let pad = [good_size(span[0]), good_size(span[1])];
        let mut c = Convolution {
            source,
            target,
            pad,
            spectrum: Vec::new(),
            row_fwd: fft::forward(pad[0]),
            row_inv: fft::inverse(pad[0]),
            col_fwd: fft::forward(pad[1]),
            col_inv: fft::inverse(pad[1]),
            rows: vec![Complex64::default(); pad[0] * pad[1]],
            cols: vec![Complex64::default(); pad[0] * pad[1]],
        };
        // Offsets from -(s - 1) to t - 1 at indices 0 .. s + t - 1: the target's
        // value tx then sits at index tx + s - 1 of the circular product.
        let lo = [1 - source[0] as i64, 1 - source[1] as i64];
        for y in 0..span[1] {
            for x in 0..span[0] {
                c.rows[y * pad[0] + x] =
                    Complex64::new(kernel(lo[0] + x as i64, lo[1] + y as i64), 0.0);
            }
        }
        c.forward(span[1]);
        let scale = 1.0 / (pad[0] * pad[1]) as f64;
        c.spectrum = c.cols.iter().map(|v| v * scale).collect();
        c
    }

    /// Row FFTs of the first `rows` rows of `self.rows` (the others are zero), then
    /// column FFTs into `self.cols` (transposed).
    fn forward(&mut self, rows: usize) {
        let [px, py] = self.pad;
        for row in self.rows[..rows * px].chunks_exact_mut(px) {
            self.row_fwd.process(row);
        }
        for x in 0..px {
            for y in 0..py {
                self.cols[x * py + y] = if y < rows {
                    self.rows[y * px + x]
                } else {
                    Complex64::default()
                };
            }
        }
        self.col_fwd.process(&mut self.cols);
    }

    /// `target = kernel * source`.
    pub fn apply(&mut self, source: &[f64], target: &mut [f64]) {
        let [sx, sy] = self.source;
        let [tx, ty] = self.target;
        let [px, py] = self.pad;
        assert_eq!(source.len(), sx * sy);
        assert_eq!(target.len(), tx * ty);
        for y in 0..sy {
            let row = &mut self.rows[y * px..(y + 1) * px];
            for (x, v) in row.iter_mut().enumerate() {
                *v = Complex64::new(if x < sx { source[y * sx + x] } else { 0.0 }, 0.0);
            }
        }
        self.forward(sy);
        for (v, k) in self.cols.iter_mut().zip(&self.spectrum) {
            *v *= k;
        }
        self.col_inv.process(&mut self.cols);
        for y in 0..ty {
            let yy = y + sy - 1;
            let row = &mut self.rows[y * px..(y + 1) * px];
            for (x, v) in row.iter_mut().enumerate() {
                *v = self.cols[x * py + yy];
            }
            self.row_inv.process(row);
            for x in 0..tx {
                target[y * tx + x] = row[x + sx - 1].re;
            }
        }
    }
}

/// What [`polonsky_keer`] found.
#[derive(Debug, Clone, Copy)]
pub struct ContactSolve {
    /// The rigid approach D.
    pub approach: f64,
    /// Conjugate-gradient steps.
    pub iterations: usize,
    /// The largest `|displacement + offset - D|` over the loaded cells, over D.
    pub residual: f64,
}

/// Projected conjugate gradients with the load constraint (Polonsky and Keer,
/// Wear 231, 1999) for `compliance * L[p] + offset - D >= 0`, `p >= 0`, their
/// product zero, `area * sum(p) = load`: `p` holds the starting guess (any field
/// with a positive load) and returns the solution. `window` applies `L` on the grid.
pub fn polonsky_keer(
    window: &mut Convolution,
    compliance: f64,
    offset: &[f64],
    area: f64,
    load: f64,
    p: &mut [f64],
    tolerance: f64,
) -> ContactSolve {
    let n = p.len();
    let scale = load / (area * p.iter().sum::<f64>());
    p.iter_mut().for_each(|v| *v *= scale);
    let (mut u, mut g, mut t, mut r) = (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let mut g_old = 1.0;
    let mut conjugate = false;
    let mut iterations = 0;
    loop {
        window.apply(p, &mut u);
        let (mut sum, mut count) = (0.0, 0usize);
        for k in 0..n {
            g[k] = compliance * u[k] + offset[k];
            if p[k] > 0.0 {
                sum += g[k];
                count += 1;
            }
        }
        let mean = sum / count as f64;
        g.iter_mut().for_each(|v| *v -= mean);
        let big_g: f64 = (0..n).filter(|&k| p[k] > 0.0).map(|k| g[k] * g[k]).sum();
        let beta = if conjugate { big_g / g_old } else { 0.0 };
        for k in 0..n {
            t[k] = if p[k] > 0.0 { g[k] + beta * t[k] } else { 0.0 };
        }
        g_old = big_g;
        window.apply(&t, &mut r);
        let (mut rs, mut rc) = (0.0, 0usize);
        for k in 0..n {
            r[k] *= compliance;
            if p[k] > 0.0 {
                rs += r[k];
                rc += 1;
            }
        }
        let rmean = rs / rc as f64;
        let (mut gt, mut rt) = (0.0, 0.0);
        for k in 0..n {
            if p[k] > 0.0 {
                gt += g[k] * t[k];
                rt += (r[k] - rmean) * t[k];
            }
        }
        let step = if rt > 0.0 { gt / rt } else { 0.0 };
        let old = p.to_vec();
        for k in 0..n {
            if p[k] > 0.0 {
                p[k] = (p[k] - step * t[k]).max(0.0);
            }
        }
        conjugate = true;
        for k in 0..n {
            if old[k] == 0.0 && g[k] < 0.0 {
                p[k] = -step * g[k];
                conjugate = false;
            }
        }
        let total = area * p.iter().sum::<f64>();
        p.iter_mut().for_each(|v| *v *= load / total);
        iterations += 1;
        let change: f64 = p.iter().zip(&old).map(|(a, b)| (a - b).abs()).sum::<f64>() * area;
        if change < tolerance * load || iterations >= 2000 {
            break;
        }
    }
    assert!(iterations < 2000, "projected CG did not converge");
    // The approach and the residual of the final pressure.
    window.apply(p, &mut u);
    let loaded: Vec<usize> = (0..n).filter(|&k| p[k] > 0.0).collect();
    let approach = loaded
        .iter()
        .map(|&k| compliance * u[k] + offset[k])
        .sum::<f64>()
        / loaded.len() as f64;
    let residual = loaded
        .iter()
        .map(|&k| (compliance * u[k] + offset[k] - approach).abs())
        .fold(0.0, f64::max)
        / approach.abs();
    ContactSolve {
        approach,
        iterations,
        residual,
    }
}

/// The body's state at t = 0.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Start {
    /// Unloaded; the load is applied at t = 0 (a glassy response).
    Fresh,
    /// Fully relaxed under the load at rest.
    Relaxed,
}

/// A simulation's inputs (any consistent units).
#[derive(Debug, Clone)]
pub struct Setup {
    /// The body's creep compliance (plane strain).
    pub creep: CreepSeries,
    /// The paraboloid's radius R.
    pub radius: f64,
    /// The normal load Q.
    pub load: f64,
    /// The sliding speed V > 0.
    pub speed: f64,
    /// Cells across the square window (`n x n`).
    pub cells: usize,
    /// The window's half width (centred on the slider's axis).
    pub half_width: f64,
    /// Steps per cell of travel, m (`V dt = h / m`).
    pub substeps: usize,
    /// The length of the material lines upstream of the window.
    pub upstream: f64,
    /// The body's state at t = 0.
    pub start: Start,
    /// The contact solver's tolerance on the relative change of the pressure.
    pub tolerance: f64,
}

/// The scalars of one step.
#[derive(Debug, Clone, Copy)]
pub struct Snapshot {
    /// Distance slid since t = 0.
    pub travel: f64,
    /// The largest pressure.
    pub max_pressure: f64,
    /// `sum(p df/dx) h^2 / Q` with `df/dx = x / R` at the cell centres.
    pub friction: f64,
    /// The rigid approach D.
    pub approach: f64,
    /// Loaded cells.
    pub contact_cells: usize,
}

/// One exactly integrated Kelvin-Voigt branch over a step.
#[derive(Debug, Clone, Copy)]
struct Branch {
    compliance: f64,
    decay: f64,
    b0: f64,
    b1: f64,
}

/// The simulation.
pub struct Simulator {
    /// Its inputs.
    pub setup: Setup,
    /// The cell side h.
    pub cell: f64,
    /// x (= y) of the cell centres.
    pub centres: Vec<f64>,
    /// The pressure on the window, `[j * n + i]`.
    pub pressure: Vec<f64>,
    /// The rigid approach of the last step.
    pub approach: f64,
    /// Steps done.
    pub steps: usize,
    /// Projected CG steps in all.
    pub cg_iterations: usize,
    /// The largest relative residual of a step's contact problem.
    pub worst_residual: f64,
    shape: Vec<f64>,
    branches: Vec<Branch>,
    effective: f64,
    /// Lattice slots per material line, M.
    slots: usize,
    /// Branch displacements, `[k][j * M + q]`.
    creep: Vec<Vec<f64>>,
    /// W at the previous step on `M + 1` slots, `[j * (M + 1) + q]`.
    previous: Vec<f64>,
    window: Convolution,
    lattice: Convolution,
    scratch: Vec<f64>,
}

impl Simulator {
    /// Sets up the window, the lattice and the state at t = 0.
    pub fn new(setup: Setup) -> Self {
        let n = setup.cells;
        let m = setup.substeps;
        assert!(m >= 1 && n >= 4 && setup.speed > 0.0);
        let h = 2.0 * setup.half_width / n as f64;
        let centres: Vec<f64> = (0..n)
            .map(|i| -setup.half_width + (i as f64 + 0.5) * h)
            .collect();
        let mut shape = vec![0.0; n * n];
        for j in 0..n {
            for i in 0..n {
                let (x, y) = (centres[i], centres[j]);
                shape[j * n + i] = (x * x + y * y) / (2.0 * setup.radius);
            }
        }
        let dt = h / (m as f64 * setup.speed);
        let mut effective = setup.creep.glassy;
        let mut branches = Vec::new();
        for b in &setup.creep.branches {
            if b.compliance == 0.0 || !b.retardation_time.is_finite() {
                continue;
            }
            let r = dt / b.retardation_time;
            let decay = (-r).exp();
            // (1 - e) / r without cancellation for small r.
            let ratio = if r < 1e-4 {
                1.0 - r / 2.0 + r * r / 6.0 - r * r * r / 24.0
            } else {
                -(-r).exp_m1() / r
            };
            let branch = Branch {
                compliance: b.compliance,
                decay,
                b0: ratio - decay,
                b1: 1.0 - ratio,
            };
            effective += b.compliance * branch.b1;
            branches.push(branch);
        }
        let half = 0.5 * h;
        let window = Convolution::new([n, n], [n, n], |di, dj| {
            love(di as f64 * h, dj as f64 * h, half, half)
        });
        let upstream_cells = (setup.upstream / h).ceil() as usize;
        let slots = m * (n + upstream_cells);
        // Source: the pressure on the fine lattice (every m-th slot of a row).
        let lattice = Convolution::new([m * (n - 1) + 1, n], [slots + 1, n], |dq, dj| {
            love(dq as f64 * h / m as f64, dj as f64 * h, half, half)
        });
        let mut sim = Simulator {
            cell: h,
            centres,
            pressure: vec![0.0; n * n],
            approach: 0.0,
            steps: 0,
            cg_iterations: 0,
            worst_residual: 0.0,
            shape,
            branches,
            effective,
            slots,
            creep: Vec::new(),
            previous: vec![0.0; n * (slots + 1)],
            window,
            lattice,
            scratch: Vec::new(),
            setup,
        };
        sim.start();
        sim
    }

    /// The static contact at t = 0 and the branches' state then.
    fn start(&mut self) {
        let s = self.setup.clone();
        let compliance = match s.start {
            Start::Fresh => s.creep.glassy,
            Start::Relaxed => self.effective_relaxed(),
        };
        assert!(compliance > 0.0, "a fresh start needs a glassy compliance");
        // Start from a uniform pressure on the relaxed Hertz circle.
        let a = (0.75 * s.load * s.radius * self.effective_relaxed()).cbrt();
        let n = s.cells;
        for j in 0..n {
            for i in 0..n {
                let (x, y) = (self.centres[i], self.centres[j]);
                self.pressure[j * n + i] = if x * x + y * y < a * a { 1.0 } else { 0.0 };
            }
        }
        let offset = self.shape.clone();
        self.solve(compliance, &offset);
        let w = self.lattice_displacement();
        let m1 = self.slots + 1;
        self.creep = self
            .branches
            .iter()
            .map(|b| {
                let mut c = vec![0.0; n * self.slots];
                if s.start == Start::Relaxed {
                    for j in 0..n {
                        for q in 0..self.slots {
                            c[j * self.slots + q] = b.compliance * w[j * m1 + q];
                        }
                    }
                }
                c
            })
            .collect();
        self.previous = w;
    }

    /// `J_g + sum_k J_k` over the branches that creep.
    fn effective_relaxed(&self) -> f64 {
        self.setup.creep.relaxed()
    }

    fn solve(&mut self, compliance: f64, offset: &[f64]) {
        let area = self.cell * self.cell;
        let r = polonsky_keer(
            &mut self.window,
            compliance,
            offset,
            area,
            self.setup.load,
            &mut self.pressure,
            self.setup.tolerance,
        );
        self.approach = r.approach;
        self.cg_iterations += r.iterations;
        self.worst_residual = self.worst_residual.max(r.residual);
    }

    /// W = L[p] on the lattice's `M + 1` slots of every material line.
    fn lattice_displacement(&mut self) -> Vec<f64> {
        let n = self.setup.cells;
        let m = self.setup.substeps;
        let sx = m * (n - 1) + 1;
        self.scratch.clear();
        self.scratch.resize(sx * n, 0.0);
        for j in 0..n {
            for i in 0..n {
                self.scratch[j * sx + m * i] = self.pressure[j * n + i];
            }
        }
        let mut w = vec![0.0; n * (self.slots + 1)];
        let source = std::mem::take(&mut self.scratch);
        self.lattice.apply(&source, &mut w);
        self.scratch = source;
        w
    }

    /// One step of `h / m` of travel.
    pub fn step(&mut self) {
        let n = self.setup.cells;
        let m = self.setup.substeps;
        let (slots, m1) = (self.slots, self.slots + 1);
        // Shift: the point now at slot q was at q + 1; a fresh point enters at M - 1.
        for c in &mut self.creep {
            for j in 0..n {
                let line = &mut c[j * slots..(j + 1) * slots];
                line.copy_within(1.., 0);
                line[slots - 1] = 0.0;
            }
        }
        // W where each point was at the previous step.
        let before: Vec<f64> = (0..n * slots)
            .map(|k| self.previous[(k / slots) * m1 + k % slots + 1])
            .collect();
        // The history at the cell centres.
        let mut offset = self.shape.clone();
        for j in 0..n {
            for i in 0..n {
                let k = j * slots + m * i;
                let mut h = 0.0;
                for (b, c) in self.branches.iter().zip(&self.creep) {
                    h += b.decay * c[k] + b.compliance * b.b0 * before[k];
                }
                offset[j * n + i] += h;
            }
        }
        self.solve(self.effective, &offset);
        let w = self.lattice_displacement();
        for (b, c) in self.branches.iter().zip(self.creep.iter_mut()) {
            for j in 0..n {
                for q in 0..slots {
                    let k = j * slots + q;
                    c[k] =
                        b.decay * c[k] + b.compliance * (b.b0 * before[k] + b.b1 * w[j * m1 + q]);
                }
            }
        }
        self.previous = w;
        self.steps += 1;
    }

    /// Distance slid.
    pub fn travel(&self) -> f64 {
        self.steps as f64 * self.cell / self.setup.substeps as f64
    }

    /// The scalars now.
    pub fn snapshot(&self) -> Snapshot {
        let n = self.setup.cells;
        let area = self.cell * self.cell;
        let mut moment = 0.0;
        for j in 0..n {
            for i in 0..n {
                moment += self.pressure[j * n + i] * self.centres[i] / self.setup.radius;
            }
        }
        Snapshot {
            travel: self.travel(),
            max_pressure: self.pressure.iter().fold(0.0, |m, &v| m.max(v)),
            friction: moment * area / self.setup.load,
            approach: self.approach,
            contact_cells: self.pressure.iter().filter(|&&v| v > 0.0).count(),
        }
    }

    /// Steps until `travel` is reached; the snapshots of every step.
    pub fn run_to(&mut self, travel: f64) -> Vec<Snapshot> {
        let mut out = Vec::new();
        while self.travel() < travel - 1e-9 * self.cell {
            self.step();
            out.push(self.snapshot());
        }
        out
    }

    /// Whether the pressure reaches the window's outermost ring of cells.
    pub fn touches_edge(&self) -> bool {
        let n = self.setup.cells;
        (0..n).any(|k| {
            self.pressure[k] > 0.0
                || self.pressure[(n - 1) * n + k] > 0.0
                || self.pressure[k * n] > 0.0
                || self.pressure[k * n + n - 1] > 0.0
        })
    }
}
