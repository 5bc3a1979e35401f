//! Any layer rheology of the creep form ([`super::rheology::CreepForm`]: glassy
//! spring, Kelvin–Voigt branches, viscous flow, every part scaled by the law's
//! shape `phi(p) = C[p] / C[0]`) integrated along the material path in the steady
//! sliding frame, where `d/dt = -V d/dx` (docs/architecture.md, conventions).
//! Material enters the window at its largest x and moves in -x; the pressure is
//! constant over a cell (side h), so each part is integrated exactly over a cell:
//!
//! * glassy: `w_g,i = (C_g / C[0]) F(p_i)`, with `F(p) = G(p) = int_0^p C[q] dq`
//!   (`exact`) or `C[p] p` (`secant`);
//! * flow (paper eq. 2's dashpot): `dw_v/dt = (C_v / C[0]) C[p] p / T`, so at the
//!   centre of cell i
//!   `w_v,i = (C_v / C[0]) (h / (V T)) (sum_{j upstream} C[p_j] p_j + C[p_i] p_i / 2)`;
//! * Kelvin–Voigt branch k: `tau_k dw_k/dt + w_k = (C_k / C[0]) F(p)`, a first-order
//!   linear ODE along the row. Over a cell its forcing `F_i` is constant, so with
//!   `a = exp(-h / (V tau_k))` and `b = exp(-h / (2 V tau_k))` the value entering the
//!   next cell is `e_out = a e_in + (1 - a) F_i` and the cell-centre value is
//!   `w_k,i = b e_in + (1 - b) F_i` (`e = 0` where material enters).
//!
//! That exact centre value has, for a branch without a glassy spring in series, an
//! undamped odd–even mode: imposing `w_i` at the centre fixes each cell's pressure
//! from half a cell of response, and the error factor from one cell to the next is
//! `-b`, so the pressure jump at a Kelvin–Voigt layer's leading edge rings across
//! the contact (up to twice the jump) however fine the grid. The centre value used
//! is therefore the exact one plus the upwind correction
//! `kappa s (b - a) (F_i - F_{i+1})` (`F` of the upstream cell, 0 beyond the
//! window), with `kappa = 0.1` and `s` the branches' share of a cell's own response
//! at zero pressure, `sum (1 - b_k) C_k / (C_g + sum (1 - b_k) C_k)` (near 1 for a
//! Kelvin–Voigt layer, near 0 when a glassy spring dominates, which needs no
//! correction). The error factor of the mode then has modulus about 0.57 per cell
//! instead of 1 (the characteristic roots of the two-term recursion, determinant
//! `a gamma / theta`), while for a smooth pressure the correction is
//! `kappa s (b - a) h dF/dx = O(h^2 / (V tau))`, of the scheme's own second order.
//! Larger kappa damps faster but raises that error (0.2 doubles it), and a
//! second-difference correction is unstable beyond kappa = 0.3. Edge values stay
//! exact, so the dissipation below is unaffected.
//!
//! For the paper's Maxwell layer (`C_g = C_v = C[0]`, no branches) this is exactly
//! the sum of paper eq. 8 read with the loaded cell's compliance (`secant`) or its
//! exact integral (`exact`); the other reading of eq. 8, with the receiving cell's
//! compliance multiplying all upstream creep, folds at low `V T / h` and is not
//! offered. Applying the layer is one sweep per row from the leading edge with one
//! state per branch: O(n (1 + branches)). Rows (fixed y) do not interact.
//!
//! The power dissipated ([`ViscoelasticRows::dissipated_force`]) is the power of the
//! pressure on the parts that do not store energy: `p dw_v/dt` for the flow and
//! `(p - F_k^{-1}(w_k)) dw_k/dt` for branch k. Over a cell the flow dissipates
//! `p_i (w_v,out - w_v,in)`; a branch `p_i (e_out - e_in)` less the change of its
//! stored energy `Phi_k(w) = int_0^w F_k^{-1}`. Downstream of the window the branch
//! relaxes at zero pressure and dissipates the energy it still holds, so summed
//! along a whole row the stored energies cancel and the branch dissipates exactly
//! `sum_i p_i (e_out,i - e_in,i)`.

