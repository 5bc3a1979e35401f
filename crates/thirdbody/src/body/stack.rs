//! The surface cell kernel of any layered stack ([`super::layered::Stack`]): the
//! normal displacement at the centre of the cell `(di, dj)` cells away from a square
//! cell of side `h` under unit pressure, from the Fourier integral
//! `K(X, Y) = (1 / 4 pi^2) int int C A(k) / k S(kx, ky) cos(kx X) cos(ky Y) dkx dky`,
//! `C = 2 (1 - nu_top^2) / E_top`, `A(k)` the stack's surface factor
//! ([`super::layered::LayeredSolver::surface_factor`]) and
//! `S = h^2 sinc(kx h / 2) sinc(ky h / 2)` the cell's transform.
//!
//! # Method
//! `A(k) = 1 + c0 e^{-k d} + beta k d e^{-k d} + R(k)`, three closed forms and a
//! remainder:
//! - `C / k` is the top material's half-space: Love's kernel ([`super::homogeneous`]);
//! - `C e^{-k d} / k` has the point response `C / (2 pi sqrt(r^2 + d^2))`, whose cell
//!   integral has the primitive `u asinh(v / sqrt(u^2 + d^2)) + v asinh(u / sqrt(v^2 +
//!   d^2)) - d atan(u v / (d sqrt(u^2 + v^2 + d^2)))` (mixed derivative
//!   `1 / sqrt(u^2 + v^2 + d^2)`);
//! - `C d e^{-k d}` has `C d^2 / (2 pi (r^2 + d^2)^{3/2})`, primitive
//!   `d atan(u v / (d sqrt(u^2 + v^2 + d^2)))` (the solid angle of a rectangle);
//! - `d` is the stack's thickness, `c0 = A(0) - 1` (`A(0) = 0` on a rigid base) and
//!   `beta = A'(0) / d + c0` (`A'(0)` the closed-form slope on a rigid base,
//!   Richardson-extrapolated differences on a half-space) make `R(0) = R'(0) = 0`:
//!   `C R(k) / k` is bounded and carries no net load.
//!
//! `C R / k` (tabulated once in `|k|`: Chebyshev panels in `k` near 0, in `ln k`
//! above) is cut into three bands by two smooth low-passes of the form
//! `W(k) = (erfc((k - k_c) / w) - erfc((k + k_c) / w)) / 2`, `k_c = 5.6 w`, for which
//! `(1 - W(k)) / k` is an even entire function of k: no band has a `|k|` cusp at the
//! origin, so each band's spatial kernel decays fast instead of like a power of r.
//! - Long waves, `W_1` (`k_c = 0.1 / h`): band-limited to `k h < 0.2`; its radial point
//!   response `(1 / 2 pi) int W_1 C R J0(k r) dk` by Gauss–Legendre panels (geometric
//!   in k, narrower than the Bessel period), tabulated in r, and its cell integrals by
//!   3 x 3 Gauss–Legendre points. No periodicity: stacks far thicker than the window,
//!   whose `R` varies on `k ~ 1 / thickness`, are exact here.
//! - Middle waves, `W - W_1` (`w = 21 / h`): an inverse FFT of the periodised spectrum
//!   `sum_{m, n} F(k + 2 pi (m, n) / h)`, `F = C (W - W_1) R / k S`, which gives the
//!   cell-centre values exactly up to periodic images; the band's kernel is confined
//!   to a few hundred cells (the edge of `W_1`), so a period of
//!   `max(2 n, n + 640)` cells (a power of two) leaves them below rounding. The aliases
//!   `(m, n) != 0` are smooth on the Brillouin zone: they are summed at 24 x 24
//!   Chebyshev nodes and interpolated (16 x 16 are already within 1e-11 of the
//!   peak of 64 x 64).
//! - Short waves, `1 - W`, are left out: their kernel has no net load and is
//!   concentrated within a few `1 / w` of the load point, and a cell centre lies
//!   `h / 2` from the loaded cell's edges, so they move it by about
//!   `exp(-(w h / 4)^2)`. That is what lets layers far thinner than a cell (whose `R`
//!   decays only at `k ~ 1 / thickness`) be handled without resolving them.
//!
//! A stack of identical materials on the same half-space has `A = 1`,
//! `c0 = beta = 0`, `R = 0`: its kernel is Love's by construction.
//!
//! Accuracy (tests below): one layer on a half-space matches
//! the former one-coating kernel to 1.5e-13 of the peak; direct polar
//! quadrature of the Fourier integral agrees to 1.3e-13 (stiff and soft layers 0.05
//! and 20 cells thick, every base) and to 2.4e-13 out to offset (255, 200) for four
//! layers 0.01 to 1000 cells thick with E ratios 1e6 across; doubling the period,
//! widening `w` and the long-wave edge and adding alias nodes moves stacks of one to
//! eight layers 1e-3 to 1e3 cells thick with E ratios 1e3 by 1.7e-12 at most.
//! Cost: 1024 x 1024 cells in 0.39-0.63 s (medians) on two cores shared with other
//! work (`crates/thirdbody-bench/benches/stack_kernel.rs`, `docs/performance.md`).

use std::f64::consts::PI;

use rayon::prelude::*;
use realfft::num_complex::Complex;
use realfft::RealFftPlanner;

