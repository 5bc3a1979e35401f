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
//!
//! # The solvers' kernel: leading-edge damping
//!
//! The kernels above are exact for a pressure uniform on each cell, read at the
//! cell centres. Where the glassy compliance is far below the creeping one and the
//! creep length spans many cells, that collocation of the creep integral (a causal
//! integral along x, nearly of the first kind) leaves the odd–even mode along x
//! almost free: its symbol at the shortest wave is about `J_g` against the
//! `sum_k J_k / (2 lambda_k)` a cell answers with, so a pressure jump at a glassy
//! leading edge rings across the contact and the pressures alternate in sign: at
//! E_g/E_0 = 1e4 no contact interval near the contact gives a positive pressure on
//! a 1,024-cell line (the best of them leaves 26 % of the peak negative), and at
//! E_g/E_0 = 1000 the 3-D solves failed. The layer has the same mode and the same
//! cure ([`crate::layer`]'s viscoelastic rows). [`BodyModel::surface_kernel`] and
//! [`BodyModel::line_kernel`] therefore add to each creeping branch the upwind
//! correction `w_k (W(x) - W(x + h))` of the displacement, `W` the elastic response
//! per unit compliance (Love's cell kernel, or the strip's), `x + h` the upstream
//! neighbour, with
//! `w_k = kappa_k s (b_k - a_k) exp(-2 x_k) J_k`, `x_k = 1 / lambda_k`,
//! `a_k = exp(-x_k)`, `b_k = exp(-x_k / 2)`, `kappa_k` the branch's share
//! ([`damping_share`]: 0.1 up to 4 cells of creep, 0.3 from 16 cells)
//! and `s = sum_k (1 - b_k) J_k / (J_g + sum_k (1 - b_k) J_k)` the branches' share
//! of a cell's own response: the layer's correction with `W` for its local
//! forcing. It raises the mode's symbol by `2 sum_k w_k`; for a smooth pressure it
//! is `sum_k w_k h dW/dx`, a lag of `w_k h / J_k = O(h^2 / l_k)` beside the branch's
//! own `l_k`: it vanishes as the grid is refined, as `lambda -> inf` (`b - a ~ x /
//! 2`), as `lambda -> 0` (`exp(-2x)`), and where the glassy compliance dominates
//! (`s -> 0`). Measured against the exact kernel where both solve, the friction
//! moves by at most 0.14 % (E_g/E_0 = 100, 5.8 cells per creep length, 128^2; 0.03 %
//! on 256^2) and by 2e-4 relative in line contacts; cases that failed now solve
//! (docs/validation.md). With `kappa = 0.1` for every branch, long creep over a
//! nearly glassy edge still rang: E_g/E_0 = 1000 with 11 to 22 cells per creep
//! length took 26 s on 256^2 and failed on 384^2 and 512^2, E_g/E_0 = 1e6 with 55
//! and 550 cells failed on 128^2. There the correction's lag, relative to the
//! creep's own, is `kappa / (2 lambda^2)` and small, so the share rises to 0.3 in
//! a smooth step in `ln lambda` from 4 to 16 cells: those cases solve in 0.6 to 67
//! s (most within 6 s), and the friction moves by at most 0.09 % where it was
//! measured (docs/validation.md). [`steady_sliding_kernel`] and
//! [`steady_sliding_line_kernel`] stay the exact kernels; [`leading_edge_damping`]
//! gives `sum_k w_k`.
//!
//! # The solvers' kernel: creep shorter than a cell
//!
//! A branch whose creep length `l` is far below the cell acts, to first order, as
//! a lag of the displacement: `(1 / l) int_0^inf exp(-u / l) W(x + u) du = W(x) + l
//! W'(x) + O(l^2)`. Read at the cell centres of a pressure uniform on cells, that
//! `W'` is the slope of the discrete displacement, which near the contact's edges
//! (cells cut by the edge, the edge's square-root pressure) is not the slider's:
//! the friction of a Zener sphere at V tau / a0 = 1e-4 came out 2.6 % low on 128^2,
//! 5.5 % on 64^2, an error first order in the cell that does not fade as the speed
//! falls. On the contact, though, the displacement is the gap's, so its slope is
//! known: `J_d W' = -f' - sum_b (J_b / l_b) (E_b - 1) W` (differentiating the
//! contact condition; `E_b` the exponential average of a branch creeping over more
//! than 2 cells, whose derivative is `(E_b - 1) / l_b`; `J_d` the glassy compliance
//! plus every branch creeping over less, whose average is the identity to first
//! order in `l / a`). The solvers' kernel therefore takes each branch's part
//! `w(lambda) J_k` as relaxed compliance and moves its lag `sum w J_k l_k` into the
//! gap: the slider's height is read at `f - c f'` with `c = sum_k w_k J_k l_k / J_d`
//! ([`BodyModel::creep_shift`]); the remaining part `(1 - w_k) J_k` keeps its exact
//! kernel, and a branch beyond 2 cells, `J_b E_b`, becomes `J_b (1 - c / l_b)` of
//! its exact kernel plus `J_b c / l_b` of the elastic one (its part of the slope;
//! `c` is below 2 cells, so the first weight is positive). The weight `w` is 1
//! below `lambda = 0.05` cells, 0 above 2 cells, and a smooth step in `ln lambda`
//! between: there the exact kernel's error
//! (first order, falling as lambda grows: -2.6 %, -1.4 %, -0.4 %, -0.2 % in that
//! friction at lambda = 0.02, 0.16, 0.5, 1.6 on 128^2) and the lag's (second order
//! in `l / a`, from the leading edge, where the material has not yet been loaded:
//! +0.2 %, +0.6 %, +0.9 %, +2.6 %) have opposite signs, and the step weighs them
//! so that they largely cancel (docs/validation.md). A one-parameter lag is exact
//! for a paraboloid up to a constant (the next term, `f''`, moves the approach
//! only). In a line contact the lag still helps (-1.3 % against -2.7 % at 128
//! cells), but there the contact's two edges jump from cell to cell as it moves,
//! where a circle's edge crosses cells at every offset, so some of the first-order
//! error stays. [`steady_sliding_kernel`] and [`steady_sliding_line_kernel`] stay
//! the exact kernels.
//!
//! # Line contacts (plane strain)
//!
//! [`steady_sliding_line_kernel`] is the same hereditary integral with the 2-D
//! Green's function: a cylinder along y pressed per unit length, cells of width
//! `h` along x each loaded uniformly along y. The elastic strip kernel per unit
//! plane-strain compliance is `g(X) = (2 / pi) int_{-h/2}^{h/2} ln(L / |X - s|) ds`
//! ([`super::line::strip_displacement`], datum: the surface at distance `L` from
//! the load), and the derivation above, with `W = (2 / pi) int p ln(L / |x - s|)
//! ds` in place of Love's integral, gives
//! `K(X) = J_g g(X) + sum_k J_k (1 / l_k) int_0^inf exp(-u / l_k) g(X + u) du`.
//! In cell units `g(X) = (2 h / pi) (ln(L / h) - I(X))` with the strip's
//! logarithmic integral `I(X) = int_{-1/2}^{1/2} ln|X - s| ds`, and since the
//! exponential weight has unit mass the branch term is
//! `(2 h / pi) J_k (ln(L / h) - N_k(X))`, `N(X) = (1 / lambda) int_0^inf
//! exp(-u / lambda) I(X + u) du`. Because `I` grows like `ln|X|`, `N` does not
//! vanish as `lambda -> inf`: `N(X) = ln(lambda) - gamma + O((|X| / lambda)
//! ln(lambda / |X|))` (gamma Euler's constant) for `|X| << lambda`. The kernel
//! keeps the datum of its long-wave compliance: far from the load (`|X| >>
//! l_k`) it is `J_relaxed g(X) + O(l / X)`, so the surface at distance `L >> l`
//! stays the zero. As `V -> 0` it tends to `J_relaxed g`; as `V -> inf` its
//! shape `K(X) - K(0)` tends to `J_g (g(X) - g(0))` but its level falls like
//! `(2 h / pi) J_k (ln(L / l_k) + gamma)` per branch, without bound: a material
//! point far upstream has crept under the load's logarithmic far field for a
//! time `~ L / V` and longer. That level is a rigid translation of the surface
//! (it moves the approach, not the pressure). Conventions: `V = +inf` (and a
//! frozen branch) gives `J_g g` exactly, as the point kernel does; a branch whose
//! creep length exceeds 1e100 cells contributes the constant
//! `(2 h / pi) J_k (ln(L / (h lambda)) + gamma)` (the neglected terms are below
//! 1e-90 of it), below 1e-100 cells its relaxed elastic kernel.
//!
//! *Method.* `N` at the integer offsets obeys the panel recursion above with
//! `L_1` replaced by `I`, on the same 24-node product-integration panels (unit
//! panels between cell centres, the four half panels touching the loaded cell's
//! edges `X = -+1/2`, where `I` has the log-singular slopes `-+(X -+ 1/2) ln|X -+
//! 1/2|`, subtracted and integrated with the same per-branch scalars; `I` is even,
//! so the panels left of the load reuse the values on the right with mirrored
//! weights). To keep the values small for long creep lengths the recursion runs
//! on `N - c`, `c = max(ln(lambda) - gamma, 0)` (the weights of a panel sum to
//! `1 - exp(-len / lambda)`, taken from `expm1`). It starts at `X_t = max(nx -
//! 1, 4)` from the tail in closed form: with the far-field series of the strip,
//! `I(X) = ln X - sum_{m >= 1} X^(-2m) / (4^m 2m (2m + 1))` (`X >= 4`: 12 terms
//! reach 1e-21), `N(X_t) = ln X_t + phi(beta) - sum_m X_t^(-2m) eps_2m(beta) /
//! (4^m 2m (2m + 1))` with `beta = X_t / lambda`, `phi(beta) = int_0^inf exp(-v)
//! dv / (beta + v)` (`= e^beta E_1(beta)`: the exponential average of `ln` is `ln
//! X + phi`) and `eps_n(beta) = int_0^inf exp(-v) (beta / (beta + v))^n dv` (the
//! average of `X^-n`), all by Gauss–Legendre on the pieces of `tail_moments`.
//! The cost is one strip integral per node (`24 nx`, shared by the branches) and
//! one dot product per panel and branch.