use rayon::prelude::*;

use super::law::SIGMOID_MONOTONE_DELTA;
use super::rheology::{CreepForm, Flow};
use super::{ComplianceLaw, Integration, Layer, LayerLinearisation, LayerResponse};
use crate::convolution::Parallelism;
use crate::passes::{Passes, CHUNK};

/// `sum_k u_k v_k` with four partial sums, so that the additions of a long branch
/// list overlap instead of waiting on each other.
fn dot(u: &[f64], v: &[f64]) -> f64 {
    let mut lanes = [0.0; 4];
    let (uc, vc) = (u.chunks_exact(4), v.chunks_exact(4));
    let tail: f64 = uc
        .remainder()
        .iter()
        .zip(vc.remainder())
        .map(|(a, b)| a * b)
        .sum();
    for (a, b) in uc.zip(vc) {
        for j in 0..4 {
            lanes[j] += a[j] * b[j];
        }
    }
    (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]) + tail
}

/// Fraction of the full upwind correction applied (module docs).
const UPWIND: f64 = 0.1;

/// One Kelvin–Voigt branch on the grid.
#[derive(Debug, Clone, Copy)]
struct BranchStep {
    /// `C_k / C[0]`.
    scale: f64,
    /// `exp(-h / (V tau_k))`: what is left of the entering value over a cell.
    keep_full: f64,
    /// `1 - keep_full`.
    take_full: f64,
    /// `exp(-h / (2 V tau_k))`: the same over half a cell.
    keep_half: f64,
    /// `1 - keep_half`.
    take_half: f64,
}

/// A layer of the creep form on a grid's rows: the row sweep and its linearisation.
#[derive(Debug, Clone)]
pub struct ViscoelasticRows {
    layer: Layer,
    nx: usize,
    ny: usize,
    cell: f64,
    /// `C[0]` of the law the parts are scaled against.
    reference: f64,
    /// `C_g / C[0]`.
    glassy_scale: f64,
    /// `(C_v / C[0]) h / (V T)`: flow per cell of path, 0 for no flow or infinite V.
    flow_per_cell: f64,
    branches: Vec<BranchStep>,
    /// `kappa s sum_k (b_k - a_k) C_k / C[0]`: the upwind correction's weight.
    upwind: f64,
    /// `sum_k (1 - b_k) C_k / C[0]`: the branches' own response over half a cell.
    branch_own: f64,
    /// How the row passes are split over threads.
    passes: Passes,
}

impl ViscoelasticRows {
    /// The layer on rows of `nx` cells of side `cell`, sliding at `velocity`.
    pub fn new(layer: Layer, nx: usize, ny: usize, cell: f64, velocity: f64) -> Self {
        let form: CreepForm = layer.rheology.creep_form();
        let reference = layer.reference_compliance();
        let flow_per_cell = match form.flow {
            Some(Flow { compliance, time }) if velocity.is_finite() => {
                (compliance / reference) * (cell / (velocity * time))
            }
            _ => 0.0,
        };
        let branches = form
            .branches
            .iter()
            .map(|b| {
                // h / (V tau): 0 for infinite V (the branch has no time to move),
                // +inf when it relaxes within a cell.
                let x = cell / (velocity * b.time);
                BranchStep {
                    scale: b.compliance / reference,
                    keep_full: (-x).exp(),
                    take_full: -(-x).exp_m1(),
                    keep_half: (-0.5 * x).exp(),
                    take_half: -(-0.5 * x).exp_m1(),
                }
            })
            .collect::<Vec<BranchStep>>();
        let glassy_scale = form.glassy / reference;
        let branch_own: f64 = branches.iter().map(|b| b.take_half * b.scale).sum();
        let share = if branch_own > 0.0 {
            branch_own / (glassy_scale + branch_own)
        } else {
            0.0
        };
        let upwind = UPWIND
            * share
            * branches
                .iter()
                .map(|b| (b.keep_half - b.keep_full) * b.scale)
                .sum::<f64>();
        ViscoelasticRows {
            upwind,
            branch_own,
            passes: Passes::new(nx * ny, Parallelism::Rayon),
            glassy_scale,
            layer,
            nx,
            ny,
            cell,
            reference,
            flow_per_cell,
            branches,
        }
    }

