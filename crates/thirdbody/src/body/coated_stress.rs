//! Stresses inside a coated half-space in Fourier space: for a surface pressure
//! `p(x, y) = p^ e^{i (kx x + ky y)}` (compressive, sigma_zz(0) = -p) on a coating
//! (E1, nu1, thickness h1) bonded to a substrate (E2, nu2) (paper eq. 5), every
//! stress component at depth z is `sigma^(z) e^{i (kx x + ky y)}` with
//! `sigma^ = T(kx, ky, z) p^`. Stresses are tension-positive, z points into the body.
//!
//! Derivation (same solution as the surface response in [`super::coated`]): along
//! the wave vector, `xi = (kx x + ky y) / k`, the field is plane strain in the
//! (xi, z) plane with the Papkovich–Neuber potentials
//! `phi = Phi(kz) cos k xi`, `psi = k Psi(kz) cos k xi` (Barber, Elasticity, ch. 20):
//! per unit `p / k^2`, with `' = d/d(kz)` and `zeta = kz`,
//! `sigma_zz = Phi'' + zeta Psi'' - 2 (1 - nu) Psi'`,
//! `sigma_xixi = -Phi - zeta Psi - 2 nu Psi'`,
//! `sigma_etaeta = -2 nu Psi'` (eta across the wave vector, where `u_eta = 0`),
//! `tau_xiz = -(Phi' + zeta Psi' - (1 - 2 nu) Psi)` times `sin k xi`.
//! The six coefficients (four in the coating, `e^{-zeta}` and `e^{zeta - kh1}` in
//! Phi and Psi; two decaying ones in the substrate) solve the six conditions of eq. 5
//! and the free surface; the system is solved numerically with partial pivoting in
//! this bounded basis, which stays well conditioned from `k h1 -> 0` to `k h1 >> 1`.
//! A sine factor is `-i` in complex notation, so the shear components `T_xz`,
//! `T_yz` are imaginary and the others real. Rotating from (xi, eta) to (x, y):
//! `xx = xixi c^2 + etaeta s^2`, `yy = xixi s^2 + etaeta c^2`,
//! `xy = (xixi - etaeta) c s`, `xz = T_xiz c`, `yz = T_xiz s`, `(c, s) = (kx, ky) / k`.
//!
//! At the interface z = h1, sigma_zz, tau_xz, tau_yz and the in-plane strains are
//! continuous while sigma_xx, sigma_yy, sigma_xy jump; [`interface_stress_transfer`]
//! gives both sides. Homogeneous check (E1 = E2, nu1 = nu2): Boussinesq's
//! `T_zz = -(1 + kz) e^{-kz}`, `T_xixi = -(1 - kz) e^{-kz}`, `T_etaeta = -2 nu e^{-kz}`,
//! `T_xiz = i kz e^{-kz}` (the classical half-plane response to a sinusoidal
//! pressure, e.g. Barber, Elasticity, ch. 12, with `sigma_etaeta = nu (sigma_xixi +
//! sigma_zz)` of plane strain).

use realfft::num_complex::Complex;

use crate::case::Elastic;

/// Stress transfer coefficients in the order `[xx, yy, zz, yz, xz, xy]`.
pub type StressTransfer = [Complex<f64>; 6];

/// Which side of the coating–substrate interface.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// The coating, 0 <= z <= h1.
    Coating,
    /// The substrate, z >= h1.
    Substrate,
}

/// How a coated body's stress kernels are computed (`crate::stress::CoatedStressKernels`
/// picks one per lattice; tests compare them on both sides of each switch).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StressMethod {
    /// Love's kernels, two carriers and the remainder (lattice sum and Hankel
    /// transforms): exact, at a cost that grows like `(cell / h1)^2` for thin coatings.
    Full,
    /// A coating thinner than the cell: as `Full`, but the remainder is split at
    /// `k1 = 4 / cell`: its short waves (a kernel within five cells of the loaded
    /// one) on a small periodic box whose alias sum is capped and smoothly tapered,
    /// its long waves in bands of wavenumbers a factor 4 apart, each on a box wider
    /// than its kernel's reach, and below `~4 / span` by Hankel transforms. The
    /// cost grows neither with `cell / h1` nor with E1/E2.
    SubCell,
    /// A coating much thinner than the cell: Love's kernels and the two carriers (the
    /// long-wave limit and its O(k h1) slope), without the O((k l)^2) remainder.
    ThinFilm,
    /// A coating much thicker than the window: Love's kernels of the side's material
    /// plus the constant the far interface adds.
    ThickCoating,
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

