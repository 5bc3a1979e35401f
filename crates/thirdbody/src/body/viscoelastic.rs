//! Linear viscoelastic half-space in steady sliding: the normal surface influence
//! kernel per square cell, `K(X, Y) = J_g L(X, Y) + sum_k J_k (1 / l_k)
//! int_0^inf exp(-u / l_k) L(X + u, Y) du` with `l_k = V tau_k`, for a body whose
//! plane-strain creep compliance is the Prony series
//! `J(t) = J_g + sum_k J_k (1 - exp(-t / tau_k))` and whose Poisson ratio is
//! constant. `L` is Love's cell kernel per unit plane-strain compliance
//! ([`super::homogeneous::rectangle_inverse_distance_integral`] divided by pi), so
//! an elastic body of compliance `J = (1 - nu^2) / E` has the kernel `J L`. The
//! kernel comes from the hereditary integral of the correspondence principle
//! written along the path of a material point (derivation below); it is accurate to
//! a few 1e-15 of its peak for every creep length (tested against brute-force
//! quadrature from 1e-6 cell to 9e6 cells, and at the limits 1e-90 and 1e90 cells).
//!
//! # Derivation
//!
//! Frame fixed to the slider, x the sliding direction (the slider moves in +x over
//! the body, so body material flows through the contact in -x), z into the body,
//! `w > 0` into the body, `p >= 0` compressive. For an elastic half-space of
//! plane-strain compliance `J` the normal surface displacement under a frictionless
//! normal pressure is `J W` with `W(x, y) = (1 / pi) int int p(xi, eta) / r` (Love;
//! Johnson, Contact Mechanics, eq. 3.20). With a constant Poisson ratio the
//! correspondence principle replaces the product by a Stieltjes convolution in
//! time at each material point (small strains: the displacement of the material
//! point now under x is the displacement at x):
//! `w(t) = int_{-inf}^t J(t - s) dW_s / ds ds`, where `W_s` is `W` of the pressure
//! the point felt at time `s`. In steady sliding at speed `V > 0` the pressure is
//! fixed in the slider's frame and a material point now at x was at `x + u` a time
//! `u / V` ago (it moves toward -x), so `W_{t - sigma} = W(x + V sigma, y)`.
//! Integrating by parts (the boundary term far in the past vanishes, `W -> 0` far
//! upstream, and `J(0) = J_g`):
//! `w(x, y) = J_g W(x, y) + int_0^inf J'(sigma) W(x + V sigma, y) dsigma`, and with
//! `J'(sigma) = sum_k (J_k / tau_k) exp(-sigma / tau_k)` and `u = V sigma`:
//! `w(x, y) = J_g W(x, y) + sum_k (J_k / l_k) int_0^inf exp(-u / l_k) W(x + u, y) du`,
//! `l_k = V tau_k` the creep length of branch k. For a pressure uniform on cells
//! this is `w(x, y) = sum_cells p K(x - x', y - y')` with the kernel `K` above.
//! Sign check: the branch term at a field point reads `L` at `X + u >= X`, i.e.
//! the load as it was upstream of the field point; a point downstream of the
//! load (`X < 0`) keeps the creep it gathered while passing under it, so the
//! displacement trails downstream, toward -x, and `K` is even in `Y` but not in
//! `X`. Limits: `V -> inf` (`l_k -> inf`, the branch weight `(1 / l) int_0^inf
//! exp(-u / l) L du ~ ln(l) / l -> 0`) gives the glassy elastic kernel `J_g L`;
//! `V -> 0` (`l_k -> 0`, the weight tends to a Dirac mass at `u = 0`) gives the
//! relaxed one `(J_g + sum_k J_k) L`.
//!
//! # Conventions of this module
//!
//! * `J_g = 0` is allowed (a body without instantaneous compliance: the kernel is
//!   then bounded and smooth instead of log-sloped at the cell edges) as long as
//!   the kernel does not vanish: at least one compliance that takes part at the
//!   given speed must be positive.
//! * `tau_k = +inf` is a frozen branch: it never creeps, contributes nothing at any
//!   speed (also at `V = 0`, where `V tau` would be undefined) and does not count as
//!   a positive compliance.
//! * `V = +inf` is allowed (glassy kernel), `V = 0` too (relaxed kernel). Creep
//!   lengths below 1e-100 cells are treated as relaxed and above 1e100 cells as
//!   frozen: the neglected terms are below 1e-97 of the kernel.
//!
//! # Numerical method
//!
//! Work in cell units (`h = 1`, `lambda = l / h`, `L(X, Y) = h L_1(X / h, Y / h)`)
//! on one row `Y = dj` at a time. The branch term at integer `X`,
//! `M(X) = (1 / lambda) int_X^inf exp(-(s - X) / lambda) L_1(s) ds`, obeys over any
//! panel `[a, b]` the exact recursion `M(a) = S(a, b) + exp(-(b - a) / lambda) M(b)`
//! with `S(a, b) = (1 / lambda) int_a^b exp(-(s - a) / lambda) L_1(s) ds`, which is
//! stable (the factor is at most 1). The panels are the unit intervals between
//! cell centres, split at the cell edges `X = -1/2, 1/2` of the loaded cell, where
//! `L_1` has log-singular slopes on the row `dj = 0` and nearby complex
//! singularities on the row `dj = 1`. On each panel `L_1` is interpolated at 24
//! Gauss–Legendre points and `S` integrated exactly against the interpolant
//! (product integration): the 24 weights `(1 / lambda) int exp(-tau / lambda)
//! l_m(tau) dtau` of the Lagrange basis depend only on lambda, so they are computed
//! once per branch (composite Gauss–Legendre on pieces no longer than `2 lambda`,
//! truncated at `46 lambda`) and every panel costs one dot product for any lambda:
//! for `lambda << 1` they tend to the basis values at the panel's start (no
//! cancellation), for `lambda >> 1` to the plain Gauss weights over lambda. On the
//! four half-panels touching the edges on the row `dj = 0` the singular part
//! `(2 / pi) ((X - 1/2) ln|X - 1/2| - (X + 1/2) ln|X + 1/2|)` is subtracted before
//! interpolation and its weighted integral added from two per-branch scalars
//! computed on geometrically graded pieces. The values of `L_1` at the nodes come
//! from Love's primitive tabulated once per kernel at the shared abscissae
//! (`X +- 1/2` of every node is a node abscissa of a neighbouring panel, and the
//! primitive is odd in both arguments), so the cost is one primitive per node and
//! row, shared by all branches. The recursion starts at
//! `X_t = max(nx - 1, ny, 4)` from the tail `M(X_t)`: with `s = X_t / X`,
//! `X L_1(X, Y) = g(s)` is analytic on `0 <= s <= 1` (its nearest singularity is at
//! `|s| >~ 1` since `X_t >= Y`), so it is interpolated by 40 Chebyshev polynomials
//! in s (values by a 12 x 12 Gauss–Legendre rule over the cell, free of the
//! primitive's cancellation far away) and `M(X_t) = (1 / lambda) sum_k c_k mu_k` with
//! `mu_k = int_0^inf exp(-v) T_k(2 beta / (beta + v) - 1) dv / (beta + v)`,
//! `beta = X_t / lambda`, per branch on pieces graded geometrically in `beta + v`
//! (this covers the log-growing range `lambda >> X_t` in closed quadrature, the
//! exponential-integral behaviour `e^beta E_1(beta)` of `mu_0`, without any
//! truncation of the window).

