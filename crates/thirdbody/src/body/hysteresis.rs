//! The power dissipated in a linear viscoelastic half-space in steady sliding, as
//! a force `D / V`, from the surface pressure alone: for the Prony creep
//! compliance of [`super::viscoelastic`] (`J(t) = J_g + sum_k J_k (1 - exp(-t /
//! tau_k))`, constant Poisson ratio) it is the loss-compliance integral
//! `D / V = sum_k J_k int d^2k / (2 pi)^2 |p^(k)|^2 (2 / |k|) xi^2 l_k / (1 +
//! xi^2 l_k^2)`, `l_k = V tau_k`, `xi` the wavenumber along the sliding direction
//! (equation (H) below), evaluated for the bilinear interpolant of the cell-centre
//! pressures. It is the independent side of the energy balance `mu Q V = D`: the
//! solver's friction comes from the slider's slope, this from the body's loss.
//! [`line_dissipated_force`] is the same for a line contact (plane strain, the
//! loss per unit length; its derivation and method are in its documentation).
//!
//! # Derivation
//!
//! Frame and signs of [`super::viscoelastic`]: x is the sliding direction, body
//! material flows through the contact toward -x at speed V, `w > 0` into the body,
//! `p >= 0` compressive. Fourier transform `f^(k) = int f(x) exp(-i k.x) d^2x`,
//! `k = (xi, eta)`.
//!
//! *Kernel form.* The steady-sliding displacement is
//! `w = J_g W + sum_k (J_k / l_k) int_0^inf exp(-u / l_k) W(x + u, y) du` with
//! `W = L p`, `L` Love's operator per unit plane-strain compliance, whose Fourier
//! multiplier is `2 / |k|` (`L p = (1 / pi) int p / r`, and the 2-D transform of
//! `1 / r` is `2 pi / |k|`). A shift by `+u` multiplies by `exp(i xi u)`, so
//! `(1 / l) int_0^inf exp(-u / l) exp(i xi u) du = 1 / (1 - i xi l)` and
//! `w^ = J*(xi) (2 / |k|) p^` with `J*(xi) = J_g + sum_k J_k / (1 - i xi l_k)`:
//! the complex compliance `J_g + sum_k J_k / (1 + i omega tau_k)` at `omega = -xi V`
//! (Tschoegl, The Phenomenological Theory of Linear Viscoelastic Behavior, 1989:
//! `J*(omega) = J' - i J''`, `J''(omega) = sum_k J_k omega tau_k / (1 +
//! omega^2 tau_k^2)`).
//! The pressure does work on the moving surface at the rate
//! `D = int p (Dw / Dt) dA` with the material derivative `Dw / Dt = -V dw / dx`
//! (steady in the slider's frame, material moving at -V), so by Parseval
//! `D / V = -int p dw/dx dA = -int d^2k / (2 pi)^2 conj(p^) (i xi) w^`. Its real
//! part keeps `Re[i xi / (1 - i xi l)] = -xi^2 l / (1 + xi^2 l^2)` and the glassy
//! term drops out (`i xi` is odd); hence
//!
//! `(H)  D / V = sum_k J_k int d^2k / (2 pi)^2 |p^(k)|^2 (2 / |k|) g(xi, l_k)`,
//! `g(xi, l) = xi^2 l / (1 + xi^2 l^2) = |xi| J''(|xi| V) / J_k` per branch,
//!
//! the loss-compliance form of Persson's rubber friction (Persson, J. Chem. Phys.
//! 115, 3840, 2001, written with the compliance, the pressure being prescribed).
//!
//! *Dashpot form (a check of the constants).* Branch k is a Kelvin–Voigt element:
//! its strain obeys `tau_k e' + e = J_k (unit-compliance response to the stress)`;
//! with a constant Poisson ratio its strain field is `J_k` times the
//! unit-compliance elastic field of the lagged traction `q_k(x) = (1 / l_k)
//! int_0^inf exp(-u / l_k) p(x + u) du` (the traction the material point felt,
//! weighted by its memory). Its dashpot carries the stress `(tau_k / J_k) C_1 e'`
//! (`C_1` the unit-compliance stiffness), so it dissipates
//! `int e' : (tau_k / J_k) C_1 : e' dV = tau_k J_k int qdot_k L[qdot_k] dA`
//! (Clapeyron: the unit-compliance strain energy of a traction `t` is
//! `(1 / 2) int t L t`), `qdot_k = -V dq_k / dx`. With `q^ = p^ / (1 - i xi l)`
//! that is `tau_k J_k V^2 int |p^|^2 xi^2 / (1 + xi^2 l_k^2) (2 / |k|)`, and
//! divided by V it is (H) term by term. The limits: `l -> 0` gives
//! `J_k l_k int (dp/dx) L (dp/dx) dA` (viscous, proportional to the speed),
//! `l -> inf` gives `(J_k / l_k) int p L p dA` (each branch's elastic energy
//! dissipated once per passage over the length `l`).
//!
//! *One-dimensional form.* `g` depends on xi only, so
//! `D / V = sum_k J_k (2 / (2 pi)^2) int_0^inf g(xi, l_k) M(xi) dxi` with
//! `M(xi) = int |p^(xi, eta)|^2 (2 / |k|) d eta`, the elastic energy's density
//! over the sliding wavenumber (`M` is even; `int M dxi / (2 pi)^2 = int p L p`).
//! `M` does not depend on the branches: every branch and speed costs one sum over
//! the same `M` nodes.
//!
//! # The field integrated
//!
//! The solver's pressure is a value per cell. A piecewise-constant field has jumps
//! whose dissipation diverges like `ln(h / l)` as `l -> 0` (the jump's `|p^|^2 ~
//! xi^-2` makes `int xi^2 l / (1 + xi^2 l^2) xi^-2 d xi / |xi|` logarithmic up to
//! `xi ~ 1 / l`), so this module integrates the bilinear interpolant of the
//! cell-centre values, `p(x, y) = sum p_ij hat(x / h - i) hat(y / h - j)`, whose
//! transform is `h^2 sinc^2(xi h / 2) sinc^2(eta h / 2) S(xi, eta)` with the
//! trigonometric polynomial `S = sum p_ij exp(-i (xi i + eta j) h)`: the form
//! factor `sinc^4` per direction of `|p^|^2` makes every integral converge for
//! every `l`, and the result converges to the continuum value as the grid is
//! refined for every creep length (second order for a smooth pressure). The
//! spectrum is taken over the whole plane (the field's images of the Brillouin
//! zone included, three each side explicitly, beyond that along xi by the column
//! sums with `2 / |k| ~ 2 / |xi|`; along eta the zones beyond the third are cut,
//! measured 2e-5 of the result for a white-noise field and 2e-7 for a smooth one).
//! The integrand is exact: the only approximations are the quadratures below.
//!
//! # Numerical method
//!
//! Cell units (`h = 1`, `lambda = l / h`); `|S|^2` comes exactly from one 2-D FFT
//! of the grid zero-padded to `2 nx x 2 ny` (a trigonometric polynomial of degree
//! below the padding is fixed by those samples), lattice spacings
//! `d_xi = 2 pi / 2nx`, `d_eta = 2 pi / 2ny`, `d = max`. Two structures are
//! narrower than the lattice: the line `xi = 0`, where `g` has its Lorentzian of
//! width `1 / lambda` (for long creep lengths, down to 1e-9 of a lattice spacing:
//! the wake behind the window) and `M` its `ln|xi|` singularity; and the point
//! `k = 0` of `2 / |k|`, which makes the eta integral at small xi a peak of width
//! xi. They are handled as follows.
//!
//! * A smooth window `chi(xi) = (erf((xi + c) / s) - erf((xi - c) / s)) / 2`,
//!   `c = 18 d`, `s = 3 d` splits the xi integral. `(1 - chi) g M` is smooth (the
//!   window vanishes to 1e-17 on the line `xi = 0` and its transition is resolved,
//!   its transform at the aliasing distance being `exp(-(3 pi)^2 / 4)` = 3e-10 of
//!   the transition's share) and is summed by the trapezoid rule on the xi
//!   lattice over the whole line (images of the zone), with `M` there by the
//!   trapezoid rule on the eta lattice (error `exp(-pi xi / d_eta)`, below 1e-16
//!   once the window lets anything through).
//! * `chi g M` on `[0, 36 d]` is integrated by Gauss–Legendre on panels: panels of
//!   width `2 d_xi` (one period of `|S|^2` along xi) from `2 d_xi` up, and
//!   geometrically graded ones (ratio 2) below, down to `min(1e-3 d_xi, 1e-4 /
//!   lambda_max)` (not below 1e-60), which resolves every Lorentzian and the
//!   logarithm. At these nodes the row transforms
//!   `sigma_j(xi) = sum_i p_ij exp(-i xi (i - i_c))` are summed directly (by their
//!   Taylor series below `xi = 1 / (2 max|i - i_c|)`), transformed along y by one
//!   FFT, and `M(xi)` is the eta trapezoid sum after subtracting
//!   `T(eta) = P(eta) exp(-eta^2 / 2 s_g^2)`, `s_g = 4 d_eta`, whose polynomial
//!   `P` makes `T` match the even part of `|S|^2 sinc^4(eta / 2)` to order `eta^6`
//!   (its Taylor coefficients are products of the moments `sum_j sigma_j (j -
//!   j_c)^n`): the remainder behaves like `|eta|^7` at the peak, the odd part cancels
//!   exactly on the symmetric lattice, and `int T (2 / |k|) d eta` is added from
//!   `J_n(xi) = int eta^n exp(-eta^2 / 2 s_g^2) 2 / sqrt(xi^2 + eta^2) d eta`,
//!   computed by the trapezoid rule in `t` after `eta = xi sinh t` (a
//!   double-exponentially decaying integrand: error `exp(-pi^2 / 2 dt)`). Below
//!   `1e-4 d` the lattice part is taken at `xi = 0` (the neglected change is
//!   `O(xi^2 / d^2)`).
//!
//! # Square-root edges
//!
//! Where a slider presses the body directly, its pressure falls to zero like the
//! square root of the distance to the contact's edge, and the bilinear field of the
//! cell values misses it: the edge's strip of cells holds a share of the loss
//! of order `h ln(1 / h)` the interpolant does not have, which the viscous end (a
//! creep length below a cell, weighing the highest wavenumbers) feels most (on
//! Hertz's pressure at 128^2, 1.1 % low for a creep length of 0.05 cells).
//! [`dissipated_force_square_root_edges`] integrates instead the field `sqrt(max(0,
//! s))` with `s` the bilinear interpolant of the squared cell values, continued
//! below zero one cell beyond the contact (an unloaded cell next to two loaded ones
//! in a line along x, y or a diagonal takes the line's linear extrapolation where
//! it is negative; the mean over such lines): a Hertzian `s` is a quadratic, which
//! the interpolant nearly holds, so the field has the edge where it is and the
//! square root's shape. Where most such lines extrapolate to zero or above (the
//! pressure does not fall toward the cell: a jump, as at a glassy leading edge
//! whose glassy zone is far below a cell), or no line has two loaded cells, the
//! field between that cell and its neighbours is the bilinear one of the pressures
//! (the root of a ramp of squares would bulge there). It is sampled at the centres of cells `r` times finer (at
//! least 384 cells along the longer side; for creep lengths below a tenth of a cell,
//! where the loss gathers within a creep length of the edges, as many as fit in 768),
//! scaled to carry the cells' load, and
//! integrated as above; what remains is the finer grid's own edge error (Hertz at
//! 128^2, that creep length: 0.24 % on 640 cells, 0.37 % on 384). On a field without edges the root adds
//! `(h^2 / 8) p'^2 / p` to the interpolant's second-order error (the Gaussian's
//! error doubles). Creep lengths of 16 cells and more keep the bilinear field:
//! their loss lives at wavenumbers the edge barely reaches (the two agree to 1e-3).
//!
//! The cost is two FFT passes of the padded grid, the lattice sums of the window
//! (`~ 3.5 nx x 3.5 ny` square roots per column; the dominant term) and the near
//! nodes (~150 direct row transforms), shared by all branches; each branch is then
//! a sum over the nodes. Build a [`DissipationPlan`] once per grid size (its FFT
//! plans cost time to build; it is the caller's, never a `static`).

