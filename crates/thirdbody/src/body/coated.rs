//! Coated elastic half-space: a coating (E1, nu1) of thickness h1 perfectly bonded
//! (paper eq. 5) to a substrate half-space (E2, nu2), loaded by a normal surface
//! pressure; the influence kernel of a uniformly loaded square cell (paper eq. 10).
//!
//! # Surface response in Fourier space
//! Conventions: z points into the body, the surface is z = 0, the pressure p >= 0
//! is compressive (sigma_zz(0) = -p), the normal displacement w > 0 into the body.
//! Fourier transform `p^(k) = int p(x, y) e^{-i k.x} dx dy`, `k = |k|`.
//! For one Fourier component the problem is a plane-strain problem in the plane of
//! (k, z). With the Papkovich–Neuber solution
//! `2 mu u = grad phi + z grad psi - (3 - 4 nu) psi e_z`
//! (Barber, Elasticity, ch. 20, solutions A and B) and
//! `phi = (A e^{-kz} + C e^{k(z-h1)}) cos k xi`, `psi = k (B e^{-kz} + D e^{k(z-h1)})
//! cos k xi` in the coating, and only the decaying terms in the substrate, the six
//! conditions (zero shear and sigma_zz = -p at z = 0; continuity of u_xi, w,
//! sigma_zz, tau_xz at z = h1, eq. 5) give
//!
//! `w^(k) = 2 (1 - nu1^2) / (E1 k) * A(k h1) * p^(k)`,
//! `A(t) = (1 + 4 b t e^{-2t} - a b e^{-4t}) / (1 - (a + b + 4 b t^2) e^{-2t} + a b e^{-4t})`,
//! `a = (alpha g2 - g1) / (1 + alpha g2)`, `b = (alpha - 1) / (alpha + g1)`,
//! `alpha = mu1 / mu2`, `g_i = 3 - 4 nu_i`
//!
//! (the form of Perriot & Barthel, J. Mater. Res. 19 (2004) 600, eq. 4; equivalent
//! to Chen, Int. J. Eng. Sci. 9 (1971) 775 and O'Sullivan & King, J. Tribol. 110
//! (1988) 235). A unit test checks it against a direct numerical solution of the
//! six conditions. Checks: E1 = E2, nu1 = nu2 gives a = b = 0, A = 1; A -> 1 for
//! t -> inf (the coating alone); A(0) = E1 (1 - nu2^2) / (E2 (1 - nu1^2)) (the
//! substrate alone). For stiff coatings a, b -> 1 and the textbook denominator
//! cancels; it is evaluated in the cancellation-free form
//! `(1-a)(1-b) + x [a(1-b) + b(1-a) e^{-2t}] + 2 b e^{-t} (sinh t - t)(x + 2 t e^{-t})`,
//! `x = 1 - e^{-2t}`, whose terms are all positive when 0 < a, b < 1.
//!
//! # Kernel of a square cell
//! The displacement at the centre of a cell offset by (X, Y) from a cell of side
//! 2a under unit pressure is written as
//! `K(X, Y) = K_sub(X, Y) + K_D(X, Y)`:
//! `K_sub` is Love's closed form with the substrate's moduli (the k -> 0 limit;
//! [`super::homogeneous`]); `K_D` is the cell integral of the radial point response
//! whose transform `C (A(k h1) - A(0)) / k`, `C = 2 (1 - nu1^2) / E1`, is bounded
//! at k = 0 (no 1/k singularity, no periodic images: no FFT is involved). For a
//! radial function g, the integral over `[0, u] x [0, v]` is, splitting the
//! rectangle along its diagonal and substituting `r = u cosh tau`,
//! `F(u, v) = int_0^{asinh(v/u)} M(u cosh tau) / cosh tau dtau + (u <-> v)`,
//! `M(R) = int_0^R g(r) r dr = (C h1 / 2 pi) mu(R / h1)` (module `coated_radial`);
//! the cell integral is the signed sum of F over its four corners. The
//! `F` of all `(nx + 1) x (ny + 1)` corner offsets are accumulated along tau with
//! Gauss–Legendre panels, so the whole kernel costs O(nx ny) evaluations of a
//! tabulated smooth function.
//!
//! Accuracy (tests/coated_kernel.rs): against a direct polar quadrature of the
//! Fourier integral (eq. 10) the kernel agrees to 4e-14 relative (E1/E2 = 10 and
//! 0.1, h1 = 0.05 and 20 cells, offsets up to (7, 4)); at far offsets its difference
//! from the substrate kernel follows the analytic multipole tail; the radial table
//! reproduces its direct evaluation to 1e-11. Cost: about 0.3-0.5 s for 256 x 256
//! cells on two cores (benches/coated_kernel.rs) when h1 is not much below a cell;
//! very thin stiff coatings cost more, because the radial table then needs the
//! Hankel integral up to large R / h1 (256 x 256, h1 = 0.05 cell: 0.1 s for
//! E1/E2 = 0.1, 0.8 s for 10, 6 s for 100).

