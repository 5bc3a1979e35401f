//! The third-body layer between the slider and the body: its data as a case gives it
//! ([`Layer`]), and the interface through which the contact solvers see any layer
//! rheology on a grid ([`LayerResponse`], [`LayerLinearisation`]). The solvers know
//! nothing else of the layer: the displacement `w3(p)` for a pressure field, its
//! Jacobian (applied, and solved row-wise as a preconditioner), whether `w3 = c p`
//! exactly (then the contact problem is symmetric and conjugate gradients apply), the
//! compliance field to report, and a diagnosis when the model has no unique solution.
//! Every rheology preset ([`rheology`]: the paper's nonlinear Maxwell layer of eq. 2,
//! Kelvin–Voigt, Zener, Burgers, Prony series, fractional Zener, box spectrum) is one
//! implementation of [`rheology::RheologyModel`] in its own file and reduces to one
//! creep form, integrated along the rows by [`viscoelastic`]; [`Layer::on_grid`]
//! builds that response. The pressure dependence `C[p]` is apart, in [`law`].
//!
//! Conventions (docs/architecture.md): material enters the window at its largest x and
//! moves in -x, so a layer's response is causal along each row from the leading edge;
//! rows (fixed y) do not interact.

pub mod law;
pub mod rheology;
pub mod viscoelastic;

pub use law::{ComplianceLaw, LawValue, Table};
pub use rheology::{
    CreepForm, Flow, RelaxationBranch, RetardationBranch, Rheology, RheologyModel, SolverUnits,
};
pub use viscoelastic::{ViscoelasticJacobian, ViscoelasticRows};

use crate::convolution::Parallelism;
use crate::error::{require_positive, Error, Result};
use crate::grid::Grid;

/// How the elastic parts' forcing is integrated over a cell (see [`viscoelastic`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Integration {
    /// Exact integration: the instantaneous part is `G(p)`.
    #[default]
    Exact,
    /// The paper's eq. 8 with the loaded cell's secant compliance: `C[p] p`.
    Secant,
}

/// A viscoelastic third-body layer, as a case describes it.
#[derive(Debug, Clone, PartialEq)]
pub struct Layer {
    /// The rheology: its parts, their compliances at zero pressure and their times.
    pub rheology: Rheology,
    /// Pressure dependence: every part's compliance is scaled by `C[p] / C[0]`.
    pub law: ComplianceLaw,
    /// Integration of the elastic parts over a cell.
    pub integration: Integration,
}

/// What the automatic window and the initial guesses need of a layer: a linear
/// layer that behaves like it (compliance `compliance`, creeping with time constant
/// `relaxation_time`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LayerEstimate {
    /// Compliance of the layer at small pressure.
    pub compliance: f64,
    /// Time over which it creeps (infinite for no creep).
    pub relaxation_time: f64,
}

/// A layer rheology on a grid at a sliding velocity: what the contact solvers see.
pub trait LayerResponse: std::fmt::Debug + Send + Sync {
    /// The layer's normal displacement `w3` of every cell for the pressure `p`.
    fn displacement(&self, p: &[f64], w3: &mut [f64]);
    /// The Jacobian `dw3/dp` at `p`, for Newton steps.
    fn linearise(&self, p: &[f64]) -> Box<dyn LayerLinearisation>;
    /// The power dissipated in the layer divided by the sliding speed, at `p`
    /// (the tangential force that energy balance predicts; 0 for an elastic layer).
    fn dissipated_force(&self, p: &[f64]) -> f64;
    /// A cell's own `dw3/dp` at zero pressure (sets the solvers' pressure scale).
    fn zero_pressure_self_compliance(&self) -> f64;
    /// `Some(c)` when `w3 = c p` exactly (a creep-free linear spring bed): the contact
    /// operator is then symmetric positive definite and conjugate gradients apply.
    fn winkler_compliance(&self) -> Option<f64>;
    /// Why the contact problem has no unique solution at `p`, if the model says so
    /// (checked when Newton stalls); `None` when the layer is not to blame.
    fn stall_diagnosis(&self, p: &[f64]) -> Option<String>;
    /// The compliance `C[p]` of every cell, to report (paper Fig. 3b).
    fn compliance(&self, p: &[f64]) -> Vec<f64>;
    /// This response with each contact's leading edge located inside its first
    /// loaded cell from a solution's pressure `p` and gap `gap` (the solvers solve
    /// again with it), when the edges moved since the ones it uses; `None` when
    /// they did not or when the response does not depend on them.
    fn relocated(&self, _p: &[f64], _gap: &[f64]) -> Option<Box<dyn LayerResponse>> {
        None
    }
    /// Whether [`LayerResponse::relocated`] can ever return a response.
    fn places_edges(&self) -> bool {
        false
    }
    /// The contacts' edges along x this response places inside their cells (none
    /// by default): there the pressure a cell carries on average differs from its
    /// centre value ([`cell_mean_pressure`]).
    fn contact_edges(&self) -> &[ContactEdge] {
        &[]
    }
}

