//! Restarted GMRES with right preconditioning (Saad & Schultz 1986; Saad, Iterative
//! Methods for Sparse Linear Systems, 2nd ed., Alg. 9.5), for the non-symmetric
//! Newton systems of the layered contact. Right preconditioning keeps the minimised
//! residual the true one, so the stopping test is on `||b - A x|| / ||b||`.
//! Written here because the solver needs caller-owned workspaces reused across
//! Newton steps and a matrix-free operator with mutable scratch (the FFT), which the
//! Rust Krylov crates we looked at do not offer together.

/// Outcome of a GMRES solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GmresInfo {
    /// Matrix-vector products done.
    pub iterations: usize,
    /// Final relative residual `||b - A x|| / ||b||`.
    pub relative_residual: f64,
    /// Whether the tolerance was met.
    pub converged: bool,
}

/// Reusable storage for GMRES(m) on vectors of length n.
#[derive(Debug, Clone)]
pub struct Gmres {
    n: usize,
    restart: usize,
    basis: Vec<Vec<f64>>,
    hessenberg: Vec<Vec<f64>>,
    cosines: Vec<f64>,
    sines: Vec<f64>,
    rhs: Vec<f64>,
    coefficients: Vec<f64>,
    work: Vec<f64>,
    preconditioned: Vec<f64>,
}

impl Gmres {
    /// Storage for vectors of length `n` and restart length `restart`.
    pub fn new(n: usize, restart: usize) -> Self {
        Gmres {
            n,
            restart,
            basis: (0..=restart).map(|_| vec![0.0; n]).collect(),
            hessenberg: (0..restart).map(|_| vec![0.0; restart + 1]).collect(),
            cosines: vec![0.0; restart],
            sines: vec![0.0; restart],
            rhs: vec![0.0; restart + 1],
            coefficients: vec![0.0; restart],
            work: vec![0.0; n],
            preconditioned: vec![0.0; n],
        }
    }

    /// Makes the storage fit vectors of length `n` and restart length `restart`,
    /// keeping the allocations (a Newton step's system changes size with the contact
    /// set; its GMRES workspace is reused). Nothing stored carries over into a solve.
    pub fn reshape(&mut self, n: usize, restart: usize) {
        self.n = n;
        self.restart = restart;
        // The basis vectors are sized when first written (`solve`): a step that
        // converges in a few products touches only a few of them.
        self.basis.resize_with(restart + 1, Vec::new);
        self.hessenberg.resize_with(restart, Vec::new);
        self.hessenberg
            .iter_mut()
            .for_each(|h| h.resize(restart + 1, 0.0));
        self.cosines.resize(restart, 0.0);
        self.sines.resize(restart, 0.0);
        self.rhs.resize(restart + 1, 0.0);
        self.coefficients.resize(restart, 0.0);
        self.work.resize(n, 0.0);
        self.preconditioned.resize(n, 0.0);
    }