use super::quadrature::GaussLegendre;
use super::viscoelastic::CreepSeries;
use crate::error::{Error, Result};
use rayon::prelude::*;
use realfft::num_complex::Complex;
use realfft::{RealFftPlanner, RealToComplex};
use rustfft::{Fft, FftPlanner};
use std::f64::consts::PI;
use std::sync::Arc;

/// Images of the Brillouin zone kept explicitly on each side, per direction.
const IMAGES: usize = 3;
/// Further zones along xi summed with `2 / |k| ~ 2 / |xi|` (the column sums).
const TAIL_ZONES: usize = 64;
/// The window's transition width, in lattice spacings `d`.
const TRANSITION: f64 = 3.0;
/// The window's half width, in lattice spacings.
const WINDOW: f64 = 18.0;
/// End of the near range (the window is below 1e-17 there), in lattice spacings.
const NEAR_END: f64 = 36.0;
/// Gauss–Legendre points per panel of the near range.
const PANEL_NODES: usize = 8;
/// Terms of the Taylor series of the row transforms at small xi.
const TAYLOR_TERMS: usize = 24;
/// Width of the Gaussian of the subtracted part, in eta spacings.
const SUBTRACTION_WIDTH: f64 = 4.0;
/// The subtraction is used below this xi, in eta spacings (above it the plain
/// eta lattice is exact to `exp(-12 pi)`).
const SUBTRACTION_BELOW: f64 = 12.0;
/// Below this xi, in lattice spacings, the lattice part is taken at xi = 0.
const FROZEN_BELOW: f64 = 1e-4;
/// Step of the trapezoid rule in `t` for `J_n`.
const SINH_STEP: f64 = 0.1;

/// FFT plans and quadrature rules for one grid size. It costs time to build: the
/// caller owns it and reuses it for every pressure on that grid.
pub struct DissipationPlan {
    nx: usize,
    ny: usize,
    px: usize,
    py: usize,
    row: Arc<dyn RealToComplex<f64>>,
    column: Arc<dyn Fft<f64>>,
    rule: GaussLegendre,
}

impl std::fmt::Debug for DissipationPlan {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("DissipationPlan")
            .field("nx", &self.nx)
            .field("ny", &self.ny)
            .finish()
    }
}

impl DissipationPlan {
    /// The plan for pressures on `nx x ny` cells.
    pub fn new(nx: usize, ny: usize) -> Result<Self> {
        check_grid(nx, ny)?;
        let (px, py) = (2 * nx, 2 * ny);
        Ok(DissipationPlan {
            nx,
            ny,
            px,
            py,
            row: RealFftPlanner::<f64>::new().plan_fft_forward(px),
            column: FftPlanner::<f64>::new().plan_fft_forward(py),
            rule: GaussLegendre::new(PANEL_NODES),
        })
    }

    /// The grid `[nx, ny]` it is for.
    pub fn grid(&self) -> [usize; 2] {
        [self.nx, self.ny]
    }

    /// `M` at every node (cell units), for creep lengths up to `lambda_max` cells.
    fn energy_density(&self, pressure: &[f64], lambda_max: f64) -> EnergyDensity {
        let (nx, ny, px, py) = (self.nx, self.ny, self.px, self.py);
        let cols = px / 2 + 1;
        let dxi = 2.0 * PI / px as f64;
        let deta = 2.0 * PI / py as f64;
        let d = dxi.max(deta);
        let window = Window {
            centre: WINDOW * d,
            width: TRANSITION * d,
        };
        let near_end = NEAR_END * d;

        // |S|^2 on the lattice: row transforms, then column transforms.
        let mut sigma = vec![Complex::new(0.0, 0.0); cols * ny];
        let mut input = self.row.make_input_vec();
        let mut output = self.row.make_output_vec();
        let mut scratch = self.row.make_scratch_vec();
        for j in 0..ny {
            input.fill(0.0);
            input[..nx].copy_from_slice(&pressure[j * nx..(j + 1) * nx]);
            self.row
                .process_with_scratch(&mut input, &mut output, &mut scratch)
                .expect("buffers from the plan");
            for (a, v) in output.iter().enumerate() {
                sigma[a * ny + j] = *v;
            }
        }
        let scratch_len = self.column.get_inplace_scratch_len();
        let mut power = vec![0.0; cols * py];
        power.par_chunks_mut(py).enumerate().for_each_init(
            || {
                (
                    vec![Complex::new(0.0, 0.0); py],
                    vec![Complex::new(0.0, 0.0); scratch_len],
                )
            },
            |(buffer, scratch), (a, out)| {
                buffer.fill(Complex::new(0.0, 0.0));
                buffer[..ny].copy_from_slice(&sigma[a * ny..(a + 1) * ny]);
                self.column.process_with_scratch(buffer, scratch);
                for (o, b) in out.iter_mut().zip(buffer.iter()) {
                    *o = b.norm_sqr();
                }
            },
        );

        // The eta lattice over the whole line, images included.
        let m_max = (2 * IMAGES + 1) * py / 2;
        let etas: Vec<f64> = (0..=m_max).map(|m| m as f64 * deta).collect();
        let squares: Vec<f64> = etas.iter().map(|e| e * e).collect();
        let form: Vec<f64> = etas.iter().map(|&e| sinc4(e)).collect();
        let lattice = EtaLattice {
            py,
            deta,
            etas: &etas,
            squares: &squares,
            form: &form,
        };
        let paired: Vec<Vec<f64>> = (0..cols)
            .into_par_iter()
            .map(|c| lattice.paired(&power[c * py..(c + 1) * py]))
            .collect();

        // The window's outside: trapezoid rule on the xi lattice.
        let q_max = ((2 * IMAGES + 1) * px / 2).max(((near_end + 2.0 * PI) / dxi).ceil() as usize);
        let column = |q: usize| {
            let c = q % px;
            c.min(px - c)
        };
        let far: Vec<Node> = (1..=q_max)
            .into_par_iter()
            .filter_map(|q| {
                let xi = q as f64 * dxi;
                let outside = window.outside(xi);
                if outside < 1e-20 {
                    return None;
                }
                let m = sinc4(xi) * lattice.sum(&paired[column(q)], xi);
                Some(Node {
                    xi,
                    weight: outside * dxi,
                    density: m,
                })
            })
            .collect();
        // Beyond the kept images along xi: `2 / |k| ~ 2 / xi` times the column's
        // eta integral of `|S|^2 sinc^4`.
        let column_mass: Vec<f64> = paired
            .iter()
            .map(|v| deta * v.iter().sum::<f64>())
            .collect();
        let tail: Vec<Node> = (q_max + 1..=q_max + TAIL_ZONES * px)
            .map(|q| {
                let xi = q as f64 * dxi;
                Node {
                    xi,
                    weight: window.outside(xi) * dxi,
                    density: sinc4(xi) * 2.0 / xi * column_mass[column(q)],
                }
            })
            .collect();

        // The window's inside: graded Gauss–Legendre nodes.
        let xi_min = (1e-3 * dxi).min(1e-4 / lambda_max).max(1e-60);
        let panel = 2.0 * dxi;
        let mut panels = Vec::new();
        let mut lo = panel;
        while lo < near_end {
            panels.push((lo, lo + panel));
            lo += panel;
        }
        let mut hi = panel;
        while hi > xi_min {
            panels.push((0.5 * hi, hi));
            hi *= 0.5;
        }
        panels.push((0.0, hi));
        let mut nodes = Vec::with_capacity(panels.len() * PANEL_NODES);
        for (a, b) in panels {
            let (half, mid) = (0.5 * (b - a), 0.5 * (b + a));
            for (x, w) in self.rule.nodes.iter().zip(&self.rule.weights) {
                let xi = mid + half * x;
                let inside = 1.0 - window.outside(xi);
                nodes.push((xi, w * half * inside));
            }
        }
        let rows = RowTransforms::new(pressure, nx, ny);
        let sg = SUBTRACTION_WIDTH * deta;
        let frozen = NearState::new(self, &rows, &lattice, 0.0, sg);
        let near: Vec<Node> = nodes
            .into_par_iter()
            .map(|(xi, weight)| {
                let density = if xi < FROZEN_BELOW * d {
                    frozen.density(xi, sg)
                } else {
                    NearState::new(self, &rows, &lattice, xi, sg).density(xi, sg)
                };
                Node {
                    xi,
                    weight,
                    density,
                }
            })
            .collect();
        EnergyDensity { far, tail, near }
    }
}

/// One quadrature node of the xi integral: `weight * g(xi) * density`.
#[derive(Debug, Clone, Copy)]
struct Node {
    xi: f64,
    weight: f64,
    density: f64,
}

/// `M(xi)` with its quadrature weights (cell units).
struct EnergyDensity {
    far: Vec<Node>,
    tail: Vec<Node>,
    near: Vec<Node>,
}

impl EnergyDensity {
    /// `(2 / (2 pi)^2) int_0^inf g(xi, lambda) M(xi) dxi` (cell units).
    fn loss_integral(&self, lambda: f64) -> f64 {
        let sum: f64 = self
            .far
            .iter()
            .chain(&self.tail)
            .chain(&self.near)
            .map(|n| n.weight * loss_weight(n.xi, lambda) * n.density)
            .sum();
        2.0 * sum / (4.0 * PI * PI)
    }
}

/// The xi window `chi`.
#[derive(Debug, Clone, Copy)]
struct Window {
    centre: f64,
    width: f64,
}

impl Window {
    /// `1 - chi(xi)`, accurate where it is small.
    fn outside(&self, xi: f64) -> f64 {
        0.5 * (libm::erfc((xi + self.centre) / self.width)
            + libm::erfc((self.centre - xi) / self.width))
    }
}

/// The eta lattice over the whole line (`m d_eta`, `|m| <= m_max`).
struct EtaLattice<'a> {
    py: usize,
    deta: f64,
    etas: &'a [f64],
    /// `eta_m^2`.
    squares: &'a [f64],
    form: &'a [f64],
}

impl EtaLattice<'_> {
    /// `v[m] = (|S|^2(eta_m) + |S|^2(-eta_m)) sinc^4(eta_m / 2)` (`v[0]` once), `column`
    /// the lattice values of `|S(xi, .)|^2`.
    fn paired(&self, column: &[f64]) -> Vec<f64> {
        let py = self.py;
        let mut v = Vec::with_capacity(self.etas.len());
        v.push(column[0]);
        for m in 1..self.etas.len() {
            let b = m % py;
            v.push((column[b] + column[(py - b) % py]) * self.form[m]);
        }
        v
    }

    /// `d_eta sum_m v[m] 2 / sqrt(xi^2 + eta_m^2)`: the trapezoid rule of
    /// `int |S|^2 sinc^4 (2 / |k|) d eta` for `v` from [`Self::paired`].
    /// At `xi = 0` the point `eta = 0` is left out (its remainder is 0).
    fn sum(&self, v: &[f64], xi: f64) -> f64 {
        let start = usize::from(xi == 0.0);
        2.0 * self.deta * inverse_distance_sum(&v[start..], &self.squares[start..], xi * xi)
    }
}

/// `sum_m v[m] / sqrt(x2 + e2[m])` in four independent lanes (vectorisable).
fn inverse_distance_sum(v: &[f64], e2: &[f64], x2: f64) -> f64 {
    let mut lanes = [0.0; 4];
    let (vs, es) = (v.chunks_exact(4), e2.chunks_exact(4));
    let (v_rest, e_rest) = (vs.remainder(), es.remainder());
    for (vc, ec) in vs.zip(es) {
        for ((lane, a), b) in lanes.iter_mut().zip(vc).zip(ec) {
            *lane += a / (x2 + b).sqrt();
        }
    }
    let mut sum = lanes[0] + lanes[1] + lanes[2] + lanes[3];
    for (a, b) in v_rest.iter().zip(e_rest) {
        sum += a / (x2 + b).sqrt();
    }
    sum
}

/// The row transforms `sigma_j(xi) = sum_i p_ij exp(-i xi (i - i_c))` at any xi:
/// direct sums, or Taylor series at small xi.
struct RowTransforms<'a> {
    pressure: &'a [f64],
    nx: usize,
    ny: usize,
    /// The centroid of `|p|` (cells), the phase reference.
    centre: [f64; 2],
    /// `max |i - i_c|` (at least 1/2).
    reach: f64,
    /// `moments[k * ny + j] = sum_i p_ij ((i - i_c) / reach)^k`.
    moments: Vec<f64>,
}