/// Rotates the plane-strain stresses of wave vector (kx, ky) to x, y.
pub(crate) fn rotate(kx: f64, ky: f64, s: [f64; 4]) -> StressTransfer {
    let k = kx.hypot(ky);
    let (c, sn) = if k > 0.0 {
        (kx / k, ky / k)
    } else {
        (1.0, 0.0)
    };
    let [xixi, etaeta, zz, xiz] = s;
    // tau_xiz = -xiz sin(k xi) -> complex coefficient i xiz.
    let shear = Complex::new(0.0, xiz);
    [
        Complex::new(xixi * c * c + etaeta * sn * sn, 0.0),
        Complex::new(xixi * sn * sn + etaeta * c * c, 0.0),
        Complex::new(zz, 0.0),
        shear * sn,
        shear * c,
        Complex::new((xixi - etaeta) * c * sn, 0.0),
    ]
}

/// Stress transfer at depth z >= 0 (coating side at z = h1 itself), for a wave
/// vector (kx, ky) != 0. At k = 0 the response depends on the direction of
/// approach; the limit along x is returned.
///
/// Not part of the API (bodies give their stresses through [`crate::stress`]):
/// public only for the independent transforms of `tests/coated_stress.rs`.
#[doc(hidden)]
pub fn coated_stress_transfer(
    coating: Elastic,
    thickness: f64,
    substrate: Elastic,
    kx: f64,
    ky: f64,
    z: f64,
) -> StressTransfer {
    let side = if z <= thickness {
        Side::Coating
    } else {
        Side::Substrate
    };
    stress_transfer_on_side(coating, thickness, substrate, kx, ky, z, side)
}