use super::homogeneous::{
    half_primitive, homogeneous_surface_kernel_quadrant, rectangle_inverse_distance_integral,
};
use super::quadrature::GaussLegendre;
use super::{BodyModel, SurfaceKernel};
use crate::case::Elastic;
use crate::error::{Error, Result};
use crate::grid::Grid;
use crate::provenance::{self, Reference};
use crate::stress::{HomogeneousStressKernels, Side, StressKernels};
use rayon::prelude::*;
use std::f64::consts::PI;

/// Gauss–Legendre points per panel of the product integration.
const PANEL_NODES: usize = 24;
/// Chebyshev terms of the tail.
const TAIL_TERMS: usize = 40;
/// Gauss–Legendre points of the per-branch weight integrals.
const RULE_POINTS: usize = 32;
/// Gauss–Legendre points per direction of the far cell integral of the tail.
const FAR_POINTS: usize = 12;
/// Exponential weights are cut where `exp(-t) < 1.1e-20`.
const EXP_CUTOFF: f64 = 46.0;
/// Creep lengths (in cells) below this are relaxed, above its inverse frozen.
const LAMBDA_FLOOR: f64 = 1e-100;

/// One Kelvin–Voigt branch of the creep compliance:
/// `compliance * (1 - exp(-t / retardation_time))`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CreepBranch {
    /// Its compliance `J_k >= 0` (plane-strain, the units of `1 / E*`).
    pub compliance: f64,
    /// Its retardation time `tau_k > 0`; `+inf` is a frozen branch.
    pub retardation_time: f64,
}

/// The plane-strain creep compliance of a linear viscoelastic body as a Prony
/// series, `J(t) = glassy + sum_k J_k (1 - exp(-t / tau_k))`; an elastic body of
/// Young's modulus E and Poisson ratio nu is `glassy = (1 - nu^2) / E` without
/// branches.
#[derive(Debug, Clone, PartialEq)]
pub struct CreepSeries {
    /// The glassy (instantaneous) compliance `J_g >= 0`.
    pub glassy: f64,
    /// The retarded branches.
    pub branches: Vec<CreepBranch>,
}

fn invalid(field: impl Into<String>, value: f64, allowed: &str) -> Error {
    Error::InvalidValue {
        field: field.into(),
        value: value.to_string(),
        allowed: allowed.to_string(),
    }
}

impl CreepSeries {
    /// Checks every field; the error names the first bad one.
    pub fn validate(&self) -> Result<()> {
        if !(self.glassy.is_finite() && self.glassy >= 0.0) {
            return Err(invalid(
                "creep.glassy",
                self.glassy,
                "a finite compliance >= 0",
            ));
        }
        for (k, b) in self.branches.iter().enumerate() {
            if !(b.compliance.is_finite() && b.compliance >= 0.0) {
                return Err(invalid(
                    format!("creep.branches[{k}].compliance"),
                    b.compliance,
                    "a finite compliance >= 0",
                ));
            }
            if b.retardation_time.is_nan() || b.retardation_time <= 0.0 {
                return Err(invalid(
                    format!("creep.branches[{k}].retardation_time"),
                    b.retardation_time,
                    "a time > 0 (+inf for a frozen branch)",
                ));
            }
        }
        let relaxed = self.relaxed();
        if !relaxed.is_finite() {
            return Err(invalid(
                "creep.branches",
                relaxed,
                "a finite total compliance",
            ));
        }
        if relaxed == 0.0 {
            return Err(invalid(
                "creep",
                relaxed,
                "at least one compliance > 0 (glassy or of a branch with a finite time)",
            ));
        }
        Ok(())
    }

    /// The relaxed compliance `J_g + sum_k J_k` over the branches that creep
    /// (finite retardation time).
    pub fn relaxed(&self) -> f64 {
        self.glassy
            + self
                .branches
                .iter()
                .filter(|b| b.retardation_time.is_finite())
                .map(|b| b.compliance)
                .sum::<f64>()
    }
}

/// A linear viscoelastic half-space as the solvers see it: its plane-strain creep
/// compliance and its constant Poisson ratio (built from a case's
/// [`super::ViscoelasticHalfSpace`]).
#[derive(Debug, Clone, PartialEq)]
pub struct ViscoelasticBody {
    /// The plane-strain creep compliance `J(t) = (1 - nu^2) D(t)`.
    pub creep: CreepSeries,
    /// Poisson's ratio (only the stresses use it).
    pub poisson: f64,
    /// The works its rheology comes from.
    pub references: Vec<Reference>,
}

impl ViscoelasticBody {
    /// The compliances that creep at `velocity` on cells of side `cell`: whether
    /// any branch's creep length lies strictly between the relaxed and frozen
    /// limits of [`steady_sliding_kernel`] (otherwise the kernel is even).
    fn creeps_at(&self, velocity: f64, cell: f64) -> bool {
        self.creep.branches.iter().any(|b| {
            let lambda = velocity * b.retardation_time / cell;
            b.compliance > 0.0
                && b.retardation_time.is_finite()
                && (LAMBDA_FLOOR..=1.0 / LAMBDA_FLOOR).contains(&lambda)
        })
    }
}

impl BodyModel for ViscoelasticBody {
    fn surface_kernel(
        &self,
        cell: f64,
        nx: usize,
        ny: usize,
        velocity: f64,
    ) -> Result<SurfaceKernel> {
        let half = steady_sliding_kernel(&self.creep, cell, nx, ny, velocity)?;
        if self.creeps_at(velocity, cell) {
            return Ok(SurfaceKernel::EvenInY { half, nx });
        }
        // No branch creeps at this speed: the kernel is the elastic one of the
        // glassy or relaxed compliance, even in x.
        let width = 2 * nx - 1;
        let quadrant = (0..ny)
            .flat_map(|dj| (0..nx).map(move |di| (dj, di)))
            .map(|(dj, di)| half[dj * width + di + nx - 1])
            .collect();
        Ok(SurfaceKernel::Even { quadrant, nx })
    }

