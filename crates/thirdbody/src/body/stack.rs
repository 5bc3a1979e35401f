//! The surface cell kernel of any layered stack ([`super::layered::Stack`]): the
//! normal displacement at the centre of the cell `(di, dj)` cells away from a square
//! cell of side `h` under unit pressure, `K(X, Y) = (1 / 4 pi^2) int int C A(k) / k
//! * S(kx, ky) cos(kx X) cos(ky Y) dkx dky` with `C = 2 (1 - nu_top^2) / E_top`,
//! `A(k)` the stack's surface factor ([`super::layered::LayeredSolver::surface_factor`])
//! and `S = h^2 sinc(kx h / 2) sinc(ky h / 2)` the cell's transform.
//!
//! # Method
//! `A(k)` is split as `1 + c0 e^{-k d} + beta k d e^{-k d} + R(k)`:
//! - `C / k` is the top material's half-space: Love's closed form
//!   ([`super::homogeneous`]);
//! - `C e^{-k d} / k` is the point response `C / (2 pi sqrt(r^2 + d^2))`, whose cell
//!   integral has the primitive `u asinh(v / sqrt(u^2 + d^2)) + v asinh(u / sqrt(v^2 +
//!   d^2)) - d atan(u v / (d sqrt(u^2 + v^2 + d^2)))` (mixed derivative
//!   `1 / sqrt(u^2 + v^2 + d^2)`);
//! - `C d e^{-k d}` is `C d^2 / (2 pi (r^2 + d^2)^{3/2})`, primitive
//!   `d atan(u v / (d sqrt(u^2 + v^2 + d^2)))` (the solid angle of a rectangle);
//! - `d` is the stack's thickness; `c0 = A(0) - 1` (`A(0) = 0` on a rigid base) and
//!   `beta = A'(0) / d + c0` make `R(0) = R'(0) = 0`, so `C R(k) / k` is bounded,
//!   vanishes at `k = 0` and its spatial kernel has no `1 / r` and no net load: its
//!   periodic images are small.
//!
//! The remainder is evaluated on the cell lattice by an inverse FFT of its periodised
//! spectrum `sum_{m, n} F(k + 2 pi (m, n) / h)`, `F = C W(k) R(k) / k S(k)`, which
//! gives the cell-centre values exactly up to periodic images of period `P h`
//! (`P >= 2 max(nx, ny)`). The aliases `(m, n) != 0` are a smooth function on the
//! Brillouin zone: they are summed at Chebyshev nodes and interpolated. `R(k) / k` is
//! tabulated once (Chebyshev panels in `k` near 0 and in `ln k` above).
//! `W(k) = (erfc((k - k_c) / w) - erfc((k + k_c) / w)) / 2` is a smooth low-pass:
//! `(1 - W(k)) / k` is an even entire function, so the part left out, `C (1 - W) R /
//! k`, has a spatial kernel without net load that is concentrated within a few `1 / w`
//! of the load point; a cell centre lies `h / 2` from the loaded cell's edges, so its
//! cell integral there is of order `exp(-(w h / 4)^2)`. That is what lets layers far
//! thinner than a cell (whose `R(k)` decays only at `k ~ 1 / thickness`) be handled
//! without resolving them: their short-wave part carries no load to any cell centre.
//! A stack of identical materials on the same half-space has `A = 1`, `c0 = beta = 0`
//! and `R = 0`: its kernel is Love's by construction.

use std::f64::consts::PI;

use rayon::prelude::*;
use realfft::num_complex::Complex;
use realfft::RealFftPlanner;

use super::homogeneous::homogeneous_surface_kernel_quadrant;
use super::layered::{Base, LayeredSolver, LongWave, Ply, Stack};
use super::quadrature::{ChebyshevPanels, GaussLegendre};
use crate::error::{require_positive, Error, Result};

/// A stack of bonded layers on an elastic half-space or a rigid base, as a body
/// whose surface cell kernel is known. Stresses of stacks are not yet offered, so
/// it does not implement [`super::ElasticBody`].
#[derive(Debug, Clone, PartialEq)]
pub struct StackBody {
    /// The layers and their base.
    pub stack: Stack,
}

