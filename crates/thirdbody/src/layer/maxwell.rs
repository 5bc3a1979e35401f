//! The nonlinear Maxwell layer of the paper: a spring bed (paper eq. 2,
//! `dw3/dt = C[p] (p/T + dp/dt)`) integrated along the material path in the
//! steady sliding frame (docs/architecture.md (conventions)). Material enters the window at its largest x
//! and moves in -x, so the displacement of cell i of a row is
//!
//! * `exact`:  `w3_i = G(p_i) + (h / (V T)) (sum_{j upstream} C[p_j] p_j + C[p_i] p_i / 2)`,
//!   with `G(p) = int_0^p C[q] dq` (the exact integral of eq. 2 along the path);
//! * `secant`: `w3_i = C[p_i] p_i + (same creep sum)`: the paper's eq. 8 read with the
//!   compliance of the loaded cell.
//!
//! "Upstream" means larger x in the same row; rows (fixed y) do not interact. The
//! other reading of eq. 8, with the receiving cell's `C_i` multiplying all upstream
//! creep, folds (`dw3/dp = 0`) at low `V T / h` and has no continuous solution; it is
//! not offered. Applying the layer is one cumulative sum per row from the leading
//! edge: O(n). Behind the contact the layer keeps its creep (a Maxwell layer never
//! recovers).

use super::{ComplianceLaw, Layer, LayerLinearisation, LayerResponse};

/// The Maxwell layer on a grid's rows: the row sweep and its linearisation.
#[derive(Debug, Clone)]
pub struct MaxwellRows {
    layer: Layer,
    nx: usize,
    ny: usize,
    /// `h / (V T)`: creep per cell of path, 0 for an infinite velocity.
    creep_per_cell: f64,
}

impl MaxwellRows {
    /// The layer on rows of `nx` cells of side `cell`, sliding at `velocity`.
    pub fn new(layer: Layer, nx: usize, ny: usize, cell: f64, velocity: f64) -> Self {
        let creep_per_cell = if velocity.is_infinite() {
            0.0
        } else {
            cell / (velocity * layer.relaxation_time)
        };
        MaxwellRows {
            layer,
            nx,
            ny,
            creep_per_cell,
        }
    }

    /// The layer.
    pub fn layer(&self) -> &Layer {
        &self.layer
    }

    /// `h / (V T)`.
    pub fn creep_per_cell(&self) -> f64 {
        self.creep_per_cell
    }

    /// Layer displacement `w3` of every cell: one sweep per row from the leading edge.
    pub fn maxwell_row_sweep(&self, p: &[f64], w3: &mut [f64]) {
        let k = self.creep_per_cell;
        for (prow, wrow) in p.chunks_exact(self.nx).zip(w3.chunks_exact_mut(self.nx)) {
            let mut upstream = 0.0;
            for i in (0..self.nx).rev() {
                let (inst, _) = self.layer.instantaneous(prow[i]);
                let (q, _) = self.layer.creep(prow[i]);
                wrow[i] = inst + k * (upstream + 0.5 * q);
                upstream += q;
            }
        }
    }

    /// The linearisation at a pressure field, for Newton steps.
    pub fn jacobian(&self, p: &[f64]) -> MaxwellJacobian {
        let mut diagonal = vec![0.0; p.len()];
        let mut creep_slope = vec![0.0; p.len()];
        for (k, &pk) in p.iter().enumerate() {
            let (_, d_inst) = self.layer.instantaneous(pk);
            let (_, d_creep) = self.layer.creep(pk);
            creep_slope[k] = self.creep_per_cell * d_creep;
            diagonal[k] = d_inst + 0.5 * creep_slope[k];
        }
        MaxwellJacobian {
            nx: self.nx,
            diagonal,
            creep_slope,
        }
    }

    /// Cells along x.
    pub fn nx(&self) -> usize {
        self.nx
    }

    /// Rows.
    pub fn ny(&self) -> usize {
        self.ny
    }
}

