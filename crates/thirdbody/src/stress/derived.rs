//! Fields derived from the stress tensor at a point: principal stresses (eigenvalues
//! of the symmetric 3 x 3 tensor, by the trigonometric solution of its
//! characteristic cubic; O. K. Smith, Comm. ACM 4, 168, 1961), the maximum shear
//! stress `tau1 = (s1 - s3) / 2` (Johnson, Contact Mechanics, §4.2) and the von
//! Mises equivalent stress
//! `sqrt(((sx - sy)^2 + (sy - sz)^2 + (sz - sx)^2) / 2 + 3 (txy^2 + txz^2 + tyz^2))`.
//! Components are ordered `[sigma_x, sigma_y, sigma_z, tau_xy, tau_xz, tau_yz]`,
//! tension positive.

use std::f64::consts::PI;

/// Principal stresses `[s1, s2, s3]`, `s1 >= s2 >= s3`, of the tensor
/// `[sx, sy, sz, txy, txz, tyz]`.
pub fn principal_stresses(s: [f64; 6]) -> [f64; 3] {
    let [sx, sy, sz, txy, txz, tyz] = s;
    let off = txy * txy + txz * txz + tyz * tyz;
    let mean = (sx + sy + sz) / 3.0;
    let (dx, dy, dz) = (sx - mean, sy - mean, sz - mean);
    // p^2 = tr((A - mean I)^2) / 6.
    let p2 = (dx * dx + dy * dy + dz * dz + 2.0 * off) / 6.0;
    if p2 <= 0.0 {
        // Hydrostatic (or zero) state: all principal stresses equal.
        return [mean; 3];
    }
    let p = p2.sqrt();
    // det((A - mean I) / p) / 2 = cos(3 phi).
    let det =
        dx * (dy * dz - tyz * tyz) - txy * (txy * dz - tyz * txz) + txz * (txy * tyz - dy * txz);
    let r = (det / (2.0 * p * p2)).clamp(-1.0, 1.0);
    let phi = r.acos() / 3.0;
    let s1 = mean + 2.0 * p * phi.cos();
    let s3 = mean + 2.0 * p * (phi + 2.0 * PI / 3.0).cos();
    let s2 = 3.0 * mean - s1 - s3;
    // Rounding can put s2 a hair outside [s3, s1]; max/min (unlike clamp) do not
    // panic on a non-finite tensor, whose NaN then shows in the results.
    [s1, s2.max(s3).min(s1), s3]
}

/// Maximum shear stress `(s1 - s3) / 2`.
pub fn max_shear(s: [f64; 6]) -> f64 {
    let [s1, _, s3] = principal_stresses(s);
    0.5 * (s1 - s3)
}

/// Von Mises equivalent stress.
pub fn von_mises(s: [f64; 6]) -> f64 {
    let [sx, sy, sz, txy, txz, tyz] = s;
    (0.5 * ((sx - sy).powi(2) + (sy - sz).powi(2) + (sz - sx).powi(2))
        + 3.0 * (txy * txy + txz * txz + tyz * tyz))
        .sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Eigenvalues of a symmetric 3 x 3 matrix by cyclic Jacobi rotations: an
    /// independent method for the trigonometric formula.
    fn jacobi_eigenvalues(s: [f64; 6]) -> [f64; 3] {
        let [sx, sy, sz, txy, txz, tyz] = s;
        let mut a = [[sx, txy, txz], [txy, sy, tyz], [txz, tyz, sz]];
        for _ in 0..100 {
            for (p, q) in [(0, 1), (0, 2), (1, 2)] {
                if a[p][q].abs() < 1e-300 {
                    continue;
                }
                let theta = 0.5 * (2.0 * a[p][q]).atan2(a[q][q] - a[p][p]);
                let (c, sn) = (theta.cos(), theta.sin());
                // A <- J^T A J with the rotation in the (p, q) plane.
                let mut b = a;
                for k in 0..3 {
                    b[k][p] = c * a[k][p] - sn * a[k][q];
                    b[k][q] = sn * a[k][p] + c * a[k][q];
                }
                let mut d = b;
                for k in 0..3 {
                    d[p][k] = c * b[p][k] - sn * b[q][k];
                    d[q][k] = sn * b[p][k] + c * b[q][k];
                }
                a = d;
            }
        }
        let mut e = [a[0][0], a[1][1], a[2][2]];
        e.sort_by(|x, y| y.total_cmp(x));
        e
    }

    #[test]
    fn principal_stresses_match_jacobi() {
        let cases = [
            [1.0, 2.0, 3.0, 0.0, 0.0, 0.0],
            [-0.3, 0.7, -1.1, 0.25, -0.4, 0.6],
            [0.1, 0.1, 0.1, 0.0, 0.0, 0.0],
            [1.0, 1.0, -2.0, 0.5, 0.0, 0.0],
            [-1.0, -1.0, -1.0, 1e-9, 0.0, 0.0],
            [5.0, -3.0, 0.2, 1.0, 2.0, -0.5],
        ];
        for s in cases {
            let fast = principal_stresses(s);
            let slow = jacobi_eigenvalues(s);
            let scale = s.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for k in 0..3 {
                assert!(
                    (fast[k] - slow[k]).abs() < 1e-12 * scale,
                    "{s:?}: {fast:?} vs {slow:?}"
                );
            }
            // Invariant: the trace.
            let trace: f64 = fast.iter().sum();
            assert!((trace - (s[0] + s[1] + s[2])).abs() < 1e-12 * scale);
        }
    }

    #[test]
    fn von_mises_from_principal_and_uniaxial() {
        assert!((von_mises([-2.5, 0.0, 0.0, 0.0, 0.0, 0.0]) - 2.5).abs() < 1e-15);
        // Pure shear tau: von Mises = sqrt(3) tau, tau1 = tau.
        let s = [0.0, 0.0, 0.0, 0.0, 0.7, 0.0];
        assert!((von_mises(s) - 3f64.sqrt() * 0.7).abs() < 1e-14);
        assert!((max_shear(s) - 0.7).abs() < 1e-14);
        let s = [-0.3, 0.7, -1.1, 0.25, -0.4, 0.6];
        let [a, b, c] = jacobi_eigenvalues(s);
        let vm = (0.5 * ((a - b).powi(2) + (b - c).powi(2) + (c - a).powi(2))).sqrt();
        assert!((von_mises(s) - vm).abs() < 1e-12);
    }
}