use std::f64::consts::PI;

use rayon::prelude::*;

use super::coated_radial::{RadialRemainder, MAX_DIRECT_S};
use super::homogeneous::love_rectangle_displacement;
use super::quadrature::GaussLegendre;
use super::ElasticBody;
use crate::case::Elastic;
use crate::error::{require_positive, Error, Result};
use crate::provenance::{self, Reference};
use crate::stress::{CoatedStressKernels, Side, StressKernels};

/// A coating of thickness `thickness` perfectly bonded to a substrate half-space.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoatedHalfSpace {
    /// The coating (E1, nu1).
    pub coating: Elastic,
    /// Coating thickness h1 > 0.
    pub thickness: f64,
    /// The substrate (E2, nu2).
    pub substrate: Elastic,
}

impl ElasticBody for CoatedHalfSpace {
    fn surface_kernel_quadrant(&self, cell: f64, nx: usize, ny: usize) -> Result<Vec<f64>> {
        coated_surface_kernel(self.coating, self.thickness, self.substrate, cell, nx, ny)
    }

    fn stress_kernels(&self, interface_side: Side) -> Box<dyn StressKernels> {
        Box::new(CoatedStressKernels {
            coating: self.coating,
            thickness: self.thickness,
            substrate: self.substrate,
            interface_side,
        })
    }

    fn interface_depths(&self) -> Vec<f64> {
        vec![self.thickness]
    }

    fn softest_modulus(&self) -> f64 {
        self.coating
            .plane_strain_modulus()
            .min(self.substrate.plane_strain_modulus())
    }

    fn references(&self) -> Vec<Reference> {
        let response = "the coated body's Fourier response (surface and stress kernels)";
        vec![
            Reference::new(provenance::CHEN, response),
            Reference::new(provenance::OSULLIVAN_KING, response),
            Reference::new(
                provenance::PERRIOT_BARTHEL,
                "the coated body's response in a cancellation-free form",
            ),
            Reference::new(
                provenance::LOVE,
                "the substrate's part of the coated kernels (uniform pressure on a rectangle)",
            ),
        ]
    }
}

/// The two-layer coefficients of `A(t)` for one pair of materials.
#[derive(Debug, Clone, Copy)]
pub struct TransferFactor {
    a: f64,
    b: f64,
    one_minus_a: f64,
    one_minus_b: f64,
}

impl TransferFactor {
    /// Coefficients for a coating bonded to a substrate (any -1 < nu <= 0.5).
    pub fn new(coating: Elastic, substrate: Elastic) -> Self {
        let mu1 = coating.young / (2.0 * (1.0 + coating.poisson));
        let mu2 = substrate.young / (2.0 * (1.0 + substrate.poisson));
        let alpha = mu1 / mu2;
        let g1 = 3.0 - 4.0 * coating.poisson;
        let g2 = 3.0 - 4.0 * substrate.poisson;
        TransferFactor {
            a: (alpha * g2 - g1) / (1.0 + alpha * g2),
            b: (alpha - 1.0) / (alpha + g1),
            one_minus_a: (1.0 + g1) / (1.0 + alpha * g2),
            one_minus_b: (1.0 + g1) / (alpha + g1),
        }
    }

    /// The denominator of A(t), cancellation-free.
    fn denominator(&self, t: f64) -> f64 {
        let (a, b) = (self.a, self.b);
        let e2 = (-2.0 * t).exp();
        let x = -(-2.0 * t).exp_m1();
        let e1 = (-t).exp();
        self.one_minus_a * self.one_minus_b
            + x * (a * self.one_minus_b + b * self.one_minus_a * e2)
            + 2.0 * b * e1 * sinh_minus_identity(t) * (x + 2.0 * t * e1)
    }