/// The numerical parameters of the remainder (the defaults are what
/// [`StackBody::surface_kernel_quadrant`] uses; tests vary them to check convergence).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Resolution {
    /// Width `w h` of the low-pass's edge; its centre is at `5.6 w`.
    pub width: f64,
    /// Lattice period over the largest kernel extent (rounded up to a power of two).
    pub padding: usize,
    /// Chebyshev nodes per axis for the aliases.
    pub nodes: usize,
    /// Centre `k_1 h` of the edge between the long-wave band (radial quadrature) and
    /// the lattice band; the edge's width is `k_1 / 5.6`.
    pub split: f64,
    /// Least distance, in cells, between the kernel's extent and its first periodic
    /// image.
    pub clearance: usize,
}

impl Default for Resolution {
    fn default() -> Self {
        Resolution {
            width: 21.0,
            padding: 2,
            nodes: 40,
            split: 0.1,
            clearance: 640,
        }
    }
}

impl StackBody {
    /// The surface kernel on one quadrant of offsets, `[dj * nx + di]` for
    /// `0 <= di < nx`, `0 <= dj < ny`, on square cells of side `cell`, as
    /// [`super::ElasticBody::surface_kernel_quadrant`].
    pub fn surface_kernel_quadrant(&self, cell: f64, nx: usize, ny: usize) -> Result<Vec<f64>> {
        self.kernel_with(cell, nx, ny, Resolution::default())
    }

    /// Depths of the bottoms of the layers, top to bottom.
    pub fn interface_depths(&self) -> Vec<f64> {
        self.stack.interface_depths()
    }

    /// The smallest plane-strain modulus `E / (1 - nu^2)` of the layers and an elastic
    /// base.
    pub fn softest_modulus(&self) -> f64 {
        let base = match self.stack.base {
            Base::HalfSpace(m) => m.plane_strain_modulus(),
            Base::Rigid(_) => f64::INFINITY,
        };
        self.stack
            .layers
            .iter()
            .map(|p| p.material.plane_strain_modulus())
            .fold(base, f64::min)
    }

    pub(crate) fn kernel_with(
        &self,
        cell: f64,
        nx: usize,
        ny: usize,
        resolution: Resolution,
    ) -> Result<Vec<f64>> {
        self.stack.validate()?;
        require_positive("grid.cell", cell)?;
        if nx == 0 || ny == 0 {
            return Err(Error::invalid(
                "grid.cells",
                format!("[{nx}, {ny}]"),
                "at least one cell along each axis",
            ));
        }
        // Work in cells: lengths / cell; the kernel scales with the cell.
        let scaled = Stack {
            layers: self
                .stack
                .layers
                .iter()
                .map(|p| Ply {
                    material: p.material,
                    thickness: p.thickness / cell,
                })
                .collect(),
            base: self.stack.base,
        };
        let top = scaled.top_material();
        let compliance = 2.0 * (1.0 - top.poisson * top.poisson) / top.young;
        let t0 = std::time::Instant::now();
        let split = LongWaveSplit::new(&scaled)?;
        let mut kernel = closed_form_quadrant(&split, nx, ny);
        let t1 = t0.elapsed().as_secs_f64();
        let love = homogeneous_surface_kernel_quadrant(top, 1.0, nx, ny);
        let t2 = t0.elapsed().as_secs_f64();
        let remainder = Remainder::new(&scaled, &split, compliance, resolution)?;
        let t3 = t0.elapsed().as_secs_f64();
        let fft = remainder.lattice_kernel(nx, ny, resolution);
        let t4 = t0.elapsed().as_secs_f64();
        let long = remainder.long_wave_kernel(nx, ny);
        let t5 = t0.elapsed().as_secs_f64();
        if std::env::var("STACK_TIMING").is_ok() {
            eprintln!(
                "closed {t1:.3} love {:.3} table {:.3} lattice {:.3} long {:.3} kmax {}",
                t2 - t1,
                t3 - t2,
                t4 - t3,
                t5 - t4,
                remainder.k_max
            );
        }
        for (((k, l), r), g) in kernel.iter_mut().zip(&love).zip(&fft).zip(&long) {
            // closed_form_quadrant is per unit C / (2 pi).
            *k = cell * (l + compliance / (2.0 * PI) * *k + r + g);
        }
        if kernel.iter().any(|v| !v.is_finite()) {
            return Err(Error::invalid(
                "stack",
                format!("{:?}", self.stack.layers.len()),
                "a stack whose kernel is finite",
            ));
        }
        Ok(kernel)
    }
}