/// A contact's edge along x inside a cell (`cell`, a flat index) of a row: the
/// pressure is zero beyond the edge, `theta` cells from the cell's centre
/// (`0 < theta <= 1`), and on the other side follows the line `L` through the cell's
/// centre value and its loaded neighbour's (`neighbour`, absent at the window's
/// edge). Where a layer cannot deform instantly the pressure jumps at a leading edge
/// (no [`Rise`]), or rises behind it: `p(s) = L(s) rho(s)`, s in cells from the edge
/// (springs in series with a flow whose creep length is below the cell); the cell's
/// centre value is then `L`'s at the centre, and the pressure there
/// [`ContactEdge::centre_share`] of it. At every edge a cell's centre value is not
/// its mean.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactEdge {
    /// The cell the edge cuts.
    pub cell: usize,
    /// Its loaded neighbour in the same row.
    pub neighbour: Option<usize>,
    /// Distance from the edge to the cell's centre, in cells.
    pub theta: f64,
    /// How the pressure rises behind the edge ([`Rise::NONE`]: it jumps).
    pub rise: Rise,
}

/// `int_0^x s^n e^(-s / l) ds` for n = 0, 1, 2, by parts: `m_n = n l m_(n-1) - l
/// x^n e^(-x/l)`, `m_0 = l (1 - e^(-x/l))`.
pub(crate) fn exponential_moments(x: f64, l: f64) -> [f64; 3] {
    let decay = (-x / l).exp();
    let m0 = -l * (-x / l).exp_m1();
    let m1 = l * m0 - l * x * decay;
    let m2 = 2.0 * l * m1 - l * x * x * decay;
    [m0, m1, m2]
}

/// Most exponentials a [`Rise`] keeps.
pub const RISE_TERMS: usize = 4;

/// The pressure's rise behind a leading edge per unit of its line, `rho(s) = 1 -
/// sum_m a_m e^(-s / l_m)`, s in cells from the edge: a glassy spring in series
/// with a flow rises with one exponential (`a = 1`, `l = C_g / (flow per cell)`),
/// each retarded branch adds one (docs of the viscoelastic layer). Terms with a zero
/// amplitude are unused; all zero: no rise, the pressure jumps at the edge.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Rise {
    /// `a_m`, each > 0 where used.
    pub amplitudes: [f64; RISE_TERMS],
    /// `l_m` in cells, each > 0 where used.
    pub lengths: [f64; RISE_TERMS],
}

impl Rise {
    /// No rise: the pressure jumps at the edge.
    pub const NONE: Rise = Rise {
        amplitudes: [0.0; RISE_TERMS],
        lengths: [0.0; RISE_TERMS],
    };

    /// One exponential over `length` cells (none for `length <= 0`).
    pub fn single(length: f64) -> Rise {
        let mut r = Rise::NONE;
        if length > 0.0 {
            r.amplitudes[0] = 1.0;
            r.lengths[0] = length;
        }
        r
    }