use super::homogeneous::homogeneous_surface_kernel_quadrant;
use super::layered::{Base, LayeredSolver, LongWave, Ply, Stack};
use super::quadrature::{ChebyshevPanels, GaussLegendre};
use super::{BodyModel, Side};
use crate::error::{require_positive, Error, Result};
use crate::provenance::{self, Reference};
use crate::stress::{LayeredStressKernels, StressKernels};

/// A stack of bonded layers on an elastic half-space or a rigid base: the
/// [`BodyModel`] of [`crate::Body::Layered`].
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
            nodes: 24,
            split: 0.1,
            clearance: 640,
        }
    }
}

impl BodyModel for StackBody {
    fn surface_kernel(
        &self,
        cell: f64,
        nx: usize,
        ny: usize,
        _velocity: f64,
        _lag: bool,
    ) -> Result<super::SurfaceKernel> {
        Ok(super::SurfaceKernel::Even {
            quadrant: StackBody::surface_kernel_quadrant(self, cell, nx, ny)?,
            nx,
        })
    }

    fn line_kernel(
        &self,
        cell: f64,
        nx: usize,
        _velocity: f64,
        reference: f64,
        _lag: bool,
    ) -> Result<super::SurfaceKernel> {
        Ok(super::SurfaceKernel::Even {
            quadrant: super::stack_line::line_kernel(&self.stack, cell, nx, reference)?,
            nx,
        })
    }

    fn kernel_depends_on_velocity(&self) -> bool {
        false
    }

    fn kernel_is_even(&self, _velocity: f64) -> bool {
        true
    }

    fn dissipated_force(
        &self,
        _grid: &crate::grid::Grid,
        _pressure: &[f64],
        _velocity: f64,
        _edges: super::EdgeProfile,
    ) -> Result<f64> {
        Ok(0.0)
    }

    fn stress_kernels(&self, interface_side: Side) -> Box<dyn StressKernels> {
        Box::new(LayeredStressKernels {
            stack: self.stack.clone(),
            interface_side,
        })
    }

    fn interface_depths(&self) -> Vec<f64> {
        let mut depths = self.stack.interface_depths();
        if matches!(self.stack.base, Base::Rigid(_)) {
            // The base's face: nothing below it.
            depths.pop();
        }
        depths
    }

    fn deepest(&self) -> Option<f64> {
        match self.stack.base {
            Base::HalfSpace(_) => None,
            Base::Rigid(_) => Some(self.stack.thickness()),
        }
    }

    fn softest_modulus(&self) -> f64 {
        StackBody::softest_modulus(self)
    }

    fn references(&self) -> Vec<Reference> {
        let response = "the layered body's Fourier response (surface and stress kernels)";
        vec![
            Reference::new(provenance::CHEN, response),
            Reference::new(provenance::OSULLIVAN_KING, response),
            Reference::new(
                provenance::PERRIOT_BARTHEL,
                "the coated body's response in a cancellation-free form",
            ),
            Reference::new(
                provenance::KAUSEL_ROESSET,
                "the layers' stiffness matrices, stable for any thickness",
            ),
            Reference::new(
                provenance::LOVE,
                "the top material's part of the layered kernels (uniform pressure on a rectangle)",
            ),
        ]
    }
}

impl StackBody {
    /// The surface kernel on one quadrant of offsets, `[dj * nx + di]` for
    /// `0 <= di < nx`, `0 <= dj < ny`, on square cells of side `cell`, as
    /// [`super::BodyModel::surface_kernel`] (an even kernel).
    pub fn surface_kernel_quadrant(&self, cell: f64, nx: usize, ny: usize) -> Result<Vec<f64>> {
        self.kernel_with(cell, nx, ny, Resolution::default())
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
        let diagonal = (nx as f64 + 0.5).hypot(ny as f64 + 0.5);
        if let Some(ply) = scaled.layers.first() {
            if THICK_TOP * diagonal < ply.thickness {
                return thick_top_kernel(&scaled, compliance, cell, nx, ny);
            }
        }
        let split = LongWaveSplit::new(&scaled)?;
        let mut kernel = closed_form_quadrant(&split, nx, ny);
        let love = homogeneous_surface_kernel_quadrant(top, 1.0, nx, ny);
        // A stiff layer on a far softer base changes A(k) at k far below 1 / d (the
        // stack's contrast E_min / E_max times it): the remainder's table starts
        // there once the contrast is below 0.01 (above, its first panel at 0.05 / d
        // holds, and the kernels stay as they were).
        let remainder =
            Remainder::new(&scaled, &split, compliance, resolution, knee_floor(&scaled))?;
        let fft = remainder.lattice_kernel(nx, ny, resolution);
        let long = remainder.long_wave_kernel(nx, ny);
        for (((k, l), r), g) in kernel.iter_mut().zip(&love).zip(&fft).zip(&long) {
            // closed_form_quadrant is per unit C / (2 pi).
            *k = cell * (l + compliance / (2.0 * PI) * *k + r + g);
        }
        if kernel.iter().any(|v| !v.is_finite()) {
            return Err(Error::invalid(
                "stack",
                format!("{} layers", self.stack.layers.len()),
                "a stack whose kernel is finite",
            ));
        }
        Ok(kernel)
    }
}

/// A top layer this many times thicker than the window's diagonal is its own
/// half-space plus a constant ([`thick_top_kernel`]): the closed-form long-wave
/// terms, of the scale of the stack's thickness, would cancel to rounding over the
/// window (a 1e15-thick layer under a window of 1e-1 lost seven digits).
const THICK_TOP: f64 = 1e4;