/// The long-wave terms `c0 e^{-kd} + beta k d e^{-kd}` (module doc), lengths in cells.
#[derive(Debug, Clone, Copy)]
struct LongWaveSplit {
    c0: f64,
    beta: f64,
    d: f64,
}

impl LongWaveSplit {
    fn new(stack: &Stack) -> Result<Self> {
        let total: f64 = stack.layers.iter().map(|p| p.thickness).sum();
        if stack.layers.is_empty() {
            return Ok(LongWaveSplit {
                c0: 0.0,
                beta: 0.0,
                d: 1.0,
            });
        }
        let d = total;
        let (a0, a1) = match stack.long_wave_limit() {
            LongWave::Slope(s) => (0.0, s),
            LongWave::Factor(a0) => {
                // A'(0) by Richardson extrapolation of the difference quotient
                // D(k) = (A(k) - A0) / k = A1 + A2 k + ...: 2 D(k) - D(2k) = A1 + O(k^2).
                let mut solver = LayeredSolver::new(stack)?;
                let k = 1e-3 / total;
                let q1 = (solver.surface_factor(k) - a0) / k;
                let q2 = (solver.surface_factor(2.0 * k) - a0) / (2.0 * k);
                (a0, 2.0 * q1 - q2)
            }
        };
        let c0 = a0 - 1.0;
        Ok(LongWaveSplit {
            c0,
            beta: a1 / d + c0,
            d,
        })
    }

    /// `c0 e^{-kd} + beta k d e^{-kd}`.
    fn spectrum(&self, k: f64) -> f64 {
        let kd = k * self.d;
        (self.c0 + self.beta * kd) * (-kd).exp()
    }
}

/// The cell kernel (per unit `C / 2 pi`, cells of side 1) of the long-wave terms.
fn closed_form_quadrant(split: &LongWaveSplit, nx: usize, ny: usize) -> Vec<f64> {
    let LongWaveSplit { c0, beta, d } = *split;
    let primitive = |u: f64, v: f64| {
        let r = (u * u + v * v + d * d).sqrt();
        let solid = if u == 0.0 || v == 0.0 {
            0.0
        } else {
            d * (u * v / (d * r)).atan()
        };
        let exponential = u * (v / (u * u + d * d).sqrt()).asinh()
            + v * (u / (v * v + d * d).sqrt()).asinh()
            - solid;
        c0 * exponential + beta * solid
    };
    corner_sums(nx, ny, primitive)
}

/// `K(i, j) = sum over the cell's corners of +-F(corner - centre)` for an odd-odd
/// primitive `F` of a radial point response, on cells of side 1.
fn corner_sums(nx: usize, ny: usize, f: impl Fn(f64, f64) -> f64 + Sync) -> Vec<f64> {
    let w = nx + 1;
    let corner: Vec<f64> = (0..(ny + 1) * w)
        .into_par_iter()
        .map(|m| f((m % w) as f64 - 0.5, (m / w) as f64 - 0.5))
        .collect();
    (0..nx * ny)
        .into_par_iter()
        .map(|m| {
            let (i, j) = (m % nx, m / nx);
            let at = |k: usize, l: usize| corner[l * w + k];
            at(i + 1, j + 1) - at(i + 1, j) - at(i, j + 1) + at(i, j)
        })
        .collect()
}

/// `q(k) = C W(k) R(k) / k` (module doc) tabulated on `[0, k_max]`, lengths in cells.
#[derive(Debug, Clone)]
struct Remainder {
    /// Panels in `k` on `[0, knee]`.
    near: ChebyshevPanels,
    /// Panels in `ln k` on `[knee, k_max]`.
    far: ChebyshevPanels,
    knee: f64,
    /// Beyond it q is zero to rounding.
    k_max: f64,
    /// Centre and width of the band edge (`Resolution::split`).
    split: f64,
    split_width: f64,
}

const DEGREE: usize = 16;
/// Panel width in `ln k`.
const LOG_PANEL: f64 = 0.1;