    /// The terms `(a_m, l_m)` in use.
    pub fn terms(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.amplitudes
            .iter()
            .zip(&self.lengths)
            .map(|(&a, &l)| (a, l))
            .filter(|&(a, l)| a != 0.0 && l > 0.0)
    }

    /// Whether there is no rise (the pressure jumps).
    pub fn is_none(&self) -> bool {
        self.terms().next().is_none()
    }

    /// `rho(s)`: `(1 - sum a_m) + sum a_m (1 - e^(-s / l_m))`, 1 without a rise.
    pub fn share(&self, s: f64) -> f64 {
        let rest: f64 = self.terms().map(|(a, _)| a).sum();
        self.terms()
            .fold(1.0 - rest, |sum, (a, l)| sum - a * (-s / l).exp_m1())
    }

    /// The same rise with every length at most `longest`.
    pub fn shortened(mut self, longest: f64) -> Rise {
        for l in &mut self.lengths {
            *l = l.min(longest);
        }
        self
    }
}

impl ContactEdge {
    /// `(a, b)` with the load the cell carries, per unit area of a cell, `a p_cell +
    /// b p_neighbour`: the integral of the pressure from the edge to the cell's face
    /// on the neighbour's side. Without a rise, of the line alone: `(theta + 1/2) p_c
    /// + (1/4 - theta^2) (p_n - p_c) / 2`; for `theta = 1/2` (the edge on the cell's
    /// other face) it is `(1, 0)`. A rise takes [`ContactEdge::rise_deficit`] from it.
    pub fn mean_weights(&self) -> (f64, f64) {
        let length = self.theta + 0.5;
        let (a, b) = match self.neighbour {
            Some(_) => {
                let slope = 0.5 * (0.25 - self.theta * self.theta);
                (length - slope, slope)
            }
            None => (length, 0.0),
        };
        if self.rise.is_none() {
            (a, b)
        } else {
            let (da, db) = self.rise_deficit(length);
            (a - da, b - db)
        }
    }

    /// `(a, b)` with what the rise takes from the line over the first `x` cells
    /// behind the edge, `int_0^x L(s) (1 - rho(s)) ds = a p_cell + b p_neighbour`:
    /// with `L(s) = (p_c - theta d) + d s`, `d = p_n - p_c`, and per term the
    /// moments `E = int_0^x e^(-s/l) ds = l (1 - e^(-x/l))`, `M = int_0^x s e^(-s/l)
    /// ds = l E - l x e^(-x/l)`, it is `sum_m a_m ((p_c - theta d) E_m + d M_m)`.
    /// Zero without a rise.
    pub fn rise_deficit(&self, x: f64) -> (f64, f64) {
        let (mut da, mut db) = (0.0, 0.0);
        for (amplitude, l) in self.rise.terms() {
            let [e, m, _] = exponential_moments(x, l);
            let (ta, tb) = match self.neighbour {
                Some(_) => (e * (1.0 + self.theta) - m, m - self.theta * e),
                None => (e, 0.0),
            };
            da += amplitude * ta;
            db += amplitude * tb;
        }
        (da, db)
    }

    /// The pressure at the cell's centre per unit of its centre value: `rho(theta)`
    /// (1 without a rise).
    pub fn centre_share(&self) -> f64 {
        self.rise.share(self.theta)
    }

    /// Whether the edge leads (its loaded neighbour downstream, at -x): material
    /// enters the contact there.
    pub fn is_leading(&self) -> bool {
        self.neighbour.is_none_or(|n| n < self.cell)
    }