    fn line_kernel(
        &self,
        _cell: f64,
        _nx: usize,
        _velocity: f64,
        _reference: f64,
    ) -> Result<SurfaceKernel> {
        Err(crate::error::Error::invalid(
            "slider.shape",
            "a line contact",
            "a point contact on a viscoelastic body (its line kernel is not built yet)",
        ))
    }

    fn kernel_depends_on_velocity(&self) -> bool {
        true
    }

    fn kernel_is_even(&self, velocity: f64) -> bool {
        // Any branch with compliance and a finite time creeps at a finite speed
        // > 0. (The kernel treats creep lengths beyond 1e-100 and 1e100 cells as
        // relaxed or frozen, and is then even: saying "not even" there only costs
        // Newton where conjugate gradients would do.)
        !(self.creep.branches.iter().any(|b| {
            b.compliance > 0.0
                && b.retardation_time.is_finite()
                && velocity > 0.0
                && velocity.is_finite()
        }))
    }

    fn dissipated_force(&self, grid: &Grid, pressure: &[f64], velocity: f64) -> Result<f64> {
        super::hysteresis::dissipated_force(
            &self.creep,
            velocity,
            pressure,
            grid.nx,
            grid.ny,
            grid.cell,
        )
    }

    fn stress_kernels(&self, _interface_side: Side) -> Box<dyn StressKernels> {
        // With a constant Poisson ratio the stresses under given surface tractions
        // do not depend on the modulus (the correspondence principle applied to
        // Boussinesq's solution): Love's kernels of any modulus apply.
        Box::new(HomogeneousStressKernels {
            material: Elastic {
                young: 1.0,
                poisson: self.poisson,
            },
        })
    }

    fn interface_depths(&self) -> Vec<f64> {
        Vec::new()
    }

    fn softest_modulus(&self) -> f64 {
        1.0 / self.creep.relaxed()
    }

    fn surface_compliance(
        &self,
        wavenumber_x: f64,
        velocity: f64,
    ) -> Option<realfft::num_complex::Complex<f64>> {
        // A branch creeping over the length l = V tau answers the wave with the
        // factor 1 / (1 - i k_x l) (the exponential memory of the kernel's
        // derivation, transformed); a frozen one (tau = inf) not at all, and at
        // V = 0 it is relaxed.
        let mut compliance = realfft::num_complex::Complex::from(self.creep.glassy);
        for b in &self.creep.branches {
            if !b.retardation_time.is_finite() || b.compliance == 0.0 {
                continue;
            }
            let kl = wavenumber_x * velocity * b.retardation_time;
            // V = inf (any k_x, as the kernel takes it) leaves the glassy part.
            if kl.is_finite() {
                compliance += b.compliance / realfft::num_complex::Complex::new(1.0, -kl);
            }
        }
        Some(compliance)
    }

    fn references(&self) -> Vec<Reference> {
        let mut works = vec![Reference::new(
            provenance::LOVE,
            "the viscoelastic body's elastic cell kernel and its stresses (uniform \
             pressure on a rectangle)",
        )];
        works.extend(self.references.iter().cloned());
        works
    }
}

/// The steady-sliding influence kernel of a viscoelastic half-space on square
/// cells of side `cell`: `[dj * (2 nx - 1) + (di + nx - 1)]` is the normal surface
/// displacement at the centre of the cell `(di, dj)` cells away from a cell under
/// unit pressure (`di > 0`: the field point is upstream of the load, at larger x),
/// for `-(nx - 1) <= di <= nx - 1` and `0 <= dj < ny` (the kernel is even in dj,
/// not in di). `velocity` is the sliding speed `V >= 0` (`+inf` allowed), in the
/// length unit of `cell` per time unit of the retardation times; the result is in
/// the compliance's units times length (the displacement per unit pressure).
pub fn steady_sliding_kernel(
    series: &CreepSeries,
    cell: f64,
    nx: usize,
    ny: usize,
    velocity: f64,
) -> Result<Vec<f64>> {
    series.validate()?;
    if !(cell.is_finite() && cell > 0.0) {
        return Err(invalid("cell", cell, "a finite length > 0"));
    }
    if velocity.is_nan() || velocity < 0.0 {
        return Err(invalid("velocity", velocity, "a speed >= 0 (+inf allowed)"));
    }
    if nx == 0 || ny == 0 {
        return Err(Error::InvalidValue {
            field: "grid".into(),
            value: format!("{nx} x {ny}"),
            allowed: "at least one cell in each direction".into(),
        });
    }
    // Split the branches: relaxed, frozen, or creeping over lambda cells.
    let mut elastic = series.glassy;
    let mut creeping: Vec<(f64, f64)> = Vec::new();
    for b in &series.branches {
        if !b.retardation_time.is_finite() || b.compliance == 0.0 {
            continue;
        }
        let lambda = velocity * b.retardation_time / cell;
        if lambda < LAMBDA_FLOOR {
            elastic += b.compliance;
        } else if lambda <= 1.0 / LAMBDA_FLOOR {
            creeping.push((b.compliance, lambda));
        }
    }
    if elastic == 0.0 && creeping.is_empty() {
        return Err(invalid(
            "velocity",
            velocity,
            "a speed at which some compliance creeps (the body has no glassy compliance)",
        ));
    }
    let width = 2 * nx - 1;
    let unit = Elastic {
        young: 1.0,
        poisson: 0.0,
    };
    let quadrant = homogeneous_surface_kernel_quadrant(unit, cell, nx, ny);
    let mut out = vec![0.0; width * ny];
    for dj in 0..ny {
        for di in 0..width {
            let i = di.abs_diff(nx - 1);
            out[dj * width + di] = elastic * quadrant[dj * nx + i];
        }
    }
    if creeping.is_empty() {
        return Ok(out);
    }
    let rows = BranchTerms::new(nx, ny, &creeping).rows();
    for (dj, row) in rows.iter().enumerate() {
        for (o, r) in out[dj * width..(dj + 1) * width].iter_mut().zip(row) {
            *o += cell * r;
        }
    }
    Ok(out)
}

/// Love's primitive `F(u, v)` (its mixed derivative is `1 / r`).
fn primitive(u: f64, v: f64) -> f64 {
    half_primitive(u, v) + half_primitive(v, u)
}