impl Remainder {
    fn new(
        stack: &Stack,
        split: &LongWaveSplit,
        compliance: f64,
        resolution: Resolution,
    ) -> Result<Self> {
        let w = resolution.width;
        let centre = 5.6 * w;
        let k_max = centre + 5.6 * w;
        let thinnest = stack
            .layers
            .iter()
            .map(|p| p.thickness)
            .fold(split.d, f64::min);
        let knee = (0.05 / split.d).min(0.05 / thinnest).min(0.05);
        let solver = LayeredSolver::new(stack)?;
        let value = |solver: &mut LayeredSolver, k: f64| {
            let low_pass = 0.5 * (libm::erfc((k - centre) / w) - libm::erfc((k + centre) / w));
            let a = if stack.layers.is_empty() {
                1.0
            } else {
                solver.surface_factor(k)
            };
            compliance * low_pass * (a - 1.0 - split.spectrum(k)) / k
        };
        let near_panels = 4;
        let near_points = ChebyshevPanels::points(0.0, knee, near_panels, DEGREE);
        let near_values: Vec<f64> = near_points
            .par_iter()
            .map_init(|| solver.clone(), |s, &k| value(s, k))
            .collect();
        let (lo, hi) = (knee.ln(), k_max.ln());
        let far_panels = ((hi - lo) / LOG_PANEL).ceil() as usize;
        let far_points = ChebyshevPanels::points(lo, hi, far_panels, DEGREE);
        let far_values: Vec<f64> = far_points
            .par_iter()
            .map_init(|| solver.clone(), |s, &t| value(s, t.exp()))
            .collect();
        // Where q has fallen to rounding for good, stop summing aliases.
        let peak = near_values
            .iter()
            .chain(&far_values)
            .fold(0.0f64, |m, v| m.max(v.abs()));
        let last = far_values
            .iter()
            .rposition(|v| v.abs() > 1e-17 * peak.max(compliance))
            .map_or(knee, |i| {
                (lo + (i / DEGREE + 1) as f64 * (hi - lo) / far_panels as f64).exp()
            });
        Ok(Remainder {
            near: ChebyshevPanels::from_values(0.0, knee, near_panels, DEGREE, &near_values),
            far: ChebyshevPanels::from_values(lo, hi, far_panels, DEGREE, &far_values),
            knee,
            k_max: last.min(k_max),
            split: resolution.split,
            split_width: resolution.split / 5.6,
        })
    }

    /// The long-wave band's share `W_1(k)` (an even low-pass like `W`).
    fn long_share(&self, k: f64) -> f64 {
        let (c, w) = (self.split, self.split_width);
        0.5 * (libm::erfc((k - c) / w) - libm::erfc((k + c) / w))
    }

    /// The lattice band's spectrum: `q (1 - W_1)`.
    fn q_lattice(&self, k: f64) -> f64 {
        if k > 2.0 * self.split + 6.0 * self.split_width {
            self.q(k)
        } else {
            self.q(k) * (1.0 - self.long_share(k))
        }
    }

    /// The long-wave band's cell kernel: its radial point response
    /// `g(r) = (1 / 2 pi) int W_1 q J0(k r) k dk` (tabulated in r), integrated over each
    /// cell by 3 x 3 Gauss-Legendre points (g is band-limited to `k h < 0.2`: the rule's
    /// error is of order `(0.1)^6 / 6!` of g).
    fn long_wave_kernel(&self, nx: usize, ny: usize) -> Vec<f64> {
        let k_end = self.split + 5.6 * self.split_width;
        let rule = GaussLegendre::new(12);
        let point_response = |r: f64| -> f64 {
            let f = |k: f64| self.long_share(k) * self.q(k) * k * libm::j0(k * r);
            // Panels: k in [0, knee], then geometric (ratio 1.25) with widths below
            // 2 / r for the Bessel oscillation.
            let mut sum = rule.integrate(0.0, self.knee, f);
            let mut lo = self.knee;
            while lo < k_end {
                let hi = (lo * 1.25).min(k_end);
                let pieces = ((hi - lo) * r / 2.0).ceil().max(1.0) as usize;
                let step = (hi - lo) / pieces as f64;
                for p in 0..pieces {
                    let a = lo + p as f64 * step;
                    sum += rule.integrate(a, a + step, f);
                }
                lo = hi;
            }
            sum / (2.0 * PI)
        };
        let r_max = 2f64.sqrt() * (nx.max(ny) as f64 + 1.0);
        let panels = (r_max / 8.0).ceil() as usize;
        let points = ChebyshevPanels::points(0.0, r_max, panels, DEGREE);
        let values: Vec<f64> = points.par_iter().map(|&r| point_response(r)).collect();
        let g = ChebyshevPanels::from_values(0.0, r_max, panels, DEGREE, &values);
        if std::env::var("STACK_TIMING").is_ok() {
            eprintln!("  hankel table done");
        }
        let cell_rule = GaussLegendre::new(3);
        let offsets: Vec<(f64, f64)> = cell_rule
            .nodes
            .iter()
            .zip(&cell_rule.weights)
            .map(|(x, w)| (0.5 * x, 0.5 * w))
            .collect();
        (0..nx * ny)
            .into_par_iter()
            .map(|m| {
                let (i, j) = ((m % nx) as f64, (m / nx) as f64);
                let mut sum = 0.0;
                for (xa, wa) in &offsets {
                    for (yb, wb) in &offsets {
                        let r = ((i + xa).powi(2) + (j + yb).powi(2)).sqrt();
                        sum += wa * wb * g.eval(r);
                    }
                }
                sum
            })
            .collect()
    }