impl<'a> RowTransforms<'a> {
    fn new(pressure: &'a [f64], nx: usize, ny: usize) -> Self {
        let (mut total, mut cx, mut cy) = (0.0, 0.0, 0.0);
        for j in 0..ny {
            for i in 0..nx {
                let a = pressure[j * nx + i].abs();
                total += a;
                cx += a * i as f64;
                cy += a * j as f64;
            }
        }
        let centre = if total > 0.0 {
            [cx / total, cy / total]
        } else {
            [0.5 * (nx as f64 - 1.0), 0.5 * (ny as f64 - 1.0)]
        };
        let reach = centre[0].max(nx as f64 - 1.0 - centre[0]).max(0.5);
        let mut moments = vec![0.0; TAYLOR_TERMS * ny];
        for j in 0..ny {
            for i in 0..nx {
                let u = (i as f64 - centre[0]) / reach;
                let mut power = pressure[j * nx + i];
                for k in 0..TAYLOR_TERMS {
                    moments[k * ny + j] += power;
                    power *= u;
                }
            }
        }
        RowTransforms {
            pressure,
            nx,
            ny,
            centre,
            reach,
            moments,
        }
    }

    /// `sigma_j(xi)` for every row into `out[..ny]`.
    fn at(&self, xi: f64, out: &mut [Complex<f64>]) {
        let (nx, ny) = (self.nx, self.ny);
        if xi * self.reach <= 0.5 {
            // sum_k (-i xi reach)^k / k! moment_k
            let z = Complex::new(0.0, -xi * self.reach);
            let mut c = Complex::new(1.0, 0.0);
            out[..ny].fill(Complex::new(0.0, 0.0));
            for k in 0..TAYLOR_TERMS {
                for (o, m) in out[..ny]
                    .iter_mut()
                    .zip(&self.moments[k * ny..(k + 1) * ny])
                {
                    *o += c * m;
                }
                c = c * z / (k as f64 + 1.0);
            }
        } else {
            let (cosines, sines): (Vec<f64>, Vec<f64>) = (0..nx)
                .map(|i| {
                    let (s, c) = (xi * (i as f64 - self.centre[0])).sin_cos();
                    (c, s)
                })
                .unzip();
            for (j, o) in out[..ny].iter_mut().enumerate() {
                let row = &self.pressure[j * nx..(j + 1) * nx];
                let (mut re, mut im) = ([0.0; 4], [0.0; 4]);
                let (rows, cs, ss) = (
                    row.chunks_exact(4),
                    cosines.chunks_exact(4),
                    sines.chunks_exact(4),
                );
                let (row_rest, c_rest, s_rest) = (rows.remainder(), cs.remainder(), ss.remainder());
                for ((pc, cc), sc) in rows.zip(cs).zip(ss) {
                    for l in 0..4 {
                        re[l] += pc[l] * cc[l];
                        im[l] -= pc[l] * sc[l];
                    }
                }
                let (mut r, mut m) = (re[0] + re[1] + re[2] + re[3], im[0] + im[1] + im[2] + im[3]);
                for ((p, c), s) in row_rest.iter().zip(c_rest).zip(s_rest) {
                    r += p * c;
                    m -= p * s;
                }
                *o = Complex::new(r, m);
            }
        }
    }
}

/// The eta integral at one small xi: the lattice sum of the remainder and the
/// coefficients of the subtracted part.
struct NearState {
    /// `deta * sum (F - T) 2 / |k|` (without the `sinc^4(xi / 2)` factor).
    lattice: f64,
    /// `P_0, P_2, P_4, P_6`.
    poly: [f64; 4],
    /// Whether `T` was subtracted.
    subtracted: bool,
}

impl NearState {
    fn new(
        plan: &DissipationPlan,
        rows: &RowTransforms,
        lattice: &EtaLattice,
        xi: f64,
        sg: f64,
    ) -> Self {
        let (ny, py) = (plan.ny, plan.py);
        let mut buffer = vec![Complex::new(0.0, 0.0); py];
        rows.at(xi, &mut buffer);
        // Taylor coefficients in eta of S_c(eta) = sum_j sigma_j exp(-i eta (j - j_c)).
        let mut s = [Complex::new(0.0, 0.0); 7];
        for (j, sigma) in buffer[..ny].iter().enumerate() {
            let v = j as f64 - rows.centre[1];
            let mut power = 1.0;
            for sk in s.iter_mut() {
                *sk += sigma * power;
                power *= v;
            }
        }
        let mut factorial = 1.0;
        for (k, sk) in s.iter_mut().enumerate() {
            if k > 0 {
                factorial *= k as f64;
            }
            // (-i)^k / k!
            let phase = match k % 4 {
                0 => Complex::new(1.0, 0.0),
                1 => Complex::new(0.0, -1.0),
                2 => Complex::new(-1.0, 0.0),
                _ => Complex::new(0.0, 1.0),
            };
            *sk = *sk * phase / factorial;
        }
        // |S_c|^2 = S_c conj(S_c): coefficient of eta^k.
        let mut a = [0.0; 7];
        for (k, ak) in a.iter_mut().enumerate() {
            for l in 0..=k {
                *ak += (s[l] * s[k - l].conj()).re;
            }
        }
        // Times the Taylor series of sinc^4(eta / 2), then exp(+eta^2 / 2 sg^2).
        let form = sinc4_series();
        let gauss = [
            1.0,
            0.0,
            1.0 / (2.0 * sg * sg),
            0.0,
            1.0 / (8.0 * sg.powi(4)),
            0.0,
            1.0 / (48.0 * sg.powi(6)),
        ];
        let even_f: [f64; 7] = std::array::from_fn(|k| {
            if k % 2 == 1 {
                0.0
            } else {
                (0..=k).step_by(2).map(|l| a[l] * form[k - l]).sum()
            }
        });
        let p: [f64; 7] = std::array::from_fn(|k| (0..=k).map(|l| even_f[l] * gauss[k - l]).sum());
        let poly = [p[0], p[2], p[4], p[6]];

        plan.column.process(&mut buffer);
        let power: Vec<f64> = buffer.iter().map(|b| b.norm_sqr()).collect();
        let subtracted = xi < SUBTRACTION_BELOW * lattice.deta;
        let mut v = lattice.paired(&power);
        if subtracted {
            // The lattice's own point eta = 0 of the remainder is 0 exactly.
            v[0] = 0.0;
            let scale = 1.0 / (2.0 * sg * sg);
            for (vm, e2) in v.iter_mut().zip(lattice.squares).skip(1) {
                if *e2 * scale > 400.0 {
                    break;
                }
                let t = (poly[0] + e2 * (poly[1] + e2 * (poly[2] + e2 * poly[3])))
                    * (-e2 * scale).exp();
                *vm -= 2.0 * t;
            }
        }
        let lattice_sum = lattice.sum(&v, xi);
        NearState {
            lattice: lattice_sum,
            poly,
            subtracted,
        }
    }

    /// `M(xi)`.
    fn density(&self, xi: f64, sg: f64) -> f64 {
        let mut m = self.lattice;
        if self.subtracted {
            let j = gaussian_moments(xi, sg);
            m += self.poly.iter().zip(&j).map(|(p, j)| p * j).sum::<f64>();
        }
        sinc4(xi) * m
    }
}

/// `J_n(xi) = int eta^n exp(-eta^2 / 2 sg^2) 2 / sqrt(xi^2 + eta^2) d eta` for
/// n = 0, 2, 4, 6: `eta = xi sinh t` and the trapezoid rule in t.
fn gaussian_moments(xi: f64, sg: f64) -> [f64; 4] {
    let mut sum = [0.5, 0.0, 0.0, 0.0];
    let mut t = 0.0;
    loop {
        t += SINH_STEP;
        let e = xi * t.sinh();
        let z = e * e / (2.0 * sg * sg);
        if z > 80.0 {
            break;
        }
        let g = (-z).exp();
        let e2 = e * e;
        sum[0] += g;
        sum[1] += g * e2;
        sum[2] += g * e2 * e2;
        sum[3] += g * e2 * e2 * e2;
    }
    sum.map(|s| 4.0 * SINH_STEP * s)
}

/// `sinc^4(x / 2) = (sin(x / 2) / (x / 2))^4`, the form factor of `|p^|^2` of the
/// bilinear interpolant along one direction.
fn sinc4(x: f64) -> f64 {
    let h = 0.5 * x;
    if h.abs() < 1e-3 {
        let h2 = h * h;
        (1.0 - h2 / 6.0 * (1.0 - h2 / 20.0)).powi(4)
    } else {
        (h.sin() / h).powi(4)
    }
}

/// Taylor coefficients of `sinc^4(eta / 2)` up to `eta^6`.
fn sinc4_series() -> [f64; 7] {
    let sinc = [
        1.0,
        0.0,
        -1.0 / 24.0,
        0.0,
        1.0 / 1920.0,
        0.0,
        -1.0 / 322560.0,
    ];
    let mul = |a: &[f64; 7], b: &[f64; 7]| -> [f64; 7] {
        std::array::from_fn(|k| (0..=k).map(|l| a[l] * b[k - l]).sum())
    };
    let square = mul(&sinc, &sinc);
    mul(&square, &square)
}

/// `g(xi, lambda) = xi^2 lambda / (1 + xi^2 lambda^2)`, without overflow.
fn loss_weight(xi: f64, lambda: f64) -> f64 {
    let u = lambda * xi;
    if u > 1e150 {
        xi / u
    } else {
        xi * u / (1.0 + u * u)
    }
}

fn check_grid(nx: usize, ny: usize) -> Result<()> {
    if nx == 0 {
        return Err(Error::invalid("nx", nx, "at least one cell"));
    }
    if ny == 0 {
        return Err(Error::invalid("ny", ny, "at least one cell"));
    }
    Ok(())
}

fn check_inputs(
    creep: &CreepSeries,
    velocity: f64,
    pressure: &[f64],
    nx: usize,
    ny: usize,
    cell: f64,
) -> Result<()> {
    if !(creep.glassy.is_finite() && creep.glassy >= 0.0) {
        return Err(Error::invalid(
            "creep.glassy",
            creep.glassy,
            "a finite compliance >= 0",
        ));
    }
    for (k, b) in creep.branches.iter().enumerate() {
        if !(b.compliance.is_finite() && b.compliance >= 0.0) {
            return Err(Error::invalid(
                &format!("creep.branches[{k}].compliance"),
                b.compliance,
                "a finite compliance >= 0",
            ));
        }
        if b.retardation_time.is_nan() || b.retardation_time <= 0.0 {
            return Err(Error::invalid(
                &format!("creep.branches[{k}].retardation_time"),
                b.retardation_time,
                "a time > 0 (+inf for a frozen branch)",
            ));
        }
    }
    if velocity.is_nan() || velocity < 0.0 {
        return Err(Error::invalid(
            "velocity",
            velocity,
            "a speed >= 0 (+inf allowed)",
        ));
    }
    if !(cell.is_finite() && cell > 0.0) {
        return Err(Error::invalid("cell", cell, "a finite length > 0"));
    }
    check_grid(nx, ny)?;
    if pressure.len() != nx * ny {
        return Err(Error::invalid(
            "pressure",
            format!("{} values", pressure.len()),
            &format!("nx * ny = {} values", nx * ny),
        ));
    }
    if let Some(k) = pressure.iter().position(|p| !p.is_finite()) {
        return Err(Error::invalid(
            &format!("pressure[{k}]"),
            pressure[k],
            "a finite pressure",
        ));
    }
    Ok(())
}

/// The power dissipated in the body divided by the sliding speed V (a force),
/// for a pressure uniform on each cell as the solver holds it, integrated as the
/// bilinear interpolant of the cell-centre values (module doc, eq. (H)).
/// `pressure[j * nx + i]` on square cells of side `cell`; `creep` holds
/// plane-strain compliances; `velocity` is in the length unit of `cell` per time
/// unit of the retardation times. V = 0, V = inf, branches without compliance or
/// with infinite times, and a zero pressure give 0. Builds a [`DissipationPlan`];
/// use [`dissipated_force_with`] to reuse one.
pub fn dissipated_force(
    creep: &CreepSeries,
    velocity: f64,
    pressure: &[f64],
    nx: usize,
    ny: usize,
    cell: f64,
) -> Result<f64> {
    check_inputs(creep, velocity, pressure, nx, ny, cell)?;
    let plan = DissipationPlan::new(nx, ny)?;
    dissipated_force_with(&plan, creep, velocity, pressure, cell)
}