    /// Solves `A x = b` starting from the given `x`, with `apply(v, out)`: `out = A v`
    /// and `precondition(r, out)`: `out ~ A^-1 r`. Stops at relative residual `tol`
    /// or after `max_iterations` products.
    pub fn solve(
        &mut self,
        apply: &mut dyn FnMut(&[f64], &mut [f64]),
        precondition: &mut dyn FnMut(&[f64], &mut [f64]),
        b: &[f64],
        x: &mut [f64],
        tol: f64,
        max_iterations: usize,
    ) -> GmresInfo {
        let n = self.n;
        assert!(b.len() == n && x.len() == n, "GMRES vector length");
        let b_norm = norm(b);
        if b_norm == 0.0 {
            x.fill(0.0);
            return GmresInfo {
                iterations: 0,
                relative_residual: 0.0,
                converged: true,
            };
        }
        let mut iterations = 0;
        loop {
            // r0 = b - A x
            apply(x, &mut self.work);
            self.basis[0].resize(n, 0.0);
            for ((r, bk), wk) in self.basis[0].iter_mut().zip(b).zip(&self.work) {
                *r = bk - wk;
            }
            let beta = norm(&self.basis[0]);
            let mut relative = beta / b_norm;
            if relative <= tol || iterations >= max_iterations {
                return GmresInfo {
                    iterations,
                    relative_residual: relative,
                    converged: relative <= tol,
                };
            }
            self.basis[0].iter_mut().for_each(|v| *v /= beta);
            self.rhs.fill(0.0);
            self.rhs[0] = beta;
            let mut used = 0;
            for j in 0..self.restart {
                precondition(&self.basis[j], &mut self.preconditioned);
                apply(&self.preconditioned, &mut self.work);
                iterations += 1;
                // Modified Gram–Schmidt.
                for i in 0..=j {
                    let h = dot(&self.work, &self.basis[i]);
                    self.hessenberg[j][i] = h;
                    let bi = &self.basis[i];
                    self.work.iter_mut().zip(bi).for_each(|(w, v)| *w -= h * v);
                }
                let h_next = norm(&self.work);
                self.hessenberg[j][j + 1] = h_next;
                // Apply the previous Givens rotations, then make a new one.
                for i in 0..j {
                    let (c, s) = (self.cosines[i], self.sines[i]);
                    let (a, bb) = (self.hessenberg[j][i], self.hessenberg[j][i + 1]);
                    self.hessenberg[j][i] = c * a + s * bb;
                    self.hessenberg[j][i + 1] = -s * a + c * bb;
                }
                let (a, bb) = (self.hessenberg[j][j], self.hessenberg[j][j + 1]);
                let r = a.hypot(bb);
                let (c, s) = if r == 0.0 {
                    (1.0, 0.0)
                } else {
                    (a / r, bb / r)
                };
                self.cosines[j] = c;
                self.sines[j] = s;
                self.hessenberg[j][j] = r;
                self.hessenberg[j][j + 1] = 0.0;
                self.rhs[j + 1] = -s * self.rhs[j];
                self.rhs[j] *= c;
                used = j + 1;
                relative = self.rhs[j + 1].abs() / b_norm;
                self.basis[j + 1].resize(n, 0.0);
                if h_next > 0.0 {
                    let inv = 1.0 / h_next;
                    let work = &self.work;
                    self.basis[j + 1]
                        .iter_mut()
                        .zip(work)
                        .for_each(|(v, w)| *v = w * inv);
                }
                // A norm that is not finite (the system overflowed) ends the cycle: the
                // caller sees the non-finite iterate.
                if relative <= tol
                    || iterations >= max_iterations
                    || h_next == 0.0
                    || !h_next.is_finite()
                {
                    break;
                }
            }
            // Back substitution for the Krylov coefficients, then x += M^-1 V y.
            let y = &mut self.coefficients[..used];
            for i in (0..used).rev() {
                let mut s = self.rhs[i];
                for (k, yk) in y.iter().enumerate().skip(i + 1) {
                    s -= self.hessenberg[k][i] * yk;
                }
                y[i] = s / self.hessenberg[i][i];
            }
            self.work.fill(0.0);
            for (i, yi) in y.iter().enumerate() {
                let v = &self.basis[i];
                self.work
                    .iter_mut()
                    .zip(v)
                    .for_each(|(w, vv)| *w += yi * vv);
            }
            precondition(&self.work, &mut self.preconditioned);
            x.iter_mut()
                .zip(&self.preconditioned)
                .for_each(|(xi, d)| *xi += d);
        }
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_nonsymmetric_system_against_a_known_solution() {
        // A = tridiagonal non-symmetric plus a lower-triangular creep-like part.
        let n = 60;
        let a = |i: usize, j: usize| -> f64 {
            if i == j {
                4.0
            } else if j + 1 == i {
                -1.0
            } else if i + 1 == j {
                -0.5
            } else if j > i {
                0.02
            } else {
                0.0
            }
        };
        let exact: Vec<f64> = (0..n).map(|k| (k as f64 * 0.37).sin()).collect();
        let product = |v: &[f64], out: &mut [f64]| {
            for (i, o) in out.iter_mut().enumerate() {
                *o = v.iter().enumerate().map(|(j, vj)| a(i, j) * vj).sum();
            }
        };
        let mut b = vec![0.0; n];
        product(&exact, &mut b);
        let mut apply = product;
        for (restart, diag) in [(10, 1.0), (60, 4.0)] {
            let mut precondition = |r: &[f64], out: &mut [f64]| {
                out.iter_mut().zip(r).for_each(|(o, v)| *o = v / diag);
            };
            let mut g = Gmres::new(n, restart);
            let mut x = vec![0.0; n];
            let info = g.solve(&mut apply, &mut precondition, &b, &mut x, 1e-12, 1000);
            assert!(info.converged, "{info:?}");
            for k in 0..n {
                assert!(
                    (x[k] - exact[k]).abs() < 1e-10,
                    "{k}: {} {}",
                    x[k],
                    exact[k]
                );
            }
        }
    }
}