    /// The largest pressure between the edge and the cell's centre, `max L(s)
    /// rho(s)` over `0 <= s <= theta`, and its `s` (cells from the edge), from the
    /// centre values `p`. Where the pressure falls away from a leading edge, its
    /// peak lies there or, behind a rise, within the cell, not at a centre.
    /// Without a rise `L` is linear and the larger end wins. With one, `f = L rho`
    /// is sampled on a grid geometric in `s` from a thousandth of the shortest rise
    /// length (where the rise happens) and uniform to `theta`, and the best sample
    /// refined by golden-section search between its neighbours (written here: a
    /// one-dimensional maximum of a smooth function on an interval).
    pub fn peak_behind(&self, p: &[f64]) -> (f64, f64) {
        let centre = p[self.cell];
        let slope = self.neighbour.map_or(0.0, |n| p[n] - centre);
        let line = |s: f64| centre + slope * (s - self.theta);
        let f = |s: f64| line(s) * self.rise.share(s);
        if self.rise.is_none() {
            return if line(0.0) > centre {
                (line(0.0), 0.0)
            } else {
                (centre, self.theta)
            };
        }
        let shortest = self
            .rise
            .terms()
            .map(|(_, l)| l)
            .fold(f64::INFINITY, f64::min);
        const SAMPLES: usize = 200;
        let mut s: Vec<f64> = vec![0.0];
        let first = (1e-3 * shortest).min(self.theta);
        let ratio = (self.theta / first).powf(1.0 / SAMPLES as f64);
        s.extend((0..=SAMPLES).map(|k| first * ratio.powi(k as i32)));
        s.extend((1..=SAMPLES).map(|k| self.theta * k as f64 / SAMPLES as f64));
        s.retain(|&v| v <= self.theta);
        s.sort_by(f64::total_cmp);
        s.dedup();
        let best = (0..s.len())
            .max_by(|&i, &j| f(s[i]).total_cmp(&f(s[j])))
            .unwrap_or(0);
        let (mut lo, mut hi) = (s[best.saturating_sub(1)], s[(best + 1).min(s.len() - 1)]);
        let golden = 0.5 * (5f64.sqrt() - 1.0);
        for _ in 0..60 {
            let (a, b) = (hi - golden * (hi - lo), lo + golden * (hi - lo));
            if f(a) >= f(b) {
                hi = b;
            } else {
                lo = a;
            }
        }
        let refined = 0.5 * (lo + hi);
        if f(refined) >= f(s[best]) {
            (f(refined), refined)
        } else {
            (f(s[best]), s[best])
        }
    }
}

/// The pressure each cell carries on average (`out`), from the centre values `p`:
/// `p` itself but at the cells the contacts' edges cut ([`ContactEdge::mean_weights`]).
/// This is what acts on the body and what the load and the friction integrate.
pub fn cell_mean_pressure(entries: &[ContactEdge], p: &[f64], out: &mut [f64]) {
    out.copy_from_slice(p);
    for e in entries {
        let (a, b) = e.mean_weights();
        out[e.cell] = a * p[e.cell] + e.neighbour.map_or(0.0, |d| b * p[d]);
    }
}

/// Per cell, the weight of its centre value in the sum of the mean pressures over
/// the grid (`n` cells): 1 but at the cells contacts' edges cut and their neighbours.
pub fn load_weights(entries: &[ContactEdge], n: usize) -> Vec<f64> {
    let mut w = vec![1.0; n];
    for e in entries {
        let (a, b) = e.mean_weights();
        w[e.cell] += a - 1.0;
        if let Some(d) = e.neighbour {
            w[d] += b;
        }
    }
    w
}

/// The linearised layer `J = dw3/dp`, lower triangular along each row in the order
/// of the material path (from the largest x), up to entries the preconditioner may
/// leave out (the creep form's branches reach one cell downstream through the
/// slope of their forcing).
pub trait LayerLinearisation {
    /// `out = J dp`.
    fn apply(&self, dp: &[f64], out: &mut [f64]);
    /// Solves `(J + extra_diagonal I) y = r` restricted to the cells where `active` is
    /// true (others get 0), by forward substitution along each row from the leading
    /// edge; a preconditioner, so diagonals that are not safely positive may be
    /// replaced by `extra_diagonal`.
    fn solve_restricted(&self, extra_diagonal: f64, active: &[bool], r: &[f64], y: &mut [f64]);
}