/// [`dissipated_force`] with the caller's plan (its grid is the pressure's).
pub fn dissipated_force_with(
    plan: &DissipationPlan,
    creep: &CreepSeries,
    velocity: f64,
    pressure: &[f64],
    cell: f64,
) -> Result<f64> {
    check_inputs(creep, velocity, pressure, plan.nx, plan.ny, cell)?;
    if velocity == 0.0 || velocity.is_infinite() {
        return Ok(0.0);
    }
    let branches: Vec<(f64, f64)> = creep
        .branches
        .iter()
        .filter(|b| b.compliance > 0.0 && b.retardation_time.is_finite())
        .map(|b| (b.compliance, velocity * b.retardation_time / cell))
        .filter(|&(_, lambda)| lambda > 0.0 && lambda.is_finite())
        .collect();
    if branches.is_empty() || pressure.iter().all(|&p| p == 0.0) {
        return Ok(0.0);
    }
    let lambda_max = branches.iter().map(|b| b.1).fold(0.0, f64::max);
    let density = plan.energy_density(pressure, lambda_max);
    let sum: f64 = branches
        .iter()
        .map(|&(compliance, lambda)| compliance * density.loss_integral(lambda))
        .sum();
    Ok(sum * cell * cell)
}

/// How the contact pressure falls to zero at the contact's edges, which decides
/// the field the dissipation integrates between the cell centres.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EdgeProfile {
    /// Like a square root of the distance to the edge, as under a smooth slider
    /// pressing the body directly (Hertz): [`dissipated_force_square_root_edges`].
    SquareRoot,
    /// Unknown (under a layer the pressure may vanish linearly or jump): the
    /// bilinear interpolant of the cell values, [`dissipated_force`].
    Bilinear,
}

/// Creep lengths (in cells) below which the square-root edges are resolved on a
/// finer grid: above it the bilinear field's error is below 1e-3 of the result
/// (module doc, "Square-root edges").
const EDGE_REFINEMENT_BELOW: f64 = 16.0;
/// Cells along the finer grid's longer side, at least (grids of this many cells
/// and more are not refined): the estimate then costs that of the bilinear one on
/// a grid of 384 to 766 cells across, 0.05 to 0.3 s.
const EDGE_REFINEMENT_CELLS: usize = 384;
/// Creep lengths (in cells) below which the finer grid is made as fine as fits in
/// [`SLOW_EDGE_REFINEMENT_CELLS`] across: there the dissipation gathers within a
/// creep length of the edges, and the 384-cell grid left the estimate of a Hertz
/// pressure 0.37 % low at l / a = 1e-3 on 128^2 (0.24 % on the 640 cells of the
/// odd factor 5; a Zener body at V tau / a0 = 1e-4 on 128^2: 0.21 % below the
/// finest solves, 0.04 % on 640 cells).
const FAR_BELOW_A_CELL: f64 = 0.1;
/// The finer grid's most cells across for creep far below a cell: a grid of `n <
/// 384` cells is refined by the largest odd factor up to `768 / n` (if above the
/// 384 rule's), at most 768 across (as fine as the 384 rule ever went), 0.3 to 0.9 s.
const SLOW_EDGE_REFINEMENT_CELLS: usize = 768;

/// [`dissipated_force`] for a pressure whose contact edges fall like a square
/// root ([`EdgeProfile::SquareRoot`]): where some branch creeps less than
/// 16 cells, the loss is integrated over the field `sqrt(max(0, s))` sampled on
/// cells `r` times finer, `s` the bilinear interpolant of the squared cell values
/// continued linearly to negative values one cell beyond the contact (the
/// bilinear field of the pressures next to a cell where they do not fall like a
/// root), scaled to carry the cells' load (module doc, "Square-root edges");
/// elsewhere it is [`dissipated_force`].
pub fn dissipated_force_square_root_edges(
    creep: &CreepSeries,
    velocity: f64,
    pressure: &[f64],
    nx: usize,
    ny: usize,
    cell: f64,
) -> Result<f64> {
    check_inputs(creep, velocity, pressure, nx, ny, cell)?;
    let shortest = creep
        .branches
        .iter()
        .filter(|b| b.compliance > 0.0)
        .map(|b| velocity * b.retardation_time / cell)
        .fold(f64::INFINITY, f64::min);
    let side = nx.max(ny);
    let mut factor = EDGE_REFINEMENT_CELLS.div_ceil(side);
    if shortest < FAR_BELOW_A_CELL {
        // Odd, so that the finer centres include the cells' own: the bilinear field
        // kept next to a jump is then sampled without smoothing its kinks.
        let most = SLOW_EDGE_REFINEMENT_CELLS / side;
        factor = factor.max(most - (most + 1) % 2);
    }
    let fine = (shortest < EDGE_REFINEMENT_BELOW && factor >= 2)
        .then(|| square_root_edge_field(pressure, nx, ny, factor))
        .flatten();
    match fine {
        Some(fine) => {
            let cell = cell / factor as f64;
            dissipated_force(creep, velocity, &fine, nx * factor, ny * factor, cell)
        }
        None => dissipated_force(creep, velocity, pressure, nx, ny, cell),
    }
}

/// The square-root-edged field of [`dissipated_force_square_root_edges`] at the
/// centres of cells `factor` times finer, scaled to the load of `pressure`
/// (`None` for a field without load).
fn square_root_edge_field(
    pressure: &[f64],
    nx: usize,
    ny: usize,
    factor: usize,
) -> Option<Vec<f64>> {
    let at = |i: i64, j: i64| -> Option<f64> {
        (i >= 0 && j >= 0 && (i as usize) < nx && (j as usize) < ny)
            .then(|| pressure[j as usize * nx + i as usize])
    };
    let loaded = |i: i64, j: i64| at(i, j).is_some_and(|p| p > 0.0);
    // The squared pressure, continued beyond the contact: an unloaded cell next to
    // two loaded ones in a line (along x, y or a diagonal) takes the mean of the
    // lines' extrapolations that are negative, where most are. Where most are not,
    // or no line has two loaded cells, the pressure does not fall like a square root
    // there (a glassy leading edge's near jump): the cell is marked, and the field
    // between its centre and its neighbours' is the bilinear one of the pressures.
    let mut squared = vec![0.0; nx * ny];
    let mut not_root = vec![false; nx * ny];
    for j in 0..ny as i64 {
        for i in 0..nx as i64 {
            let k = j as usize * nx + i as usize;
            let p = pressure[k];
            if p > 0.0 {
                squared[k] = p * p;
                continue;
            }
            let (mut sum, mut count, mut others, mut touches) = (0.0, 0, 0, false);
            for (di, dj) in [
                (1, 0),
                (-1, 0),
                (0, 1),
                (0, -1),
                (1, 1),
                (1, -1),
                (-1, 1),
                (-1, -1),
            ] {
                touches |= loaded(i + di, j + dj);
                if loaded(i + di, j + dj) && loaded(i + 2 * di, j + 2 * dj) {
                    let near = at(i + di, j + dj).unwrap_or(0.0);
                    let far = at(i + 2 * di, j + 2 * dj).unwrap_or(0.0);
                    let continued = 2.0 * near * near - far * far;
                    if continued < 0.0 {
                        sum += continued;
                        count += 1;
                    } else {
                        others += 1;
                    }
                }
            }
            if count > 0 && count >= others {
                squared[k] = sum / count as f64;
            } else if touches {
                not_root[k] = true;
            }
        }
    }
    // Bilinear in the squared values at the fine centres (coarse centres at
    // integer coordinates; held constant beyond the outermost ones).
    let (fx, fy) = (nx * factor, ny * factor);
    let coordinate = |f: usize, n: usize| -> (usize, f64) {
        let x = ((f as f64 + 0.5) / factor as f64 - 0.5).clamp(0.0, (n - 1) as f64);
        let lower = (x.floor() as usize).min(n.saturating_sub(2));
        (lower, x - lower as f64)
    };
    let mut fine = vec![0.0; fx * fy];
    fine.par_chunks_mut(fx).enumerate().for_each(|(jf, row)| {
        let (j0, ty) = coordinate(jf, ny);
        let j1 = (j0 + 1).min(ny - 1);
        for (i_f, out) in row.iter_mut().enumerate() {
            let (i0, tx) = coordinate(i_f, nx);
            let i1 = (i0 + 1).min(nx - 1);
            let corners = [j0 * nx + i0, j0 * nx + i1, j1 * nx + i0, j1 * nx + i1];
            let weights = [
                (1.0 - ty) * (1.0 - tx),
                (1.0 - ty) * tx,
                ty * (1.0 - tx),
                ty * tx,
            ];
            *out = if corners.iter().any(|&c| not_root[c]) {
                corners
                    .iter()
                    .zip(&weights)
                    .map(|(&c, w)| w * pressure[c])
                    .sum()
            } else {
                let s: f64 = corners
                    .iter()
                    .zip(&weights)
                    .map(|(&c, w)| w * squared[c])
                    .sum();
                s.max(0.0).sqrt()
            };
        }
    });
    let load: f64 = pressure.iter().sum();
    let fine_load = fine.iter().sum::<f64>() / (factor * factor) as f64;
    if !(load > 0.0 && fine_load > 0.0) {
        return None;
    }
    let scale = load / fine_load;
    fine.iter_mut().for_each(|v| *v *= scale);
    Some(fine)
}

/// Images of the Brillouin zone summed explicitly on each side by
/// [`line_dissipated_force`] (the rest in closed form).
const LINE_IMAGES: i32 = 24;
/// Gauss–Legendre points per panel of width `pi / nx` of the line integral.
const LINE_PANEL_NODES: usize = 8;