    /// `f(t) = A(t) - 1`, which decays like `4 b t^2 e^{-2t}`.
    pub fn excess(&self, t: f64) -> f64 {
        let (a, b) = (self.a, self.b);
        let e2 = (-2.0 * t).exp();
        let x = -(-2.0 * t).exp_m1();
        let numerator = e2
            * (a * self.one_minus_b
                + b * self.one_minus_a
                + 4.0 * b * t * (1.0 + t)
                + 2.0 * a * b * x);
        numerator / self.denominator(t)
    }

    /// `A(t)`.
    pub fn factor(&self, t: f64) -> f64 {
        1.0 + self.excess(t)
    }

    /// Taylor coefficients `f_0 .. f_{n-1}` of `f(t) = A(t) - 1` at t = 0, by power
    /// series division of the cancellation-free numerator and denominator.
    pub fn taylor_coefficients(&self, n: usize) -> Vec<f64> {
        let (a, b) = (self.a, self.b);
        let exp_series = |rate: f64| -> Vec<f64> {
            let mut c = vec![1.0; n];
            for k in 1..n {
                c[k] = c[k - 1] * rate / k as f64;
            }
            c
        };
        let e2 = exp_series(-2.0);
        let e1 = exp_series(-1.0);
        let mut x: Vec<f64> = e2.iter().map(|c| -c).collect();
        x[0] = 0.0;
        let mut sinh_minus = vec![0.0; n];
        for k in (3..n).step_by(2) {
            sinh_minus[k] = exp_series(1.0)[k];
        }
        let mut two_t_e1 = vec![0.0; n];
        for k in 1..n {
            two_t_e1[k] = 2.0 * e1[k - 1];
        }
        let x_plus = add(&x, &two_t_e1);
        let last = mul(&mul(&e1, &sinh_minus), &x_plus);
        let mut den = vec![0.0; n];
        let middle = mul(&x, &e2);
        for k in 0..n {
            den[k] =
                a * self.one_minus_b * x[k] + b * self.one_minus_a * middle[k] + 2.0 * b * last[k];
        }
        den[0] += self.one_minus_a * self.one_minus_b;
        let mut inner = vec![0.0; n];
        inner[0] = a * self.one_minus_b + b * self.one_minus_a;
        if n > 1 {
            inner[1] = 4.0 * b;
        }
        if n > 2 {
            inner[2] = 4.0 * b;
        }
        for k in 0..n {
            inner[k] += 2.0 * a * b * x[k];
        }
        let num = mul(&e2, &inner);
        let mut f = vec![0.0; n];
        for k in 0..n {
            let mut s = num[k];
            for j in 0..k {
                s -= f[j] * den[k - j];
            }
            f[k] = s / den[0];
        }
        f
    }
}

fn add(p: &[f64], q: &[f64]) -> Vec<f64> {
    p.iter().zip(q).map(|(a, b)| a + b).collect()
}

/// Truncated product of two power series.
fn mul(p: &[f64], q: &[f64]) -> Vec<f64> {
    let n = p.len();
    let mut r = vec![0.0; n];
    for i in 0..n {
        for j in 0..n - i {
            r[i + j] += p[i] * q[j];
        }
    }
    r
}

/// `sinh t - t` without cancellation for small t.
fn sinh_minus_identity(t: f64) -> f64 {
    if t.abs() < 0.5 {
        let t2 = t * t;
        // t^3/3! + t^5/5! + ... to 1e-17 relative for |t| < 0.5.
        let mut term = t * t2 / 6.0;
        let mut sum = term;
        let mut k = 3.0;
        while term.abs() > 1e-18 * sum.abs() {
            term *= t2 / ((k + 1.0) * (k + 2.0));
            sum += term;
            k += 2.0;
        }
        sum
    } else {
        t.sinh() - t
    }
}

/// The coating factor `A(k h1)` of the surface response (see the module doc);
/// accepts -1 < nu <= 0.5 (the caller validates materials).
///
/// Not part of the API: public only for the quadratures `tests/coated_kernel.rs`
/// checks the kernel against.
#[doc(hidden)]
pub fn coating_factor(coating: Elastic, substrate: Elastic, k_thickness: f64) -> f64 {
    TransferFactor::new(coating, substrate).factor(k_thickness)
}