    fn q(&self, k: f64) -> f64 {
        if k <= self.knee {
            self.near.eval(k)
        } else if k <= self.k_max {
            self.far.eval(k.ln())
        } else {
            0.0
        }
    }

    /// The aliases `(m, n) != 0` of `q(|k|) sinc(kx / 2) sinc(ky / 2)` at `(kx, ky)`
    /// in the Brillouin zone.
    fn aliases(&self, kx: f64, ky: f64) -> f64 {
        let reach = (self.k_max / (2.0 * PI)).ceil() as i64 + 1;
        let (sx, sy) = ((0.5 * kx).sin(), (0.5 * ky).sin());
        let mut sum = 0.0;
        for m in -reach..=reach {
            let px = kx + 2.0 * PI * m as f64;
            if px.abs() > self.k_max {
                continue;
            }
            // sinc(px / 2) = (-1)^m sin(kx / 2) / (px / 2).
            let cx = if px == 0.0 {
                1.0
            } else {
                (if m % 2 == 0 { sx } else { -sx }) / (0.5 * px)
            };
            let span = (self.k_max * self.k_max - px * px).sqrt();
            let mut row = 0.0;
            for n in -reach..=reach {
                if m == 0 && n == 0 {
                    continue;
                }
                let py = ky + 2.0 * PI * n as f64;
                if py.abs() > span {
                    continue;
                }
                let cy = if py == 0.0 {
                    1.0
                } else {
                    (if n % 2 == 0 { sy } else { -sy }) / (0.5 * py)
                };
                row += self.q_lattice((px * px + py * py).sqrt()) * cy;
            }
            sum += row * cx;
        }
        sum
    }