/// `L_1(x, y)`: Love's cell kernel per unit compliance on a unit cell.
fn love(x: f64, y: f64) -> f64 {
    rectangle_inverse_distance_integral(x, y, 0.5, 0.5) / PI
}

/// `x L_1(x, y)` by a tensor Gauss–Legendre rule over the cell, for points far
/// from it (no cancellation as `x -> inf`).
fn love_far_scaled(gl: &GaussLegendre, x: f64, y: f64) -> f64 {
    let mut sum = 0.0;
    for (xi, wx) in gl.nodes.iter().zip(&gl.weights) {
        let dx = 1.0 - 0.5 * xi / x;
        let mut inner = 0.0;
        for (eta, wy) in gl.nodes.iter().zip(&gl.weights) {
            let dy = (y - 0.5 * eta) / x;
            inner += wy / (dx * dx + dy * dy).sqrt();
        }
        sum += wx * inner;
    }
    0.25 * sum / PI
}

/// Points and weights of `(1 / lambda) int_0^len exp(-t / lambda) g(t) dt` for `g`
/// smooth, or with a `t ln t` type singularity at 0 or at `len` if flagged.
fn exp_weighted_rule(
    gl: &GaussLegendre,
    lambda: f64,
    len: f64,
    singular_start: bool,
    singular_end: bool,
) -> Vec<(f64, f64)> {
    let end = len.min(EXP_CUTOFF * lambda);
    let pieces = (end / (2.0 * lambda)).ceil().max(1.0) as usize;
    let mut breaks: Vec<f64> = (0..=pieces)
        .map(|p| end * p as f64 / pieces as f64)
        .collect();
    if singular_start {
        let first = breaks[1];
        breaks.extend((1..=50).map(|k| first * 0.5f64.powi(k)));
    }
    if singular_end && end == len {
        let width = len - breaks[pieces - 1];
        breaks.extend((1..=40).map(|k| len - width * 0.5f64.powi(k)));
    }
    breaks.sort_by(f64::total_cmp);
    breaks.dedup();
    let mut rule = Vec::with_capacity(breaks.len() * gl.nodes.len());
    for w in breaks.windows(2) {
        let (half, mid) = (0.5 * (w[1] - w[0]), 0.5 * (w[1] + w[0]));
        for (x, wt) in gl.nodes.iter().zip(&gl.weights) {
            let t = mid + half * x;
            rule.push((t, wt * half * (-t / lambda).exp() / lambda));
        }
    }
    rule
}

/// The Lagrange basis of the nodes `t` (on `[0, 1]`) at `x`, into `out`.
fn lagrange_basis(t: &[f64], bary: &[f64], x: f64, out: &mut [f64]) {
    if let Some(m) = t.iter().position(|&tm| tm == x) {
        out.fill(0.0);
        out[m] = 1.0;
        return;
    }
    let mut total = 0.0;
    for ((o, tm), b) in out.iter_mut().zip(t).zip(bary) {
        *o = b / (x - tm);
        total += *o;
    }
    for o in out.iter_mut() {
        *o /= total;
    }
}

/// What one branch needs, computed once per kernel.
struct BranchWeights {
    /// Its compliance.
    compliance: f64,
    /// Product weights on a unit panel, and the same reversed (mirrored nodes).
    unit: Vec<f64>,
    unit_reversed: Vec<f64>,
    /// Product weights on a half panel.
    half: Vec<f64>,
    /// `exp(-1 / lambda)` and `exp(-1 / (2 lambda))`.
    decay_unit: f64,
    decay_half: f64,
    /// `(1 / lambda) int_0^(1/2) exp(-t / lambda) t ln t dt`.
    singular_start: f64,
    /// `(1 / lambda) int_0^(1/2) exp(-t / lambda) (t - 1/2) ln(1/2 - t) dt`.
    singular_end: f64,
    /// `mu_k / lambda` of the tail.
    tail: Vec<f64>,
}

impl BranchWeights {
    fn new(compliance: f64, lambda: f64, nodes: &[f64], bary: &[f64], x_top: f64) -> Self {
        let gl = GaussLegendre::new(RULE_POINTS);
        let n = nodes.len();
        let mut basis = vec![0.0; n];
        let mut product = |len: f64| {
            let mut w = vec![0.0; n];
            for (t, wt) in exp_weighted_rule(&gl, lambda, len, false, false) {
                lagrange_basis(nodes, bary, t / len, &mut basis);
                for (wm, b) in w.iter_mut().zip(&basis) {
                    *wm += wt * b;
                }
            }
            w
        };
        let unit = product(1.0);
        let half = product(0.5);
        let unit_reversed = unit.iter().rev().copied().collect();
        let singular_start = exp_weighted_rule(&gl, lambda, 0.5, true, false)
            .iter()
            .map(|(t, w)| w * t * t.ln())
            .sum();
        let singular_end = exp_weighted_rule(&gl, lambda, 0.5, false, true)
            .iter()
            .map(|(t, w)| w * (t - 0.5) * (0.5 - t).ln())
            .sum();
        let tail = tail_moments(&gl, x_top / lambda)
            .iter()
            .map(|m| m / lambda)
            .collect();
        BranchWeights {
            compliance,
            unit,
            unit_reversed,
            half,
            decay_unit: (-1.0 / lambda).exp(),
            decay_half: (-0.5 / lambda).exp(),
            singular_start,
            singular_end,
            tail,
        }
    }
}

/// `mu_k = int_0^inf exp(-v) T_k(2 beta / (beta + v) - 1) dv / (beta + v)`,
/// `k < TAIL_TERMS`: pieces graded geometrically in `beta + v` (ratio 2^(1/4),
/// resolving the pole at `v = -beta` and the Chebyshev oscillations) and no longer
/// than 1 (resolving the exponential), cut at `v = 46`.
fn tail_moments(gl: &GaussLegendre, beta: f64) -> Vec<f64> {
    let mut breaks: Vec<f64> = (0..=EXP_CUTOFF as usize).map(|v| v as f64).collect();
    let ratio = 2f64.powf(0.25);
    let mut w = beta * ratio;
    while w - beta < EXP_CUTOFF {
        breaks.push(w - beta);
        w *= ratio;
    }
    breaks.sort_by(f64::total_cmp);
    breaks.dedup();
    let mut mu = vec![0.0; TAIL_TERMS];
    for p in breaks.windows(2) {
        let (half, mid) = (0.5 * (p[1] - p[0]), 0.5 * (p[1] + p[0]));
        for (x, wt) in gl.nodes.iter().zip(&gl.weights) {
            let v = mid + half * x;
            let weight = wt * half * (-v).exp() / (beta + v);
            let c = 2.0 * beta / (beta + v) - 1.0;
            let (mut t0, mut t1) = (1.0, c);
            mu[0] += weight;
            mu[1] += weight * c;
            for m in mu.iter_mut().skip(2) {
                let t2 = 2.0 * c * t1 - t0;
                *m += weight * t2;
                t0 = t1;
                t1 = t2;
            }
        }
    }
    mu
}