/// Surface compliance in Fourier space, `w^(k) / p^(k) = 2 (1 - nu1^2) / (E1 k) A(k h1)`,
/// for a wavenumber `k > 0`.
pub fn coated_surface_compliance(
    coating: Elastic,
    thickness: f64,
    substrate: Elastic,
    k: f64,
) -> f64 {
    let nu = coating.poisson;
    2.0 * (1.0 - nu * nu) / (coating.young * k) * coating_factor(coating, substrate, k * thickness)
}

/// Window diagonal over h1 below which the coating is treated as thick: its kernel is
/// the coating half-space's plus the constant the far substrate adds (see
/// [`thick_coating_kernel`]), whose error falls as (diagonal / h1)^3 (5e-13 here). The
/// full expansion loses digits in that range instead (2.7e-10 of the kernel at 1e-4,
/// 1.2e-8 at 2e-6; mu off by 4e-3 at h1 = 1e14 on a 0.1 window and the uncoated
/// answer beyond).
const THICK_COATING_S: f64 = 1e-4;

/// The surface kernel of a coating much thicker than the window: Love's kernel of the
/// coating material plus, on every cell, `cell^2 (1 - nu1^2) / (pi E1 h1) I` with
/// `I = int_0^inf (A(t) - 1) dt`: the point-load response `(1/2 pi) int C(k) J0(k r) k
/// dk` with `C(k) = 2 (1 - nu1^2) A(k h1) / (E1 k)` is `(1 - nu1^2) / (pi E1 r)` plus
/// that constant, with `J0(k r) = 1 - O((k r)^2)` over the k ~ 1/h1 where `A != 1`.
fn thick_coating_kernel(
    coating: Elastic,
    thickness: f64,
    factor: &TransferFactor,
    cell: f64,
    nx: usize,
    ny: usize,
) -> Vec<f64> {
    // A(t) - 1 falls like t e^{-2t}: panels of 0.25 to t = 60 leave < 1e-40.
    let rule = GaussLegendre::new(TAU_NODES);
    let excess: f64 = (0..240)
        .map(|k| {
            let lo = 0.25 * k as f64;
            rule.integrate(lo, lo + 0.25, |t| factor.factor(t) - 1.0)
        })
        .sum();
    let nu = coating.poisson;
    let offset = cell * cell * (1.0 - nu * nu) / (PI * coating.young * thickness) * excess;
    let a = 0.5 * cell;
    let mut kernel = vec![0.0; nx * ny];
    kernel.par_chunks_mut(nx).enumerate().for_each(|(dj, row)| {
        for (di, out) in row.iter_mut().enumerate() {
            let (x, y) = (di as f64 * cell, dj as f64 * cell);
            *out = love_rectangle_displacement(coating, a, a, x, y) + offset;
        }
    });
    kernel
}

/// Tau panels no wider than this in the corner integrals.
const TAU_PANEL: f64 = 0.25;
/// Gauss–Legendre nodes per tau panel.
const TAU_NODES: usize = 8;