/// No layer: the body's surface is the contact surface (`w3 = 0`). Lets the Newton
/// solver treat a bare body like a layered one.
#[derive(Debug, Clone, Copy)]
pub(crate) struct NoLayer;

impl LayerResponse for NoLayer {
    fn displacement(&self, _p: &[f64], w3: &mut [f64]) {
        w3.fill(0.0);
    }
    fn linearise(&self, _p: &[f64]) -> Box<dyn LayerLinearisation> {
        Box::new(NoLayer)
    }
    fn zero_pressure_self_compliance(&self) -> f64 {
        0.0
    }
    fn winkler_compliance(&self) -> Option<f64> {
        Some(0.0)
    }
    fn stall_diagnosis(&self, _p: &[f64]) -> Option<String> {
        None
    }
    fn compliance(&self, p: &[f64]) -> Vec<f64> {
        vec![0.0; p.len()]
    }
    fn dissipated_force(&self, _p: &[f64]) -> f64 {
        0.0
    }
}

impl LayerLinearisation for NoLayer {
    fn apply(&self, _dp: &[f64], out: &mut [f64]) {
        out.fill(0.0);
    }
    fn solve_restricted(&self, extra_diagonal: f64, active: &[bool], r: &[f64], y: &mut [f64]) {
        for ((yk, &rk), &a) in y.iter_mut().zip(r).zip(active) {
            *yk = if a { rk / extra_diagonal } else { 0.0 };
        }
    }
}

impl Layer {
    /// The paper's Maxwell layer (eq. 2) of compliance `compliance` at zero
    /// pressure (for a table law, its first compliance) and relaxation time
    /// `relaxation_time`.
    pub fn maxwell(
        compliance: f64,
        relaxation_time: f64,
        law: ComplianceLaw,
        integration: Integration,
    ) -> Self {
        Layer {
            rheology: Rheology::Maxwell {
                compliance,
                relaxation_time,
            },
            law,
            integration,
        }
    }

    pub(crate) fn validate(&self) -> Result<()> {
        self.rheology.validate()?;
        if let ComplianceLaw::Sigmoid { delta, p0 } = self.law {
            if !(0.0..=1.0).contains(&delta) {
                return Err(Error::invalid("layer.delta", delta, "0 <= delta <= 1"));
            }
            require_positive("layer.p0", p0)?;
        }
        Ok(())
    }

    /// The layer's response on `grid`'s cells at sliding velocity `velocity` (may be
    /// infinite): the one place where a case's layer picks its implementation.
    /// Its row passes use the rayon pool when `parallelism` asks for it and the grid
    /// is large enough to gain ([`crate::convolution::PARALLEL_MIN_CELLS`]).
    pub fn on_grid(
        &self,
        grid: &Grid,
        velocity: f64,
        parallelism: Parallelism,
    ) -> Box<dyn LayerResponse> {
        Box::new(
            ViscoelasticRows::new(self.clone(), grid.nx, grid.ny, grid.cell, velocity)
                .with_row_length(if grid.is_line() { 1.0 } else { grid.cell })
                .with_parallelism(parallelism),
        )
    }

    /// Whether the layer is a linear spring bed at `velocity`, `w3 = c p` (what
    /// [`LayerResponse::winkler_compliance`] finds on any grid): a linear law and
    /// nothing that creeps in the time a cell passes (infinite velocity, or a creep
    /// form of a glassy spring only). The contact problem is then symmetric and
    /// Polonsky–Keer conjugate gradients solve it.
    pub fn is_spring_bed(&self, velocity: f64) -> bool {
        let form = self.rheology.creep_form();
        matches!(self.law, ComplianceLaw::Linear)
            && (velocity == f64::INFINITY || (form.branches.is_empty() && form.flow.is_none()))
    }