/// The power dissipated per unit length in a viscoelastic half-space under a
/// line contact (plane strain), divided by the sliding speed V: the 1-D analogue
/// of eq. (H), for the pressure `pressure[i]` (mean over cell i of width `cell`,
/// uniform along y) integrated as the piecewise-linear interpolant of the cell
/// values, `p(x) = sum_i p_i hat(x / h - i)`.
///
/// *Derivation.* With `p^(k) = int p exp(-i k x) dx`, the plane-strain
/// displacement of a pressure wave is `w^ = (2 / |k|) J*(k) p^` (the transform of
/// `(2 / pi) ln(1 / |x|)` is `2 pi / |k|` up to a Dirac mass at k = 0, which does
/// not move the slope), `J*(k) = J_g + sum_k J_k / (1 - i k l_k)` as in the 2-D
/// case (the sign convention of `surface_compliance`). `D / V = -int p dw/dx dx =
/// -(1 / 2 pi) int conj(p^) (i k) w^ dk`, whose real part keeps
/// `Re[i k / (1 - i k l)] = -k^2 l / (1 + k^2 l^2)`, so
///
/// `(H1)  D / V = sum_k J_k (2 / pi) int_0^inf |p^(k)|^2 k l_k / (1 + k^2 l_k^2) dk`.
///
/// For the interpolant, in cell units `theta = k h`, `lambda = l / h`: `p^ = h
/// sinc^2(theta / 2) S(theta)`, `S(theta) = sum_i p_i exp(-i theta i)`, so
/// `D / V = h (2 / pi) sum_k J_k int_0^inf sinc^4(theta / 2) |S|^2 w(theta,
/// lambda_k) dtheta`, `w = theta lambda / (1 + theta^2 lambda^2)`. `|S|^2` has
/// period `2 pi` and is even: the integral folds onto `[0, pi]` against
/// `P(theta) = sum_n f(|theta + 2 pi n|)`, `f = sinc^4(. / 2) w`; for `n != 0`,
/// `sinc^4((theta + 2 pi n) / 2) = 16 sin^4(theta / 2) / (theta + 2 pi n)^4`, summed
/// for `|n| <= 24` and beyond by the midpoint rule's integral `(1 / 2 pi) int_U^inf
/// w(u) / u^4 du = (lambda / 2 pi) (1 / (2 U^2) - (lambda^2 / 2) ln(1 + 1 /
/// (lambda U)^2))` (a series in `1 / (lambda U)^2` when that cancels) with its
/// first Euler–Maclaurin correction `(2 pi / 24) d(w / u^4)/du` at `U > 150`
/// (the next term is `~20 / U^6` = 2e-12 of the sum). `int_0^pi |S|^2 P` is
/// integrated by 8-point Gauss–Legendre on `nx` panels of width `pi / nx` (on
/// which `|S|^2`, of degree `nx - 1`, turns by less than half a period: the rule's
/// error for `exp(i x)` on `[0, pi]` is 5e-15), the first graded geometrically
/// toward 0 down to `1e-4 / lambda_max` for the peak of `w` at `1 / lambda`. On
/// the uniform panels node `j` of every panel lies on the shifted lattice
/// `pi (k + tau_j) / nx`, so `S` there comes from one FFT of length `2 nx` per
/// node position (8 in all); on the graded panel it is summed directly. No image
/// of the zone is cut: the only errors are the quadratures. The cost is 8 FFTs
/// and `8 nx` folded weights per branch. V = 0, V = inf, branches without
/// compliance or with infinite times, and a zero pressure give 0.
pub fn line_dissipated_force(
    creep: &CreepSeries,
    velocity: f64,
    pressure: &[f64],
    cell: f64,
) -> Result<f64> {
    check_inputs(creep, velocity, pressure, pressure.len(), 1, cell)?;
    if velocity == 0.0 || velocity.is_infinite() {
        return Ok(0.0);
    }
    let branches: Vec<(f64, f64)> = creep
        .branches
        .iter()
        .filter(|b| b.compliance > 0.0 && b.retardation_time.is_finite())
        .map(|b| (b.compliance, velocity * b.retardation_time / cell))
        .filter(|&(_, lambda)| lambda > 0.0 && lambda.is_finite())
        .collect();
    if branches.is_empty() || pressure.iter().all(|&p| p == 0.0) {
        return Ok(0.0);
    }
    let nx = pressure.len();
    let lambda_max = branches.iter().map(|b| b.1).fold(0.0, f64::max);
    // Panels on [0, pi]: nx of width pi / nx, the first graded toward 0.
    let width = PI / nx as f64;
    let lowest = (1e-3 * width).min(1e-4 / lambda_max).max(1e-300);
    let mut breaks = vec![0.0];
    let mut t = lowest;
    while t < width {
        breaks.push(t);
        t *= 2.0;
    }
    breaks.push(width);
    let rule = GaussLegendre::new(LINE_PANEL_NODES);
    // (theta, weight, |S(theta)|^2): the graded first panel by direct sums.
    let centre = 0.5 * (nx - 1) as f64;
    let mut nodes: Vec<(f64, f64, f64)> = breaks
        .windows(2)
        .flat_map(|p| {
            let (half, mid) = (0.5 * (p[1] - p[0]), 0.5 * (p[1] + p[0]));
            rule.nodes
                .iter()
                .zip(&rule.weights)
                .map(move |(x, w)| (mid + half * x, w * half))
                .collect::<Vec<_>>()
        })
        .map(|(theta, weight)| (theta, weight, line_power(pressure, theta, centre)))
        .collect();
    // The panels [k, k + 1] pi / nx, k >= 1: node j sits at pi (k + tau_j) / nx for
    // every k, so S there is one FFT of length 2 nx of p_i exp(-i pi tau_j i / nx).
    let fft = FftPlanner::<f64>::new().plan_fft_forward(2 * nx);
    for (x, w) in rule.nodes.iter().zip(&rule.weights) {
        let tau = 0.5 * (1.0 + x);
        let mut buffer: Vec<Complex<f64>> = (0..2 * nx)
            .map(|i| {
                if i < nx {
                    let (s, c) = (-PI * tau * i as f64 / nx as f64).sin_cos();
                    Complex::new(pressure[i] * c, pressure[i] * s)
                } else {
                    Complex::new(0.0, 0.0)
                }
            })
            .collect();
        fft.process(&mut buffer);
        nodes.extend((1..nx).map(|k| {
            (
                (k as f64 + tau) * width,
                0.5 * w * width,
                buffer[k].norm_sqr(),
            )
        }));
    }
    let sum: f64 = nodes
        .par_iter()
        .map(|&(theta, weight, power)| {
            let folded: f64 = branches
                .iter()
                .map(|&(compliance, lambda)| compliance * folded_line_weight(theta, lambda))
                .sum();
            weight * power * folded
        })
        .sum();
    Ok(cell * 2.0 / PI * sum)
}

/// `|S(theta)|^2 = |sum_i p_i exp(-i theta (i - centre))|^2`, the phase advanced by
/// rotation and re-seeded exactly every 64 terms.
fn line_power(pressure: &[f64], theta: f64, centre: f64) -> f64 {
    let (s1, c1) = theta.sin_cos();
    let (mut re, mut im) = (0.0, 0.0);
    for (block, chunk) in pressure.chunks(64).enumerate() {
        let (mut s, mut c) = (-(theta * ((block * 64) as f64 - centre))).sin_cos();
        for &p in chunk {
            re += p * c;
            im += p * s;
            // exp(-i theta) times (c + i s).
            let next_c = c * c1 + s * s1;
            s = s * c1 - c * s1;
            c = next_c;
        }
    }
    re * re + im * im
}

/// `P(theta) = sum_n f(|theta + 2 pi n|)`, `f(u) = sinc^4(u / 2) w(u, lambda)`, for
/// `0 < theta <= pi` ([`line_dissipated_force`]).
fn folded_line_weight(theta: f64, lambda: f64) -> f64 {
    let w = |u: f64| loss_weight(u, lambda) / u;
    let centre = sinc4(theta) * w(theta);
    let mut images = 0.0;
    for n in 1..=LINE_IMAGES {
        let two_pi_n = 2.0 * PI * f64::from(n);
        for u in [two_pi_n + theta, two_pi_n - theta] {
            images += w(u) / (u * u * u * u);
        }
    }
    let edge = 2.0 * PI * (f64::from(LINE_IMAGES) + 0.5);
    for u in [edge + theta, edge - theta] {
        images += line_image_tail(u, lambda) / (2.0 * PI) + line_image_slope(u, lambda) * PI / 12.0;
    }
    let s = (0.5 * theta).sin();
    centre + 16.0 * s * s * s * s * images
}

/// `d/du (w(u, lambda) / u^4) = -lambda (3 + 5 z^2) / (u^4 (1 + z^2)^2)`, `z =
/// lambda u`: the midpoint rule's first correction.
fn line_image_slope(u: f64, lambda: f64) -> f64 {
    let z = lambda * u;
    if z > 1e100 {
        -5.0 / (lambda * u.powi(6))
    } else {
        let z2 = z * z;
        -lambda * (3.0 + 5.0 * z2) / (u.powi(4) * (1.0 + z2) * (1.0 + z2))
    }
}