/// Displacement at cell offset `(di, dj)` (0 <= di < nx, 0 <= dj < ny, row-major
/// `dj * nx + di`) per unit pressure on one square cell of side `cell`, on the
/// coated body. The kernel is even in di and dj.
///
/// Not part of the API (bodies give their kernels through [`ElasticBody`]): public
/// only for `benches/coated_kernel.rs` and the checks in `tests/coated_kernel.rs`.
#[doc(hidden)]
pub fn coated_surface_kernel(
    coating: Elastic,
    thickness: f64,
    substrate: Elastic,
    cell: f64,
    nx: usize,
    ny: usize,
) -> Result<Vec<f64>> {
    coating.validate("coating")?;
    substrate.validate("substrate")?;
    require_positive("coating.thickness", thickness)?;
    require_positive("grid.cell", cell)?;
    if nx == 0 || ny == 0 {
        return Err(Error::invalid(
            "grid.cells",
            format!("[{nx}, {ny}]"),
            "at least one cell along each axis",
        ));
    }
    let a = 0.5 * cell;
    let h = thickness;
    let n = nx.max(ny);
    let factor = TransferFactor::new(coating, substrate);
    // Corner offsets are (i + 1/2) cell, i = 0..=n, so s = R / h spans:
    let s_lo = a / h;
    let s_hi = 2f64.sqrt() * (n as f64 + 0.5) * cell / h;
    if s_hi < THICK_COATING_S {
        return Ok(thick_coating_kernel(coating, h, &factor, cell, nx, ny));
    }
    let radial = RadialRemainder::new(&factor, s_lo, s_hi).map_err(|_| {
        // Only s_hi (window diagonal / h1) can be brought below the limit.
        let thinnest = s_hi * h / MAX_DIRECT_S;
        Error::invalid(
            "coating.thickness",
            thickness,
            &format!(
                "a coating at least {thinnest:.3e} thick for E1/E2 = {:.3e} on this window \
                 (a thinner, much stiffer coating needs the kernel's radial integral beyond \
                 R/h1 = {MAX_DIRECT_S:e}); use a smaller window, a thicker coating, or the \
                 substrate alone",
                coating.young / substrate.young
            ),
        )
    })?;
    let scale = (1.0 - coating.poisson * coating.poisson) / coating.young * h / PI;
    // half[i][j] = int_0^{asinh(v_j/u_i)} mu(u_i cosh tau / h) / cosh tau dtau.
    let rule = GaussLegendre::new(TAU_NODES);
    // Corners used: half(i, j) with i < nx, j < ny and half(j, i); row i needs
    // j up to ny - 1 (if i < nx) and up to nx - 1 (if i < ny).
    let row_length = |i: usize| (if i < nx { ny } else { 0 }).max(if i < ny { nx } else { 0 });
    let mut half: Vec<Vec<f64>> = (0..n).map(|i| vec![0.0; row_length(i)]).collect();
    half.par_iter_mut().enumerate().for_each(|(i, row)| {
        let alpha = (i as f64 + 0.5) * cell / h;
        let mut tau = 0.0;
        let mut sum = 0.0;
        for (j, out) in row.iter_mut().enumerate() {
            let beta = (j as f64 + 0.5) * cell / h;
            let end = (beta / alpha).asinh();
            let pieces = ((end - tau) / TAU_PANEL).ceil().max(1.0) as usize;
            let step = (end - tau) / pieces as f64;
            for p in 0..pieces {
                let lo = tau + p as f64 * step;
                sum += rule.integrate(lo, lo + step, |x| {
                    let c = x.cosh();
                    radial.mu(alpha * c) / c
                });
            }
            tau = end;
            *out = sum;
        }
    });
    // Corner primitive F(|u_i|, |v_j|) of the remainder.
    let corner = |i: usize, j: usize| scale * (half[i][j] + half[j][i]);
    // Signed corner index for the edge at offset d + sign/2 cells.
    let edge = |d: usize, upper: bool| -> (usize, f64) {
        if upper {
            (d, 1.0)
        } else if d >= 1 {
            (d - 1, 1.0)
        } else {
            (0, -1.0)
        }
    };
    let mut kernel = vec![0.0; nx * ny];
    kernel.par_chunks_mut(nx).enumerate().for_each(|(dj, row)| {
        for (di, out) in row.iter_mut().enumerate() {
            let mut remainder = 0.0;
            for (upper_u, su) in [(true, 1.0), (false, -1.0)] {
                let (iu, sign_u) = edge(di, upper_u);
                for (upper_v, sv) in [(true, 1.0), (false, -1.0)] {
                    let (jv, sign_v) = edge(dj, upper_v);
                    remainder += su * sv * sign_u * sign_v * corner(iu, jv);
                }
            }
            let x = di as f64 * cell;
            let y = dj as f64 * cell;
            *out = love_rectangle_displacement(substrate, a, a, x, y) + remainder;
        }
    });
    if kernel.iter().any(|v| !v.is_finite()) {
        return Err(Error::invalid(
            "coating",
            format!("E1 = {}, E2 = {}", coating.young, substrate.young),
            "moduli whose coated kernel is finite (the asymptotic series failed)",
        ));
    }
    Ok(kernel)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The thick-coating kernel against the full expansion: their difference falls as
    /// (window diagonal / h1)^3, the first term the thick kernel leaves out, down to
    /// 5e-10 at a ratio of 1e-3; below 1e-4 (the switch) the full expansion's own
    /// rounding (2.7e-10 at 1e-4, 1.2e-8 at 2e-6) is the larger error.
    #[test]
    fn a_coating_much_thicker_than_the_window_is_its_own_half_space_plus_a_constant() {
        let (e1, e2) = (elastic(3.0, 0.25), elastic(1.0, 0.3));
        let (cell, n) = (1e-3, 16);
        let diagonal = 2f64.sqrt() * (n as f64 + 0.5) * cell;
        let difference = |ratio: f64| {
            let h = diagonal / ratio;
            let thick = thick_coating_kernel(e1, h, &TransferFactor::new(e1, e2), cell, n, n);
            let full = coated_surface_kernel(e1, h, e2, cell, n, n).unwrap();
            thick
                .iter()
                .zip(&full)
                .map(|(a, b)| (a - b).abs() / b.abs())
                .fold(0.0, f64::max)
        };
        let (d1, d2, d3) = (difference(1e-1), difference(1e-2), difference(1e-3));
        for (coarse, fine) in [(d1, d2), (d2, d3)] {
            let order = (coarse / fine).log10();
            assert!(
                (order - 3.0).abs() < 0.1,
                "order {order}: {d1:e} {d2:e} {d3:e}"
            );
        }
        assert!(d3 < 1e-9, "{d3:e}");
        // The constant is what the coating half-space misses; a softer substrate
        // adds compliance, so it is positive here and the kernel exceeds Love's.
        let h = diagonal / (0.5 * THICK_COATING_S);
        let thick = coated_surface_kernel(e1, h, e2, cell, n, n).unwrap();
        let love0 = love_rectangle_displacement(e1, 0.5 * cell, 0.5 * cell, 0.0, 0.0);
        assert!(thick[0] > love0 && thick[0] - love0 < 1e-3 * love0);
    }

    fn elastic(young: f64, poisson: f64) -> Elastic {
        Elastic { young, poisson }
    }

    /// Dense Gaussian elimination with partial pivoting (test oracle).
    fn solve_dense(mut m: Vec<Vec<f64>>, mut r: Vec<f64>) -> Vec<f64> {
        let n = r.len();
        for c in 0..n {
            let p = (c..n)
                .max_by(|&i, &j| m[i][c].abs().total_cmp(&m[j][c].abs()))
                .unwrap();
            m.swap(c, p);
            r.swap(c, p);
            let (top, bottom) = m.split_at_mut(c + 1);
            let pivot = &top[c];
            for (i, row) in bottom.iter_mut().enumerate() {
                let f = row[c] / pivot[c];
                for (x, p) in row.iter_mut().zip(pivot).skip(c) {
                    *x -= f * p;
                }
                r[c + 1 + i] -= f * r[c];
            }
        }
        let mut x = vec![0.0; n];
        for i in (0..n).rev() {
            let s: f64 = (i + 1..n).map(|j| m[i][j] * x[j]).sum();
            x[i] = (r[i] - s) / m[i][i];
        }
        x
    }

    /// The six boundary and interface conditions of the module doc, assembled
    /// from the Papkovich–Neuber potentials and solved numerically: returns
    /// `w(0) mu1 k / ((1 - nu1) p)`, which is A(t).
    fn factor_from_boundary_value_problem(c: Elastic, s: Elastic, t: f64) -> f64 {
        let mu = [
            c.young / (2.0 * (1.0 + c.poisson)),
            s.young / (2.0 * (1.0 + s.poisson)),
        ];
        let nu = [c.poisson, s.poisson];
        // Rows of [u_xi, w, sigma_zz, tau] (common factors dropped) per basis
        // function at depth z = kz; basis: (is_psi, value, d/dz sign).
        let rows = |z: f64, body: usize| -> [Vec<f64>; 4] {
            let g = 3.0 - 4.0 * nu[body];
            let basis: Vec<(bool, f64, f64)> = if body == 0 {
                vec![
                    (false, (-z).exp(), -1.0),
                    (false, (z - t).exp(), 1.0),
                    (true, (-z).exp(), -1.0),
                    (true, (z - t).exp(), 1.0),
                ]
            } else {
                vec![(false, (t - z).exp(), -1.0), (true, (t - z).exp(), -1.0)]
            };
            let mut q: [Vec<f64>; 4] = Default::default();
            for (psi, v, d) in basis {
                if psi {
                    q[0].push(z * v);
                    q[1].push(z * d * v - g * v);
                    q[2].push(z * v - 2.0 * (1.0 - nu[body]) * d * v);
                    q[3].push(z * d * v - (1.0 - 2.0 * nu[body]) * v);
                } else {
                    q[0].push(v);
                    q[1].push(d * v);
                    q[2].push(v);
                    q[3].push(d * v);
                }
            }
            q
        };
        let (top, inner, outer) = (rows(0.0, 0), rows(t, 0), rows(t, 1));
        let mut m = Vec::new();
        let mut r = Vec::new();
        let pad = |v: &Vec<f64>| [v.clone(), vec![0.0, 0.0]].concat();
        m.push(pad(&top[2]));
        r.push(-1.0);
        m.push(pad(&top[3]));
        r.push(0.0);
        for (q, displacement) in [(0, true), (1, true), (2, false), (3, false)] {
            let (s1, s2) = if displacement {
                (1.0 / mu[0], 1.0 / mu[1])
            } else {
                (1.0, 1.0)
            };
            let mut row: Vec<f64> = inner[q].iter().map(|v| v * s1).collect();
            row.extend(outer[q].iter().map(|v| -v * s2));
            m.push(row);
            r.push(0.0);
        }
        let x = solve_dense(m, r);
        let w: f64 = top[1].iter().zip(&x).map(|(a, b)| a * b).sum::<f64>() / (2.0 * mu[0]);
        w * mu[0] / (1.0 - nu[0])
    }

    #[test]
    fn closed_form_factor_solves_the_bonded_two_layer_problem() {
        let cases = [
            (elastic(10.0, 0.3), elastic(1.0, 0.25)),
            (elastic(0.1, 0.2), elastic(1.0, 0.45)),
            (elastic(3.0, 0.3), elastic(1.0, 0.3)),
            (elastic(1.0, 0.1), elastic(1.0, 0.4)),
        ];
        for (c, s) in cases {
            for t in [0.01, 0.1, 0.3, 1.0, 3.0, 8.0] {
                let closed = coating_factor(c, s, t);
                let direct = factor_from_boundary_value_problem(c, s, t);
                assert!(
                    (closed - direct).abs() < 1e-11 * direct.abs(),
                    "{c:?} {s:?} t = {t}: {closed} vs {direct}"
                );
            }
        }
    }

    #[test]
    fn factor_limits() {
        let (c, s) = (elastic(7.0, 0.2), elastic(1.5, 0.35));
        let a0 = c.young * (1.0 - 0.35 * 0.35) / (s.young * (1.0 - 0.04));
        assert!((coating_factor(c, s, 1e-9) - a0).abs() < 1e-7 * a0);
        assert!((coating_factor(c, s, 40.0) - 1.0).abs() < 1e-14);
        let same = elastic(2.0, 0.3);
        for t in [0.0, 0.5, 3.0] {
            assert_eq!(coating_factor(same, same, t), 1.0);
        }
    }

    #[test]
    fn stiff_coating_factor_keeps_its_digits() {
        // E1/E2 = 1e4: compare with the boundary-value problem, whose pivoted
        // elimination does not suffer the textbook cancellation at small t.
        let (c, s) = (elastic(1e4, 0.3), elastic(1.0, 0.3));
        for t in [1e-4, 1e-3, 0.05] {
            let closed = coating_factor(c, s, t);
            let direct = factor_from_boundary_value_problem(c, s, t);
            assert!(
                (closed - direct).abs() < 1e-8 * direct,
                "t = {t}: {closed} vs {direct}"
            );
        }
    }

    #[test]
    fn taylor_coefficients_reproduce_the_function() {
        for (c, s) in [
            (elastic(10.0, 0.3), elastic(1.0, 0.25)),
            (elastic(0.1, 0.2), elastic(1.0, 0.45)),
        ] {
            let f = TransferFactor::new(c, s);
            let coefficients = f.taylor_coefficients(60);
            // The radius of convergence exceeds 0.05 for both.
            for t in [0.004, 0.01, -0.01] {
                let series: f64 = coefficients.iter().rev().fold(0.0, |acc, &cn| acc * t + cn);
                let exact = f.excess(t);
                assert!(
                    (series - exact).abs() < 1e-12 * exact.abs(),
                    "{t}: {series} {exact}"
                );
            }
        }
    }
}