    /// The remainder's cell kernel on the quadrant (cells of side 1).
    fn lattice_kernel(&self, nx: usize, ny: usize, resolution: Resolution) -> Vec<f64> {
        let n = nx.max(ny);
        let period = (resolution.padding * n)
            .max(n + resolution.clearance)
            .next_power_of_two();
        let half = period / 2;
        let step = 2.0 * PI / period as f64;
        // Aliases at Chebyshev nodes on [0, pi]^2, then their coefficients.
        let nc = resolution.nodes;
        let node = |q: usize| 0.5 * PI * (1.0 + (PI * (q as f64 + 0.5) / nc as f64).cos());
        let values: Vec<f64> = (0..nc * nc)
            .into_par_iter()
            .map(|m| self.aliases(node(m % nc), node(m / nc)))
            .collect();
        let ta = std::time::Instant::now();
        let coefficients = chebyshev_coefficients_2d(&values, nc);
        // T_j at the lattice wavenumbers, u = 2 k / pi - 1.
        let basis: Vec<f64> = (0..=half)
            .flat_map(|a| {
                let u = 2.0 * (a as f64 * step) / PI - 1.0;
                let mut t = vec![0.0; nc];
                t[0] = 1.0;
                if nc > 1 {
                    t[1] = u;
                }
                for j in 2..nc {
                    t[j] = 2.0 * u * t[j - 1] - t[j - 2];
                }
                t
            })
            .collect();
        // partial[jy][a] = sum_jx c[jy][jx] T_jx(u_a).
        let partial: Vec<f64> = (0..nc * (half + 1))
            .into_par_iter()
            .map(|m| {
                let (jy, a) = (m / (half + 1), m % (half + 1));
                let t = &basis[a * nc..(a + 1) * nc];
                coefficients[jy * nc..(jy + 1) * nc]
                    .iter()
                    .zip(t)
                    .map(|(c, t)| c * t)
                    .sum()
            })
            .collect();
        // The periodised spectrum on the lattice quadrant, row b (ky), column a (kx),
        // transformed along kx right away: rows[b][i] for i < nx.
        let mut planner = RealFftPlanner::<f64>::new();
        let c2r = planner.plan_fft_inverse(period);
        let sinc = |k: f64| {
            if k == 0.0 {
                1.0
            } else {
                (0.5 * k).sin() / (0.5 * k)
            }
        };
        let rows: Vec<Vec<f64>> = (0..=half)
            .into_par_iter()
            .map_init(
                || {
                    (
                        c2r.make_input_vec(),
                        c2r.make_output_vec(),
                        c2r.make_scratch_vec(),
                    )
                },
                |(input, output, scratch), b| {
                    let ky = b as f64 * step;
                    let ty = &basis[b * nc..(b + 1) * nc];
                    let sy = sinc(ky);
                    for (a, z) in input.iter_mut().enumerate() {
                        let kx = a as f64 * step;
                        let alias: f64 = (0..nc)
                            .map(|jy| ty[jy] * partial[jy * (half + 1) + a])
                            .sum();
                        let direct = self.q_lattice((kx * kx + ky * ky).sqrt()) * sinc(kx) * sy;
                        *z = Complex::new(direct + alias, 0.0);
                    }
                    c2r.process_with_scratch(input, output, scratch)
                        .expect("real spectrum of the right length");
                    output[..nx].to_vec()
                },
            )
            .collect();
        if std::env::var("STACK_TIMING").is_ok() {
            eprintln!("  rows done {:.3}", ta.elapsed().as_secs_f64());
        }
        // Along ky for each di.
        let scale = 1.0 / (period as f64 * period as f64);
        let columns: Vec<Vec<f64>> = (0..nx)
            .into_par_iter()
            .map_init(
                || {
                    (
                        c2r.make_input_vec(),
                        c2r.make_output_vec(),
                        c2r.make_scratch_vec(),
                    )
                },
                |(input, output, scratch), i| {
                    for (b, z) in input.iter_mut().enumerate() {
                        *z = Complex::new(rows[b][i], 0.0);
                    }
                    c2r.process_with_scratch(input, output, scratch)
                        .expect("real spectrum of the right length");
                    output[..ny].iter().map(|v| v * scale).collect()
                },
            )
            .collect();
        let mut kernel = vec![0.0; nx * ny];
        for (i, column) in columns.iter().enumerate() {
            for (j, v) in column.iter().enumerate() {
                kernel[j * nx + i] = *v;
            }
        }
        kernel
    }
}