/// The kernel of a stack whose top layer is far thicker than the window (lengths in
/// cells): Love's kernel of the top material plus, on every offset, the constant
/// the layers' interfaces add, `(1 / 2 pi) int_0^inf C (A(k) - 1) dk` per unit cell
/// area. The difference varies on the scale of the top layer's thickness h1, so over
/// a window of diagonal W it is that constant to O((W / h1)^2) of itself, far below
/// rounding at `W < h1 / THICK_TOP`.
fn thick_top_kernel(
    scaled: &Stack,
    compliance: f64,
    cell: f64,
    nx: usize,
    ny: usize,
) -> Result<Vec<f64>> {
    let top = scaled.top_material();
    let h1 = scaled.layers[0].thickness;
    let mut solver = LayeredSolver::new(scaled)?;
    // In t = k h1, `A - 1` decays like e^{-2 t} (the first reflection): panels of
    // 0.25 up to t = 40 leave below 1e-30; near t = 0 a rigid base's `A ~ t` and a
    // half-space's finite `A(0)` are both smooth.
    let rule = GaussLegendre::new(8);
    let mut integral = 0.0;
    for panel in 0..160 {
        let lo = 0.25 * panel as f64;
        integral += rule.integrate(lo, lo + 0.25, |t| solver.surface_factor(t / h1) - 1.0);
    }
    let constant = compliance * integral / (2.0 * PI * h1);
    let love = homogeneous_surface_kernel_quadrant(top, 1.0, nx, ny);
    Ok(love.iter().map(|l| cell * (l + constant)).collect())
}

/// The long-wave terms `c0 e^{-kd} + beta k d e^{-kd}` (module doc), lengths in cells.
#[derive(Debug, Clone, Copy)]
pub(super) struct LongWaveSplit {
    pub(super) c0: f64,
    pub(super) beta: f64,
    pub(super) d: f64,
}