/// The branch terms `sum_k J_k M_k` of every row, in cell units.
struct BranchTerms {
    nx: usize,
    ny: usize,
    /// Field points reach `|X| <= n_lo = nx - 1`; the recursion starts at `x_top`.
    n_lo: usize,
    x_top: usize,
    /// Panel nodes on `[0, 1]`.
    nodes: Vec<f64>,
    branches: Vec<BranchWeights>,
}

impl BranchTerms {
    fn new(nx: usize, ny: usize, creeping: &[(f64, f64)]) -> Self {
        let n_lo = nx - 1;
        let x_top = n_lo.max(ny).max(4);
        let gl = GaussLegendre::new(PANEL_NODES);
        let nodes: Vec<f64> = gl.nodes.iter().map(|x| 0.5 * (1.0 + x)).collect();
        let bary: Vec<f64> = (0..nodes.len())
            .map(|m| {
                1.0 / (0..nodes.len())
                    .filter(|&j| j != m)
                    .map(|j| nodes[m] - nodes[j])
                    .product::<f64>()
            })
            .collect();
        let branches = creeping
            .par_iter()
            .map(|&(c, lambda)| BranchWeights::new(c, lambda, &nodes, &bary, x_top as f64))
            .collect();
        BranchTerms {
            nx,
            ny,
            n_lo,
            x_top,
            nodes,
            branches,
        }
    }

    fn rows(&self) -> Vec<Vec<f64>> {
        let n = self.nodes.len();
        let kn = self.x_top;
        // table[(l * kn + k) * n + m] = F(k + 1/2 + t_m, l - 1/2), 0 <= k < x_top
        let table: Vec<f64> = (0..=self.ny)
            .into_par_iter()
            .flat_map_iter(|l| {
                let v = l as f64 - 0.5;
                (0..kn).flat_map(move |k| {
                    self.nodes
                        .iter()
                        .map(move |t| primitive(k as f64 + 0.5 + t, v))
                })
            })
            .collect();
        (0..self.ny)
            .into_par_iter()
            .map(|dj| {
                let lo = &table[dj * kn * n..(dj + 1) * kn * n];
                let hi = &table[(dj + 1) * kn * n..(dj + 2) * kn * n];
                let d: Vec<f64> = hi.iter().zip(lo).map(|(a, b)| a - b).collect();
                self.row(dj, &d)
            })
            .collect()
    }