/// Chebyshev coefficients `c[jy * n + jx]` of a function sampled at the tensor
/// Chebyshev points of the first kind (`values[qy * n + qx]`, node
/// `cos(pi (q + 1/2) / n)`).
fn chebyshev_coefficients_2d(values: &[f64], n: usize) -> Vec<f64> {
    let transform = |v: &[f64]| -> Vec<f64> {
        (0..n)
            .map(|j| {
                let s: f64 = v
                    .iter()
                    .enumerate()
                    .map(|(q, x)| x * (PI * j as f64 * (q as f64 + 0.5) / n as f64).cos())
                    .sum();
                s * if j == 0 { 1.0 } else { 2.0 } / n as f64
            })
            .collect()
    };
    // Along x for each row, then along y for each column.
    let rows: Vec<Vec<f64>> = values.chunks(n).map(transform).collect();
    let mut c = vec![0.0; n * n];
    for jx in 0..n {
        let column: Vec<f64> = rows.iter().map(|r| r[jx]).collect();
        for (jy, v) in transform(&column).into_iter().enumerate() {
            c[jy * n + jx] = v;
        }
    }
    c
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::body::coated::coated_surface_kernel;
    use crate::body::layered::BaseContact;
    use crate::case::Elastic;

    fn elastic(young: f64, poisson: f64) -> Elastic {
        Elastic { young, poisson }
    }

    fn worst(a: &[f64], b: &[f64]) -> f64 {
        let peak = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        a.iter()
            .zip(b)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max)
            / peak
    }

    fn ply(young: f64, poisson: f64, thickness: f64) -> Ply {
        Ply {
            material: elastic(young, poisson),
            thickness,
        }
    }

    /// The kernel at `(x, y)` cells by direct quadrature of the Fourier integral in
    /// polar coordinates, cells of side 1: Love's kernel of the top material plus
    /// `(C / 4 pi^2) int_0^inf (A(k) - 1) Psi(k) dk`, `Psi(k) = int_0^{2 pi} S cos(kx x)
    /// cos(ky y) dtheta` by the trapezoidal rule (periodic and smooth: it converges
    /// once the points outnumber the integrand's angular frequencies, k (x + y + 1)),
    /// `k` by 16-point Gauss-Legendre panels (geometric near 0, width 1/2 above).
    fn polar_quadrature(stack: &Stack, x: f64, y: f64) -> f64 {
        let top = stack.top_material();
        let c = 2.0 * (1.0 - top.poisson * top.poisson) / top.young;
        let love = crate::body::homogeneous::love_rectangle_displacement(top, 0.5, 0.5, x, y);
        let mut solver = LayeredSolver::new(stack).unwrap();
        let t = stack.layers[0].thickness;
        let k_end = 25.0 / t;
        let psi = |k: f64| {
            let n = 4 * ((k * (x + y + 1.0) / 4.0).ceil() as usize + 12);
            let quarter = n / 4;
            let mut sum = 0.0;
            for i in 0..=quarter {
                let th = 0.5 * PI * i as f64 / quarter as f64;
                let (kx, ky) = (k * th.cos(), k * th.sin());
                let sinc = |u: f64| {
                    if u == 0.0 {
                        1.0
                    } else {
                        (0.5 * u).sin() / (0.5 * u)
                    }
                };
                let f = sinc(kx) * sinc(ky) * (kx * x).cos() * (ky * y).cos();
                sum += if i == 0 || i == quarter { 0.5 * f } else { f };
            }
            sum * 2.0 * PI / quarter as f64 * 0.25 * 4.0
        };
        let rule = GaussLegendre::new(16);
        let mut edges = vec![0.0, 1e-6];
        while *edges.last().unwrap() < k_end {
            let last = *edges.last().unwrap();
            edges.push((last * 1.3).min(last + 0.5).min(k_end));
        }
        let integral: f64 = edges
            .windows(2)
            .map(|e| rule.integrate(e[0], e[1], |k| (solver.surface_factor(k) - 1.0) * psi(k)))
            .sum();
        love + c / (4.0 * PI * PI) * integral
    }

    #[test]
    fn agrees_with_direct_polar_quadrature() {
        let mut worst_all: f64 = 0.0;
        for t in [0.05, 20.0] {
            for base in [
                Base::HalfSpace(elastic(1.0, 0.3)),
                Base::Rigid(BaseContact::Bonded),
                Base::Rigid(BaseContact::Frictionless),
            ] {
                for layers in [
                    vec![ply(30.0, 0.25, t), ply(1.0 / 30.0, 0.45, t)],
                    vec![ply(1.0 / 30.0, 0.45, t), ply(30.0, 0.25, t)],
                ] {
                    let stack = Stack { layers, base };
                    let kernel = StackBody {
                        stack: stack.clone(),
                    }
                    .surface_kernel_quadrant(1.0, 8, 8)
                    .unwrap();
                    let peak = kernel[0];
                    for (i, j) in [(0, 0), (1, 0), (2, 1), (5, 3)] {
                        let direct = polar_quadrature(&stack, i as f64, j as f64);
                        let e = (kernel[j * 8 + i] - direct).abs() / peak;
                        worst_all = worst_all.max(e);
                        eprintln!(
                            "t {t} {base:?} ({i}, {j}): {} vs {direct}: {e:.1e}",
                            kernel[j * 8 + i]
                        );
                    }
                }
            }
        }
        eprintln!("worst {worst_all:.1e}");
    }

    /// Stacks at the ends of the range: 1 to 8 layers 1e-3 to 1e3 cells thick, E
    /// ratios 1e-3 to 1e3, every base.
    fn extreme_stacks() -> Vec<Stack> {
        let thickness = [1e-3, 1e3, 0.1, 10.0, 1.0, 1e2, 0.01, 1e3];
        let mut stacks = Vec::new();
        for base in [
            Base::HalfSpace(elastic(1.0, 0.3)),
            Base::HalfSpace(elastic(1e-3, 0.45)),
            Base::HalfSpace(elastic(1e3, 0.2)),
            Base::Rigid(BaseContact::Bonded),
            Base::Rigid(BaseContact::Frictionless),
        ] {
            for (count, first) in [(1, 0), (1, 1), (2, 2), (3, 0), (8, 0), (4, 4)] {
                for stiff_first in [true, false] {
                    let layers = (0..count)
                        .map(|i| {
                            let stiff = (i % 2 == 0) == stiff_first;
                            let (e, nu) = if stiff { (1e3, 0.2) } else { (1e-3, 0.45) };
                            ply(e, nu, thickness[(first + i) % 8])
                        })
                        .collect();
                    stacks.push(Stack { layers, base });
                }
            }
        }
        stacks
    }

    #[test]
    fn dev_self_convergence() {
        let fine = Resolution {
            width: 28.0,
            padding: 4,
            nodes: 60,
            split: 0.15,
            clearance: 1280,
        };
        let mut all: f64 = 0.0;
        for stack in extreme_stacks() {
            let body = StackBody {
                stack: stack.clone(),
            };
            let n = 96;
            let a = body.surface_kernel_quadrant(1.0, n, n).unwrap();
            let b = body.kernel_with(1.0, n, n, fine).unwrap();
            let e = worst(&a, &b);
            all = all.max(e);
            let t: Vec<f64> = stack.layers.iter().map(|p| p.thickness).collect();
            eprintln!("{:?} {t:?} peak {:.3e}: {e:.1e}", stack.base, b[0]);
        }
        eprintln!("worst {all:.1e}");
    }

    #[test]
    fn dev_against_coated() {
        let substrate = elastic(1.0, 0.3);
        for ratio in [10.0, 0.1] {
            for t in [0.05, 1.0, 20.0] {
                let coating = elastic(ratio, 0.25);
                let oracle = coated_surface_kernel(coating, t, substrate, 1.0, 64, 64).unwrap();
                let body = StackBody {
                    stack: Stack {
                        layers: vec![Ply {
                            material: coating,
                            thickness: t,
                        }],
                        base: Base::HalfSpace(substrate),
                    },
                };
                for (w, pad, nodes, split, clearance) in [
                    (21.0, 2, 40, 0.1, 640),
                    (12.0, 2, 40, 0.1, 640),
                    (21.0, 4, 40, 0.1, 640),
                    (21.0, 2, 60, 0.1, 640),
                    (21.0, 2, 40, 0.1, 1280),
                    (21.0, 2, 40, 0.2, 640),
                ] {
                    let r = Resolution {
                        width: w,
                        padding: pad,
                        nodes,
                        split,
                        clearance,
                    };
                    let k = body.kernel_with(1.0, 64, 64, r).unwrap();
                    eprintln!("ratio {ratio} t {t} w {w} pad {pad} nodes {nodes} split {split} clear {clearance}: {:.2e}", worst(&k, &oracle));
                }
            }
        }
        let _ = BaseContact::Bonded;
    }
}