    /// The linear layer the automatic window and the initial guesses assume: the
    /// relaxed compliance (the largest contact), creeping at the rate of the flow.
    pub fn estimate(&self) -> LayerEstimate {
        let form = self.rheology.creep_form();
        let compliance = form.relaxed();
        LayerEstimate {
            compliance,
            // c0 / T of the estimate is the flow's C_v / T (for the Maxwell layer
            // c0 = C_v, and the ratio is exactly 1).
            relaxation_time: form
                .flow
                .map_or(f64::INFINITY, |f| f.time * (compliance / f.compliance)),
        }
    }

    /// The compliance `C[0]` the law is evaluated with: a table's first compliance;
    /// else the rheology's own ([`rheology::RheologyModel::reference_compliance`]:
    /// the Maxwell or Kelvin–Voigt compliance, so that the paper's layer is computed
    /// exactly as eq. 8 writes it; 1 for presets whose parts carry their own).
    pub fn reference_compliance(&self) -> f64 {
        match &self.law {
            ComplianceLaw::Table(t) => t.compliances()[0],
            ComplianceLaw::Linear | ComplianceLaw::Sigmoid { .. } => {
                self.rheology.reference_compliance()
            }
        }
    }

    /// The compliance law at pressure p for the reference compliance (continued
    /// with `C[0]` below zero).
    pub fn law_at(&self, p: f64) -> LawValue {
        self.law.at(self.reference_compliance(), p)
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// The paper's sigmoid layer (C0 = 0.02, T = 1) for the layer modules' tests.
    pub(crate) fn sigmoid(delta: f64, p0: f64, integration: Integration) -> Layer {
        Layer::maxwell(0.02, 1.0, ComplianceLaw::Sigmoid { delta, p0 }, integration)
    }

    /// Composite Simpson quadrature of f on [a, b] with n (even) panels: an
    /// integrator independent of the closed forms it checks.
    pub(crate) fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
        let h = (b - a) / n as f64;
        let inner: f64 = (1..n)
            .map(|k| f(a + k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 })
            .sum();
        (f(a) + f(b) + inner) * h / 3.0
    }

    /// The rise with the terms `(a_m, l_m)`.
    fn rise_of(terms: &[(f64, f64)]) -> Rise {
        let mut rise = Rise::NONE;
        for (m, &(a, l)) in terms.iter().enumerate() {
            rise.amplitudes[m] = a;
            rise.lengths[m] = l;
        }
        rise
    }

    #[test]
    fn the_peak_behind_a_leading_edge_is_the_profiles_maximum() {
        // The profile L(s) rho(s) between the edge and the centre, sampled at a
        // million points: its maximum against `peak_behind`'s, for a pressure falling
        // away from the edge (centre 1.0, the downstream neighbour 0.6) and rising
        // (1.0 and 1.4), without a rise (the line's larger end), one exponential of
        // several lengths, and two (one of them negative, an overshoot).
        let rises: [&[(f64, f64)]; 6] = [
            &[],
            &[(1.0, 1e-4)],
            &[(1.0, 0.02)],
            &[(1.0, 0.4)],
            &[(0.7, 0.01), (0.3, 0.3)],
            &[(1.2, 0.05), (-0.2, 0.5)],
        ];
        for next in [0.6, 1.4] {
            for theta in [1e-3, 0.2, 0.5, 1.0] {
                for terms in rises {
                    let rise = rise_of(terms);
                    let edge = ContactEdge {
                        cell: 1,
                        neighbour: Some(0),
                        theta,
                        rise,
                    };
                    let p = [next, 1.0];
                    let profile = |s: f64| (1.0 + (next - 1.0) * (s - theta)) * rise.share(s);
                    let n = 1_000_000;
                    let (mut best, mut at) = (f64::NEG_INFINITY, 0.0);
                    for k in 0..=n {
                        let s = theta * k as f64 / n as f64;
                        if profile(s) > best {
                            (best, at) = (profile(s), s);
                        }
                    }
                    let (peak, s) = edge.peak_behind(&p);
                    // The sampled maximum lies below the true one by at most half
                    // the curvature times (theta / n)^2: about 2e-9 for the
                    // shortest rise (|f''| about 0.4 / l at the peak).
                    assert!(
                        peak >= best - 1e-12 && peak <= best + 1e-8,
                        "next {next}, theta {theta}, {terms:?}: {peak} at {s}, sampled {best} at {at}"
                    );
                    assert!((profile(s) - peak).abs() < 1e-15, "{terms:?}");
                    assert!((0.0..=theta).contains(&s));
                }
            }
        }
    }