/// The layer's Jacobian `dw3/dp`: lower triangular in each row in the order of
/// the material path (from largest x), `J_ii = diagonal_i`, `J_ij = creep_slope_j`
/// for j upstream of i in the same row.
#[derive(Debug, Clone)]
pub struct MaxwellJacobian {
    nx: usize,
    /// `d(instantaneous)/dp + (h / 2VT) d(Cp)/dp`.
    pub diagonal: Vec<f64>,
    /// `(h / VT) d(Cp)/dp`.
    pub creep_slope: Vec<f64>,
}

impl MaxwellJacobian {
    /// `out = J dp`.
    pub fn apply(&self, dp: &[f64], out: &mut [f64]) {
        let nx = self.nx;
        for (r, (drow, orow)) in dp
            .chunks_exact(nx)
            .zip(out.chunks_exact_mut(nx))
            .enumerate()
        {
            let diag = &self.diagonal[r * nx..(r + 1) * nx];
            let slope = &self.creep_slope[r * nx..(r + 1) * nx];
            let mut upstream = 0.0;
            for i in (0..nx).rev() {
                orow[i] = diag[i] * drow[i] + upstream;
                upstream += slope[i] * drow[i];
            }
        }
    }

    /// Solves `(J + extra_diagonal I) y = r` restricted to the cells where `active`
    /// is true (other entries of `y` are set to 0), by forward substitution along
    /// each row from the leading edge. Diagonals that are not safely positive are
    /// replaced by `extra_diagonal` (this is a preconditioner, not an exact solve).
    pub fn solve_restricted(&self, extra_diagonal: f64, active: &[bool], r: &[f64], y: &mut [f64]) {
        let nx = self.nx;
        for row in 0..r.len() / nx {
            let base = row * nx;
            let mut upstream = 0.0;
            for i in (0..nx).rev() {
                let k = base + i;
                if !active[k] {
                    y[k] = 0.0;
                    continue;
                }
                let mut d = self.diagonal[k] + extra_diagonal;
                if d <= 0.1 * extra_diagonal {
                    d = extra_diagonal.max(f64::MIN_POSITIVE);
                }
                y[k] = (r[k] - upstream) / d;
                upstream += self.creep_slope[k] * y[k];
            }
        }
    }
}

impl LayerResponse for MaxwellRows {
    fn displacement(&self, p: &[f64], w3: &mut [f64]) {
        self.maxwell_row_sweep(p, w3);
    }

    fn linearise(&self, p: &[f64]) -> Box<dyn LayerLinearisation> {
        Box::new(self.jacobian(p))
    }

    fn zero_pressure_self_compliance(&self) -> f64 {
        let (_, d_inst) = self.layer.instantaneous(0.0);
        let (_, d_creep) = self.layer.creep(0.0);
        d_inst + 0.5 * (self.creep_per_cell * d_creep)
    }

    fn winkler_compliance(&self) -> Option<f64> {
        (self.creep_per_cell == 0.0 && matches!(self.layer.law, ComplianceLaw::Linear))
            .then_some(self.layer.compliance)
    }

    /// Where a cell's own response `d(instantaneous)/dp + (h / 2VT) d(C p)/dp` is not
    /// positive, the discrete row relation folds (a larger pressure gives a smaller
    /// displacement) and the contact problem has no unique solution. This happens
    /// when `C[p] p` decreases with p (the sigmoid law with delta near 1 at p well
    /// above p0) and the cells are long against the creep length V T.
    fn stall_diagnosis(&self, p: &[f64]) -> Option<String> {
        let jac = self.jacobian(p);
        let worst = (0..p.len())
            .filter(|&k| p[k] > 0.0 && jac.diagonal[k] <= 0.0)
            .map(|k| p[k])
            .fold(f64::INFINITY, f64::min);
        worst.is_finite().then(|| {
            format!(
                "the layer's row relation folds at pressures above about {worst:.3e} (its \
                 displacement falls as the pressure rises, so the discrete problem has no \
                 unique solution); this happens when C[p] p decreases with p (delta near 1, \
                 p >> p0) and the cells are long against V T (h / (V T) = {:.3e} here): use \
                 a smaller delta, a larger p0, or cells shorter than V T",
                self.creep_per_cell
            )
        })
    }