/// Both sides of the interface z = h1: `(coating side, substrate side)`.
///
/// Not part of the API: public only for `tests/coated_stress.rs`.
#[doc(hidden)]
pub fn interface_stress_transfer(
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
            Side::Coating,
        ),
        stress_transfer_on_side(
            coating,
            thickness,
            substrate,
            kx,
            ky,
            thickness,
            Side::Substrate,
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
pub fn plane_stress_transfer(
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
        Side::Coating => plane_stresses(coating, zeta, &x[..4], &coating_basis(zeta, t)),
        Side::Substrate => plane_stresses(substrate, zeta, &x[4..], &substrate_basis(zeta, t)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::body::coated::coated_surface_compliance;

    /// Surface normal displacement per unit pressure from the same solution,
    /// `w^ / p^`: the oracle of `coated_surface_compliance`.
    fn surface_compliance_from_potentials(
        coating: Elastic,
        thickness: f64,
        substrate: Elastic,
        k: f64,
    ) -> f64 {
        let t = k * thickness;
        let x = potential_coefficients(coating, substrate, t);
        let q = quantities(coating, 0.0, &coating_basis(0.0, t));
        let w: f64 = q[1].iter().zip(&x[..4]).map(|(a, b)| a * b).sum();
        let mu1 = coating.young / (2.0 * (1.0 + coating.poisson));
        // 2 mu w = k (p / k^2) * sum.
        w / (2.0 * mu1 * k)
    }

    fn elastic(young: f64, poisson: f64) -> Elastic {
        Elastic { young, poisson }
    }

    const STIFF: (Elastic, Elastic) = (
        Elastic {
            young: 10.0,
            poisson: 0.25,
        },
        Elastic {
            young: 1.0,
            poisson: 0.35,
        },
    );
    const SOFT: (Elastic, Elastic) = (
        Elastic {
            young: 0.1,
            poisson: 0.45,
        },
        Elastic {
            young: 1.0,
            poisson: 0.2,
        },
    );

    fn close(a: Complex<f64>, b: Complex<f64>, tol: f64) -> bool {
        (a - b).norm() <= tol * (1.0 + b.norm())
    }

    #[test]
    fn equal_materials_give_boussinesq_fourier_stresses() {
        let m = elastic(2.0, 0.3);
        for (kx, ky) in [(1.0, 0.0), (0.3, -0.8), (0.0, 2.5)] {
            let k: f64 = f64::hypot(kx, ky);
            let (c, s) = (kx / k, ky / k);
            for z in [0.0, 0.2, 0.7, 1.3, 4.0] {
                let kz = k * z;
                let e = (-kz).exp();
                let (xixi, etaeta) = (-(1.0 - kz) * e, -2.0 * 0.3 * e);
                let shear = Complex::new(0.0, kz * e);
                let expected = [
                    Complex::new(xixi * c * c + etaeta * s * s, 0.0),
                    Complex::new(xixi * s * s + etaeta * c * c, 0.0),
                    Complex::new(-(1.0 + kz) * e, 0.0),
                    shear * s,
                    shear * c,
                    Complex::new((xixi - etaeta) * c * s, 0.0),
                ];
                let got = coated_stress_transfer(m, 0.9, m, kx, ky, z);
                for q in 0..6 {
                    assert!(
                        close(got[q], expected[q], 1e-13),
                        "k = ({kx}, {ky}), z = {z}, component {q}: {} vs {}",
                        got[q],
                        expected[q]
                    );
                }
            }
        }
    }

    #[test]
    fn surface_conditions_and_compliance() {
        for (c, s) in [STIFF, SOFT] {
            for k in [0.01, 0.5, 3.0, 30.0] {
                let t = coated_stress_transfer(c, 0.4, s, 0.6 * k, 0.8 * k, 0.0);
                assert!(close(t[2], Complex::new(-1.0, 0.0), 1e-12));
                assert!(t[3].norm() < 1e-12 && t[4].norm() < 1e-12);
                // The displacement of the same solution against the closed form A(kh).
                let w = surface_compliance_from_potentials(c, 0.4, s, k);
                let expected = coated_surface_compliance(c, 0.4, s, k);
                assert!(
                    ((w - expected) / expected).abs() < 1e-11,
                    "k = {k}: {w} vs {expected}"
                );
            }
        }
    }

    /// Strains (xx, yy, xy) from stresses by Hooke's law.
    fn in_plane_strains(m: Elastic, t: &StressTransfer) -> [Complex<f64>; 3] {
        let (e, nu) = (m.young, m.poisson);
        [
            (t[0] - (t[1] + t[2]) * nu) / e,
            (t[1] - (t[0] + t[2]) * nu) / e,
            t[5] * (1.0 + nu) / e,
        ]
    }

    #[test]
    fn interface_continuity_and_jump() {
        for (c, s) in [STIFF, SOFT] {
            for (kx, ky) in [(0.4, 0.3), (2.0, -1.0), (0.02, 0.05)] {
                let (top, bottom) = interface_stress_transfer(c, 0.7, s, kx, ky);
                for q in [2, 3, 4] {
                    assert!(
                        close(top[q], bottom[q], 1e-11),
                        "component {q}: {} vs {}",
                        top[q],
                        bottom[q]
                    );
                }
                let (et, eb) = (in_plane_strains(c, &top), in_plane_strains(s, &bottom));
                for q in 0..3 {
                    assert!(
                        close(et[q], eb[q], 1e-11),
                        "strain {q}: {} vs {}",
                        et[q],
                        eb[q]
                    );
                }
                // sigma_xx jumps, as docs/architecture.md (numerics) predicts from the strains.
                let predicted = (et[0] + et[1] * s.poisson)
                    * (s.young / (1.0 - s.poisson * s.poisson))
                    + bottom[2] * (s.poisson / (1.0 - s.poisson));
                assert!(close(bottom[0], predicted, 1e-11));
                assert!((top[0] - bottom[0]).norm() > 1e-3 * top[0].norm());
            }
        }
    }

    #[test]
    fn stresses_satisfy_equilibrium_in_both_layers() {
        // i kx T_xz + i ky T_yz + dT_zz/dz = 0 and i kx T_xx + i ky T_xy + dT_xz/dz = 0,
        // with the z derivative by central differences.
        let i = Complex::new(0.0, 1.0);
        for (c, s) in [STIFF, SOFT] {
            let (kx, ky, h) = (1.3, -0.6, 0.5);
            for z in [0.1, 0.3, 0.9, 2.0] {
                let d = 1e-5;
                let at = |z: f64| coated_stress_transfer(c, h, s, kx, ky, z);
                let (lo, mid, hi) = (at(z - d), at(z), at(z + d));
                let dzz = (hi[2] - lo[2]) / (2.0 * d);
                let dxz = (hi[4] - lo[4]) / (2.0 * d);
                let vertical = i * kx * mid[4] + i * ky * mid[3] + dzz;
                let horizontal = i * kx * mid[0] + i * ky * mid[5] + dxz;
                assert!(
                    vertical.norm() < 1e-7 && horizontal.norm() < 1e-7,
                    "z = {z}: {vertical} {horizontal}"
                );
            }
        }
    }

    #[test]
    fn zero_wavenumber_gives_finite_long_wave_limit() {
        // Along x at k -> 0: sigma_zz = -p at every depth, no shear.
        for z in [0.0, 0.3, 5.0] {
            let t = coated_stress_transfer(STIFF.0, 0.4, STIFF.1, 0.0, 0.0, z);
            assert!(t.iter().all(|c| c.re.is_finite() && c.im.is_finite()));
            assert!(close(t[2], Complex::new(-1.0, 0.0), 1e-6));
            assert!(t[3].norm() < 1e-6 && t[4].norm() < 1e-6);
        }
    }

    #[test]
    fn thick_coating_near_the_surface_is_the_coating_alone() {
        let (c, s) = STIFF;
        let (kx, ky) = (2.0, 1.0);
        for z in [0.0, 0.5, 1.0] {
            let coated = coated_stress_transfer(c, 40.0, s, kx, ky, z);
            let alone = coated_stress_transfer(c, 40.0, c, kx, ky, z);
            for q in 0..6 {
                assert!(close(coated[q], alone[q], 1e-12), "z = {z}, {q}");
            }
        }
    }
}