    /// Splits the row passes over the rayon pool only when `parallelism` asks for it
    /// and the grid has at least `PARALLEL_MIN_CELLS` cells (the default asks for
    /// it), by the rules of the solvers' passes.
    pub fn with_parallelism(mut self, parallelism: Parallelism) -> Self {
        self.passes = Passes::new(self.nx * self.ny, parallelism);
        self
    }

    /// The layer.
    pub fn layer(&self) -> &Layer {
        &self.layer
    }

    /// The forcing `F(p)` of the elastic parts (`G(p)` or `C[p] p`) and `dF/dp`, and
    /// the flow's rate density `C[p] p` and its derivative, from one evaluation of
    /// the law (the costly part of every row pass).
    fn forcing_and_creep(&self, p: f64) -> ((f64, f64), (f64, f64)) {
        let l = self.layer.law.at(self.reference, p);
        let creep = (l.compliance * p, l.compliance + l.slope * p.max(0.0));
        let forcing = match self.layer.integration {
            Integration::Exact => (l.integral, l.compliance),
            Integration::Secant => creep,
        };
        (forcing, creep)
    }

    /// The forcing and its derivative alone (tests).
    #[cfg(test)]
    fn forcing(&self, p: f64) -> (f64, f64) {
        self.forcing_and_creep(p).0
    }

    /// The flow's rate density and its derivative alone (tests).
    #[cfg(test)]
    fn creep(&self, p: f64) -> (f64, f64) {
        self.forcing_and_creep(p).1
    }

    /// Layer displacement `w3` of every cell: one sweep per row from the leading edge.
    pub fn row_sweep(&self, p: &[f64], w3: &mut [f64]) {
        // Rows are independent: one per task, each with its own branch states.
        let rows = p
            .par_chunks_exact(self.nx)
            .zip(w3.par_chunks_exact_mut(self.nx))
            .with_min_len(self.passes.min_rows(self.nx));
        rows.for_each_init(
            || vec![0.0; self.branches.len()],
            |state, (prow, wrow)| {
                let mut upstream = 0.0;
                let mut upstream_forcing = 0.0;
                state.fill(0.0);
                for i in (0..self.nx).rev() {
                    let ((f, _), (q, _)) = self.forcing_and_creep(prow[i]);
                    let mut retarded = 0.0;
                    for (b, e) in self.branches.iter().zip(state.iter_mut()) {
                        let force = b.scale * f;
                        retarded += b.keep_half * *e + b.take_half * force;
                        *e = b.keep_full * *e + b.take_full * force;
                    }
                    if !self.branches.is_empty() {
                        retarded += self.upwind * (f - upstream_forcing);
                    }
                    wrow[i] = self.glassy_scale * f
                        + self.flow_per_cell * (upstream + 0.5 * q)
                        + retarded;
                    upstream += q;
                    upstream_forcing = f;
                }
            },
        );
    }