    fn compliance(&self, p: &[f64]) -> Vec<f64> {
        p.iter().map(|&v| self.layer.law_at(v).compliance).collect()
    }
}

impl LayerLinearisation for MaxwellJacobian {
    fn apply(&self, dp: &[f64], out: &mut [f64]) {
        MaxwellJacobian::apply(self, dp, out);
    }

    fn solve_restricted(&self, extra_diagonal: f64, active: &[bool], r: &[f64], y: &mut [f64]) {
        MaxwellJacobian::solve_restricted(self, extra_diagonal, active, r, y);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layer::tests::sigmoid;
    use crate::layer::{ComplianceLaw, Integration};

    #[test]
    fn delta_zero_is_the_linear_law_exactly() {
        let lin = Layer {
            compliance: 0.02,
            relaxation_time: 1.0,
            law: ComplianceLaw::Linear,
            integration: Integration::Exact,
        };
        for integration in [Integration::Exact, Integration::Secant] {
            let s = sigmoid(0.0, 0.003, integration);
            let l = Layer {
                integration,
                ..lin.clone()
            };
            for &p in &[0.0, 1e-4, 3e-3, 0.1] {
                assert_eq!(s.instantaneous(p), l.instantaneous(p));
                assert_eq!(s.creep(p), l.creep(p));
            }
        }
    }

    #[test]
    fn row_sweep_matches_the_explicit_sum() {
        // Explicit double loop over the definition in the module docs.
        let op = MaxwellRows::new(sigmoid(0.5, 0.002, Integration::Exact), 5, 2, 0.1, 0.05);
        let p: Vec<f64> = (0..10).map(|k| 0.001 * ((k * 7) % 5) as f64).collect();
        let mut w = vec![0.0; 10];
        op.maxwell_row_sweep(&p, &mut w);
        let k = 0.1 / 0.05;
        for r in 0..2 {
            for i in 0..5 {
                let mut s = 0.0;
                for j in i + 1..5 {
                    s += op.layer.creep(p[r * 5 + j]).0;
                }
                let own = op.layer.creep(p[r * 5 + i]).0;
                let e = op.layer.law_at(p[r * 5 + i]).integral + k * (s + own / 2.0);
                assert!((w[r * 5 + i] - e).abs() < 1e-15);
            }
        }
    }

    #[test]
    fn jacobian_matches_finite_differences_and_inverts() {
        for integration in [Integration::Exact, Integration::Secant] {
            let op = MaxwellRows::new(sigmoid(0.8, 0.002, integration), 6, 2, 0.1, 0.03);
            let p: Vec<f64> = (0..12).map(|k| 0.0007 * (1 + (k * 5) % 7) as f64).collect();
            let jac = op.jacobian(&p);
            let dp: Vec<f64> = (0..12).map(|k| ((k * 3) % 4) as f64 - 1.5).collect();
            let mut jd = vec![0.0; 12];
            jac.apply(&dp, &mut jd);
            let e = 1e-8;
            let plus: Vec<f64> = p.iter().zip(&dp).map(|(a, b)| a + e * b).collect();
            let minus: Vec<f64> = p.iter().zip(&dp).map(|(a, b)| a - e * b).collect();
            let (mut wp, mut wm) = (vec![0.0; 12], vec![0.0; 12]);
            op.maxwell_row_sweep(&plus, &mut wp);
            op.maxwell_row_sweep(&minus, &mut wm);
            for k in 0..12 {
                let fd = (wp[k] - wm[k]) / (2.0 * e);
                assert!(
                    (jd[k] - fd).abs() < 1e-6 * fd.abs().max(1e-3),
                    "{k}: {} {fd}",
                    jd[k]
                );
            }
            // The restricted triangular solve inverts J on all-active cells.
            let active = vec![true; 12];
            let mut y = vec![0.0; 12];
            jac.solve_restricted(0.0, &active, &jd, &mut y);
            for k in 0..12 {
                assert!((y[k] - dp[k]).abs() < 1e-9, "{k}");
            }
        }
    }
}