    /// One row: `d[k * n + m] = D(k + 1/2 + t_m)`, `D(u) = F(u, dj + 1/2) - F(u, dj - 1/2)`.
    fn row(&self, dj: usize, d: &[f64]) -> Vec<f64> {
        let n = self.nodes.len();
        let y = dj as f64;
        let n_lo = self.n_lo as i64;
        let x_top = self.x_top as i64;
        // The four half panels starting at -1, -1/2, 0, 1/2; on the row dj = 0 the
        // edge singularity is subtracted.
        let starts = [-1.0, -0.5, 0.0, 0.5];
        let half_values: Vec<Vec<f64>> = starts
            .iter()
            .map(|&c| {
                self.nodes
                    .iter()
                    .map(|t| {
                        let x: f64 = c + 0.5 * t;
                        let mut f = love(x, y);
                        if dj == 0 {
                            // f = g + (2 / pi) ((x - 1/2) ln|x - 1/2| - (x + 1/2) ln|x + 1/2|):
                            // remove the term of the edge this panel touches.
                            if c < 0.0 {
                                f += 2.0 / PI * (x + 0.5) * (x + 0.5).abs().ln();
                            } else {
                                f -= 2.0 / PI * (x - 0.5) * (x - 0.5).abs().ln();
                            }
                        }
                        f
                    })
                    .collect()
            })
            .collect();
        // The tail's Chebyshev coefficients of g(s) = X L_1(X, y), X = x_top / s.
        let far = GaussLegendre::new(FAR_POINTS);
        let values: Vec<f64> = (0..TAIL_TERMS)
            .map(|j| {
                let theta = PI * (j as f64 + 0.5) / TAIL_TERMS as f64;
                let s = 0.5 * (1.0 + theta.cos());
                love_far_scaled(&far, x_top as f64 / s, y)
            })
            .collect();
        let coefficients: Vec<f64> = (0..TAIL_TERMS)
            .map(|k| {
                let sum: f64 = values
                    .iter()
                    .enumerate()
                    .map(|(j, v)| v * (PI * k as f64 * (j as f64 + 0.5) / TAIL_TERMS as f64).cos())
                    .sum();
                sum * if k == 0 { 1.0 } else { 2.0 } / TAIL_TERMS as f64
            })
            .collect();
        let mut acc = vec![0.0; 2 * self.nx - 1];
        let dot = |w: &[f64], k: usize| -> f64 {
            w.iter()
                .zip(&d[k * n..(k + 1) * n])
                .map(|(a, b)| a * b)
                .sum()
        };
        for b in &self.branches {
            // Q(k) = sum_m W_m D(k + 1/2 + t_m); D is odd, so for k <= -2 it is
            // minus the mirrored sum at k' = -k - 2 (k = -1 straddles the edge
            // singularity of D and is never needed).
            let q = |k: i64| -> f64 {
                if k >= 0 {
                    dot(&b.unit, k as usize)
                } else {
                    -dot(&b.unit_reversed, (-k - 2) as usize)
                }
            };
            let half_sum = |p: usize| -> f64 {
                let mut s: f64 = b.half.iter().zip(&half_values[p]).map(|(w, v)| w * v).sum();
                if dj == 0 {
                    // Panels ending at -1/2 / starting at -1/2 / ending at 1/2 /
                    // starting at 1/2.
                    s += 2.0 / PI
                        * match p {
                            0 => -b.singular_end,
                            1 => -b.singular_start,
                            2 => b.singular_end,
                            _ => b.singular_start,
                        };
                }
                s
            };
            let mut m: f64 = b.tail.iter().zip(&coefficients).map(|(w, c)| w * c).sum();
            if x_top == n_lo {
                acc[(x_top + n_lo) as usize] += b.compliance * m;
            }
            let mut q_right = q(x_top - 1);
            for i in (-n_lo..x_top).rev() {
                if i == -1 || i == 0 {
                    let p = (i + 1) as usize * 2;
                    m = half_sum(p + 1) + b.decay_half * m;
                    m = half_sum(p) + b.decay_half * m;
                    if i == -1 {
                        q_right = q(-2);
                    }
                } else {
                    let q_left = q(i - 1);
                    m = (q_right - q_left) / PI + b.decay_unit * m;
                    q_right = q_left;
                }
                if i <= n_lo {
                    acc[(i + n_lo) as usize] += b.compliance * m;
                }
            }
        }
        acc
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_surface_compliance_is_relaxed_for_long_waves_and_glassy_for_short_ones() {
        let body = ViscoelasticBody {
            creep: series(0.1, &[(0.9, 2.0), (0.5, f64::INFINITY)]),
            poisson: 0.3,
            references: Vec::new(),
        };
        let at = |k: f64, v: f64| body.surface_compliance(k, v).unwrap();
        // The frozen branch never takes part.
        assert!((at(0.0, 1.0) - 1.0).norm() < 1e-15);
        assert!((at(3.0, 0.0) - 1.0).norm() < 1e-15);
        assert!((at(1e12, 1.0) - 0.1).norm() < 1e-11);
        assert!((at(3.0, f64::INFINITY) - 0.1).norm() < 1e-15);
        // k V tau = 1: the branch answers with 0.9 / (1 - i).
        let c = at(0.25, 2.0);
        assert!(
            (c.re - 0.55).abs() < 1e-15 && (c.im - 0.45).abs() < 1e-15,
            "{c}"
        );
    }

    fn series(glassy: f64, branches: &[(f64, f64)]) -> CreepSeries {
        CreepSeries {
            glassy,
            branches: branches
                .iter()
                .map(|&(compliance, retardation_time)| CreepBranch {
                    compliance,
                    retardation_time,
                })
                .collect(),
        }
    }

    /// Love's kernel per unit compliance on cells of side `cell`, in the layout of
    /// [`steady_sliding_kernel`].
    fn elastic_layout(cell: f64, nx: usize, ny: usize) -> Vec<f64> {
        let unit = Elastic {
            young: 1.0,
            poisson: 0.0,
        };
        let q = homogeneous_surface_kernel_quadrant(unit, cell, nx, ny);
        let width = 2 * nx - 1;
        (0..width * ny)
            .map(|m| q[(m / width) * nx + (m % width).abs_diff(nx - 1)])
            .collect()
    }

    fn max_abs(v: &[f64]) -> f64 {
        v.iter().fold(0.0, |a, b| a.max(b.abs()))
    }

    /// Adaptive Gauss–Legendre: a 20-point rule against the same on both halves.
    fn adaptive(
        gl: &GaussLegendre,
        f: &dyn Fn(f64) -> f64,
        a: f64,
        b: f64,
        whole: f64,
        tol: f64,
        depth: u32,
    ) -> f64 {
        let m = 0.5 * (a + b);
        let left = gl.integrate(a, m, f);
        let right = gl.integrate(m, b, f);
        if (left + right - whole).abs() < tol || depth == 0 {
            left + right
        } else {
            adaptive(gl, f, a, m, left, tol, depth - 1)
                + adaptive(gl, f, m, b, right, tol, depth - 1)
        }
    }

    /// The branch term per unit compliance on a unit cell, `(1 / lambda) int_0^inf
    /// exp(-u / lambda) L_1(X + u, Y) du`, by brute force: the cell integral over eta
    /// in closed form, `G(s) = int deta / sqrt(s^2 + (Y - eta)^2)`, the one over xi
    /// folded into the exact weight `w(s) = (1 / lambda) int dxi exp(-u / lambda)` of
    /// `s = X + u - xi`, and `(1 / pi) int G(s) w(s) ds` by adaptive quadrature
    /// between the breakpoints `X -+ 1/2` (kinks of w) and 0 (log singularity of G).
    fn brute_force(x: f64, y: f64, lambda: f64) -> f64 {
        let gl = GaussLegendre::new(20);
        let g = move |s: f64| ((y + 0.5) / s.abs()).asinh() - ((y - 0.5) / s.abs()).asinh();
        let inside = move |s: f64| g(s) * -(-(s - x + 0.5) / lambda).exp_m1();
        let outside =
            move |s: f64| g(s) * (-(s - x - 0.5) / lambda).exp() * -(-1.0 / lambda).exp_m1();
        let mut breaks = vec![x - 0.5, x + 0.5];
        // The weight rises from 0 over lambda after x - 1/2.
        let mut t = lambda;
        while t < 1.0 {
            breaks.push(x - 0.5 + t);
            t *= 2.0;
        }
        let mut t = 1.0;
        while t < 60.0 * lambda {
            breaks.push(x + 0.5 + t.min(60.0 * lambda));
            t *= 2.0;
        }
        breaks.push(x + 0.5 + 60.0 * lambda);
        if x - 0.5 < 0.0 && 0.0 < x + 0.5 + 60.0 * lambda {
            breaks.push(0.0);
        }
        breaks.sort_by(f64::total_cmp);
        breaks.dedup();
        let mut sum = 0.0;
        for p in breaks.windows(2) {
            let f: &dyn Fn(f64) -> f64 = if p[1] <= x + 0.5 { &inside } else { &outside };
            let whole = gl.integrate(p[0], p[1], f);
            sum += adaptive(&gl, f, p[0], p[1], whole, 1e-16 / lambda.max(1.0), 40);
        }
        sum / PI
    }

    #[test]
    fn viscoelastic_body_speed_limits_are_the_glassy_and_relaxed_kernels() {
        let (cell, nx, ny) = (0.25, 12, 7);
        let s = series(0.3, &[(0.5, 2.0), (0.2, 0.01), (0.4, f64::INFINITY)]);
        let l = elastic_layout(cell, nx, ny);
        let peak = max_abs(&l);
        let fast = steady_sliding_kernel(&s, cell, nx, ny, f64::INFINITY).unwrap();
        let slow = steady_sliding_kernel(&s, cell, nx, ny, 0.0).unwrap();
        for m in 0..l.len() {
            assert!((fast[m] - 0.3 * l[m]).abs() <= 1e-12 * peak, "{m}");
            assert!((slow[m] - 1.0 * l[m]).abs() <= 1e-12 * peak, "{m}");
        }
        // Creep lengths 1e-9 cell and 1e12 windows through the quadrature: the
        // neglected terms are lambda |dL/dX| <~ 1e-9 and ln(lambda) / lambda.
        let one = series(0.3, &[(0.7, 1.0)]);
        let near_slow = steady_sliding_kernel(&one, cell, nx, ny, 1e-9 * cell).unwrap();
        let window = nx as f64 * cell;
        let near_fast = steady_sliding_kernel(&one, cell, nx, ny, 1e12 * window).unwrap();
        let (mut slow_err, mut fast_err) = (0.0f64, 0.0f64);
        for m in 0..l.len() {
            slow_err = slow_err.max((near_slow[m] - l[m]).abs() / peak);
            fast_err = fast_err.max((near_fast[m] - 0.3 * l[m]).abs() / peak);
        }
        eprintln!("l = 1e-9 cell: {slow_err:.2e} of the peak; l = 1e12 windows: {fast_err:.2e}");
        assert!(slow_err < 2e-9, "{slow_err}");
        // The first-order term: M = L + lambda dL/dX + O(lambda^2), with
        // dL_1/dX = (G(X + 1/2) - G(X - 1/2)) / pi, G(s) = int_{Y-1/2}^{Y+1/2} deta / r.
        let g = |s: f64, y: f64| ((y + 0.5) / s.abs()).asinh() - ((y - 0.5) / s.abs()).asinh();
        let width = 2 * nx - 1;
        let mut first_order_err = 0.0f64;
        for m in 0..l.len() {
            let (x, y) = ((m % width) as f64 - (nx - 1) as f64, (m / width) as f64);
            let slope = (g(x + 0.5, y) - g(x - 0.5, y)) / PI;
            let want = l[m] + 0.7 * 1e-9 * cell * slope;
            first_order_err = first_order_err.max((near_slow[m] - want).abs() / peak);
        }
        eprintln!("l = 1e-9 cell against L + l dL/dX: {first_order_err:.2e} of the peak");
        assert!(first_order_err < 1e-13, "{first_order_err}");
        assert!(fast_err < 1e-11, "{fast_err}");
    }

    #[test]
    fn viscoelastic_body_matches_brute_force_quadrature() {
        // J_g = 0 and one branch: the kernel is the branch term alone.
        let (cell, nx, ny) = (0.5, 9, 5);
        let offsets = [
            (0, 0),
            (1, 0),
            (-1, 0),
            (-3, 0),
            (5, 0),
            (-8, 0),
            (8, 4),
            (0, 1),
            (-2, 1),
            (2, 3),
            (-6, 2),
        ];
        let mut worst = 0.0f64;
        for lambda in [0.01, 1.0, 30.0] {
            let s = series(0.0, &[(1.0, 2.0)]);
            let k = steady_sliding_kernel(&s, cell, nx, ny, lambda * cell / 2.0).unwrap();
            let err = brute_force_error(&k, nx, &offsets, cell, lambda);
            worst = worst.max(err);
        }
        eprintln!("brute force: worst {worst:.2e} of the peak");
    }

    /// The largest error of the kernel `k` (`nx` cells along x, cells of side
    /// `cell`) against the brute force at `offsets`, over its peak; each must be
    /// below 1e-10 of the peak.
    fn brute_force_error(
        k: &[f64],
        nx: usize,
        offsets: &[(i64, usize)],
        cell: f64,
        lambda: f64,
    ) -> f64 {
        let peak = max_abs(k);
        let mut worst = 0.0f64;
        for &(di, dj) in offsets {
            let got = k[dj * (2 * nx - 1) + (di + nx as i64 - 1) as usize];
            let want = cell * brute_force(di as f64, dj as f64, lambda);
            let err = (got - want).abs() / peak;
            worst = worst.max(err);
            assert!(
                err < 1e-10,
                "lambda {lambda} ({di}, {dj}): {got} vs {want}, {err:.1e}"
            );
        }
        worst
    }

    #[test]
    fn viscoelastic_body_matches_brute_force_for_every_creep_length() {
        // From 1e-6 cell to 1e6 windows of 9 cells.
        let (nx, ny) = (9, 3);
        let mut worst = 0.0f64;
        for lambda in [1e-6, 1e-4, 0.003, 0.1, 0.5, 7.0, 300.0, 1e4, 1e6, 9e6] {
            let s = series(0.0, &[(1.0, 1.0)]);
            let k = steady_sliding_kernel(&s, 1.0, nx, ny, lambda).unwrap();
            let offsets = [(0, 0), (-1, 0), (1, 0), (-8, 0), (8, 0), (-4, 1), (3, 2)];
            let err = brute_force_error(&k, nx, &offsets, 1.0, lambda);
            worst = worst.max(err);
        }
        eprintln!("brute force, lambda 1e-6 to 9e6 cells: worst {worst:.2e} of the peak");
    }

    #[test]
    fn viscoelastic_body_large_grid_matches_brute_force_far_away() {
        // Far offsets of a 128 x 96 grid, where the primitive's differences cancel
        // most and the recursion runs longest.
        let (nx, ny) = (128, 96);
        let mut worst = 0.0f64;
        for lambda in [0.2, 40.0, 1e5] {
            let s = series(0.0, &[(1.0, 1.0)]);
            let k = steady_sliding_kernel(&s, 1.0, nx, ny, lambda).unwrap();
            let peak = max_abs(&k);
            for (di, dj) in [(-127, 0), (127, 0), (-100, 95), (60, 80), (-3, 50), (0, 95)] {
                let got = k[dj * (2 * nx - 1) + (di + nx as i64 - 1) as usize];
                let want = brute_force(di as f64, dj as f64, lambda);
                let err = (got - want).abs() / peak;
                worst = worst.max(err);
                assert!(
                    err < 1e-10,
                    "lambda {lambda} ({di}, {dj}): {got} vs {want}, {err:.1e}"
                );
                assert!((got - want).abs() < 1e-9 * want, "relative, ({di}, {dj})");
            }
        }
        eprintln!("128 x 96 far offsets: worst {worst:.2e} of the peak");
    }

    #[test]
    fn viscoelastic_body_extreme_creep_lengths_reach_the_limits() {
        let s = series(0.25, &[(0.75, 1.0)]);
        let (nx, ny) = (6, 4);
        let l = elastic_layout(1.0, nx, ny);
        let peak = max_abs(&l);
        for (lambda, limit, tol) in [
            (1e-90, 1.0, 1e-14),
            (1e-30, 1.0, 1e-14),
            (1e30, 0.25, 1e-14),
            (1e90, 0.25, 1e-14),
        ] {
            let k = steady_sliding_kernel(&s, 1.0, nx, ny, lambda).unwrap();
            for m in 0..l.len() {
                assert!(
                    (k[m] - limit * l[m]).abs() <= tol * peak,
                    "lambda {lambda}: {} vs {}",
                    k[m],
                    limit * l[m]
                );
            }
        }
    }

    #[test]
    fn viscoelastic_body_branches_superpose() {
        // Three branches at once (one relaxed, one creeping, one frozen at this
        // speed) equal the glassy kernel plus each branch alone.
        let (cell, nx, ny, v) = (0.3, 7, 5, 2.0);
        let all = series(0.2, &[(0.3, 1e-120), (0.5, 0.4), (0.7, 1e120)]);
        let k = steady_sliding_kernel(&all, cell, nx, ny, v).unwrap();
        let l = elastic_layout(cell, nx, ny);
        let creeping = steady_sliding_kernel(&series(0.0, &[(0.5, 0.4)]), cell, nx, ny, v).unwrap();
        let peak = max_abs(&k);
        for m in 0..k.len() {
            let want = 0.5 * l[m] + creeping[m];
            assert!((k[m] - want).abs() < 1e-14 * peak, "{m}");
        }
    }

    #[test]
    fn viscoelastic_body_tiny_and_tall_grids_match_brute_force() {
        for (nx, ny) in [(1, 1), (2, 7), (1, 3)] {
            for lambda in [0.05, 3.0, 200.0] {
                let s = series(0.0, &[(1.0, 1.0)]);
                let k = steady_sliding_kernel(&s, 1.0, nx, ny, lambda).unwrap();
                let peak = max_abs(&k);
                for dj in 0..ny {
                    for di in -(nx as i64 - 1)..nx as i64 {
                        let got = k[dj * (2 * nx - 1) + (di + nx as i64 - 1) as usize];
                        let want = brute_force(di as f64, dj as f64, lambda);
                        assert!(
                            (got - want).abs() < 1e-10 * peak,
                            "{nx}x{ny} lambda {lambda} ({di}, {dj}): {got} vs {want}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn viscoelastic_body_tail_agrees_with_the_recursion() {
        // The same offsets from a small grid (tail from X = 4) and a wide one
        // (recursion through them from X = 60).
        let (cell, ny) = (1.0, 3);
        let mut worst = 0.0f64;
        for lambda in [1e-6, 0.003, 0.7, 12.0, 1e4, 1e9] {
            let s = series(0.1, &[(1.0, 1.0)]);
            let small = steady_sliding_kernel(&s, cell, 3, ny, lambda).unwrap();
            let wide = steady_sliding_kernel(&s, cell, 61, ny, lambda).unwrap();
            let peak = max_abs(&wide);
            for dj in 0..ny {
                for di in -2i64..=2 {
                    let a = small[dj * 5 + (di + 2) as usize];
                    let b = wide[dj * 121 + (di + 60) as usize];
                    worst = worst.max((a - b).abs() / peak);
                    assert!(
                        (a - b).abs() < 1e-12 * peak,
                        "lambda {lambda} ({di}, {dj}): {a} vs {b}"
                    );
                }
            }
        }
        eprintln!("tail vs recursion: worst {worst:.2e} of the peak");
    }

    #[test]
    fn viscoelastic_body_trails_downstream_and_moves_between_the_limits() {
        let s = series(0.5, &[(0.5, 1.0)]);
        let (nx, ny) = (16, 4);
        let l = elastic_layout(1.0, nx, ny);
        let mut last_centre = f64::INFINITY;
        for lambda in [1e-3, 0.1, 1.0, 10.0, 1e3, 1e6] {
            let k = steady_sliding_kernel(&s, 1.0, nx, ny, lambda).unwrap();
            let at = |di: i64, dj: usize| k[dj * 31 + (di + 15) as usize];
            // Downstream (X < 0) sees more than upstream.
            for di in 1..15 {
                assert!(at(-di, 0) > at(di, 0), "lambda {lambda} di {di}");
            }
            // Above the glassy kernel everywhere; upstream (X >= 0, where L falls
            // along u) below the relaxed one; the centre falling with speed.
            for m in 0..k.len() {
                assert!(k[m] >= 0.5 * l[m] * (1.0 - 1e-14), "{m}");
                if m % 31 >= 15 {
                    assert!(k[m] <= l[m] * (1.0 + 1e-14), "{m}");
                }
            }
            assert!(at(0, 0) < last_centre);
            last_centre = at(0, 0);
        }
    }

    #[test]
    fn viscoelastic_body_bad_input_names_the_field() {
        let message = |s: &CreepSeries, cell: f64, nx: usize, v: f64| {
            steady_sliding_kernel(s, cell, nx, 3, v)
                .unwrap_err()
                .to_string()
        };
        let ok = series(0.1, &[(0.2, 1.0)]);
        assert!(message(&series(-0.1, &[]), 1.0, 3, 1.0).starts_with("creep.glassy = -0.1"));
        assert!(message(&series(f64::NAN, &[]), 1.0, 3, 1.0).starts_with("creep.glassy"));
        assert!(
            message(&series(0.1, &[(0.2, 1.0), (-1.0, 1.0)]), 1.0, 3, 1.0)
                .starts_with("creep.branches[1].compliance")
        );
        assert!(message(&series(0.1, &[(0.2, f64::NAN)]), 1.0, 3, 1.0)
            .starts_with("creep.branches[0].retardation_time"));
        assert!(message(&series(0.1, &[(0.2, 0.0)]), 1.0, 3, 1.0)
            .starts_with("creep.branches[0].retardation_time"));
        assert!(message(&series(0.0, &[(0.0, 1.0)]), 1.0, 3, 1.0).starts_with("creep = 0"));
        assert!(
            message(&series(0.0, &[(1.0, f64::INFINITY)]), 1.0, 3, 1.0).starts_with("creep = 0")
        );
        assert!(message(&series(0.0, &[(1.0, 1.0)]), 1.0, 3, f64::INFINITY).starts_with("velocity"));
        assert!(message(&ok, 0.0, 3, 1.0).starts_with("cell"));
        assert!(message(&ok, 1.0, 3, f64::NAN).starts_with("velocity"));
        assert!(message(&ok, 1.0, 3, -1.0).starts_with("velocity"));
        assert!(message(&ok, 1.0, 0, 1.0).starts_with("grid"));
        assert!(ok.validate().is_ok());
    }
}