/// `int_U^inf w(u, lambda) / u^4 du = int_U^inf lambda du / (u^3 (1 + lambda^2 u^2))`.
fn line_image_tail(u: f64, lambda: f64) -> f64 {
    let z = lambda * u;
    if z <= 2.0 {
        lambda / (2.0 * u * u) * (1.0 - z * z * (1.0 / (z * z)).ln_1p())
    } else {
        // (1 / (lambda U^4)) sum_j (-1)^j z^(-2j) / (4 + 2j).
        let q = -1.0 / (z * z);
        let mut term = 1.0;
        let mut sum = 0.0;
        for j in 0..60 {
            sum += term / (4.0 + 2.0 * f64::from(j));
            term *= q;
            if term.abs() < 1e-18 {
                break;
            }
        }
        sum / (lambda * u * u * u * u)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::body::viscoelastic::CreepBranch;

    /// Composite Gauss–Legendre over `[lo, hi]` split at the geometric points
    /// `lo * 2^k` (for lo > 0) : a plain rule for the references below.
    fn geometric(rule: &GaussLegendre, lo: f64, hi: f64, f: &impl Fn(f64) -> f64) -> f64 {
        let mut sum = rule.integrate(0.0, lo, f);
        let mut a = lo;
        while a < hi {
            let b = (2.0 * a).min(hi);
            sum += rule.integrate(a, b, f);
            a = b;
        }
        sum
    }

    /// `1 - 1 / sqrt(1 + u^2)` without cancellation.
    fn phi(u: f64) -> f64 {
        let r = (1.0 + u * u).sqrt();
        u * u / (r * (1.0 + r))
    }

    /// The continuum D / V per unit branch compliance of a radial pressure with
    /// transform `|p^|^2 = spectrum(k)`: the angle done in closed form,
    /// `int_0^2pi cos^2 / (1 + B cos^2) = (2 pi / B) (1 - 1 / sqrt(1 + B))`, gives
    /// `(1 / (pi l)) int_0^inf |p^(k)|^2 (1 - 1 / sqrt(1 + k^2 l^2)) dk`.
    fn radial_reference(spectrum: &impl Fn(f64) -> f64, l: f64, scale: f64, upper: f64) -> f64 {
        let rule = GaussLegendre::new(20);
        let lo = 1e-6 * (1.0 / l).min(1.0 / scale);
        let f = |k: f64| spectrum(k) * phi(k * l);
        geometric(&rule, lo, upper, &f) / (PI * l)
    }

    /// The Gaussian `p = exp(-r^2 / 2 b^2)`: `|p^|^2 = 4 pi^2 b^4 exp(-k^2 b^2)`.
    fn gaussian_reference(b: f64, l: f64) -> f64 {
        let spectrum = |k: f64| 4.0 * PI * PI * b.powi(4) * (-(k * b).powi(2)).exp();
        radial_reference(&spectrum, l, b, 12.0 / b)
    }

    /// Hertz `p = sqrt(1 - r^2 / a^2)`: `p^ = 2 pi a^2 (sin ka - ka cos ka) / (ka)^3`
    /// (Sonine's integral); integrated to `ka = 4000`, the tail with the mean
    /// `|p^|^2 ~ (2 pi a^2)^2 / (2 (ka)^4)`.
    fn hertz_reference(a: f64, l: f64) -> f64 {
        let g = |b: f64| {
            if b < 0.1 {
                let b2 = b * b;
                1.0 / 3.0 - b2 / 30.0 + b2 * b2 / 840.0 - b2 * b2 * b2 / 45360.0
            } else {
                (b.sin() - b * b.cos()) / (b * b * b)
            }
        };
        let amp = (2.0 * PI * a * a).powi(2);
        let spectrum = |k: f64| amp * g(k * a).powi(2);
        let rule = GaussLegendre::new(20);
        let f = |k: f64| spectrum(k) * phi(k * l);
        let lo = 1e-6 * (1.0 / l).min(1.0 / a);
        let mut sum = geometric(&rule, lo, 1.0 / a, &f);
        let end = 4000.0 / a;
        let mut k = 1.0 / a;
        while k < end {
            sum += rule.integrate(k, k + 1.0 / a, &f);
            k += 1.0 / a;
        }
        let tail = |k: f64| amp / (2.0 * (k * a).powi(4)) * phi(k * l);
        sum += geometric(&rule, end, end * 2f64.powi(40), &tail) - rule.integrate(0.0, end, tail);
        sum / (PI * l)
    }

    /// Cell-centre values of `p(x, y)` on `n x n` cells over `[-w, w]^2`.
    fn sample(n: usize, w: f64, p: impl Fn(f64, f64) -> f64) -> (Vec<f64>, f64) {
        let h = 2.0 * w / n as f64;
        let mut v = vec![0.0; n * n];
        for j in 0..n {
            for i in 0..n {
                v[j * n + i] = p(-w + (i as f64 + 0.5) * h, -w + (j as f64 + 0.5) * h);
            }
        }
        (v, h)
    }

    fn one_branch(l: f64) -> CreepSeries {
        CreepSeries {
            glassy: 0.0,
            branches: vec![CreepBranch {
                compliance: 1.0,
                retardation_time: l,
            }],
        }
    }

    /// A glassy compliance and two branches: 0.5 at a retardation time of 0.2 and 2
    /// at 7 (at speed 0.1, `one_branch(0.02)` and `one_branch(0.7)` scaled).
    fn two_branches() -> CreepSeries {
        CreepSeries {
            glassy: 0.3,
            branches: vec![
                CreepBranch {
                    compliance: 0.5,
                    retardation_time: 0.2,
                },
                CreepBranch {
                    compliance: 2.0,
                    retardation_time: 7.0,
                },
            ],
        }
    }

    fn gaussian_grid(n: usize) -> (Vec<f64>, f64) {
        sample(n, 6.0, |x, y| (-(x * x + y * y) / 2.0).exp())
    }

    fn hertz_grid(n: usize) -> (Vec<f64>, f64) {
        sample(n, 1.25, |x, y| (1.0 - x * x - y * y).max(0.0).sqrt())
    }

    /// Relative errors of the grid value against `reference` on the grids `ns`.
    fn errors(
        grid: impl Fn(usize) -> (Vec<f64>, f64),
        reference: f64,
        l: f64,
        ns: &[usize],
    ) -> Vec<f64> {
        ns.iter()
            .map(|&n| {
                let (p, h) = grid(n);
                let got = dissipated_force(&one_branch(l), 1.0, &p, n, n, h).unwrap();
                got / reference - 1.0
            })
            .collect()
    }

    #[test]
    fn hysteresis_references_meet_their_closed_forms() {
        // Gaussian: l -> 0 gives l int (dp/dx) L (dp/dx) = l pi^(3/2) b / 2, l -> inf
        // gives (1 / l) int p L p = 2 pi^(3/2) b^3 / l. Hertz: l pi^2 a / 3 (the
        // integral of j_1^2 is pi / 6) and (1 / l) 4 pi^2 a^3 / 15 (the Hertz
        // displacement pi (2 a^2 - r^2) / 4a integrated against p). Measured:
        // -1.1e-14, -2.1e-7 (the ln(l) / l term), -2.7e-15, -9.8e-8, -1.0e-7.
        let s = PI.powf(1.5);
        let cases = [
            (gaussian_reference(1.0, 1e-7), 1e-7 * s / 2.0, 1e-12),
            (gaussian_reference(1.0, 1e8), 2.0 * s / 1e8, 3e-7),
            (gaussian_reference(2.0, 1e-7), 1e-7 * s, 1e-12),
            (hertz_reference(1.0, 1e-7), 1e-7 * PI * PI / 3.0, 3e-7),
            (hertz_reference(1.0, 1e8), 4.0 * PI * PI / 15.0 / 1e8, 3e-7),
        ];
        for (k, (got, want, tol)) in cases.iter().enumerate() {
            let e = got / want - 1.0;
            eprintln!("reference {k}: {e:.2e}");
            assert!(e.abs() < *tol, "{k}: {got} vs {want}: {e:.2e}");
        }
    }

    /// The bilinear field's `(2 / (2 pi)^2) int_0^inf g M dxi` in cell units for
    /// each lambda, straight from its definition: `|S|^2` by direct sums at every
    /// point, xi on geometric panels near 0 then unit panels to 100, eta by
    /// `eta = xi sinh t` on `|eta| < 1` then unit panels to 100 (no FFT, lattice,
    /// window or subtraction; the cut tails are below 1e-7).
    fn brute_force(p: &[f64], nx: usize, ny: usize, lambdas: &[f64]) -> Vec<f64> {
        let rule = GaussLegendre::new(12);
        let form = |x: f64| {
            let h = 0.5 * x;
            if h.abs() < 1e-4 {
                1.0
            } else {
                (h.sin() / h).powi(4)
            }
        };
        let density = |xi: f64| {
            let rows: Vec<(f64, f64)> = (0..ny)
                .map(|j| {
                    (0..nx).fold((0.0, 0.0), |(re, im), i| {
                        let (s, c) = (xi * i as f64).sin_cos();
                        (re + p[j * nx + i] * c, im - p[j * nx + i] * s)
                    })
                })
                .collect();
            let power = |eta: f64| {
                let (mut re, mut im) = (0.0, 0.0);
                for (j, (a, b)) in rows.iter().enumerate() {
                    let (s, c) = (eta * j as f64).sin_cos();
                    re += a * c + b * s;
                    im += b * c - a * s;
                }
                re * re + im * im
            };
            let both = |eta: f64| (power(eta) + power(-eta)) * form(eta);
            let t_end = (1.0 / xi).asinh();
            let pieces = (t_end / 0.5).ceil() as usize;
            let mut sum = 0.0;
            for k in 0..pieces {
                let (a, b) = (
                    k as f64 * t_end / pieces as f64,
                    (k + 1) as f64 * t_end / pieces as f64,
                );
                sum += rule.integrate(a, b, |t| 2.0 * both(xi * t.sinh()));
            }
            for k in 1..100 {
                sum += rule.integrate(k as f64, k as f64 + 1.0, |e| {
                    both(e) * 2.0 / (xi * xi + e * e).sqrt()
                });
            }
            form(xi) * sum
        };
        let lo = 1e-5 / lambdas.iter().fold(1.0f64, |a, &b| a.max(b));
        let mut nodes = Vec::new();
        let mut add = |a: f64, b: f64| {
            let (half, mid) = (0.5 * (b - a), 0.5 * (b + a));
            for (x, w) in rule.nodes.iter().zip(&rule.weights) {
                let xi = mid + half * x;
                nodes.push((xi, w * half, density(xi)));
            }
        };
        add(0.0, lo);
        let mut a = lo;
        while a < 1.0 {
            add(a, (2.0 * a).min(1.0));
            a *= 2.0;
        }
        for k in 1..100 {
            add(k as f64, k as f64 + 1.0);
        }
        lambdas
            .iter()
            .map(|&lambda| {
                let sum: f64 = nodes
                    .iter()
                    .map(|&(xi, w, m)| w * loss_weight(xi, lambda) * m)
                    .sum();
                2.0 * sum / (4.0 * PI * PI)
            })
            .collect()
    }

    /// `-int p dw/dx dA` with `w` from the steady-sliding kernel of one branch
    /// (compliance 1, creep length l) on the cell-wise constant pressure, the
    /// derivative by central differences at the cell centres.
    fn kernel_route(p: &[f64], n: usize, h: f64, l: f64) -> f64 {
        let kernel =
            crate::body::viscoelastic::steady_sliding_kernel(&one_branch(l), h, n, n, 1.0).unwrap();
        let width = 2 * n - 1;
        let mut w = vec![0.0; n * n];
        for jf in 0..n {
            for i_f in 0..n {
                let mut sum = 0.0;
                for js in 0..n {
                    let row = &kernel[jf.abs_diff(js) * width..];
                    for is in 0..n {
                        sum += row[i_f + n - 1 - is] * p[js * n + is];
                    }
                }
                w[jf * n + i_f] = sum;
            }
        }
        let mut d = 0.0;
        for j in 0..n {
            for i in 1..n - 1 {
                d -= p[j * n + i] * (w[j * n + i + 1] - w[j * n + i - 1]) / (2.0 * h);
            }
        }
        d * h * h
    }

    #[test]
    fn hysteresis_gaussian_converges_to_the_continuum() {
        // p = exp(-r^2 / 2) on [-6, 6]^2 (h = 0.375, 0.1875, 0.094). Measured at
        // 128^2: -2.18e-3, -2.18e-3, -1.67e-3, -9.4e-4, -7.3e-4; the error falls by
        // 3.87-3.95 from 32^2 to 64^2 and 3.96-3.99 from 64^2 to 128^2 (second
        // order: the bilinear interpolant's error).
        for l in [1e-3, 0.1, 1.0, 10.0, 1e4] {
            let e = errors(gaussian_grid, gaussian_reference(1.0, l), l, &[32, 64, 128]);
            eprintln!("Gaussian l = {l:e}: {e:?}");
            assert!(e[2].abs() < 2.5e-3, "l = {l}: {e:?}");
            for k in 0..2 {
                let ratio = e[k] / e[k + 1];
                assert!((3.7..4.2).contains(&ratio), "l = {l}: {e:?}");
            }
        }
    }

    #[test]
    fn hysteresis_hertz_converges_to_the_continuum() {
        // p = sqrt(1 - r^2) on [-1.25, 1.25]^2. Measured at 64^2 / 128^2:
        // l = 1e-3: -2.23e-2 / -1.11e-2 (first order: the viscous limit weighs the
        // edge's infinite slope), 0.1: -4.3e-3 / -1.23e-3, 1: -1.5e-3 / -3.1e-4,
        // 10: -1.24e-3 / -1.9e-4, 1e4: -1.19e-3 / -1.6e-4.
        let cases = [
            (1e-3, 1.2e-2),
            (0.1, 1.5e-3),
            (1.0, 4e-4),
            (10.0, 2.5e-4),
            (1e4, 2e-4),
        ];
        for (l, tol) in cases {
            let e = errors(hertz_grid, hertz_reference(1.0, l), l, &[64, 128]);
            eprintln!("Hertz l = {l:e}: {e:?}");
            assert!(e[1].abs() < tol, "l = {l}: {e:?}");
            assert!(e[1].abs() < e[0].abs() / 1.9, "l = {l}: {e:?}");
        }
    }

    /// Relative errors against `reference` of the square-root-edged estimate and of
    /// the bilinear one on the grids `ns`.
    fn edge_errors(
        grid: impl Fn(usize) -> (Vec<f64>, f64),
        reference: f64,
        l: f64,
        ns: &[usize],
    ) -> Vec<(f64, f64)> {
        ns.iter()
            .map(|&n| {
                let (p, h) = grid(n);
                let ours =
                    dissipated_force_square_root_edges(&one_branch(l), 1.0, &p, n, n, h).unwrap();
                let bilinear = dissipated_force(&one_branch(l), 1.0, &p, n, n, h).unwrap();
                (ours / reference - 1.0, bilinear / reference - 1.0)
            })
            .collect()
    }

    #[test]
    fn square_root_edges_meet_the_hertz_closed_forms() {
        // p = sqrt(1 - r^2) on [-1.25, 1.25]^2 (h = 0.039, 0.0195) against its closed
        // forms. Measured at 64^2 / 128^2, square-root edges (bilinear): l = 1e-3:
        // -4.8e-3 / -2.4e-3 (-2.2e-2 / -1.1e-2; -6.6e-3 / -3.7e-3 when the finer
        // grid had 384 cells at every creep length); 1e-2: -3.4e-3 / -1.3e-3 (-1.6e-2
        // / -6.2e-3); 0.1: -8.9e-4 / -1.1e-4 (-4.3e-3 / -1.2e-3). The squared Hertz
        // field is a quadratic the interpolant nearly holds: what remains is the
        // finer grid's own bilinear error at the edge, first order in its cell.
        for (l, tol) in [(1e-3, 3e-3), (1e-2, 2e-3), (0.1, 5e-4)] {
            let e = edge_errors(hertz_grid, hertz_reference(1.0, l), l, &[64, 128]);
            eprintln!("Hertz, square-root edges, l = {l:e}: {e:?}");
            let ((coarse, _), (fine, bilinear)) = (e[0], e[1]);
            assert!(fine.abs() < tol, "l = {l}: {e:?}");
            assert!(fine.abs() < bilinear.abs() / 2.5, "l = {l}: {e:?}");
            assert!(fine.abs() < coarse.abs(), "l = {l}: {e:?}");
        }
        // Creep lengths of 16 cells and more keep the bilinear field.
        for l in [1.0, 1e4] {
            let e = edge_errors(hertz_grid, hertz_reference(1.0, l), l, &[128]);
            assert_eq!(e[0].0, e[0].1, "l = {l}");
        }
    }

    #[test]
    fn square_root_edges_keep_a_smooth_field_second_order() {
        // A field without edges (the Gaussian on [-6, 6]^2) is squared, interpolated
        // and rooted: second order still, its constant about twice the bilinear
        // field's (the root adds (h^2 / 8) p'^2 / p). Measured at 32^2, 64^2, 128^2:
        // l = 1e-3: -6.4e-2, -1.8e-2, -4.1e-3; 1: -5.1e-2, -1.4e-2, -3.1e-3.
        for l in [1e-3, 1.0] {
            let e = edge_errors(gaussian_grid, gaussian_reference(1.0, l), l, &[32, 64, 128]);
            eprintln!("Gaussian, square-root edges, l = {l:e}: {e:?}");
            assert!(e[2].0.abs() < 5e-3, "l = {l}: {e:?}");
            for k in 0..2 {
                let ratio = e[k].0 / e[k + 1].0;
                assert!((3.5..4.6).contains(&ratio), "l = {l}: {e:?}");
            }
        }
    }

    #[test]
    fn square_root_edges_leave_a_jump_to_the_bilinear_field() {
        // A pressure that jumps at its edge (uniform on a disc, or a glassy leading
        // edge's near jump) does not fall like a root: its cells' fine field is the
        // bilinear one of the pressures, and so is the loss. Measured 6.0e-7 and 2.0e-8
        // (the finer grid's quadrature).
        let n = 128;
        let (p, h) = sample(n, 1.25, |x, y| if x * x + y * y < 1.0 { 1.0 } else { 0.0 });
        for l in [1e-3, 0.1] {
            let ours =
                dissipated_force_square_root_edges(&one_branch(l), 1.0, &p, n, n, h).unwrap();
            let bilinear = dissipated_force(&one_branch(l), 1.0, &p, n, n, h).unwrap();
            eprintln!("uniform disc, l = {l}: {:.2e}", ours / bilinear - 1.0);
            assert!(
                (ours / bilinear - 1.0).abs() < 1e-5,
                "l = {l}: {ours} vs {bilinear}"
            );
        }
    }

    #[test]
    fn square_root_edge_field_carries_the_load_and_follows_hertz() {
        // On cells 6 times finer than 32^2 the field carries the cells' load and
        // lies closer to sqrt(1 - r^2) than the bilinear interpolant of the cell
        // values does. Measured mean absolute errors: 8.6e-4 against 5.8e-3.
        let (n, factor) = (32, 6);
        let (p, h) = hertz_grid(n);
        let fine = square_root_edge_field(&p, n, n, factor).unwrap();
        let load: f64 = p.iter().sum();
        let fine_load = fine.iter().sum::<f64>() / (factor * factor) as f64;
        assert!(
            (fine_load / load - 1.0).abs() < 1e-13,
            "{fine_load} vs {load}"
        );
        let m = n * factor;
        let hf = h / factor as f64;
        let (mut ours, mut bilinear) = (0.0, 0.0);
        for jf in 0..m {
            for i_f in 0..m {
                let (x, y) = (
                    -1.25 + (i_f as f64 + 0.5) * hf,
                    -1.25 + (jf as f64 + 0.5) * hf,
                );
                let exact = (1.0 - x * x - y * y).max(0.0).sqrt();
                // The cell values' bilinear interpolant at (x, y).
                let (u, v) = ((x + 1.25) / h - 0.5, (y + 1.25) / h - 0.5);
                let (i0, j0) = (
                    (u.floor().max(0.0) as usize).min(n - 2),
                    (v.floor().max(0.0) as usize).min(n - 2),
                );
                let (tx, ty) = (
                    (u - i0 as f64).clamp(0.0, 1.0),
                    (v - j0 as f64).clamp(0.0, 1.0),
                );
                let b = (1.0 - ty) * ((1.0 - tx) * p[j0 * n + i0] + tx * p[j0 * n + i0 + 1])
                    + ty * ((1.0 - tx) * p[(j0 + 1) * n + i0] + tx * p[(j0 + 1) * n + i0 + 1]);
                ours += (fine[jf * m + i_f] - exact).abs();
                bilinear += (b - exact).abs();
            }
        }
        let (ours, bilinear) = (ours / (m * m) as f64, bilinear / (m * m) as f64);
        eprintln!("mean absolute error: {ours:.2e} against {bilinear:.2e}");
        assert!(ours < bilinear / 3.0, "{ours} vs {bilinear}");
        // No load, no field.
        assert!(square_root_edge_field(&[0.0; 16], 4, 4, 2).is_none());
    }

    #[test]
    fn hysteresis_limits_of_the_creep_length() {
        // Far below and above the window, the closed forms `l pi^(3/2) / 2` and
        // `2 pi^(3/2) / l` of the Gaussian, off by the grid's own error (measured
        // -3.338e-2 and -8.62e-3 at 32^2 and 64^2 for l = 1e-6; -1.153e-2 and
        // -2.918e-3 for l = 1e8); l = 1e-90 and 1e90 scale exactly.
        let s = PI.powf(1.5);
        let small = errors(gaussian_grid, 1e-6 * s / 2.0, 1e-6, &[32, 64]);
        let large = errors(gaussian_grid, 2.0 * s / 1e8, 1e8, &[32, 64]);
        eprintln!("limits: {small:?} {large:?}");
        for e in [&small, &large] {
            assert!(
                e[1].abs() < 9e-3 && (3.7..4.1).contains(&(e[0] / e[1])),
                "{e:?}"
            );
        }
        let (p, h) = gaussian_grid(32);
        let at = |l: f64| dissipated_force(&one_branch(l), 1.0, &p, 32, 32, h).unwrap();
        let (a, b) = (at(1e-90) / 1e-90, at(1e-6) / 1e-6);
        assert!((a / b - 1.0).abs() < 1e-9, "{a} vs {b}");
        let (a, b) = (at(1e90) * 1e90, at(1e8) * 1e8);
        // The next term is ln(l) / l: 2.1e-7 at l = 1e8 in the continuum.
        assert!((a / b - 1.0).abs() < 1e-6, "{a} vs {b}");
    }

    #[test]
    fn hysteresis_matches_the_kernel_route() {
        // The second route, -int p dw/dx with w = K p from the steady-sliding kernel
        // (cell-wise constant pressure, central differences), on the Gaussian:
        // measured difference at 32^2 / 64^2: 3.27e-2 / 4.99e-3 (l = 0.1),
        // -1.12e-3 / -3.52e-4 (1), -3.10e-3 / -7.75e-4 (10); both routes converge
        // to the continuum.
        for (l, tol) in [(0.1, 6e-3), (1.0, 5e-4), (10.0, 1e-3)] {
            let e: Vec<f64> = [32, 64]
                .iter()
                .map(|&n| {
                    let (p, h) = gaussian_grid(n);
                    let ours = dissipated_force(&one_branch(l), 1.0, &p, n, n, h).unwrap();
                    ours / kernel_route(&p, n, h, l) - 1.0
                })
                .collect();
            eprintln!("kernel route l = {l}: {e:?}");
            assert!(
                e[1].abs() < tol && e[1].abs() < e[0].abs() / 3.0,
                "l = {l}: {e:?}"
            );
        }
    }

    #[test]
    fn hysteresis_matches_brute_force_on_small_grids() {
        // The field's own integral by a plain quadrature of its definition. Measured:
        // a rough 5 x 4 field 1.8e-5 to 2.6e-5 (the spectrum's images beyond the
        // third zone each side, cut here, hold that much of a white field), a
        // Gaussian of 1.2 cells on 8 x 8 1.2e-7 to 2.0e-7, for every creep length.
        let rough: Vec<f64> = (0..20)
            .map(|k| ((k * 7 + 3) % 11) as f64 / 10.0 + 0.1)
            .collect();
        let smooth: Vec<f64> = (0..64)
            .map(|k| {
                let (x, y) = ((k % 8) as f64 - 3.5, (k / 8) as f64 - 3.5);
                (-(x * x + y * y) / (2.0 * 1.2 * 1.2)).exp()
            })
            .collect();
        let lambdas = [0.3, 3.0, 300.0, 1e6];
        for (p, nx, ny, tol) in [(&rough, 5, 4, 4e-5), (&smooth, 8, 8, 5e-7)] {
            let want = brute_force(p, nx, ny, &lambdas);
            let density = DissipationPlan::new(nx, ny).unwrap().energy_density(p, 1e6);
            for (l, w) in lambdas.iter().zip(&want) {
                let e = density.loss_integral(*l) / w - 1.0;
                eprintln!("brute force {nx} x {ny}, lambda {l:e}: {e:.2e}");
                assert!(e.abs() < tol, "{nx} x {ny}, lambda {l}: {e:.2e}");
            }
        }
    }

    #[test]
    fn hysteresis_branches_add_and_scale_with_the_creep_length() {
        let (p, h) = hertz_grid(24);
        let two = two_branches();
        let d = dissipated_force(&two, 0.1, &p, 24, 24, h).unwrap();
        let a = 0.5 * dissipated_force(&one_branch(0.02), 1.0, &p, 24, 24, h).unwrap();
        let b = 2.0 * dissipated_force(&one_branch(0.7), 1.0, &p, 24, 24, h).unwrap();
        // The nodes reach down to 1e-4 / lambda_max, so the sums differ slightly.
        assert!((d / (a + b) - 1.0).abs() < 1e-10, "{d} vs {}", a + b);
        let faster = dissipated_force(&two, 0.2, &p, 24, 24, h).unwrap();
        let scaled = CreepSeries {
            glassy: 0.3,
            branches: two
                .branches
                .iter()
                .map(|b| CreepBranch {
                    retardation_time: 0.5 * b.retardation_time,
                    ..*b
                })
                .collect(),
        };
        assert_eq!(
            faster,
            dissipated_force(&scaled, 0.4, &p, 24, 24, h).unwrap()
        );
        // More speed moves both branches toward their elastic limit: less loss.
        assert!(faster < d);
    }

    #[test]
    fn hysteresis_trivial_cases_give_zero() {
        let (p, h) = hertz_grid(8);
        let series = |j: f64, tau: f64| CreepSeries {
            glassy: 1.0,
            branches: vec![CreepBranch {
                compliance: j,
                retardation_time: tau,
            }],
        };
        let d = |s: &CreepSeries, v: f64, p: &[f64]| dissipated_force(s, v, p, 8, 8, h).unwrap();
        assert_eq!(d(&series(1.0, 1.0), 0.0, &p), 0.0);
        assert_eq!(d(&series(1.0, 1.0), f64::INFINITY, &p), 0.0);
        assert_eq!(d(&series(0.0, 1.0), 1.0, &p), 0.0);
        assert_eq!(d(&series(1.0, f64::INFINITY), 1.0, &p), 0.0);
        assert_eq!(d(&series(1.0, 1.0), 1.0, &[0.0; 64]), 0.0);
        let no_branches = CreepSeries {
            glassy: 1.0,
            branches: vec![],
        };
        assert_eq!(d(&no_branches, 1.0, &p), 0.0);
        let positive = d(&series(1.0, 1.0), 1.0, &p);
        assert!(positive > 0.0);
        let plan = DissipationPlan::new(8, 8).unwrap();
        let again = dissipated_force_with(&plan, &series(1.0, 1.0), 1.0, &p, h).unwrap();
        assert_eq!(again, positive);
    }

    #[test]
    fn hysteresis_bad_input_names_the_argument() {
        let ok = one_branch(1.0);
        let p = vec![1.0; 12];
        let message = |s: &CreepSeries, v: f64, p: &[f64], nx: usize, ny: usize, cell: f64| {
            let e = dissipated_force(s, v, p, nx, ny, cell).unwrap_err();
            assert!(matches!(e, Error::InvalidValue { .. }), "{e}");
            e.to_string()
        };
        assert!(message(&ok, 1.0, &p, 4, 3, -1.0).starts_with("cell = -1"));
        assert!(message(&ok, 1.0, &p, 4, 3, 0.0).starts_with("cell"));
        assert!(message(&ok, 1.0, &p, 4, 3, f64::NAN).starts_with("cell"));
        assert!(message(&ok, f64::NAN, &p, 4, 3, 1.0).starts_with("velocity"));
        assert!(message(&ok, -1.0, &p, 4, 3, 1.0).starts_with("velocity"));
        assert!(message(&ok, 1.0, &p, 4, 4, 1.0).starts_with("pressure = 12 values"));
        assert!(message(&ok, 1.0, &p, 0, 3, 1.0).starts_with("nx"));
        assert!(message(&ok, 1.0, &[], 4, 0, 1.0).starts_with("ny"));
        let mut nan = p.clone();
        nan[5] = f64::NAN;
        assert!(message(&ok, 1.0, &nan, 4, 3, 1.0).starts_with("pressure[5]"));
        let bad = |glassy: f64, j: f64, tau: f64| CreepSeries {
            glassy,
            branches: vec![
                CreepBranch {
                    compliance: 1.0,
                    retardation_time: 1.0,
                },
                CreepBranch {
                    compliance: j,
                    retardation_time: tau,
                },
            ],
        };
        assert!(message(&bad(f64::NAN, 1.0, 1.0), 1.0, &p, 4, 3, 1.0).starts_with("creep.glassy"));
        assert!(message(&bad(0.0, -1.0, 1.0), 1.0, &p, 4, 3, 1.0)
            .starts_with("creep.branches[1].compliance"));
        assert!(message(&bad(0.0, 1.0, 0.0), 1.0, &p, 4, 3, 1.0)
            .starts_with("creep.branches[1].retardation_time"));
        assert!(message(&bad(0.0, 1.0, f64::NAN), 1.0, &p, 4, 3, 1.0)
            .starts_with("creep.branches[1].retardation_time"));
        let plan = DissipationPlan::new(4, 4).unwrap();
        let e = dissipated_force_with(&plan, &ok, 1.0, &p, 1.0).unwrap_err();
        assert!(e.to_string().starts_with("pressure"), "{e}");
        assert!(DissipationPlan::new(0, 3).is_err());
    }

    /// The timing tests' body: ten branches of 0.1 with retardation times 1e-4 to
    /// 1e5 on a glassy compliance of 0.1.
    fn ten_branches() -> CreepSeries {
        CreepSeries {
            glassy: 0.1,
            branches: (0..10)
                .map(|k| CreepBranch {
                    compliance: 0.1,
                    retardation_time: 10f64.powi(k - 4),
                })
                .collect(),
        }
    }

    #[test]
    #[ignore = "timing: run with --ignored --nocapture"]
    fn hysteresis_timing_256_by_256_with_10_branches() {
        let creep = ten_branches();
        let (p, h) = hertz_grid(256);
        let plan = DissipationPlan::new(256, 256).unwrap();
        for _ in 0..5 {
            let start = std::time::Instant::now();
            let d = dissipated_force_with(&plan, &creep, 1.0, &p, h).unwrap();
            eprintln!(
                "256 x 256, 10 branches: {:?} (D / V = {d:e})",
                start.elapsed()
            );
            assert!(d > 0.0);
        }
    }

    // ---- Line contacts ----

    /// `e^z E_1(z) = int_0^inf exp(-v) dv / (z + v)` by geometric Gauss–Legendre.
    fn exp_e1(z: f64) -> f64 {
        let rule = GaussLegendre::new(20);
        geometric(&rule, 1e-3 * z.min(1.0), 80.0, &|v: f64| {
            (-v).exp() / (z + v)
        })
    }

    /// The continuum D / V per unit branch compliance of the line pressure
    /// `exp(-x^2 / 2 b^2)`: `|p^|^2 = 2 pi b^2 exp(-k^2 b^2)` in (H1) gives
    /// `(2 b^2 / l) e^z E_1(z)`, `z = b^2 / l^2`.
    fn line_gaussian_reference(b: f64, l: f64) -> f64 {
        2.0 * b * b / l * exp_e1(b * b / (l * l))
    }

    /// Cell values of `exp(-x^2 / 2)` on `n` cells over `[-8, 8]`.
    fn line_gaussian_grid(n: usize) -> (Vec<f64>, f64) {
        let h = 16.0 / n as f64;
        let p = (0..n)
            .map(|i| {
                let x = -8.0 + (i as f64 + 0.5) * h;
                (-0.5 * x * x).exp()
            })
            .collect();
        (p, h)
    }

    #[test]
    fn line_hysteresis_gaussian_converges_to_the_continuum() {
        // p = exp(-x^2 / 2) on [-8, 8] against (2 / l) e^z E_1(z). Measured at 256
        // cells: -6.5e-4, -6.4e-4, -4.4e-4, -1.5e-4, -3.6e-5 for l = 1e-3 .. 1e4;
        // the error falls by 3.93 to 3.99 per halving (second order).
        for l in [1e-3, 0.1, 1.0, 10.0, 1e4] {
            let want = line_gaussian_reference(1.0, l);
            let e: Vec<f64> = [64, 128, 256]
                .iter()
                .map(|&n| {
                    let (p, h) = line_gaussian_grid(n);
                    line_dissipated_force(&one_branch(l), 1.0, &p, h).unwrap() / want - 1.0
                })
                .collect();
            eprintln!("line Gaussian l = {l:e}: {e:?}");
            assert!(e[2].abs() < 2e-3, "l = {l}: {e:?}");
            for k in 0..2 {
                let ratio = e[k] / e[k + 1];
                assert!((3.8..4.2).contains(&ratio), "l = {l}: {e:?}");
            }
        }
    }

    /// The interpolant's `h (2 / pi) int_0^inf sinc^4(theta / 2) |S|^2 w dtheta` in
    /// a plain way: `S` by explicit sums at every node, no folding, pieces of
    /// `pi / (4 n)` to `theta = 2 pi 1500` after geometric ones below, and the tail
    /// beyond with `|S|^2` and `sin^4` replaced by their means (`sum p_i^2`,
    /// `3 / 8`), integrated numerically.
    fn line_brute_force(p: &[f64], h: f64, lambda: f64) -> f64 {
        let rule = GaussLegendre::new(12);
        let n = p.len();
        let w = |t: f64| t * lambda / (1.0 + t * t * lambda * lambda);
        let f = |t: f64| {
            let (mut re, mut im) = (0.0, 0.0);
            for (i, v) in p.iter().enumerate() {
                let (s, c) = (t * i as f64).sin_cos();
                re += v * c;
                im -= v * s;
            }
            let form = if t < 1e-3 {
                (1.0 - t * t / 24.0).powi(4)
            } else {
                (2.0 * (0.5 * t).sin() / t).powi(4)
            };
            form * (re * re + im * im) * w(t)
        };
        let step = PI / (4.0 * n as f64);
        let mut sum = geometric(&rule, 1e-6 * step.min(1.0 / lambda), step, &f);
        let end = 2.0 * PI * 1500.0;
        let mut t = step;
        while t < end {
            sum += rule.integrate(t, t + step, f);
            t += step;
        }
        let mean: f64 = p.iter().map(|v| v * v).sum();
        let tail = |u: f64| mean * 6.0 * w(u) / u.powi(4);
        let mut a = t;
        while a < 1e12 {
            sum += rule.integrate(a, 2.0 * a, tail);
            a *= 2.0;
        }
        h * 2.0 / PI * sum
    }

    #[test]
    fn line_hysteresis_matches_brute_force_on_small_grids() {
        // Measured: 9.3e-12 at worst over both fields and lambda = 0.01 .. 1e6.
        let rough = [0.3, 1.0, 0.1, 0.7, 0.9, 0.2];
        let smooth: Vec<f64> = (0..10)
            .map(|i| {
                let x = i as f64 - 4.5;
                (-x * x / (2.0 * 1.5 * 1.5)).exp()
            })
            .collect();
        let mut worst = 0.0f64;
        for p in [&rough[..], &smooth[..]] {
            for lambda in [0.01, 0.3, 3.0, 300.0, 1e6] {
                let got = line_dissipated_force(&one_branch(lambda), 0.5, p, 0.5).unwrap();
                let want = line_brute_force(p, 0.5, lambda);
                let e = got / want - 1.0;
                worst = worst.max(e.abs());
                assert!(
                    e.abs() < 5e-11,
                    "n {} lambda {lambda}: {got} vs {want}: {e:.2e}",
                    p.len()
                );
            }
        }
        eprintln!("line hysteresis vs brute force: worst {worst:.2e}");
    }

    /// `-int p dw/dx dx` with `w` from the steady-sliding line kernel (the slope the
    /// slider in contact has, the tangential force per unit length) on the
    /// cell-wise constant pressure, central differences at the cell centres.
    fn line_kernel_route(p: &[f64], h: f64, l: f64) -> f64 {
        let n = p.len();
        let k =
            crate::body::viscoelastic::steady_sliding_line_kernel(&one_branch(l), h, n, 1.0, 100.0)
                .unwrap();
        let w: Vec<f64> = (0..n)
            .map(|i| (0..n).map(|j| k[i + n - 1 - j] * p[j]).sum())
            .collect();
        let mut d = 0.0;
        for i in 1..n - 1 {
            d -= p[i] * (w[i + 1] - w[i - 1]) / (2.0 * h);
        }
        d * h
    }

    #[test]
    fn line_hysteresis_equals_the_tangential_force() {
        // The energy balance: the body's loss equals the tangential force on a
        // slider whose surface follows the displacement of the steady-sliding
        // kernel (an independent route, through the hereditary integral). Both
        // converge to the continuum; their difference falls with the cell
        // (measured at 128 / 256 / 512 cells: 1.9e-3 / 3.2e-4 / 6.0e-5 for l = 0.1,
        // 4.6e-4 / 1.1e-4 / 2.8e-5 for l = 1, 1.6e-4 / 3.9e-5 / 9.6e-6 for l = 10).
        for (l, tol) in [(0.1, 2e-3), (1.0, 1e-3), (10.0, 1e-3)] {
            let e: Vec<f64> = [128, 256, 512]
                .iter()
                .map(|&n| {
                    let (p, h) = line_gaussian_grid(n);
                    let ours = line_dissipated_force(&one_branch(l), 1.0, &p, h).unwrap();
                    ours / line_kernel_route(&p, h, l) - 1.0
                })
                .collect();
            eprintln!("line kernel route l = {l}: {e:?}");
            assert!(
                e[2].abs() < tol && e[2].abs() < e[0].abs() / 3.0,
                "l = {l}: {e:?}"
            );
        }
    }

    #[test]
    fn line_hysteresis_branches_add_and_trivial_cases_give_zero() {
        let (p, h) = line_gaussian_grid(48);
        // And a branch that never creeps, which dissipates nothing.
        let mut two = two_branches();
        two.branches.push(CreepBranch {
            compliance: 2.0,
            retardation_time: f64::INFINITY,
        });
        let d = line_dissipated_force(&two, 0.1, &p, h).unwrap();
        let a = 0.5 * line_dissipated_force(&one_branch(0.02), 1.0, &p, h).unwrap();
        let b = 2.0 * line_dissipated_force(&one_branch(0.7), 1.0, &p, h).unwrap();
        assert!((d / (a + b) - 1.0).abs() < 1e-10, "{d} vs {}", a + b);
        assert!(d > 0.0);
        assert_eq!(line_dissipated_force(&two, 0.0, &p, h).unwrap(), 0.0);
        assert_eq!(
            line_dissipated_force(&two, f64::INFINITY, &p, h).unwrap(),
            0.0
        );
        assert_eq!(line_dissipated_force(&two, 1.0, &[0.0; 5], h).unwrap(), 0.0);
        // One cell: a hat of height p.
        assert!(line_dissipated_force(&two, 1.0, &[2.0], h).unwrap() > 0.0);
    }

    #[test]
    fn line_hysteresis_bad_input_names_the_argument() {
        let ok = one_branch(1.0);
        let message = |s: &CreepSeries, v: f64, p: &[f64], cell: f64| {
            line_dissipated_force(s, v, p, cell)
                .unwrap_err()
                .to_string()
        };
        let p = [1.0, 2.0, 1.0];
        assert!(message(&ok, 1.0, &p, 0.0).starts_with("cell"));
        assert!(message(&ok, -1.0, &p, 1.0).starts_with("velocity"));
        assert!(message(&ok, f64::NAN, &p, 1.0).starts_with("velocity"));
        assert!(message(&ok, 1.0, &[], 1.0).starts_with("nx"));
        assert!(message(&ok, 1.0, &[1.0, f64::NAN], 1.0).starts_with("pressure[1]"));
        let bad = CreepSeries {
            glassy: 0.0,
            branches: vec![CreepBranch {
                compliance: -1.0,
                retardation_time: 1.0,
            }],
        };
        assert!(message(&bad, 1.0, &p, 1.0).starts_with("creep.branches[0].compliance"));
    }

    #[test]
    #[ignore = "timing: run with --ignored --nocapture"]
    fn line_hysteresis_timing_4096_cells_10_branches() {
        let creep = ten_branches();
        let (p, h) = line_gaussian_grid(4096);
        for _ in 0..3 {
            let start = std::time::Instant::now();
            let d = line_dissipated_force(&creep, 1.0, &p, h).unwrap();
            eprintln!(
                "line, 4096 cells, 10 branches: {:?} (D / V = {d:e})",
                start.elapsed()
            );
        }
    }
}