#[cfg(test)]
mod timing {
    use super::*;
    use crate::body::layered::BaseContact;
    use crate::case::Elastic;

    #[test]
    #[ignore]
    fn dev_timing_1024() {
        let ply = |young: f64, poisson: f64, thickness: f64| Ply {
            material: Elastic { young, poisson },
            thickness,
        };
        let stacks = [
            Stack {
                layers: vec![ply(10.0, 0.25, 1.0)],
                base: Base::HalfSpace(Elastic {
                    young: 1.0,
                    poisson: 0.3,
                }),
            },
            Stack {
                layers: (0..8)
                    .map(|i| {
                        ply(
                            if i % 2 == 0 { 1e3 } else { 1.0 },
                            0.3,
                            [1e-3, 1e3, 0.1, 10.0, 1.0, 1e2, 0.01, 1e3][i],
                        )
                    })
                    .collect(),
                base: Base::HalfSpace(Elastic {
                    young: 1e-3,
                    poisson: 0.3,
                }),
            },
            Stack {
                layers: vec![ply(1e-3, 0.45, 1e-3), ply(1.0, 0.3, 5.0)],
                base: Base::Rigid(BaseContact::Bonded),
            },
        ];
        for stack in stacks {
            let body = StackBody { stack };
            let mut times = Vec::new();
            for _ in 0..5 {
                let start = std::time::Instant::now();
                let k = body.surface_kernel_quadrant(1.0, 1024, 1024).unwrap();
                times.push(start.elapsed().as_secs_f64());
                assert!(k[0].is_finite());
            }
            times.sort_by(f64::total_cmp);
            eprintln!("times {times:?} median {:.3}", times[2]);
        }
    }
}