impl LongWaveSplit {
    pub(super) fn new(stack: &Stack) -> Result<Self> {
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

    /// `int_0^u int_0^v (c0 / sqrt(x^2 + y^2 + d^2) + beta d^2 / (x^2 + y^2 +
    /// d^2)^{3/2}) dy dx`: the cell primitive of the point response of
    /// `C (c0 e^{-kd} / k + beta d e^{-kd})` per unit `C / 2 pi` (module doc).
    fn primitive(&self, u: f64, v: f64) -> f64 {
        let d = self.d;
        let r = (u * u + v * v + d * d).sqrt();
        let solid = if u == 0.0 || v == 0.0 {
            0.0
        } else {
            d * (u * v / (d * r)).atan()
        };
        let exponential = u * (v / (u * u + d * d).sqrt()).asinh()
            + v * (u / (v * v + d * d).sqrt()).asinh()
            - solid;
        self.c0 * exponential + self.beta * solid
    }

    /// `c0 e^{-kd} + beta k d e^{-kd}`.
    fn spectrum(&self, k: f64) -> f64 {
        let kd = k * self.d;
        (self.c0 + self.beta * kd) * (-kd).exp()
    }
}

/// The cell kernel (per unit `C / 2 pi`, cells of side 1) of the long-wave terms.
fn closed_form_quadrant(split: &LongWaveSplit, nx: usize, ny: usize) -> Vec<f64> {
    corner_sums(nx, ny, |u, v| split.primitive(u, v))
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
pub(super) struct Remainder {
    /// Panels in `k` on `[0, knee]`.
    near: ChebyshevPanels,
    /// Panels in `ln k` on `[knee, k_max]`.
    far: ChebyshevPanels,
    pub(super) knee: f64,
    /// Beyond it q is zero to rounding.
    pub(super) k_max: f64,
    /// Centre and width of the band edge (`Resolution::split`).
    pub(super) split: f64,
    pub(super) split_width: f64,
}

/// The factor on the remainder's first panel end for a stack's stiffness contrast
/// `E_min / E_max` over its layers and base: 1 above a contrast of 0.01 (where the
/// first panel at 0.05 / d was measured to hold to 1e-10), a hundred times the
/// contrast below.
fn knee_floor(stack: &Stack) -> f64 {
    let mut moduli: Vec<f64> = stack.layers.iter().map(|p| p.material.young).collect();
    if let Base::HalfSpace(m) = stack.base {
        moduli.push(m.young);
    }
    let lowest = moduli.iter().copied().fold(f64::INFINITY, f64::min);
    let highest = moduli.iter().copied().fold(0.0, f64::max);
    (100.0 * lowest / highest).min(1.0)
}

const DEGREE: usize = 16;
/// Panel width in `ln k`.
const LOG_PANEL: f64 = 0.1;

/// The long-wave band's quadrature panels, each given to `add(lo, hi)`: `[0, knee]`,
/// then geometric panels (ratio 1.25) up to `k_end`, each cut into pieces shorter
/// than `4 / reach` so that a panel's rule resolves the oscillation at the farthest
/// offset `reach` (0.64 of the shortest period of `J0(k r)` or `cos(k x)`).
pub(crate) fn long_wave_panels(knee: f64, k_end: f64, reach: f64, add: &mut impl FnMut(f64, f64)) {
    add(0.0, knee);
    let mut lo = knee;
    while lo < k_end {
        let hi = (lo * 1.25).min(k_end);
        let pieces = ((hi - lo) * reach / 4.0).ceil().max(1.0) as usize;
        let step = (hi - lo) / pieces as f64;
        for p in 0..pieces {
            let a = lo + p as f64 * step;
            add(a, a + step);
        }
        lo = hi;
    }
}

impl Remainder {
    pub(super) fn new(
        stack: &Stack,
        split: &LongWaveSplit,
        compliance: f64,
        resolution: Resolution,
        floor: f64,
    ) -> Result<Self> {
        let w = resolution.width;
        let centre = 5.6 * w;
        let k_max = centre + 5.6 * w;
        // Below the knee R / k is a smooth function of k (its scale is 1 / d at most,
        // or `floor` times that: a stiff layer on a much softer base restrains the
        // base's surface in-plane on the length E_layer / E_base times its own
        // thickness, a change of A at k far below 1 / d).
        let knee = (0.05 / split.d).min(0.05) * floor;
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
    pub(super) fn long_share(&self, k: f64) -> f64 {
        let (c, w) = (self.split, self.split_width);
        0.5 * (libm::erfc((k - c) / w) - libm::erfc((k + c) / w))
    }

    /// The lattice band's spectrum: `q (1 - W_1)`.
    pub(super) fn q_lattice(&self, k: f64) -> f64 {
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
        // Quadrature nodes and weighted integrand `(k, w W_1 q k / 2 pi)` good up to
        // the radius `r_hi`: k in [0, knee], then geometric panels (ratio 1.25) cut
        // below 4 / r_hi (0.64 of the Bessel function's shortest period).
        let nodes_up_to = |r_hi: f64| -> Vec<(f64, f64)> {
            let mut nodes = Vec::new();
            let mut add = |lo: f64, hi: f64| {
                let (half, mid) = (0.5 * (hi - lo), 0.5 * (hi + lo));
                for (x, w) in rule.nodes.iter().zip(&rule.weights) {
                    let k = mid + half * x;
                    let f = self.long_share(k) * self.q(k) * k / (2.0 * PI);
                    nodes.push((k, w * half * f));
                }
            };
            long_wave_panels(self.knee, k_end, r_hi, &mut add);
            nodes
        };
        let r_max = 2f64.sqrt() * (nx.max(ny) as f64 + 1.0);
        let panels = (r_max / 16.0).ceil() as usize;
        let width = r_max / panels as f64;
        let points = ChebyshevPanels::points(0.0, r_max, panels, DEGREE);
        // One node set per r panel, shared by its points.
        let values: Vec<f64> = points
            .par_chunks(DEGREE)
            .enumerate()
            .flat_map_iter(|(p, chunk)| {
                let nodes = nodes_up_to((p + 1) as f64 * width);
                chunk
                    .iter()
                    .map(|&r| nodes.iter().map(|(k, f)| f * libm::j0(k * r)).sum::<f64>())
                    .collect::<Vec<f64>>()
            })
            .collect();
        let g = ChebyshevPanels::from_values(0.0, r_max, panels, DEGREE, &values);
        let cell_rule = GaussLegendre::new(3);
        let offsets: Vec<(f64, f64)> = cell_rule
            .nodes
            .iter()
            .zip(&cell_rule.weights)
            .map(|(x, w)| (0.5 * x, 0.5 * w))
            .collect();
        // Even in di <-> dj: cells above the diagonal of the common square are
        // copied from below it.
        let below = |i: usize, j: usize| j > i && j < nx && i < ny;
        let mut kernel: Vec<f64> = (0..nx * ny)
            .into_par_iter()
            .map(|m| {
                let (i, j) = (m % nx, m / nx);
                if below(i, j) {
                    return 0.0;
                }
                let (x, y) = (i as f64, j as f64);
                let mut sum = 0.0;
                for (xa, wa) in &offsets {
                    for (yb, wb) in &offsets {
                        let r = ((x + xa).powi(2) + (y + yb).powi(2)).sqrt();
                        sum += wa * wb * g.eval(r);
                    }
                }
                sum
            })
            .collect();
        for j in 0..ny {
            for i in 0..nx {
                if below(i, j) {
                    kernel[j * nx + i] = kernel[i * nx + j];
                }
            }
        }
        kernel
    }

    pub(super) fn q(&self, k: f64) -> f64 {
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
        // Symmetric in kx <-> ky: computed on one triangle of nodes.
        let triangle: Vec<f64> = (0..nc * nc)
            .into_par_iter()
            .map(|m| {
                let (qx, qy) = (m % nc, m / nc);
                if qx <= qy {
                    self.aliases(node(qx), node(qy))
                } else {
                    0.0
                }
            })
            .collect();
        let values: Vec<f64> = (0..nc * nc)
            .map(|m| {
                let (qx, qy) = (m % nc, m / nc);
                triangle[qx.min(qy) + nc * qx.max(qy)]
            })
            .collect();
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
        let sincs: Vec<f64> = (0..=half).map(|a| sinc(a as f64 * step)).collect();
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
                    let sy = sincs[b];
                    for (a, z) in input.iter_mut().enumerate() {
                        let kx = a as f64 * step;
                        let alias: f64 = (0..nc)
                            .map(|jy| ty[jy] * partial[jy * (half + 1) + a])
                            .sum();
                        let direct = self.q_lattice((kx * kx + ky * ky).sqrt()) * sincs[a] * sy;
                        *z = Complex::new(direct + alias, 0.0);
                    }
                    c2r.process_with_scratch(input, output, scratch)
                        .expect("real spectrum of the right length");
                    output[..nx].to_vec()
                },
            )
            .collect();
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
pub(super) mod tests {
    use super::*;
    use crate::body::layered::BaseContact;
    use crate::case::Elastic;

    pub(in crate::body) fn elastic(young: f64, poisson: f64) -> Elastic {
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

    pub(in crate::body) fn ply(young: f64, poisson: f64, thickness: f64) -> Ply {
        Ply {
            material: elastic(young, poisson),
            thickness,
        }
    }

    /// Stacks of `count` layers alternating E = 1e3 (nu = 0.2) and 1e-3 (nu = 0.45),
    /// stiff or soft first, their thicknesses read cyclically from `thickness` from
    /// index `first`, for each `(count, first)` of `layouts`, on every base: the ends
    /// of the range the kernels' tests sweep.
    pub(in crate::body) fn alternating_stacks(
        thickness: &[f64; 8],
        layouts: &[(usize, usize)],
    ) -> Vec<Stack> {
        let mut stacks = Vec::new();
        for base in [
            Base::HalfSpace(elastic(1.0, 0.3)),
            Base::HalfSpace(elastic(1e-3, 0.45)),
            Base::HalfSpace(elastic(1e3, 0.2)),
            Base::Rigid(BaseContact::Bonded),
            Base::Rigid(BaseContact::Frictionless),
        ] {
            for &(count, first) in layouts {
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

    /// The kernel at `(x, y)` cells by direct quadrature of the Fourier integral in
    /// polar coordinates, cells of side 1, for each of `stacks`: Love's kernel of the
    /// top material plus `(C / 4 pi^2) int_0^inf (A(k) - 1) Psi(k) dk`, `Psi(k) =
    /// int_0^{2 pi} S cos(kx x) cos(ky y) dtheta` by the trapezoidal rule (periodic and
    /// smooth: it converges once the points outnumber the integrand's angular
    /// frequencies, k (x + y + 1)), `k` by 16-point Gauss-Legendre panels (geometric
    /// near 0, width 1/2 above) up to 25 over the thinnest top layer. `Psi` depends on
    /// the offset alone, so the stacks share it (it is nine tenths of the work).
    fn polar_quadrature(stacks: &[Stack], x: f64, y: f64) -> Vec<f64> {
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
        let mut solvers: Vec<LayeredSolver> = stacks
            .iter()
            .map(|stack| LayeredSolver::new(stack).unwrap())
            .collect();
        let k_end = stacks
            .iter()
            .map(|stack| 25.0 / stack.layers[0].thickness)
            .fold(0.0, f64::max);
        let rule = GaussLegendre::new(16);
        // Psi oscillates in k with periods down to 2 pi / (x + y + 1).
        let width = (8.0 / (x + y + 1.0)).min(0.5);
        let mut edges = vec![0.0, 1e-6];
        while *edges.last().unwrap() < k_end {
            let last = *edges.last().unwrap();
            edges.push((last * 1.3).min(last + width).min(k_end));
        }
        let mut integrals = vec![0.0; stacks.len()];
        for e in edges.windows(2) {
            let (half, mid) = (0.5 * (e[1] - e[0]), 0.5 * (e[1] + e[0]));
            for (node, weight) in rule.nodes.iter().zip(&rule.weights) {
                let k = mid + half * node;
                let shared = weight * half * psi(k);
                for (integral, solver) in integrals.iter_mut().zip(&mut solvers) {
                    *integral += (solver.surface_factor(k) - 1.0) * shared;
                }
            }
        }
        stacks
            .iter()
            .zip(&integrals)
            .map(|(stack, integral)| {
                let top = stack.top_material();
                let c = 2.0 * (1.0 - top.poisson * top.poisson) / top.young;
                let love =
                    crate::body::homogeneous::love_rectangle_displacement(top, 0.5, 0.5, x, y);
                love + c / (4.0 * PI * PI) * integral
            })
            .collect()
    }

    /// The largest difference between each stack's kernel on an `n x n` window and
    /// [`polar_quadrature`] at `offsets`, over the kernel's peak; asserts each is
    /// below `tolerance`, naming the stack's base and the offset (`label` says which
    /// group).
    fn worst_against_polar_quadrature(
        stacks: &[Stack],
        n: usize,
        offsets: &[(usize, usize)],
        tolerance: f64,
        label: &str,
    ) -> f64 {
        let kernels: Vec<Vec<f64>> = stacks
            .iter()
            .map(|stack| {
                let body = StackBody {
                    stack: stack.clone(),
                };
                body.surface_kernel_quadrant(1.0, n, n).unwrap()
            })
            .collect();
        let mut worst: f64 = 0.0;
        for &(i, j) in offsets {
            let direct = polar_quadrature(stacks, i as f64, j as f64);
            for ((stack, kernel), direct) in stacks.iter().zip(&kernels).zip(direct) {
                let e = (kernel[j * n + i] - direct).abs() / kernel[0];
                worst = worst.max(e);
                assert!(
                    e < tolerance,
                    "{label}, {:?} ({i}, {j}): {} vs {direct}, {e:.2e} of the peak",
                    stack.base,
                    kernel[j * n + i]
                );
            }
        }
        worst
    }

    #[test]
    fn agrees_with_direct_polar_quadrature() {
        let mut worst_all: f64 = 0.0;
        for t in [0.05, 20.0] {
            let mut stacks = Vec::new();
            for base in [
                Base::HalfSpace(elastic(1.0, 0.3)),
                Base::Rigid(BaseContact::Bonded),
                Base::Rigid(BaseContact::Frictionless),
            ] {
                for layers in [
                    vec![ply(30.0, 0.25, t), ply(1.0 / 30.0, 0.45, t)],
                    vec![ply(1.0 / 30.0, 0.45, t), ply(30.0, 0.25, t)],
                ] {
                    stacks.push(Stack { layers, base });
                }
            }
            let offsets = [(0, 0), (1, 0), (2, 1), (5, 3)];
            let worst =
                worst_against_polar_quadrature(&stacks, 8, &offsets, 1e-9, &format!("t = {t}"));
            worst_all = worst_all.max(worst);
        }
        eprintln!("stacks vs direct polar quadrature: worst {worst_all:.1e} of the peak");
    }

    /// Stacks at the ends of the range: 1 to 8 layers 1e-3 to 1e3 cells thick, E
    /// ratios 1e-3 to 1e3, every base.
    fn extreme_stacks() -> Vec<Stack> {
        alternating_stacks(
            &[1e-3, 1e3, 0.1, 10.0, 1.0, 1e2, 0.01, 1e3],
            &[(1, 0), (1, 1), (2, 2), (3, 0), (8, 0), (4, 4)],
        )
    }

    fn one_layer(coating: Elastic, thickness: f64, substrate: Elastic) -> StackBody {
        StackBody {
            stack: Stack {
                layers: vec![Ply {
                    material: coating,
                    thickness,
                }],
                base: Base::HalfSpace(substrate),
            },
        }
    }

    #[test]
    fn thick_contrasting_stacks_agree_with_direct_quadrature_far_out() {
        // Four layers 1, 100, 0.01 and 1000 cells thick, E alternating 1e3 and 1e-3,
        // on each base; a 256 x 256 window read near and far from the load.
        let layers = vec![
            ply(1e3, 0.2, 1.0),
            ply(1e-3, 0.45, 100.0),
            ply(1e3, 0.2, 0.01),
            ply(1e-3, 0.45, 1000.0),
        ];
        let stacks: Vec<Stack> = [
            Base::HalfSpace(elastic(1.0, 0.3)),
            Base::Rigid(BaseContact::Bonded),
            Base::Rigid(BaseContact::Frictionless),
        ]
        .into_iter()
        .map(|base| Stack {
            layers: layers.clone(),
            base,
        })
        .collect();
        let offsets = [(0, 0), (3, 1), (40, 7), (255, 200)];
        let worst_all = worst_against_polar_quadrature(&stacks, 256, &offsets, 1e-8, "thick");
        eprintln!("thick stacks vs direct quadrature: worst {worst_all:.1e} of the peak");
    }

    /// A stiff layer on a far softer half-space restrains the base's surface over
    /// E_layer / E_base times its thickness, so A(k) changes at k far below 1 / d:
    /// the remainder's table must reach there (it missed it by 2e-6 of the peak
    /// when its first panel ended at 0.05 / d whatever the contrast).
    #[test]
    fn a_stiff_layer_on_a_far_softer_base_agrees_with_direct_quadrature() {
        let mut worst: f64 = 0.0;
        for (top, base, thickness) in [(1e3, 1e-3, 0.1), (1e2, 1e-2, 1.0)] {
            let stack = Stack {
                layers: vec![ply(top, 0.3, thickness)],
                base: Base::HalfSpace(elastic(base, 0.3)),
            };
            let offsets = [(0, 0), (1, 0), (5, 3), (31, 31)];
            let label = format!("E {top} on {base}");
            let e = worst_against_polar_quadrature(&[stack], 32, &offsets, 1e-8, &label);
            worst = worst.max(e);
        }
        eprintln!("stiff on soft vs direct quadrature: worst {worst:.1e} of the peak");
    }

    #[test]
    fn poisson_ratio_extremes_agree_with_direct_quadrature() {
        // Nearly incompressible and auxetic layers, where the rigid-base slopes and
        // the membrane terms are extreme.
        let stacks: Vec<Stack> = [
            Base::HalfSpace(elastic(1.0, 0.499)),
            Base::Rigid(BaseContact::Bonded),
            Base::Rigid(BaseContact::Frictionless),
        ]
        .into_iter()
        .map(|base| Stack {
            layers: vec![ply(3.0, 0.499, 0.7), ply(0.5, -0.8, 2.0)],
            base,
        })
        .collect();
        let offsets = [(0, 0), (1, 0), (4, 3)];
        let worst_all = worst_against_polar_quadrature(&stacks, 8, &offsets, 1e-9, "Poisson");
        eprintln!("Poisson extremes vs direct quadrature: worst {worst_all:.1e} of the peak");
    }

    #[test]
    fn kernel_scales_with_the_cell_and_mirrors_across_the_diagonal() {
        // Cell 0.37 with the thickness scaled alike is 0.37 times the kernel of cell
        // 1 (the normalisation by the cell inside), and a 256 x 96 window is the
        // mirror of 96 x 256 (Bessel arguments and periodic images of the long-wave
        // band at larger r; the di <-> dj mirror on a non-square quadrant).
        let (coating, substrate) = (elastic(3.0, 0.3), elastic(1.0, 0.25));
        let wide = one_layer(coating, 0.37 * 5.0, substrate)
            .surface_kernel_quadrant(0.37, 256, 96)
            .unwrap();
        let unit = one_layer(coating, 5.0, substrate)
            .surface_kernel_quadrant(1.0, 256, 96)
            .unwrap();
        let scaled: Vec<f64> = unit.iter().map(|v| 0.37 * v).collect();
        let e = worst(&wide, &scaled);
        eprintln!("cell 0.37 against 0.37 x cell 1: {e:.1e} of the peak");
        assert!(e < 1e-12, "{e:.1e}");
        let tall = one_layer(coating, 0.37 * 5.0, substrate)
            .surface_kernel_quadrant(0.37, 96, 256)
            .unwrap();
        let mirrored: Vec<f64> = (0..96 * 256)
            .map(|n| {
                let (di, dj) = (n % 256, n / 256);
                tall[di * 96 + dj]
            })
            .collect();
        let e = worst(&wide, &mirrored);
        eprintln!("256 x 96 against the mirrored 96 x 256: {e:.1e} of the peak");
        assert!(e < 1e-12, "{e:.1e}");
    }

    #[test]
    fn a_top_layer_far_thicker_than_the_window_is_its_half_space_plus_a_constant() {
        // The general expansion and the thick-top limit on the same window as the
        // top layer grows past it: their difference falls like (W / h1)^3 (the
        // first term the constant leaves out), and each is used on its side of
        // THICK_TOP; both bases, a stack of two layers.
        let (n, diagonal) = (16usize, (16.5f64).hypot(16.5));
        for base in [
            Base::HalfSpace(elastic(1.0, 0.3)),
            Base::Rigid(BaseContact::Bonded),
            Base::Rigid(BaseContact::Frictionless),
        ] {
            let mut previous = f64::INFINITY;
            for ratio in [30.0, 100.0, 300.0] {
                let h1 = ratio * diagonal;
                let stack = Stack {
                    layers: vec![
                        Ply {
                            material: elastic(3.0, 0.25),
                            thickness: h1,
                        },
                        Ply {
                            material: elastic(0.5, 0.4),
                            thickness: 2.0 * h1,
                        },
                    ],
                    base,
                };
                let general = StackBody {
                    stack: stack.clone(),
                }
                .surface_kernel_quadrant(1.0, n, n)
                .unwrap();
                let top = stack.top_material();
                let compliance = 2.0 * (1.0 - top.poisson * top.poisson) / top.young;
                let thick = thick_top_kernel(&stack, compliance, 1.0, n, n).unwrap();
                let e = worst(&thick, &general);
                eprintln!("{base:?}, h1 = {ratio} W: {e:.1e} of the peak");
                assert!(e < 2.0 / ratio.powi(3), "{base:?}, h1 = {ratio} W: {e:.1e}");
                assert!(e < previous);
                previous = e;
            }
        }
    }

    #[test]
    fn identical_layers_are_the_homogeneous_half_space() {
        // A = 1 exactly up to rounding, c0 = beta = 0: Love's kernel by construction.
        let m = elastic(2.0, 0.3);
        let body = StackBody {
            stack: Stack {
                layers: vec![
                    ply(2.0, 0.3, 0.01),
                    ply(2.0, 0.3, 3.0),
                    ply(2.0, 0.3, 500.0),
                ],
                base: Base::HalfSpace(m),
            },
        };
        let kernel = body.surface_kernel_quadrant(0.5, 48, 32).unwrap();
        let love = homogeneous_surface_kernel_quadrant(m, 0.5, 48, 32);
        let e = worst(&kernel, &love);
        assert!(e < 1e-12, "{e:.1e}");
        // No layers at all: the base half-space.
        let bare = StackBody {
            stack: Stack {
                layers: vec![],
                base: Base::HalfSpace(m),
            },
        };
        let kernel = bare.surface_kernel_quadrant(0.5, 48, 32).unwrap();
        assert!(worst(&kernel, &love) < 1e-12);
    }

    /// `(C / 2 pi) int_0^inf (A(k) - 1) dk` (cells of side 1): what a base far below
    /// adds to every cell of a window much narrower than the top layer is thick (the
    /// point response `(C / 2 pi) int A J0(k r) dk` with `J0 = 1` where `A != 1`).
    fn far_base_offset(stack: &Stack) -> f64 {
        let top = stack.top_material();
        let c = 2.0 * (1.0 - top.poisson * top.poisson) / top.young;
        let mut solver = LayeredSolver::new(stack).unwrap();
        let rule = GaussLegendre::new(16);
        let t = stack.layers[0].thickness;
        let mut edges = vec![0.0, 1e-6 / t];
        while *edges.last().unwrap() < 40.0 / t {
            let last = *edges.last().unwrap();
            edges.push(last * 1.3);
        }
        let integral: f64 = edges
            .windows(2)
            .map(|e| rule.integrate(e[0], e[1], |k| solver.surface_factor(k) - 1.0))
            .sum();
        c / (2.0 * PI) * integral
    }

    #[test]
    fn a_very_thick_top_layer_is_its_own_half_space_near_the_load() {
        // 1e3 cells of the top material: near the load, Love's kernel of the top
        // material plus the uniform displacement the distant base adds.
        let top = elastic(5.0, 0.35);
        let love = homogeneous_surface_kernel_quadrant(top, 1.0, 8, 8);
        for base in [
            Base::HalfSpace(elastic(1.0, 0.3)),
            Base::HalfSpace(elastic(1e3, 0.3)),
            Base::Rigid(BaseContact::Bonded),
            Base::Rigid(BaseContact::Frictionless),
        ] {
            let stack = Stack {
                layers: vec![Ply {
                    material: top,
                    thickness: 1e3,
                }],
                base,
            };
            let offset = far_base_offset(&stack);
            let kernel = StackBody { stack }
                .surface_kernel_quadrant(1.0, 8, 8)
                .unwrap();
            let shifted: Vec<f64> = love.iter().map(|v| v + offset).collect();
            let e = worst(&kernel, &shifted);
            assert!(e < 1e-4, "{base:?}: {e:.1e}");
            assert!(offset.abs() < 2e-3 * love[0], "{base:?}: offset {offset:e}");
        }
    }

    #[test]
    fn a_very_thin_layer_leaves_the_half_space_kernel() {
        // Its effect falls linearly with its thickness and is below 1e-3 of the peak
        // at 1e-4 cells for moderate contrasts.
        let base = elastic(1.0, 0.3);
        let half_space = homogeneous_surface_kernel_quadrant(base, 1.0, 16, 16);
        let peak_change = |ratio: f64, t: f64| {
            let kernel = one_layer(elastic(ratio, 0.25), t, base)
                .surface_kernel_quadrant(1.0, 16, 16)
                .unwrap();
            (kernel[0] - half_space[0]) / half_space[0]
        };
        for ratio in [30.0, 10.0, 0.1] {
            let (coarse, fine) = (peak_change(ratio, 1e-3), peak_change(ratio, 1e-4));
            assert!(fine.abs() < 1e-3, "E ratio {ratio}: {fine:.1e}");
            assert!(
                (coarse / fine - 10.0).abs() < 1.0,
                "E ratio {ratio}: {coarse:.2e} at 1e-3, {fine:.2e} at 1e-4"
            );
        }
        // A much softer film is a Winkler foundation: the loaded cell sinks by an
        // extra t / M (M the film's constrained modulus), its neighbours do not.
        for t in [1e-3, 1e-4] {
            let film = elastic(1e-3, 0.25);
            let kernel = one_layer(film, t, base)
                .surface_kernel_quadrant(1.0, 16, 16)
                .unwrap();
            let constrained = film.young * 0.75 / (1.25 * 0.5);
            let extra = kernel[0] - half_space[0];
            let e = (extra - t / constrained).abs() / (t / constrained);
            assert!(
                e < 2e-3,
                "t = {t}: extra {extra:e} vs {:e}",
                t / constrained
            );
            for m in 1..kernel.len() {
                let d = (kernel[m] - half_space[m]).abs();
                assert!(d < 2e-2 * extra, "t = {t}, cell {m}: {d:e} vs {extra:e}");
            }
            eprintln!("Winkler film t = {t}: extra sink within {e:.1e} of t / M");
        }
    }

    #[test]
    fn closed_form_primitives_integrate_their_point_responses() {
        // Midpoint rule over [0.2, 1.3] x [0.4, 0.9] against the corner sums.
        let (u0, u1, v0, v1) = (0.2, 1.3, 0.4, 0.9);
        for d in [0.05, 1.0, 30.0] {
            for (c0, beta) in [(1.0, 0.0), (0.0, 1.0)] {
                let split = LongWaveSplit { c0, beta, d };
                let f = |u: f64, v: f64| split.primitive(u, v);
                let exact = f(u1, v1) - f(u1, v0) - f(u0, v1) + f(u0, v0);
                let n = 800;
                let mut sum = 0.0;
                for i in 0..n {
                    for j in 0..n {
                        let x = u0 + (i as f64 + 0.5) * (u1 - u0) / n as f64;
                        let y = v0 + (j as f64 + 0.5) * (v1 - v0) / n as f64;
                        let r2 = x * x + y * y + d * d;
                        sum += c0 / r2.sqrt() + beta * d * d / (r2 * r2.sqrt());
                    }
                }
                sum *= (u1 - u0) * (v1 - v0) / (n * n) as f64;
                assert!(
                    (sum - exact).abs() < 1e-6 * exact.abs(),
                    "d = {d}, c0 = {c0}: {sum} vs {exact}"
                );
            }
        }
    }

    #[test]
    fn extreme_stacks_converge_under_finer_resolution() {
        let fine = Resolution {
            width: 28.0,
            padding: 4,
            nodes: 60,
            split: 0.15,
            clearance: 1280,
        };
        let mut all: f64 = 0.0;
        for stack in extreme_stacks().into_iter().step_by(4) {
            let body = StackBody { stack };
            let n = 40;
            let a = body.surface_kernel_quadrant(1.0, n, n).unwrap();
            let b = body.kernel_with(1.0, n, n, fine).unwrap();
            let e = worst(&a, &b);
            all = all.max(e);
            assert!(e < 1e-8, "{:?}: {e:.1e}", body.stack);
        }
        eprintln!("extreme stacks, default vs fine resolution: worst {all:.1e}");
    }

    #[test]
    fn rejects_bad_input() {
        let body = one_layer(elastic(1.0, 0.3), 1.0, elastic(2.0, 0.3));
        assert!(body.surface_kernel_quadrant(0.0, 4, 4).is_err());
        assert!(body.surface_kernel_quadrant(1.0, 0, 4).is_err());
        let bad = one_layer(elastic(1.0, 0.3), -1.0, elastic(2.0, 0.3));
        assert!(bad.surface_kernel_quadrant(1.0, 4, 4).is_err());
        assert_eq!(body.interface_depths(), vec![1.0]);
        assert_eq!(
            body.softest_modulus(),
            elastic(1.0, 0.3).plane_strain_modulus()
        );
    }
}
