//! Test oracles for one layer bonded to a half-space, derived independently of
//! [`super::layered`]: the surface factor `A(k h)` in Perriot & Barthel's
//! cancellation-free closed form (J. Mater. Res. 19 (2004) 600) and the stresses from
//! the Papkovich–Neuber potentials of the coating and the substrate, whose six
//! coefficients solve the interface and surface conditions directly (Barber,
//! Elasticity, ch. 20; the plane-strain response along the wave vector). The layered
//! solution must reproduce both; they are not used by the solvers.
//!
//! Potentials: along the wave vector, `xi = (kx x + ky y) / k`, the field is plane
//! strain in the (xi, z) plane with `phi = Phi(kz) cos k xi`, `psi = k Psi(kz) cos k
//! xi`: per unit `p / k^2`, with `' = d/d(kz)` and `zeta = kz`,
//! `sigma_zz = Phi'' + zeta Psi'' - 2 (1 - nu) Psi'`,
//! `sigma_xixi = -Phi - zeta Psi - 2 nu Psi'`, `sigma_etaeta = -2 nu Psi'`,
//! `tau_xiz = -(Phi' + zeta Psi' - (1 - 2 nu) Psi)` times `sin k xi`.

#![allow(dead_code)]

use super::layered::{rotate, StressTransfer};
use super::Side;
use crate::case::Elastic;

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
    pub(crate) fn new(coating: Elastic, substrate: Elastic) -> Self {
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
    pub(crate) fn excess(&self, t: f64) -> f64 {
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
    pub(crate) fn factor(&self, t: f64) -> f64 {
        1.0 + self.excess(t)
    }

    /// Taylor coefficients `f_0 .. f_{n-1}` of `f(t) = A(t) - 1` at t = 0, by power
    /// series division of the cancellation-free numerator and denominator.
    pub(crate) fn taylor_coefficients(&self, n: usize) -> Vec<f64> {
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

/// The six coefficients `[A1, C1, B1, D1, A2, B2]` of the potentials for the
/// dimensionless thickness `t = k h1`, per unit `p / k^2`.
fn potential_coefficients(coating: Elastic, substrate: Elastic, t: f64) -> [f64; 6] {
    let mut m = [[0.0; 6]; 6];
    let mut r = [0.0; 6];
    // Surface, coating basis at zeta = 0.
    let top = quantities(coating, 0.0, &coating_basis(0.0, t));
    m[0][..4].copy_from_slice(&top[2]);
    r[0] = -1.0;
    m[1][..4].copy_from_slice(&top[3]);
    // Interface: coating minus substrate; displacements carry 1 / (2 mu).
    let inner = quantities(coating, t, &coating_basis(t, t));
    let outer = quantities(substrate, t, &substrate_basis(t, t));
    let mu1 = coating.young / (2.0 * (1.0 + coating.poisson));
    let mu2 = substrate.young / (2.0 * (1.0 + substrate.poisson));
    for q in 0..4 {
        let (s1, s2) = if q < 2 {
            (1.0 / mu1, 1.0 / mu2)
        } else {
            (1.0, 1.0)
        };
        for j in 0..4 {
            m[2 + q][j] = inner[q][j] * s1;
        }
        for j in 0..2 {
            m[2 + q][4 + j] = -outer[q][j] * s2;
        }
    }
    solve6(m, r)
}

/// Coating basis functions at zeta: (is_psi, value, d/dzeta factor).
fn coating_basis(zeta: f64, t: f64) -> [(bool, f64, f64); 4] {
    let (down, up) = ((-zeta).exp(), (zeta - t).exp());
    [
        (false, down, -1.0),
        (false, up, 1.0),
        (true, down, -1.0),
        (true, up, 1.0),
    ]
}

/// Substrate basis functions at zeta >= t.
fn substrate_basis(zeta: f64, t: f64) -> [(bool, f64, f64); 2] {
    let down = (t - zeta).exp();
    [(false, down, -1.0), (true, down, -1.0)]
}

/// Rows of `[2 mu u_xi (sin), 2 mu w (cos), sigma_zz, tau_xiz / (-sin)]`, one entry
/// per basis function, each `Phi`-type entry contributing `Phi` and each `Psi`-type
/// entry `zeta Psi`-terms as in the module doc.
fn quantities<const N: usize>(
    m: Elastic,
    zeta: f64,
    basis: &[(bool, f64, f64); N],
) -> [[f64; N]; 4] {
    let nu = m.poisson;
    let g = 3.0 - 4.0 * nu;
    let mut q = [[0.0; N]; 4];
    for (j, &(psi, v, d)) in basis.iter().enumerate() {
        if psi {
            q[0][j] = zeta * v;
            q[1][j] = zeta * d * v - g * v;
            q[2][j] = zeta * v - 2.0 * (1.0 - nu) * d * v;
            q[3][j] = zeta * d * v - (1.0 - 2.0 * nu) * v;
        } else {
            q[0][j] = v;
            q[1][j] = d * v;
            q[2][j] = v;
            q[3][j] = d * v;
        }
    }
    q
}

/// Gaussian elimination with partial pivoting for the 6 x 6 system.
fn solve6(mut m: [[f64; 6]; 6], mut r: [f64; 6]) -> [f64; 6] {
    for c in 0..6 {
        let p = (c..6)
            .max_by(|&i, &j| m[i][c].abs().total_cmp(&m[j][c].abs()))
            .unwrap_or(c);
        m.swap(c, p);
        r.swap(c, p);
        let pivot = m[c];
        for i in c + 1..6 {
            let f = m[i][c] / pivot[c];
            for (x, p) in m[i].iter_mut().zip(pivot.iter()).skip(c) {
                *x -= f * p;
            }
            r[i] -= f * r[c];
        }
    }
    let mut x = [0.0; 6];
    for i in (0..6).rev() {
        let s: f64 = (i + 1..6).map(|j| m[i][j] * x[j]).sum();
        x[i] = (r[i] - s) / m[i][i];
    }
    x
}

/// `(sigma_xixi, sigma_etaeta, sigma_zz, tau_xiz / (-sin))` per unit p at zeta.
fn plane_stresses(
    material: Elastic,
    zeta: f64,
    coefficients: &[f64],
    basis: &[(bool, f64, f64)],
) -> [f64; 4] {
    let nu = material.poisson;
    let (mut phi, mut dphi, mut psi, mut dpsi) = (0.0, 0.0, 0.0, 0.0);
    for (&c, &(is_psi, v, d)) in coefficients.iter().zip(basis) {
        if is_psi {
            psi += c * v;
            dpsi += c * d * v;
        } else {
            phi += c * v;
            dphi += c * d * v;
        }
    }
    // Exponential basis: f'' = f.
    let (ddphi, ddpsi) = (phi, psi);
    [
        -phi - zeta * psi - 2.0 * nu * dpsi,
        -2.0 * nu * dpsi,
        ddphi + zeta * ddpsi - 2.0 * (1.0 - nu) * dpsi,
        dphi + zeta * dpsi - (1.0 - 2.0 * nu) * psi,
    ]
}

/// Stress transfer at depth z >= 0 (coating side at z = h1 itself), for a wave
/// vector (kx, ky) != 0. At k = 0 the response depends on the direction of
/// approach; the limit along x is returned.
///
/// Not part of the API (bodies give their stresses through [`crate::stress`]):
/// public only for the independent transforms of `tests/coated_stress.rs`.
#[doc(hidden)]
pub(crate) fn coated_stress_transfer(
    coating: Elastic,
    thickness: f64,
    substrate: Elastic,
    kx: f64,
    ky: f64,
    z: f64,
) -> StressTransfer {
    let side = if z <= thickness {
        Side::Above
    } else {
        Side::Below
    };
    stress_transfer_on_side(coating, thickness, substrate, kx, ky, z, side)
}

/// Both sides of the interface z = h1: `(coating side, substrate side)`.
///
/// Not part of the API: public only for `tests/coated_stress.rs`.
#[doc(hidden)]
pub(crate) fn interface_stress_transfer(
    coating: Elastic,
    thickness: f64,
    substrate: Elastic,
    kx: f64,
    ky: f64,
) -> (StressTransfer, StressTransfer) {
    (
        stress_transfer_on_side(
            coating,
            thickness,
            substrate,
            kx,
            ky,
            thickness,
            Side::Above,
        ),
        stress_transfer_on_side(
            coating,
            thickness,
            substrate,
            kx,
            ky,
            thickness,
            Side::Below,
        ),
    )
}

fn stress_transfer_on_side(
    coating: Elastic,
    thickness: f64,
    substrate: Elastic,
    kx: f64,
    ky: f64,
    z: f64,
    side: Side,
) -> StressTransfer {
    let s = plane_stress_transfer(coating, thickness, substrate, kx.hypot(ky), z, side);
    rotate(kx, ky, s)
}

/// The stresses of the wave-vector frame per unit pressure at depth z on `side`:
/// `[T_xixi, T_etaeta, T_zz, T_xiz / i]` for a wavenumber `k >= 0` (all real; the
/// shear transfer is `i` times the last entry). They depend on k only, not on the
/// direction. At k = 0 the long-wave limit is returned.
pub(crate) fn plane_stress_transfer(
    coating: Elastic,
    thickness: f64,
    substrate: Elastic,
    k: f64,
    z: f64,
    side: Side,
) -> [f64; 4] {
    // The k -> 0 limit, evaluated at a wavelength far beyond every length.
    let k = k.max(1e-9 / thickness.max(z).max(f64::MIN_POSITIVE));
    let (t, zeta) = (k * thickness, k * z);
    let x = potential_coefficients(coating, substrate, t);
    match side {
        Side::Above => plane_stresses(coating, zeta, &x[..4], &coating_basis(zeta, t)),
        Side::Below => plane_stresses(substrate, zeta, &x[4..], &substrate_basis(zeta, t)),
    }
}