    /// The power dissipated in the layer divided by the sliding speed (a force:
    /// divided by the normal load it is a friction coefficient), by the exact
    /// integration over each cell in the module docs; the branches' relaxation
    /// downstream of the window is included. Zero for an infinite velocity.
    pub fn dissipated_force(&self, p: &[f64]) -> f64 {
        // Rows in parallel, their sums added in row order (the same bits on any
        // number of threads).
        let rows: Vec<f64> = p
            .par_chunks(self.nx)
            .with_min_len(self.passes.min_rows(self.nx))
            .map_init(
                || vec![0.0; self.branches.len()],
                |state, prow| {
                    state.fill(0.0);
                    let mut row = 0.0;
                    for i in (0..self.nx).rev() {
                        let ((f, _), (q, _)) = self.forcing_and_creep(prow[i]);
                        let mut moved = self.flow_per_cell * q;
                        for (b, e) in self.branches.iter().zip(state.iter_mut()) {
                            let out = b.keep_full * *e + b.take_full * b.scale * f;
                            moved += out - *e;
                            *e = out;
                        }
                        row += prow[i] * moved;
                    }
                    row
                },
            )
            .collect();
        let total: f64 = rows.iter().fold(0.0, |t, r| t + r);
        // Each cell's term is the energy per unit area dissipated while material
        // crosses it; a row of width h carries h V of area per unit time.
        total * self.cell
    }