    #[test]
    fn a_cells_mean_pressure_is_the_integral_of_its_rising_profile() {
        // The profile behind an edge theta cells from the centre: the line through
        // the centre value and the neighbour's (one cell downstream), times
        // 1 - sum_m a_m e^(-s / l_m), integrated over the loaded part by quadrature;
        // one exponential of several lengths and two (a branch's rise).
        let (centre, next) = (0.7, 1.3);
        let rises: [&[(f64, f64)]; 6] = [
            &[],
            &[(1.0, 1e-3)],
            &[(1.0, 0.04)],
            &[(1.0, 0.3)],
            &[(1.0, 0.9)],
            &[(0.7, 0.02), (0.3, 0.6)],
        ];
        for neighbour in [Some(0), None] {
            for theta in [1e-3, 0.05, 0.3, 0.5, 1.0] {
                for terms in rises {
                    let rise = rise_of(terms);
                    let edge = ContactEdge {
                        cell: 1,
                        neighbour,
                        theta,
                        rise,
                    };
                    let slope = if neighbour.is_some() {
                        next - centre
                    } else {
                        0.0
                    };
                    let profile = |s: f64| {
                        let line = centre + (s - theta) * slope;
                        line * (1.0 - terms.iter().map(|(a, l)| a * (-s / l).exp()).sum::<f64>())
                    };
                    let (a, b) = edge.mean_weights();
                    let mean = a * centre + b * next;
                    // Panels fine against the shortest length (the integrand's
                    // scale) over 40 of the longest.
                    let x = theta + 0.5;
                    let longest = terms.iter().map(|t| t.1).fold(0.0, f64::max);
                    let split = if longest > 0.0 {
                        (40.0 * longest).min(x)
                    } else {
                        x
                    };
                    let quadrature = simpson(profile, 0.0, split, 40_000)
                        + if split < x {
                            simpson(profile, split, x, 2_000)
                        } else {
                            0.0
                        };
                    assert!(
                        (mean - quadrature).abs() < 1e-10,
                        "theta {theta}, rise {terms:?}, {neighbour:?}: {mean} {quadrature}"
                    );
                    let share = profile(theta) / centre;
                    assert!(
                        (edge.centre_share() - share).abs() < 1e-14,
                        "{} {share}",
                        edge.centre_share()
                    );
                }
            }
        }
    }

    #[test]
    fn a_spring_bed_is_what_the_rows_find_symmetric() {
        let zener = Layer {
            rheology: Rheology::Zener {
                glassy_compliance: 0.01,
                compliance: 0.02,
                retardation_time: 0.5,
            },
            law: ComplianceLaw::Linear,
            integration: Integration::Exact,
        };
        let layers = [
            Layer::maxwell(0.02, 1.0, ComplianceLaw::Linear, Integration::Exact),
            sigmoid(0.5, 0.01, Integration::Exact),
            zener,
        ];
        for layer in &layers {
            for velocity in [1e-3, 1.0, 1e3, f64::INFINITY] {
                for cell in [1e-3, 0.05] {
                    let rows = ViscoelasticRows::new(layer.clone(), 8, 2, cell, velocity);
                    assert_eq!(
                        layer.is_spring_bed(velocity),
                        rows.winkler_compliance().is_some(),
                        "{layer:?} at V = {velocity}, h = {cell}"
                    );
                }
            }
        }
    }
}
