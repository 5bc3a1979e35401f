//! Fields derived from the stress tensor at a point: principal stresses (eigenvalues
//! of the symmetric 3 x 3 tensor, by cyclic Jacobi rotations; Golub & Van Loan,
//! Matrix Computations, 4th ed., §8.5), the maximum shear
//! stress `tau1 = (s1 - s3) / 2` (Johnson, Contact Mechanics, §4.2) and the von
//! Mises equivalent stress
//! `sqrt(((sx - sy)^2 + (sy - sz)^2 + (sz - sx)^2) / 2 + 3 (txy^2 + txz^2 + tyz^2))`.
//! Components are ordered `[sigma_x, sigma_y, sigma_z, tau_xy, tau_xz, tau_yz]`,
//! tension positive.

/// Jacobi sweeps at most: each sweep squares the off-diagonal part, which is below
/// rounding after four to six of them.
const MAX_SWEEPS: usize = 16;

/// Principal stresses `[s1, s2, s3]`, `s1 >= s2 >= s3`, of the tensor
/// `[sx, sy, sz, txy, txz, tyz]`, exact to rounding also where two or three of them
/// are equal (the closed-form root of the characteristic cubic loses half the digits
/// there). A non-finite tensor gives NaN.
pub fn principal_stresses(s: [f64; 6]) -> [f64; 3] {
    // Cyclic Jacobi written out: no linear-algebra crate is needed for a 3 x 3.
    let [sx, sy, sz, txy, txz, tyz] = s;
    let mut a = [[sx, txy, txz], [txy, sy, tyz], [txz, tyz, sz]];
    if s.iter().any(|v| !v.is_finite()) {
        return [f64::NAN; 3];
    }
    // Off-diagonal entries below this move no eigenvalue by more than a hundredth
    // of a unit in the last place of the largest.
    let negligible = 1e-2 * f64::EPSILON * s.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for _ in 0..MAX_SWEEPS {
        if a[0][1].abs().max(a[0][2].abs()).max(a[1][2].abs()) <= negligible {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            let apq = a[p][q];
            if apq == 0.0 {
                continue;
            }
            // The rotation in the (p, q) plane that zeroes a[p][q], its tangent the
            // smaller root of t^2 + 2 theta t - 1 = 0 (|angle| <= pi/4).
            let theta = (a[q][q] - a[p][p]) / (2.0 * apq);
            let t = theta.signum() / (theta.abs() + theta.hypot(1.0));
            let c = 1.0 / t.hypot(1.0);
            let sn = t * c;
            a[p][p] -= t * apq;
            a[q][q] += t * apq;
            a[p][q] = 0.0;
            a[q][p] = 0.0;
            let r = 3 - p - q;
            let (arp, arq) = (a[r][p], a[r][q]);
            a[r][p] = c * arp - sn * arq;
            a[r][q] = sn * arp + c * arq;
            a[p][r] = a[r][p];
            a[q][r] = a[r][q];
        }
    }
    let mut e = [a[0][0], a[1][1], a[2][2]];
    e.sort_by(|x, y| y.total_cmp(x));
    e
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

    /// A small xorshift generator: fixed-seed random numbers in [-1, 1).
    struct Rng(u64);

    impl Rng {
        fn next(&mut self) -> f64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        }
    }

    /// A random rotation matrix, from a random unit quaternion.
    fn rotation(rng: &mut Rng) -> [[f64; 3]; 3] {
        let mut q = [0.0; 4];
        loop {
            q.iter_mut().for_each(|v| *v = rng.next());
            let n = q.iter().map(|v| v * v).sum::<f64>().sqrt();
            if n > 0.1 && n <= 1.0 {
                q.iter_mut().for_each(|v| *v /= n);
                break;
            }
        }
        let [w, x, y, z] = q;
        [
            [
                1.0 - 2.0 * (y * y + z * z),
                2.0 * (x * y - w * z),
                2.0 * (x * z + w * y),
            ],
            [
                2.0 * (x * y + w * z),
                1.0 - 2.0 * (x * x + z * z),
                2.0 * (y * z - w * x),
            ],
            [
                2.0 * (x * z - w * y),
                2.0 * (y * z + w * x),
                1.0 - 2.0 * (x * x + y * y),
            ],
        ]
    }

    /// `R diag(d) R^T` as `[sx, sy, sz, txy, txz, tyz]`.
    fn rotated(d: [f64; 3], r: &[[f64; 3]; 3]) -> [f64; 6] {
        let a = |i: usize, j: usize| (0..3).map(|k| r[i][k] * d[k] * r[j][k]).sum::<f64>();
        [a(0, 0), a(1, 1), a(2, 2), a(0, 1), a(0, 2), a(1, 2)]
    }

    /// Largest error of the principal stresses of `d` rotated by random rotations,
    /// relative to the largest |d|.
    fn worst_error(d: [f64; 3], rng: &mut Rng) -> f64 {
        let mut expected = d;
        expected.sort_by(|x, y| y.total_cmp(x));
        let scale = d.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let mut worst = 0.0f64;
        for _ in 0..1000 {
            let got = principal_stresses(rotated(d, &rotation(rng)));
            for k in 0..3 {
                worst = worst.max((got[k] - expected[k]).abs() / scale);
            }
        }
        worst
    }

    #[test]
    fn repeated_eigenvalues_are_recovered_to_rounding() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        // Double eigenvalues (the Hertz axis has sigma_x = sigma_y), one with the
        // single eigenvalue far from the pair, and a triple one.
        for d in [
            [-0.8, -0.8, -1.0],
            [-1.0, 0.3, 0.3],
            [2.5, 2.5, -1e-3],
            [1e-6, 1e-6, 1.0],
            [-0.7, -0.7, -0.7],
        ] {
            let worst = worst_error(d, &mut rng);
            println!("{d:?}: worst relative error {worst:.2e}");
            assert!(worst < 1e-14, "{d:?}: relative error {worst:.2e}");
        }
    }

    #[test]
    fn random_tensors_keep_their_invariants() {
        let mut rng = Rng(0x2545_f491_4f6c_dd1d);
        let (mut worst_trace, mut worst_second, mut worst_det) = (0.0f64, 0.0f64, 0.0f64);
        for _ in 0..10_000 {
            let s: [f64; 6] = std::array::from_fn(|_| rng.next());
            let [sx, sy, sz, txy, txz, tyz] = s;
            let [a, b, c] = principal_stresses(s);
            assert!(a >= b && b >= c, "{s:?}: {a} {b} {c} not ordered");
            // Frobenius norm: the eigenvalues' scale.
            let norm =
                (sx * sx + sy * sy + sz * sz + 2.0 * (txy * txy + txz * txz + tyz * tyz)).sqrt();
            let trace = sx + sy + sz;
            let second = sx * sy + sy * sz + sz * sx - txy * txy - txz * txz - tyz * tyz;
            let det = sx * (sy * sz - tyz * tyz) - txy * (txy * sz - tyz * txz)
                + txz * (txy * tyz - sy * txz);
            worst_trace = worst_trace.max((a + b + c - trace).abs() / norm);
            worst_second = worst_second.max((a * b + b * c + c * a - second).abs() / norm.powi(2));
            worst_det = worst_det.max((a * b * c - det).abs() / norm.powi(3));
        }
        println!(
            "trace {worst_trace:.2e}, second invariant {worst_second:.2e}, det {worst_det:.2e}"
        );
        assert!(worst_trace < 1e-14, "trace: {worst_trace:.2e}");
        assert!(worst_second < 1e-14, "second invariant: {worst_second:.2e}");
        assert!(worst_det < 1e-14, "determinant: {worst_det:.2e}");
    }

    #[test]
    fn principal_stresses_of_simple_tensors() {
        assert_eq!(
            principal_stresses([1.0, 2.0, 3.0, 0.0, 0.0, 0.0]),
            [3.0, 2.0, 1.0]
        );
        assert_eq!(principal_stresses([0.1, 0.1, 0.1, 0.0, 0.0, 0.0]), [0.1; 3]);
        assert_eq!(principal_stresses([0.0; 6]), [0.0; 3]);
        // Pure shear tau: +tau, 0, -tau.
        let [a, b, c] = principal_stresses([0.0, 0.0, 0.0, 0.0, 0.7, 0.0]);
        assert!((a - 0.7).abs() < 1e-16 && b.abs() < 1e-16 && (c + 0.7).abs() < 1e-16);
        // A shear far below the diagonal still moves the eigenvalues by its square.
        let [a, b, c] = principal_stresses([-1.0, -1.0, -1.0, 1e-9, 0.0, 0.0]);
        assert!((a + 1.0 - 1e-9).abs() < 1e-16 && b == -1.0 && (c + 1.0 + 1e-9).abs() < 1e-16);
        // A non-finite tensor gives NaN, not a panic or a hang.
        assert!(principal_stresses([f64::NAN, 0.0, 0.0, 1.0, 0.0, 0.0])
            .iter()
            .any(|v| v.is_nan()));
    }

    #[test]
    fn von_mises_from_principal_and_uniaxial() {
        assert!((von_mises([-2.5, 0.0, 0.0, 0.0, 0.0, 0.0]) - 2.5).abs() < 1e-15);
        // Pure shear tau: von Mises = sqrt(3) tau, tau1 = tau.
        let s = [0.0, 0.0, 0.0, 0.0, 0.7, 0.0];
        assert!((von_mises(s) - 3f64.sqrt() * 0.7).abs() < 1e-14);
        assert!((max_shear(s) - 0.7).abs() < 1e-14);
        let s = [-0.3, 0.7, -1.1, 0.25, -0.4, 0.6];
        let [a, b, c] = principal_stresses(s);
        let vm = (0.5 * ((a - b).powi(2) + (b - c).powi(2) + (c - a).powi(2))).sqrt();
        assert!((von_mises(s) - vm).abs() < 1e-14);
    }
}