    /// The linearisation at a pressure field, for Newton steps.
    pub fn jacobian(&self, p: &[f64]) -> ViscoelasticJacobian {
        let n = p.len();
        let mut diagonal = vec![0.0; n];
        let mut flow_slope = vec![0.0; n];
        let mut forcing_slope = vec![0.0; n];
        // Cell by cell (the law's evaluations are the cost), in chunks.
        diagonal
            .par_chunks_mut(CHUNK)
            .zip(flow_slope.par_chunks_mut(CHUNK))
            .zip(forcing_slope.par_chunks_mut(CHUNK))
            .zip(p.par_chunks(CHUNK))
            .with_min_len(self.passes.min_len())
            .for_each(|(((diagonal, flow_slope), forcing_slope), p)| {
                for (k, &pk) in p.iter().enumerate() {
                    let ((_, df), (_, dq)) = self.forcing_and_creep(pk);
                    flow_slope[k] = self.flow_per_cell * dq;
                    forcing_slope[k] = df;
                    let retarded = self.branch_own * df;
                    diagonal[k] =
                        self.glassy_scale * df + 0.5 * flow_slope[k] + retarded + self.upwind * df;
                }
            });
        ViscoelasticJacobian {
            min_rows: self.passes.min_rows(self.nx),
            upwind: self.upwind,
            nx: self.nx,
            diagonal,
            flow_slope,
            forcing_slope,
            keep_half: self.branches.iter().map(|b| b.keep_half).collect(),
            keep_full: self.branches.iter().map(|b| b.keep_full).collect(),
            take_full_scaled: self
                .branches
                .iter()
                .map(|b| b.take_full * b.scale)
                .collect(),
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
/// the material path (from largest x). `J_ii = diagonal_i`; for j upstream of i,
/// `J_ij = flow_slope_j + sum_k (C_k / C[0]) dF/dp_j (1 - a_k) a_k^(j-i-1) b_k`.
#[derive(Debug, Clone)]
pub struct ViscoelasticJacobian {
    nx: usize,
    /// `dw3_i / dp_i`.
    pub diagonal: Vec<f64>,
    /// `(C_v / C[0]) (h / VT) d(C p)/dp`: the flow's part of every downstream entry.
    pub flow_slope: Vec<f64>,
    /// `dF/dp` of the elastic parts' forcing.
    pub forcing_slope: Vec<f64>,
    /// Per branch (contiguous, for the inner loops): `b`, `a`, `(1 - a) C_k / C[0]`.
    keep_half: Vec<f64>,
    keep_full: Vec<f64>,
    take_full_scaled: Vec<f64>,
    /// The upwind correction's weight: `J_i,i+1` has `- upwind dF/dp_{i+1}`.
    upwind: f64,
    /// Fewest rows per rayon task (`usize::MAX`: one thread), from the layer's
    /// passes.
    min_rows: usize,
}

impl ViscoelasticJacobian {
    /// `sum_k b_k e_k`: what the branches carry into a cell's centre.
    fn entering(&self, state: &[f64]) -> f64 {
        dot(&self.keep_half, state)
    }

    /// Carries the branch states across a cell whose forcing changed by `df`.
    fn advance(&self, state: &mut [f64], df: f64) {
        for ((e, a), t) in state
            .iter_mut()
            .zip(&self.keep_full)
            .zip(&self.take_full_scaled)
        {
            *e = a * *e + t * df;
        }
    }

    /// `out = J dp`.
    pub fn apply(&self, dp: &[f64], out: &mut [f64]) {
        let nx = self.nx;
        let rows = dp.par_chunks_exact(nx).zip(out.par_chunks_exact_mut(nx));
        rows.with_min_len(self.min_rows).enumerate().for_each_init(
            || vec![0.0; self.keep_half.len()],
            |state, (r, (drow, orow))| {
                let diag = &self.diagonal[r * nx..(r + 1) * nx];
                let slope = &self.flow_slope[r * nx..(r + 1) * nx];
                let fslope = &self.forcing_slope[r * nx..(r + 1) * nx];
                let mut upstream = 0.0;
                let mut upstream_forcing = 0.0;
                // While nothing has entered the branches, they carry nothing.
                let mut live = false;
                state.fill(0.0);
                for i in (0..nx).rev() {
                    let df = fslope[i] * drow[i];
                    live |= df != 0.0;
                    let entering = if live {
                        let e = self.entering(state);
                        self.advance(state, df);
                        e
                    } else {
                        0.0
                    };
                    orow[i] =
                        diag[i] * drow[i] + upstream + entering - self.upwind * upstream_forcing;
                    upstream += slope[i] * drow[i];
                    upstream_forcing = df;
                }
            },
        );
    }

    /// Solves `(J + extra_diagonal I) y = r` restricted to the cells where `active`
    /// is true (other entries of `y` are set to 0), by forward substitution along
    /// each row from the leading edge. Diagonals that are not safely positive are
    /// replaced by `extra_diagonal` (this is a preconditioner, not an exact solve).
    pub fn solve_restricted(&self, extra_diagonal: f64, active: &[bool], r: &[f64], y: &mut [f64]) {
        let nx = self.nx;
        let rows = y
            .par_chunks_exact_mut(nx)
            .with_min_len(self.min_rows)
            .enumerate();
        rows.for_each_init(
            || vec![0.0; self.keep_half.len()],
            |state, (row, y)| {
                let base = row * nx;
                let mut upstream = 0.0;
                let mut upstream_forcing = 0.0;
                let mut live = false;
                state.fill(0.0);
                for i in (0..nx).rev() {
                    let k = base + i;
                    let entering = if live { self.entering(state) } else { 0.0 };
                    if active[k] {
                        let mut d = self.diagonal[k] + extra_diagonal;
                        if d <= 0.1 * extra_diagonal {
                            d = extra_diagonal.max(f64::MIN_POSITIVE);
                        }
                        y[i] = (r[k] - upstream - entering + self.upwind * upstream_forcing) / d;
                    } else {
                        y[i] = 0.0;
                    }
                    let df = self.forcing_slope[k] * y[i];
                    live |= df != 0.0;
                    if live {
                        self.advance(state, df);
                    }
                    upstream += self.flow_slope[k] * y[i];
                    upstream_forcing = df;
                }
            },
        );
    }
}

impl LayerResponse for ViscoelasticRows {
    fn displacement(&self, p: &[f64], w3: &mut [f64]) {
        self.row_sweep(p, w3);
    }

    fn linearise(&self, p: &[f64]) -> Box<dyn LayerLinearisation> {
        Box::new(self.jacobian(p))
    }

    fn zero_pressure_self_compliance(&self) -> f64 {
        self.jacobian(&[0.0]).diagonal[0]
    }

    /// `w3 = c p` exactly when the law is linear, nothing flows and every branch
    /// is either frozen (infinite velocity) or relaxed within a cell.
    fn winkler_compliance(&self) -> Option<f64> {
        if self.flow_per_cell != 0.0 || !matches!(self.layer.law, ComplianceLaw::Linear) {
            return None;
        }
        let mut scale = self.glassy_scale;
        for b in &self.branches {
            if b.keep_half == 1.0 && b.keep_full == 1.0 {
                continue;
            }
            if b.keep_half == 0.0 && b.keep_full == 0.0 {
                scale += b.scale;
                continue;
            }
            return None;
        }
        Some(scale * self.reference)
    }

    /// Where a cell's own response `dw3_i/dp_i` is not positive, the discrete row
    /// relation folds (a larger pressure gives a smaller displacement) and the
    /// contact problem has no unique solution. This happens when `C[p] p` decreases
    /// with p (the sigmoid law with delta near 1 at p well above p0) and the cells
    /// are long against the layer's creep lengths `V T`, `V tau_k`.
    fn stall_diagnosis(&self, p: &[f64]) -> Option<String> {
        let jac = self.jacobian(p);
        let worst = (0..p.len())
            .filter(|&k| p[k] > 0.0 && jac.diagonal[k] <= 0.0)
            .map(|k| p[k])
            .fold(f64::INFINITY, f64::min);
        worst.is_finite().then(|| {
            let advice = match &self.layer.law {
                ComplianceLaw::Sigmoid { delta, .. } => format!(
                    "with the sigmoid law C[p] p falls with p somewhere once delta > \
                     {SIGMOID_MONOTONE_DELTA:.3} (here delta = {delta}); use delta <= \
                     {SIGMOID_MONOTONE_DELTA:.3} (C[p] p then rises at every pressure)"
                ),
                ComplianceLaw::Table(_) => "the table's compliance falls faster than 1/p \
                     there, so C[p] p falls: make it fall more slowly (C[p] p rising \
                     with p) above that pressure"
                    .to_string(),
                ComplianceLaw::Linear => "a linear layer should not fold: please report \
                     this case"
                    .to_string(),
            };
            format!(
                "the layer's row relation folds at pressures above about {worst:.3e} (its \
                 displacement falls as the pressure rises, so the discrete problem has no \
                 unique solution, h / (V T) = {:.3e} for the flow); {advice}. Finer cells \
                 move the fold to higher pressures but do not remove it",
                self.flow_per_cell
            )
        })
    }

    /// The relaxed compliance `(C_g + sum C_k) phi(p)` (for the Maxwell layer `C[p]`).
    fn compliance(&self, p: &[f64]) -> Vec<f64> {
        let scale = self
            .branches
            .iter()
            .fold(self.glassy_scale, |s, b| s + b.scale);
        p.par_iter()
            .with_min_len(self.passes.min_cells())
            .map(|&v| scale * self.layer.law.at(self.reference, v).compliance)
            .collect()
    }

    fn dissipated_force(&self, p: &[f64]) -> f64 {
        ViscoelasticRows::dissipated_force(self, p)
    }
}

impl LayerLinearisation for ViscoelasticJacobian {
    fn apply(&self, dp: &[f64], out: &mut [f64]) {
        ViscoelasticJacobian::apply(self, dp, out);
    }

    fn solve_restricted(&self, extra_diagonal: f64, active: &[bool], r: &[f64], y: &mut [f64]) {
        ViscoelasticJacobian::solve_restricted(self, extra_diagonal, active, r, y);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layer::rheology::{RetardationBranch, Rheology};
    use crate::layer::tests::sigmoid;
    use crate::layer::ComplianceLaw;

    fn prony(law: ComplianceLaw, integration: Integration, viscosity: Option<f64>) -> Layer {
        Layer {
            rheology: Rheology::Prony {
                glassy_compliance: 0.01,
                branches: vec![
                    RetardationBranch {
                        compliance: 0.02,
                        time: 0.3,
                    },
                    RetardationBranch {
                        compliance: 0.005,
                        time: 4.0,
                    },
                ],
                viscosity,
            },
            law,
            integration,
        }
    }

    #[test]
    fn delta_zero_is_the_linear_law_exactly() {
        for integration in [Integration::Exact, Integration::Secant] {
            let s = ViscoelasticRows::new(sigmoid(0.0, 0.003, integration), 1, 1, 0.1, 1.0);
            let l = ViscoelasticRows::new(
                Layer {
                    law: ComplianceLaw::Linear,
                    ..sigmoid(0.0, 0.003, integration)
                },
                1,
                1,
                0.1,
                1.0,
            );
            for &p in &[0.0, 1e-4, 3e-3, 0.1] {
                assert_eq!(s.forcing(p), l.forcing(p));
                assert_eq!(s.creep(p), l.creep(p));
            }
        }
    }

    #[test]
    fn maxwell_row_sweep_matches_the_explicit_sum() {
        // Explicit double loop over eq. 8 (exact integral) as in the module docs.
        let op = ViscoelasticRows::new(sigmoid(0.5, 0.002, Integration::Exact), 5, 2, 0.1, 0.05);
        let p: Vec<f64> = (0..10).map(|k| 0.001 * ((k * 7) % 5) as f64).collect();
        let mut w = vec![0.0; 10];
        op.row_sweep(&p, &mut w);
        let k = 0.1 / 0.05;
        for r in 0..2 {
            for i in 0..5 {
                let mut s = 0.0;
                for j in i + 1..5 {
                    s += op.creep(p[r * 5 + j]).0;
                }
                let own = op.creep(p[r * 5 + i]).0;
                let e = op.layer.law_at(p[r * 5 + i]).integral + k * (s + own / 2.0);
                assert!((w[r * 5 + i] - e).abs() < 1e-15);
            }
        }
    }

    #[test]
    fn kelvin_voigt_branch_matches_the_ode_solution() {
        // A linear Kelvin–Voigt branch under piecewise-constant pressure: the exact
        // solution of tau w' + w = C p(t), summed as a convolution with the step
        // response C (1 - exp(-t / tau)) at each cell centre.
        let (c, tau, v, h) = (0.03, 0.7, 0.4, 0.1);
        let layer = Layer {
            rheology: Rheology::KelvinVoigt {
                compliance: c,
                retardation_time: tau,
            },
            law: ComplianceLaw::Linear,
            integration: Integration::Exact,
        };
        let nx = 7;
        let op = ViscoelasticRows::new(layer, nx, 1, h, v);
        let p: Vec<f64> = (0..nx).map(|k| 0.001 * (1 + (k * 3) % 5) as f64).collect();
        let mut w = vec![0.0; nx];
        op.row_sweep(&p, &mut w);
        let step = |t: f64| {
            if t <= 0.0 {
                0.0
            } else {
                c * (1.0 - (-t / tau).exp())
            }
        };
        for (i, wi) in w.iter().enumerate() {
            // Time at the centre of cell i since material entered at the window edge.
            let t = ((nx - i) as f64 - 0.5) * h / v;
            let mut e = 0.0;
            for (j, pj) in p.iter().enumerate().skip(i) {
                // Pressure p_j switched on at entry to cell j and off at its exit.
                let on = ((nx - 1 - j) as f64) * h / v;
                let off = on + h / v;
                e += pj * (step(t - on) - step(t - off));
            }
            // The upwind correction (module docs: kappa = 0.1, share 1 without a
            // glassy spring), with the upstream cell's forcing.
            let x = h / (v * tau);
            let upstream = if i + 1 < nx { c * p[i + 1] } else { 0.0 };
            let e = e + 0.1 * ((-x / 2.0).exp() - (-x).exp()) * (c * p[i] - upstream);
            assert!((wi - e).abs() < 1e-15, "{i}: {wi} {e}");
        }
    }

    #[test]
    fn jacobian_matches_finite_differences_and_inverts() {
        let layers = [
            sigmoid(0.8, 0.002, Integration::Exact),
            sigmoid(0.8, 0.002, Integration::Secant),
            prony(
                ComplianceLaw::Sigmoid {
                    delta: 0.6,
                    p0: 0.002,
                },
                Integration::Exact,
                Some(30.0),
            ),
            prony(
                ComplianceLaw::Sigmoid {
                    delta: 0.6,
                    p0: 0.002,
                },
                Integration::Secant,
                None,
            ),
        ];
        for layer in layers {
            let op = ViscoelasticRows::new(layer, 6, 2, 0.1, 0.03);
            let p: Vec<f64> = (0..12).map(|k| 0.0007 * (1 + (k * 5) % 7) as f64).collect();
            let jac = op.jacobian(&p);
            let dp: Vec<f64> = (0..12).map(|k| ((k * 3) % 4) as f64 - 1.5).collect();
            let mut jd = vec![0.0; 12];
            jac.apply(&dp, &mut jd);
            let e = 1e-8;
            let plus: Vec<f64> = p.iter().zip(&dp).map(|(a, b)| a + e * b).collect();
            let minus: Vec<f64> = p.iter().zip(&dp).map(|(a, b)| a - e * b).collect();
            let (mut wp, mut wm) = (vec![0.0; 12], vec![0.0; 12]);
            op.row_sweep(&plus, &mut wp);
            op.row_sweep(&minus, &mut wm);
            for k in 0..12 {
                let fd = (wp[k] - wm[k]) / (2.0 * e);
                assert!(
                    (jd[k] - fd).abs() < 1e-6 * fd.abs().max(1e-3),
                    "{k}: {} {fd}",
                    jd[k]
                );
            }
            // The restricted triangular solve inverts J on all-active cells ...
            let active = vec![true; 12];
            let mut y = vec![0.0; 12];
            jac.solve_restricted(0.0, &active, &jd, &mut y);
            for k in 0..12 {
                assert!((y[k] - dp[k]).abs() < 1e-9, "{k}");
            }
            // ... and on a subset it inverts the principal submatrix: J restricted to
            // the active cells applied to y gives back r there.
            let active: Vec<bool> = (0..12).map(|k| k % 3 != 1).collect();
            let r: Vec<f64> = (0..12).map(|k| 1e-3 * (k as f64 - 5.0)).collect();
            jac.solve_restricted(0.0, &active, &r, &mut y);
            let mut jy = vec![0.0; 12];
            jac.apply(&y, &mut jy);
            for k in (0..12).filter(|&k| active[k]) {
                assert!((jy[k] - r[k]).abs() < 1e-12, "{k}: {} {}", jy[k], r[k]);
            }
        }
    }

    #[test]
    fn dissipation_of_a_linear_branch_is_its_dashpot_work() {
        // For the linear law the branch dissipates (tau / C) (dw/dt)^2; integrate it
        // over time along a row by fine quadrature of the exact solution (pressure
        // switched on for the window's cells, then the free relaxation behind it).
        let (c, tau, v, h) = (0.02, 0.5, 0.3, 0.1);
        let layer = Layer {
            rheology: Rheology::KelvinVoigt {
                compliance: c,
                retardation_time: tau,
            },
            law: ComplianceLaw::Linear,
            integration: Integration::Exact,
        };
        let p = [0.0, 0.002, 0.004, 0.003, 0.001, 0.0];
        let op = ViscoelasticRows::new(layer, p.len(), 1, h, v);
        let d = op.dissipated_force(&p) / h;
        // Energy per unit area: integral of (tau / C) w'^2 dt, w' = (C p - w) / tau.
        let dt_cell = h / v;
        let steps = 20000;
        let mut w: f64 = 0.0;
        let mut energy = 0.0;
        for j in (0..p.len())
            .rev()
            .chain(std::iter::repeat_n(usize::MAX, 40))
        {
            let pj = if j == usize::MAX { 0.0 } else { p[j] };
            let dt = dt_cell / steps as f64;
            for _ in 0..steps {
                // Exact update over dt, energy by the midpoint rule.
                let target = c * pj;
                let w_new = target + (w - target) * (-dt / tau).exp();
                let rate = (w_new - w) / dt;
                energy += tau / c * rate * rate * dt;
                w = w_new;
            }
        }
        assert!((d - energy).abs() < 1e-6 * energy, "{d} {energy}");
    }
}