use super::homogeneous::{
    half_primitive, homogeneous_surface_kernel_quadrant, rectangle_inverse_distance_integral,
};
use super::quadrature::GaussLegendre;
use super::{BodyModel, EdgeProfile, SurfaceKernel};
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
/// Share `kappa` of the upwind correction that damps the odd–even mode of the
/// creep's collocation (module documentation, "The solvers' kernel") for a branch
/// creeping over up to 4 cells: the layer's value, whose analysis
/// it follows.
pub const LEADING_EDGE_DAMPING: f64 = 0.1;
/// The share for a branch creeping over 16 cells and more, whose
/// correction's lag, `O(kappa h^2 / l)`, is small beside the creep's own.
pub const LONG_CREEP_DAMPING: f64 = 0.3;
/// Creep lengths (cells) from which the share rises, in a smooth step in `ln
/// lambda`, from [`LEADING_EDGE_DAMPING`] ...
const LONG_CREEP_FROM: f64 = 4.0;
/// ... to [`LONG_CREEP_DAMPING`].
const LONG_CREEP_TO: f64 = 16.0;
/// Creep lengths (in cells) below this are relaxed, above its inverse frozen.
const LAMBDA_FLOOR: f64 = 1e-100;
/// The solvers' kernel moves a branch's lag wholly into the gap below this creep
/// length (cells) and keeps its exact kernel above [`LAG_TO`] (module
/// documentation, "creep shorter than a cell").
const LAG_FROM: f64 = 0.05;
/// See [`LAG_FROM`].
const LAG_TO: f64 = 2.0;
/// Terms of the far-field series of the strip integral in the line kernel's tail.
const STRIP_FAR_TERMS: usize = 12;
/// Euler's constant gamma.
const EULER_GAMMA: f64 = 0.577_215_664_901_532_9;

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
        lag: bool,
    ) -> Result<SurfaceKernel> {
        let half = sliding_kernel(&self.creep, cell, nx, ny, velocity, Solvers::Kernel { lag })?;
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
        cell: f64,
        nx: usize,
        velocity: f64,
        reference: f64,
        lag: bool,
    ) -> Result<SurfaceKernel> {
        let mut half = line_kernel(&self.creep, cell, nx, velocity, reference, lag)?;
        if self.creeps_at(velocity, cell) {
            let damping = leading_edge_damping(&self.creep, cell, velocity);
            if damping > 0.0 {
                // w (W(x) - W(x + h)) with W the strip's response per unit compliance.
                let strip = |di: f64| super::line::strip_displacement(di * cell, cell, reference);
                for (k, value) in half.iter_mut().enumerate() {
                    let di = k as f64 - (nx as f64 - 1.0);
                    *value += damping * (strip(di) - strip(di + 1.0));
                }
            }
            return Ok(SurfaceKernel::EvenInY { half, nx });
        }
        // No branch creeps at this speed: the kernel is even in x.
        Ok(SurfaceKernel::Even {
            quadrant: half[nx - 1..].to_vec(),
            nx,
        })
    }

    fn kernel_depends_on_velocity(&self) -> bool {
        true
    }

    fn creep_shift(&self, cell: f64, velocity: f64) -> f64 {
        creep_lag(&self.creep, cell, velocity)
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

    fn dissipated_force(
        &self,
        grid: &Grid,
        pressure: &[f64],
        velocity: f64,
        edges: EdgeProfile,
    ) -> Result<f64> {
        if grid.is_line() {
            return super::hysteresis::line_dissipated_force(
                &self.creep,
                velocity,
                pressure,
                grid.cell,
            );
        }
        let integral = match edges {
            EdgeProfile::SquareRoot => super::hysteresis::dissipated_force_square_root_edges,
            EdgeProfile::Bilinear => super::hysteresis::dissipated_force,
        };
        integral(&self.creep, velocity, pressure, grid.nx, grid.ny, grid.cell)
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

/// The branches at `velocity` on cells of side `cell`: the compliance that acts at
/// once (the glassy one plus the branches relaxed within 1e-100 cells) and the
/// `(J_k, lambda_k)` of those creeping over `lambda_k` cells. Frozen branches, and
/// those creeping beyond 1e100 cells, take no part.
fn split_branches(series: &CreepSeries, cell: f64, velocity: f64) -> (f64, Vec<(f64, f64)>) {
    let mut instantaneous = series.glassy;
    let mut creeping = Vec::new();
    for b in &series.branches {
        if !b.retardation_time.is_finite() || b.compliance == 0.0 {
            continue;
        }
        let lambda = velocity * b.retardation_time / cell;
        if lambda < LAMBDA_FLOOR {
            instantaneous += b.compliance;
        } else if lambda <= 1.0 / LAMBDA_FLOOR {
            creeping.push((b.compliance, lambda));
        }
    }
    (instantaneous, creeping)
}

/// The share `kappa` of the leading-edge damping for a branch creeping over
/// `lambda` cells (module documentation, "The solvers' kernel: leading-edge
/// damping"): [`LEADING_EDGE_DAMPING`] up to 4 cells, [`LONG_CREEP_DAMPING`] from
/// 16, a smooth step in `ln lambda` between.
pub fn damping_share(lambda: f64) -> f64 {
    let step = step_in_ln(lambda, LONG_CREEP_FROM, LONG_CREEP_TO);
    LEADING_EDGE_DAMPING + (LONG_CREEP_DAMPING - LEADING_EDGE_DAMPING) * step
}

/// 0 up to `from` cells of creep, 1 from `to`, between them the smooth step `t^2 (3
/// - 2 t)` of `t = ln(lambda / from) / ln(to / from)`.
fn step_in_ln(lambda: f64, from: f64, to: f64) -> f64 {
    if lambda <= from {
        return 0.0;
    }
    if lambda >= to {
        return 1.0;
    }
    let t = (lambda / from).ln() / (to / from).ln();
    t * t * (3.0 - 2.0 * t)
}

/// The share of a branch creeping over `lambda` cells that the solvers' kernel
/// takes as a lag in the gap (module documentation, "creep shorter than a cell"): 1
/// up to [`LAG_FROM`], 0 from [`LAG_TO`], a smooth step in `ln lambda` between.
fn lag_share(lambda: f64) -> f64 {
    1.0 - step_in_ln(lambda, LAG_FROM, LAG_TO)
}

/// The solvers' kernel's branches (module documentation, "creep shorter than a
/// cell"): the elastic compliance, the creeping parts kept with their exact kernels
/// as `(J, lambda)`, and the lag `c` (cells) moved into the gap.
struct SolversBranches {
    elastic: f64,
    creeping: Vec<(f64, f64)>,
    lag: f64,
}

fn solvers_branches(series: &CreepSeries, cell: f64, velocity: f64) -> SolversBranches {
    let (mut elastic, creeping) = split_branches(series, cell, velocity);
    // On the contact the displacement's slope W' solves `J_d W' = -f' - sum_b (J_b /
    // l_b) (E_b - 1) W` over the branches b creeping beyond LAG_TO cells, J_d the
    // elastic compliance plus every branch below LAG_TO (there E W' = W' to first
    // order in l / a).
    let mut slope_compliance = elastic;
    let mut lag_moment = 0.0;
    let mut kept = Vec::with_capacity(creeping.len());
    for (compliance, lambda) in creeping {
        let share = lag_share(lambda);
        if lambda < LAG_TO {
            slope_compliance += compliance;
        }
        elastic += share * compliance;
        lag_moment += share * compliance * lambda;
        if share < 1.0 {
            kept.push(((1.0 - share) * compliance, lambda));
        }
    }
    if lag_moment == 0.0 {
        return SolversBranches {
            elastic,
            creeping: kept,
            lag: 0.0,
        };
    }
    // J_d > 0 here: some branch below LAG_TO has a positive compliance.
    let lag = lag_moment / slope_compliance;
    for (compliance, lambda) in &mut kept {
        if *lambda >= LAG_TO {
            // J E becomes J ((1 - c / l) E + c / l), 1 - c / l > 0 since c is
            // below LAG_TO cells.
            elastic += *compliance * lag / *lambda;
            *compliance *= 1.0 - lag / *lambda;
        }
    }
    SolversBranches {
        elastic,
        creeping: kept,
        lag,
    }
}

/// The lag (a length) by which the solvers' kernel of a body of creep compliance
/// `series` on cells of side `cell` at `velocity` shifts the slider: the contact
/// problem reads the slider's height at `f - lag df/dx` (module documentation,
/// "creep shorter than a cell"). 0 when no branch creeps over less than
/// two cells.
pub fn creep_lag(series: &CreepSeries, cell: f64, velocity: f64) -> f64 {
    solvers_branches(series, cell, velocity).lag * cell
}

/// The weight `sum_k w_k` (compliance units) of the upwind correction
/// `w (W(x) - W(x + h))` that the solvers' kernels add to the exact ones (module
/// documentation, "The solvers' kernel: leading-edge damping"), for cells of side
/// `cell` at the sliding speed `velocity`: 0 when no branch creeps. Branches whose
/// creep length lies below the relaxed limit count in the cell's own response as
/// glassy compliance does.
pub fn leading_edge_damping(series: &CreepSeries, cell: f64, velocity: f64) -> f64 {
    let (instantaneous, creeping) = split_branches(series, cell, velocity);
    let (mut own, mut weight) = (0.0, 0.0);
    for (compliance, lambda) in creeping {
        let x = 1.0 / lambda;
        // 1 - b and b - a = b (1 - b) without cancellation for long lengths.
        let rise = -(-0.5 * x).exp_m1();
        own += rise * compliance;
        weight += damping_share(lambda) * (1.0 - rise) * rise * (-2.0 * x).exp() * compliance;
    }
    if weight == 0.0 {
        return 0.0;
    }
    own / (instantaneous + own) * weight
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
    sliding_kernel(series, cell, nx, ny, velocity, Solvers::Exact)
}

/// Which kernel [`sliding_kernel`] builds.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Solvers {
    /// The exact kernel ([`steady_sliding_kernel`]).
    Exact,
    /// The solvers' kernel (module documentation, "The solvers' kernel"): the
    /// leading-edge damping added, and with `lag` the creep shorter than a cell
    /// left to the gap.
    Kernel { lag: bool },
}

/// [`steady_sliding_kernel`] or the solvers' kernel, both from one table of Love's
/// kernel.
fn sliding_kernel(
    series: &CreepSeries,
    cell: f64,
    nx: usize,
    ny: usize,
    velocity: f64,
    solvers: Solvers,
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
    let (elastic, creeping) = if solvers == (Solvers::Kernel { lag: true }) {
        let b = solvers_branches(series, cell, velocity);
        (b.elastic, b.creeping)
    } else {
        split_branches(series, cell, velocity)
    };
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
    // Love's kernel one offset wider than the window: the damping reads the
    // upstream neighbour of the last offset.
    let wide = nx + 1;
    let love = homogeneous_surface_kernel_quadrant(unit, cell, wide, ny);
    let mut out = vec![0.0; width * ny];
    for dj in 0..ny {
        for di in 0..width {
            let i = di.abs_diff(nx - 1);
            out[dj * width + di] = elastic * love[dj * wide + i];
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
    let damping = if solvers != Solvers::Exact {
        leading_edge_damping(series, cell, velocity)
    } else {
        0.0
    };
    if damping > 0.0 {
        // w (W(x) - W(x + h)) with W Love's response per unit compliance.
        for (dj, row) in out.chunks_exact_mut(width).enumerate() {
            let love_row = &love[dj * wide..(dj + 1) * wide];
            for (k, value) in row.iter_mut().enumerate() {
                let di = k as i64 - (nx as i64 - 1);
                let here = love_row[di.unsigned_abs() as usize];
                let upstream = love_row[(di + 1).unsigned_abs() as usize];
                *value += damping * (here - upstream);
            }
        }
    }
    Ok(out)
}

/// The steady-sliding plane-strain (line contact) kernel of a viscoelastic
/// half-space on `nx` cells of width `cell` along x, each loaded uniformly along
/// y: `[di + nx - 1]` is the normal surface displacement at the centre of the
/// cell `di` cells away from a cell under unit pressure (`di > 0`: the field
/// point is upstream), `-(nx - 1) <= di <= nx - 1`, measured against the surface
/// at distance `reference` from the load for the relaxed compliance: `K(X) = J_g
/// g(X) + sum_k J_k (1 / l_k) int_0^inf exp(-u / l_k) g(X + u) du` with `g` the
/// elastic strip kernel (module documentation, "Line contacts", for the
/// derivation, the limits and the level at high speed). Units as
/// [`steady_sliding_kernel`]'s; `reference` in the length unit of `cell`.
pub fn steady_sliding_line_kernel(
    series: &CreepSeries,
    cell: f64,
    nx: usize,
    velocity: f64,
    reference: f64,
) -> Result<Vec<f64>> {
    line_kernel(series, cell, nx, velocity, reference, false)
}

/// [`steady_sliding_line_kernel`], or with `lag` the solvers' kernel without its
/// damping (module documentation, "creep shorter than a cell").
fn line_kernel(
    series: &CreepSeries,
    cell: f64,
    nx: usize,
    velocity: f64,
    reference: f64,
    lag: bool,
) -> Result<Vec<f64>> {
    series.validate()?;
    if !(cell.is_finite() && cell > 0.0) {
        return Err(invalid("cell", cell, "a finite length > 0"));
    }
    if velocity.is_nan() || velocity < 0.0 {
        return Err(invalid("velocity", velocity, "a speed >= 0 (+inf allowed)"));
    }
    if nx == 0 {
        return Err(Error::InvalidValue {
            field: "grid".into(),
            value: "0 cells".into(),
            allowed: "at least one cell".into(),
        });
    }
    if !(reference.is_finite() && reference > 0.0) {
        return Err(invalid("reference", reference, "a finite length > 0"));
    }
    // Relaxed, creeping over lambda cells, or beyond 1e100 cells (a constant).
    let (elastic, creeping) = if lag {
        let b = solvers_branches(series, cell, velocity);
        (b.elastic, b.creeping)
    } else {
        split_branches(series, cell, velocity)
    };
    let (mut level, mut beyond) = (0.0, 0.0);
    for b in &series.branches {
        let lambda = velocity * b.retardation_time / cell;
        if b.compliance > 0.0 && lambda.is_finite() && lambda > 1.0 / LAMBDA_FLOOR {
            level += b.compliance * (lambda.ln() - EULER_GAMMA);
            beyond += b.compliance;
        }
    }
    let total = elastic + creeping.iter().map(|&(j, _)| j).sum::<f64>() + beyond;
    if elastic == 0.0 && creeping.is_empty() {
        return Err(invalid(
            "velocity",
            velocity,
            "a speed at which some compliance creeps (the body has no glassy compliance)",
        ));
    }
    let n_lo = nx - 1;
    let x_top = n_lo.max(4);
    let (nodes, bary) = panel_nodes();
    let strip = |x: f64| super::line::strip_log_integral(x, 0.5);
    // table[(k - 1) * n + m] = I(k + t_m), 1 <= k < x_top.
    let table: Vec<f64> = (1..x_top)
        .into_par_iter()
        .flat_map_iter(|k| nodes.iter().map(move |t| strip(k as f64 + t)))
        .collect();
    // The half panels starting at -1, -1/2, 0, 1/2, the edge singularity removed.
    let half_values: Vec<Vec<f64>> = [-1.0, -0.5, 0.0, 0.5]
        .iter()
        .map(|&c: &f64| {
            nodes
                .iter()
                .map(|t| {
                    let x = c + 0.5 * t;
                    if c < 0.0 {
                        strip(x) - (x + 0.5) * (x + 0.5).abs().ln()
                    } else {
                        strip(x) + (x - 0.5) * (x - 0.5).abs().ln()
                    }
                })
                .collect()
        })
        .collect();
    // sum_k J_k (c_k + (N_k - c_k)) over the creeping branches.
    let averaged = creeping
        .par_iter()
        .map(|&(compliance, lambda)| {
            let weights = BranchWeights::panels(compliance, lambda, &nodes, &bary);
            line_branch(&weights, lambda, &table, &half_values, n_lo, x_top)
        })
        .reduce(
            || vec![0.0; 2 * nx - 1],
            |mut a, b| {
                a.iter_mut().zip(&b).for_each(|(x, y)| *x += y);
                a
            },
        );
    let datum = (reference / cell).ln();
    let scale = 2.0 * cell / PI;
    Ok(averaged
        .iter()
        .enumerate()
        .map(|(i, a)| {
            let x = i as f64 - n_lo as f64;
            scale * (total * datum - elastic * strip(x) - level - a)
        })
        .collect())
}

/// `J_k N_k(X)` of one creeping branch at `X = -n_lo..=n_lo` (cell units), by the
/// panel recursion on `N - c` from the tail at `x_top` (module documentation,
/// "Line contacts"). `table[(k - 1) * n + m] = I(k + t_m)`, `half_values` the
/// edge-subtracted `I` on the four half panels from -1 to 1.
fn line_branch(
    b: &BranchWeights,
    lambda: f64,
    table: &[f64],
    half_values: &[Vec<f64>],
    n_lo: usize,
    x_top: usize,
) -> Vec<f64> {
    let n = b.unit.len();
    let c = (lambda.ln() - EULER_GAMMA).max(0.0);
    let unit_mass = -(-1.0 / lambda).exp_m1();
    let half_mass = -(-0.5 / lambda).exp_m1();
    let dot = |w: &[f64], v: &[f64]| -> f64 { w.iter().zip(v).map(|(a, b)| a * b).sum() };
    let unit = |a: i64| -> f64 {
        let s = if a >= 1 {
            let k = a as usize;
            dot(&b.unit, &table[(k - 1) * n..k * n])
        } else {
            // I is even: the panel [a, a + 1] is [-a - 1, -a] mirrored.
            let k = (-a - 1) as usize;
            dot(&b.unit_reversed, &table[(k - 1) * n..k * n])
        };
        s - c * unit_mass
    };
    let half = |p: usize| -> f64 {
        // Panels ending at -1/2 / starting at -1/2 / ending at 1/2 / starting at
        // 1/2: the edge terms (t - 1/2) ln(1/2 - t), t ln t with their signs.
        let singular = match p {
            0 => b.singular_end,
            1 => b.singular_start,
            2 => -b.singular_end,
            _ => -b.singular_start,
        };
        dot(&b.half, &half_values[p]) + singular - c * half_mass
    };
    let (n_lo, x_top) = (n_lo as i64, x_top as i64);
    let mut m = line_tail(x_top as f64, lambda, c);
    let mut out = vec![0.0; (2 * n_lo + 1) as usize];
    if x_top == n_lo {
        out[(2 * n_lo) as usize] = m;
    }
    for i in (-n_lo..x_top).rev() {
        if i == 0 || i == -1 {
            let p = (i + 1) as usize * 2;
            m = half(p + 1) + b.decay_half * m;
            m = half(p) + b.decay_half * m;
        } else {
            m = unit(i) + b.decay_unit * m;
        }
        if i <= n_lo {
            out[(i + n_lo) as usize] = m;
        }
    }
    out.iter().map(|v| b.compliance * (c + v)).collect()
}

/// `N(x) - c` with `N(x) = (1 / lambda) int_0^inf exp(-u / lambda) I(x + u) du` for
/// `x >= 4` from the strip's far-field series (module documentation, "Line
/// contacts"), `c` either 0 or `ln(lambda) - gamma`. The logarithm of `phi` is
/// taken out in closed form, `phi(beta) = ln(1 + 1 / beta) + int_0^1 expm1(-v) dv
/// / (beta + v) + int_1^inf exp(-v) dv / (beta + v)`, so that `ln x + phi - c`
/// (`ln(x + lambda) - c + ...`) is summed without cancellation for long creep
/// lengths.
fn line_tail(x: f64, lambda: f64, c: f64) -> f64 {
    let gl = GaussLegendre::new(RULE_POINTS);
    let beta = x / lambda;
    let mut breaks: Vec<f64> = (0..=EXP_CUTOFF as usize).map(|v| v as f64).collect();
    let ratio = 2f64.powf(0.25);
    let mut w = beta * ratio;
    while w - beta < EXP_CUTOFF {
        breaks.push(w - beta);
        w *= ratio;
    }
    breaks.sort_by(f64::total_cmp);
    breaks.dedup();
    let mut phi = 0.0;
    let mut eps = [0.0; STRIP_FAR_TERMS];
    for p in breaks.windows(2) {
        let (half, mid) = (0.5 * (p[1] - p[0]), 0.5 * (p[1] + p[0]));
        for (t, wt) in gl.nodes.iter().zip(&gl.weights) {
            let v = mid + half * t;
            let weight = wt * half * (-v).exp();
            phi += if p[1] <= 1.0 {
                wt * half * (-v).exp_m1()
            } else {
                weight
            } / (beta + v);
            let r = beta / (beta + v);
            let r2 = r * r;
            let mut power = 1.0;
            for e in eps.iter_mut() {
                power *= r2;
                *e += weight * power;
            }
        }
    }
    let q = 0.25 / (x * x);
    let mut coefficient = 1.0;
    let mut series = 0.0;
    for (m, e) in eps.iter().enumerate() {
        coefficient *= q;
        let two_m = 2.0 * (m + 1) as f64;
        series += coefficient / (two_m * (two_m + 1.0)) * e;
    }
    // ln x + ln(1 + 1 / beta) = ln(x + lambda).
    let logarithm = if c > 0.0 {
        beta.ln_1p() + EULER_GAMMA + (lambda.ln() - EULER_GAMMA - c)
    } else {
        (x + lambda).ln()
    };
    logarithm + phi - series
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

/// `x ln x`, continued by its limit 0 at `x = 0`.
fn x_ln_x(x: f64) -> f64 {
    if x > 0.0 {
        x * x.ln()
    } else {
        0.0
    }
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
        let tail = tail_moments(&gl, x_top / lambda)
            .iter()
            .map(|m| m / lambda)
            .collect();
        BranchWeights {
            tail,
            ..BranchWeights::panels(compliance, lambda, nodes, bary)
        }
    }

    /// Everything but the tail (left empty): the product weights, decays and
    /// singular scalars of the panels.
    fn panels(compliance: f64, lambda: f64, nodes: &[f64], bary: &[f64]) -> Self {
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
        // The graded pieces at the end reach widths of 1e-14, where a node can round
        // onto the end itself (0 ln 0, a NaN, for creep lengths near 0.011 and 0.019
        // cells): the integrand's limit there is 0.
        let singular_start = exp_weighted_rule(&gl, lambda, 0.5, true, false)
            .iter()
            .map(|(t, w)| w * x_ln_x(*t))
            .sum();
        let singular_end = exp_weighted_rule(&gl, lambda, 0.5, false, true)
            .iter()
            .map(|(t, w)| w * -x_ln_x(0.5 - t))
            .sum();
        BranchWeights {
            compliance,
            unit,
            unit_reversed,
            half,
            decay_unit: (-1.0 / lambda).exp(),
            decay_half: (-0.5 / lambda).exp(),
            singular_start,
            singular_end,
            tail: Vec::new(),
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

/// The Gauss–Legendre nodes of a panel on `[0, 1]` and their barycentric weights.
fn panel_nodes() -> (Vec<f64>, Vec<f64>) {
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
    (nodes, bary)
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
        let (nodes, bary) = panel_nodes();
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
    fn the_solvers_kernel_adds_the_upwind_damping_to_the_exact_one() {
        // Module documentation, "The solvers' kernel": w (L(X) - L(X + 1)) per unit
        // compliance added to the exact kernel, X + 1 the field point's upstream
        // neighbour, w = kappa s (b - a) exp(-2x) J for one branch, kappa 0.1 up to 4
        // cells of creep, 0.3 from 16, a smooth step in ln lambda between.
        let (glassy, compliance) = (1e-3, 1.0);
        let (cell, nx, ny) = (1.0, 6, 3);
        let t = (10.0f64 / 4.0).ln() / 4.0f64.ln();
        let between = 0.1 + 0.2 * t * t * (3.0 - 2.0 * t);
        for (lambda, kappa) in [
            (2.0, 0.1),
            (4.0, 0.1),
            (16.0, 0.3),
            (40.0, 0.3),
            (10.0, between),
        ] {
            let creep = series(glassy, &[(compliance, lambda)]);
            let x = 1.0 / lambda;
            let (a, b) = ((-x).exp(), (-x / 2.0).exp());
            let share = (1.0 - b) * compliance / (glassy + (1.0 - b) * compliance);
            let w = kappa * share * (b - a) * (-2.0 * x).exp() * compliance;
            let damping = leading_edge_damping(&creep, cell, 1.0);
            assert!((damping / w - 1.0).abs() < 1e-12, "{lambda}: {damping} {w}");
        }
        let lambda = 10.0;
        let body = ViscoelasticBody {
            creep: series(glassy, &[(compliance, lambda)]),
            poisson: 0.0,
            references: Vec::new(),
        };
        let w = leading_edge_damping(&body.creep, cell, 1.0);
        let exact = steady_sliding_kernel(&body.creep, cell, nx, ny, 1.0).unwrap();
        let SurfaceKernel::EvenInY { half, .. } =
            body.surface_kernel(cell, nx, ny, 1.0, false).unwrap()
        else {
            panic!("a creeping body's kernel is not even in x")
        };
        let width = 2 * nx - 1;
        for dj in 0..ny {
            for di in -(nx as i64 - 1)..nx as i64 {
                let k = dj * width + (di + nx as i64 - 1) as usize;
                let love = |d: i64| super::love(d as f64, dj as f64);
                let expected = w * (love(di) - love(di + 1));
                let added = half[k] - exact[k];
                assert!(
                    (added - expected).abs() < 1e-12 * w,
                    "({di}, {dj}): {added} against {expected}"
                );
            }
        }
        // The line kernel: the strip's response in place of Love's.
        let reference = 100.0;
        let exact = steady_sliding_line_kernel(&body.creep, cell, nx, 1.0, reference).unwrap();
        let SurfaceKernel::EvenInY { half, .. } =
            body.line_kernel(cell, nx, 1.0, reference, false).unwrap()
        else {
            panic!("a creeping body's line kernel is not even in x")
        };
        for di in -(nx as i64 - 1)..nx as i64 {
            let k = (di + nx as i64 - 1) as usize;
            let strip = |d: i64| crate::body::line::strip_displacement(d as f64, cell, reference);
            let expected = w * (strip(di) - strip(di + 1));
            let added = half[k] - exact[k];
            assert!(
                (added - expected).abs() < 1e-12 * w,
                "line {di}: {added} against {expected}"
            );
        }
        // No damping where nothing creeps, and none left for a glassy body.
        assert_eq!(leading_edge_damping(&body.creep, cell, 0.0), 0.0);
        assert_eq!(leading_edge_damping(&body.creep, cell, f64::INFINITY), 0.0);
        let stiff = series(1e3, &[(compliance, lambda)]);
        assert!(leading_edge_damping(&stiff, cell, 1.0) < 1e-3 * w);
    }

    #[test]
    fn every_creep_length_gives_a_finite_kernel() {
        // Creep lengths near 0.011 and 0.019 cells once put a node of the edge
        // singularity's graded rule onto the panel's end (0 ln 0) and made the loaded
        // row downstream of the load NaN: a fractional Zener body, whose branches
        // spread over 40 decades of times, met one at most speeds. Every length from
        // 1e-3 to 1e3 cells on a fine logarithmic grid (those among them), point and
        // line kernels, and the values near the old failures against brute force.
        for k in 0..=1200 {
            let lambda = 10f64.powf(-3.0 + 6.0 * k as f64 / 1200.0);
            let s = series(0.1, &[(1.0, lambda)]);
            let point = steady_sliding_kernel(&s, 1.0, 6, 2, 1.0).unwrap();
            let line = steady_sliding_line_kernel(&s, 1.0, 6, 1.0, 100.0).unwrap();
            assert!(
                point.iter().chain(&line).all(|v| v.is_finite()),
                "creep length {lambda} cells"
            );
        }
        for lambda in [
            0.010964781961431828,
            0.0181970085860999,
            0.019054607179632522,
        ] {
            let s = series(0.0, &[(1.0, lambda)]);
            let point = steady_sliding_kernel(&s, 1.0, 4, 1, 1.0).unwrap();
            for di in -3..=3i64 {
                let value = point[(di + 3) as usize];
                let reference = brute_force(di as f64, 0.0, lambda);
                assert!(
                    (value - reference).abs() < 1e-12 * reference.abs().max(1.0),
                    "creep length {lambda}, offset {di}: {value} against {reference}"
                );
            }
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

    // ---- Line contacts (plane strain) ----

    use crate::body::line::{homogeneous_line_kernel, strip_displacement};

    /// `(1 / lambda) int_0^inf exp(-u / lambda) g(X + u) du` with the strip kernel
    /// `g = strip_displacement(., 1, reference)` of a unit cell, by adaptive
    /// Gauss–Legendre: pieces graded geometrically from `u = 0` (the weight's
    /// scale lambda, the logarithm's scale 1) and toward the strip's edges `X + u =
    /// -+1/2` (log-singular slopes), cut at `60 lambda` (`exp(-60)` = 9e-27).
    fn line_brute_force(x: f64, lambda: f64, reference: f64) -> f64 {
        let gl = GaussLegendre::new(20);
        let f =
            move |u: f64| (-u / lambda).exp() / lambda * strip_displacement(x + u, 1.0, reference);
        let end = 60.0 * lambda;
        let mut breaks = vec![0.0, end];
        let mut t = 1e-3 * lambda.min(1.0);
        while t < end {
            breaks.push(t);
            t *= 2.0;
        }
        for edge in [-0.5, 0.5] {
            let u = edge - x;
            if u > 0.0 && u < end {
                breaks.push(u);
                for k in 1..45 {
                    let d = 0.5f64.powi(k).min(0.25 * u);
                    breaks.push(u - d);
                    breaks.push(u + d);
                }
            }
        }
        breaks.retain(|&b| (0.0..=end).contains(&b));
        breaks.sort_by(f64::total_cmp);
        breaks.dedup();
        let mut sum = 0.0;
        for p in breaks.windows(2) {
            let whole = gl.integrate(p[0], p[1], f);
            sum += adaptive(&gl, &f, p[0], p[1], whole, 1e-17, 40);
        }
        sum
    }

    fn line_at(k: &[f64], nx: usize, di: i64) -> f64 {
        k[(di + nx as i64 - 1) as usize]
    }

    /// The worst error of the line kernel of one branch (J_g = 0, J_1 = 1, cell
    /// `cell`) against the brute force at `offsets`, over the kernel's peak.
    fn line_brute_force_error(
        nx: usize,
        cell: f64,
        lambda: f64,
        reference: f64,
        offsets: &[i64],
        tol: f64,
    ) -> f64 {
        let s = series(0.0, &[(1.0, 1.0)]);
        let k = steady_sliding_line_kernel(&s, cell, nx, lambda * cell, reference).unwrap();
        let peak = max_abs(&k);
        let mut worst = 0.0f64;
        for &di in offsets {
            let got = line_at(&k, nx, di);
            let want = cell * line_brute_force(di as f64, lambda, reference / cell);
            let err = (got - want).abs() / peak;
            worst = worst.max(err);
            assert!(
                err < tol,
                "nx {nx} lambda {lambda} di {di}: {got} vs {want}, {err:.1e}"
            );
        }
        worst
    }

    #[test]
    fn line_kernel_matches_brute_force_for_every_creep_length() {
        let offsets: Vec<i64> = (-8..=8).collect();
        let mut worst = 0.0f64;
        for lambda in [1e-6, 1e-4, 0.003, 0.1, 0.5, 1.0, 7.0, 300.0, 1e4, 1e6, 1e9] {
            let e = line_brute_force_error(9, 1.0, lambda, 20.0, &offsets, 1e-12);
            eprintln!("line brute force lambda {lambda:e}: {e:.2e} of the peak");
            worst = worst.max(e);
        }
        // Another cell and datum.
        for lambda in [0.02, 3.0, 5e3] {
            worst = worst.max(line_brute_force_error(
                5,
                0.25,
                lambda,
                0.1,
                &[-4, -1, 0, 1, 4],
                1e-12,
            ));
        }
        eprintln!("line brute force: worst {worst:.2e} of the peak");
    }

    #[test]
    fn line_kernel_far_offsets_match_brute_force() {
        // The far tail |X| >> l of a 2,000-cell grid (the recursion runs longest,
        // downstream points carry the wake) and |X| << l.
        let offsets = [-1999, -1000, -50, -2, 0, 3, 50, 1000, 1999];
        let mut worst = 0.0f64;
        for lambda in [0.01, 3.0, 1e5] {
            let e = line_brute_force_error(2000, 1.0, lambda, 50.0, &offsets, 1e-12);
            eprintln!("line far offsets lambda {lambda:e}: {e:.2e} of the peak");
            worst = worst.max(e);
        }
    }

    /// `(1 / pi) Re int_0^inf (2 J(k) / k) (2 sin(k / 2) / k) (e^{ikX} - e^{ikX'}) dk`
    /// (cell units) with `J` from `surface_compliance`: composite Gauss–Legendre,
    /// geometric pieces below k = 1, pieces shorter than a quarter period of the
    /// oscillation above, cut at `k_max`.
    fn line_fourier_difference(
        body: &ViscoelasticBody,
        v: f64,
        x: f64,
        x2: f64,
        k_max: f64,
    ) -> f64 {
        let gl = GaussLegendre::new(16);
        let f = |k: f64| {
            let j = body.surface_compliance(k, v).unwrap();
            // e^{ikX} - e^{ikX'} without cancellation at small k.
            let (a, b) = (0.5 * k * (x + x2), 0.5 * k * (x - x2));
            let diff = realfft::num_complex::Complex::new(
                -2.0 * a.sin() * b.sin(),
                2.0 * a.cos() * b.sin(),
            );
            let strip = if k < 1e-4 {
                1.0 - k * k / 24.0
            } else {
                2.0 * (0.5 * k).sin() / k
            };
            (j * 2.0 / k * strip * diff).re / PI
        };
        let mut sum = 0.0;
        let mut lo = 1e-12;
        sum += gl.integrate(0.0, lo, f);
        while lo < 1.0 {
            let hi = (2.0 * lo).min(1.0);
            sum += gl.integrate(lo, hi, f);
            lo = hi;
        }
        let step = 0.5 * PI / (x.abs().max(x2.abs()) + 1.0);
        let mut k = 1.0;
        while k < k_max {
            sum += gl.integrate(k, k + step, f);
            k += step;
        }
        sum
    }

    #[test]
    fn line_kernel_differences_match_the_fourier_route() {
        let nx = 8;
        let mut worst = 0.0f64;
        for lambda in [0.2, 1.0, 30.0, 1e4] {
            let body = ViscoelasticBody {
                creep: series(0.0, &[(1.0, 2.0)]),
                poisson: 0.3,
                references: Vec::new(),
            };
            let v = lambda / 2.0;
            let k = steady_sliding_line_kernel(&body.creep, 1.0, nx, v, 7.0).unwrap();
            let peak = max_abs(&k);
            for (x, x2) in [(1, 0), (-1, 0), (-3, 2), (5, -5), (-7, 7)] {
                let got = line_at(&k, nx, x) - line_at(&k, nx, x2);
                let want = line_fourier_difference(&body, v, x as f64, x2 as f64, 2e4);
                let err = (got - want).abs() / peak;
                worst = worst.max(err);
                assert!(
                    err < 1e-11,
                    "lambda {lambda} ({x}, {x2}): {got} vs {want}, {err:.1e}"
                );
            }
        }
        eprintln!("line kernel vs Fourier route: worst {worst:.2e} of the peak");
    }

    #[test]
    fn line_kernel_speed_limits() {
        let (cell, nx, reference) = (0.5, 10, 30.0);
        let s = series(0.3, &[(0.5, 2.0), (0.2, 0.01), (0.4, f64::INFINITY)]);
        let elastic = homogeneous_line_kernel(1.0, cell, nx, reference);
        let peak = max_abs(&elastic);
        let body = ViscoelasticBody {
            creep: s.clone(),
            poisson: 0.3,
            references: Vec::new(),
        };
        // V = 0: relaxed (1.0, the frozen branch never creeps); V = inf: glassy.
        for (v, j) in [(0.0, 1.0), (f64::INFINITY, 0.3)] {
            match body.line_kernel(cell, nx, v, reference, false).unwrap() {
                SurfaceKernel::Even { quadrant, nx: n } => {
                    assert_eq!((n, quadrant.len()), (nx, nx));
                    for d in 0..nx {
                        assert!(
                            (quadrant[d] - j * elastic[d]).abs() < 1e-14 * peak,
                            "V {v} d {d}"
                        );
                    }
                }
                other => panic!("V {v}: {other:?}"),
            }
        }
        match body.line_kernel(cell, nx, 1.0, reference, false).unwrap() {
            SurfaceKernel::EvenInY { half, nx: n } => assert_eq!((n, half.len()), (nx, 2 * nx - 1)),
            other => panic!("{other:?}"),
        }
        // Near the limits through the quadrature. lambda = 1e-9 cell: first order
        // N = I + lambda I', I' = ln|X + 1/2| - ln|X - 1/2|.
        let one = series(0.3, &[(0.7, 1.0)]);
        let lam = 1e-9;
        let k = steady_sliding_line_kernel(&one, cell, nx, lam * cell, reference).unwrap();
        let mut err = 0.0f64;
        for di in -(nx as i64 - 1)..nx as i64 {
            let x = di as f64;
            let slope = ((x + 0.5).abs() / (x - 0.5).abs()).ln();
            let want = elastic[di.unsigned_abs() as usize] - 2.0 * cell / PI * 0.7 * lam * slope;
            err = err.max((line_at(&k, nx, di) - want).abs() / peak);
        }
        eprintln!("line lambda = 1e-9 against J_r g + first order: {err:.2e} of the peak");
        assert!(err < 1e-14, "{err}");
        // lambda = 1e12 windows and beyond 1e100 cells: J_g g plus the level
        // (2 h / pi) J_k (ln(L / (h lambda)) + gamma), the neglected terms of order
        // (X / lambda) ln(lambda / X).
        for (lam, tol) in [
            (1e13, 1e-10),
            (1e60, 1e-14),
            (1e99, 1e-14),
            (1e101, 1e-14),
            (1e250, 1e-14),
        ] {
            let k = steady_sliding_line_kernel(&one, cell, nx, lam * cell, reference).unwrap();
            let level = 2.0 * cell / PI * 0.7 * ((reference / (cell * lam)).ln() + EULER_GAMMA);
            let mut err = 0.0f64;
            for di in -(nx as i64 - 1)..nx as i64 {
                let want = 0.3 * elastic[di.unsigned_abs() as usize] + level;
                err = err.max((line_at(&k, nx, di) - want).abs() / max_abs(&k));
            }
            eprintln!("line lambda = {lam:e}: {err:.2e} of the peak from J_g g + level");
            assert!(err < tol, "lambda {lam}: {err}");
        }
        // Relaxed side: 1e-90 and 1e-101 cells.
        for lam in [1e-90, 1e-101] {
            let k = steady_sliding_line_kernel(&one, cell, nx, lam * cell, reference).unwrap();
            for di in -(nx as i64 - 1)..nx as i64 {
                let want = elastic[di.unsigned_abs() as usize];
                assert!(
                    (line_at(&k, nx, di) - want).abs() < 1e-14 * peak,
                    "{lam} {di}"
                );
            }
        }
    }

    #[test]
    fn line_kernel_branches_superpose() {
        let (cell, nx, v, reference) = (0.3, 7, 2.0, 4.0);
        let all = series(
            0.2,
            &[
                (0.3, 1e-120),
                (0.5, 0.4),
                (0.7, 1e120),
                (0.9, f64::INFINITY),
            ],
        );
        let k = steady_sliding_line_kernel(&all, cell, nx, v, reference).unwrap();
        let elastic = homogeneous_line_kernel(1.0, cell, nx, reference);
        let creeping =
            steady_sliding_line_kernel(&series(0.0, &[(0.5, 0.4)]), cell, nx, v, reference)
                .unwrap();
        let lam = v * 1e120 / cell;
        let level = 2.0 * cell / PI * 0.7 * ((reference / (cell * lam)).ln() + EULER_GAMMA);
        let peak = max_abs(&k);
        for di in -(nx as i64 - 1)..nx as i64 {
            let want =
                0.5 * elastic[di.unsigned_abs() as usize] + line_at(&creeping, nx, di) + level;
            assert!((line_at(&k, nx, di) - want).abs() < 1e-14 * peak, "{di}");
        }
    }

    #[test]
    fn line_kernel_tail_agrees_with_the_recursion() {
        // The same offsets from a small grid (tail from X = 4) and a wide one
        // (recursion through them from X = 80).
        let mut worst = 0.0f64;
        for lambda in [1e-6, 0.003, 0.7, 12.0, 1e4, 1e9] {
            let s = series(0.1, &[(1.0, 1.0)]);
            let small = steady_sliding_line_kernel(&s, 1.0, 3, lambda, 9.0).unwrap();
            let wide = steady_sliding_line_kernel(&s, 1.0, 81, lambda, 9.0).unwrap();
            let peak = max_abs(&wide);
            for di in -2i64..=2 {
                let (a, b) = (line_at(&small, 3, di), line_at(&wide, 81, di));
                worst = worst.max((a - b).abs() / peak);
                assert!(
                    (a - b).abs() < 1e-13 * peak,
                    "lambda {lambda} {di}: {a} vs {b}"
                );
            }
        }
        eprintln!("line tail vs recursion: worst {worst:.2e} of the peak");
    }

    #[test]
    fn line_kernel_bad_input_names_the_field() {
        let message = |s: &CreepSeries, cell: f64, nx: usize, v: f64, reference: f64| {
            steady_sliding_line_kernel(s, cell, nx, v, reference)
                .unwrap_err()
                .to_string()
        };
        let ok = series(0.1, &[(0.2, 1.0)]);
        assert!(message(&series(-0.1, &[]), 1.0, 3, 1.0, 1.0).starts_with("creep.glassy"));
        assert!(message(&series(0.1, &[(-1.0, 1.0)]), 1.0, 3, 1.0, 1.0)
            .starts_with("creep.branches[0].compliance"));
        assert!(message(&series(0.1, &[(0.2, 0.0)]), 1.0, 3, 1.0, 1.0)
            .starts_with("creep.branches[0].retardation_time"));
        assert!(
            message(&series(0.0, &[(1.0, 1.0)]), 1.0, 3, f64::INFINITY, 1.0)
                .starts_with("velocity")
        );
        assert!(message(&ok, 0.0, 3, 1.0, 1.0).starts_with("cell"));
        assert!(message(&ok, f64::INFINITY, 3, 1.0, 1.0).starts_with("cell"));
        assert!(message(&ok, 1.0, 3, -1.0, 1.0).starts_with("velocity"));
        assert!(message(&ok, 1.0, 3, f64::NAN, 1.0).starts_with("velocity"));
        assert!(message(&ok, 1.0, 0, 1.0, 1.0).starts_with("grid"));
        assert!(message(&ok, 1.0, 3, 1.0, 0.0).starts_with("reference = 0"));
        assert!(message(&ok, 1.0, 3, 1.0, f64::NAN).starts_with("reference"));
        assert!(message(&ok, 1.0, 3, 1.0, f64::INFINITY).starts_with("reference"));
        let body = ViscoelasticBody {
            creep: ok,
            poisson: 0.3,
            references: Vec::new(),
        };
        let e = body
            .line_kernel(1.0, 3, 1.0, -2.0, false)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("reference"), "{e}");
        // One cell works.
        assert!(body.line_kernel(1.0, 1, 1.0, 2.0, false).is_ok());
    }

    #[test]
    #[ignore = "timing: run with --ignored --nocapture"]
    fn line_kernel_timing_4096_cells_10_branches() {
        let branches: Vec<(f64, f64)> = (0..10).map(|k| (0.1, 10f64.powi(k - 4))).collect();
        let s = series(0.1, &branches);
        for _ in 0..5 {
            let start = std::time::Instant::now();
            let k = steady_sliding_line_kernel(&s, 1.0, 4096, 1.0, 1e4).unwrap();
            eprintln!(
                "line kernel, 4096 cells, 10 branches: {:?}",
                start.elapsed()
            );
            assert_eq!(k.len(), 8191);
        }
    }
}
