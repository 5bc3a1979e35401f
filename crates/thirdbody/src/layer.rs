//! The third-body layer: a nonlinear Maxwell spring bed (paper eq. 2,
//! `dw3/dt = C[p] (p/T + dp/dt)`) integrated along the material path in the
//! steady sliding frame (design.md §1). Material enters the window at its largest x
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

use crate::error::{require_positive, Error, Result};

/// How the compliance depends on the local pressure.
#[derive(Debug, Clone, PartialEq)]
pub enum ComplianceLaw {
    /// Constant compliance C0 (paper eq. 1).
    Linear,
    /// Paper eq. 11: `C[p] = C0 (1 + delta - 2 delta / (1 + exp(-p / p0)))`.
    Sigmoid {
        /// Relative drop of compliance at infinite pressure, 0 <= delta <= 1.
        delta: f64,
        /// Pressure scale of the drop, > 0.
        p0: f64,
    },
    /// Compliance given at pressures, interpolated monotonically (Fritsch–Carlson
    /// piecewise cubic Hermite), constant beyond the last pressure. The first
    /// pressure is 0 and its compliance is C0.
    Table(Table),
}

/// Tabulated compliance for [`ComplianceLaw::Table`].
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    pressures: Vec<f64>,
    compliances: Vec<f64>,
    slopes: Vec<f64>,
    /// `G` at each knot.
    integrals: Vec<f64>,
}

impl Table {
    /// Builds the monotone interpolant; checks the table.
    pub fn new(pressures: Vec<f64>, compliances: Vec<f64>) -> Result<Self> {
        let n = pressures.len();
        if n < 2 || compliances.len() != n {
            return Err(Error::invalid(
                "layer.compliances",
                format!("{} values for {} pressures", compliances.len(), n),
                "as many compliances as pressures, at least 2",
            ));
        }
        if pressures[0] != 0.0 {
            return Err(Error::invalid(
                "layer.pressures[0]",
                pressures[0],
                "the table starts at pressure 0",
            ));
        }
        for k in 1..n {
            if !(pressures[k].is_finite() && pressures[k] > pressures[k - 1]) {
                return Err(Error::invalid(
                    &format!("layer.pressures[{k}]"),
                    pressures[k],
                    "finite pressures in strictly increasing order",
                ));
            }
        }
        for (k, &c) in compliances.iter().enumerate() {
            if !(c.is_finite() && c >= 0.0) {
                return Err(Error::invalid(
                    &format!("layer.compliances[{k}]"),
                    c,
                    "a finite compliance >= 0",
                ));
            }
        }
        if compliances[0] <= 0.0 {
            return Err(Error::invalid(
                "layer.compliances[0]",
                compliances[0],
                "a compliance > 0 at zero pressure",
            ));
        }
        let slopes = fritsch_carlson_slopes(&pressures, &compliances);
        let mut integrals = vec![0.0; n];
        for k in 1..n {
            let dx = pressures[k] - pressures[k - 1];
            // Exact integral of the cubic Hermite segment.
            integrals[k] = integrals[k - 1]
                + dx * (compliances[k - 1] + compliances[k]) / 2.0
                + dx * dx * (slopes[k - 1] - slopes[k]) / 12.0;
        }
        Ok(Table {
            pressures,
            compliances,
            slopes,
            integrals,
        })
    }

    /// Tabulated pressures.
    pub fn pressures(&self) -> &[f64] {
        &self.pressures
    }

    /// Tabulated compliances.
    pub fn compliances(&self) -> &[f64] {
        &self.compliances
    }

    /// Value, derivative and integral from 0 of the interpolant at p >= 0.
    fn eval(&self, p: f64) -> (f64, f64, f64) {
        let n = self.pressures.len();
        let last = n - 1;
        if p >= self.pressures[last] {
            let c = self.compliances[last];
            return (
                c,
                0.0,
                self.integrals[last] + c * (p - self.pressures[last]),
            );
        }
        let k = self.pressures.partition_point(|&q| q <= p).max(1) - 1;
        let (x0, x1) = (self.pressures[k], self.pressures[k + 1]);
        let dx = x1 - x0;
        let t = (p - x0) / dx;
        let (y0, y1, m0, m1) = (
            self.compliances[k],
            self.compliances[k + 1],
            self.slopes[k],
            self.slopes[k + 1],
        );
        let (t2, t3) = (t * t, t * t * t);
        let h00 = 2.0 * t3 - 3.0 * t2 + 1.0;
        let h10 = t3 - 2.0 * t2 + t;
        let h01 = -2.0 * t3 + 3.0 * t2;
        let h11 = t3 - t2;
        let value = h00 * y0 + h10 * dx * m0 + h01 * y1 + h11 * dx * m1;
        let d = ((6.0 * t2 - 6.0 * t) * y0
            + (3.0 * t2 - 4.0 * t + 1.0) * dx * m0
            + (-6.0 * t2 + 6.0 * t) * y1
            + (3.0 * t2 - 2.0 * t) * dx * m1)
            / dx;
        // Integrals of the Hermite basis from 0 to t.
        let t4 = t2 * t2;
        let i00 = t4 / 2.0 - t3 + t;
        let i10 = t4 / 4.0 - 2.0 * t3 / 3.0 + t2 / 2.0;
        let i01 = -t4 / 2.0 + t3;
        let i11 = t4 / 4.0 - t3 / 3.0;
        let integral =
            self.integrals[k] + dx * (i00 * y0 + i10 * dx * m0 + i01 * y1 + i11 * dx * m1);
        (value, d, integral)
    }
}

/// Fritsch–Carlson slopes: a piecewise cubic Hermite interpolant that is monotone
/// wherever the data are (Fritsch & Carlson, SIAM J. Numer. Anal. 17, 1980).
fn fritsch_carlson_slopes(x: &[f64], y: &[f64]) -> Vec<f64> {
    let n = x.len();
    let secant: Vec<f64> = (0..n - 1)
        .map(|k| (y[k + 1] - y[k]) / (x[k + 1] - x[k]))
        .collect();
    let mut m = vec![0.0; n];
    m[0] = secant[0];
    m[n - 1] = secant[n - 2];
    for k in 1..n - 1 {
        m[k] = if secant[k - 1] * secant[k] <= 0.0 {
            0.0
        } else {
            (secant[k - 1] + secant[k]) / 2.0
        };
    }
    for k in 0..n - 1 {
        if secant[k] == 0.0 {
            m[k] = 0.0;
            m[k + 1] = 0.0;
            continue;
        }
        let a = m[k] / secant[k];
        let b = m[k + 1] / secant[k];
        let s = a * a + b * b;
        if s > 9.0 {
            let tau = 3.0 / s.sqrt();
            m[k] = tau * a * secant[k];
            m[k + 1] = tau * b * secant[k];
        }
    }
    m
}

/// How eq. 2 is integrated over a cell (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Integration {
    /// Exact integration: the instantaneous part is `G(p)`.
    #[default]
    Exact,
    /// The paper's eq. 8 with the loaded cell's secant compliance: `C[p] p`.
    Secant,
}

/// A viscoelastic third-body layer.
#[derive(Debug, Clone, PartialEq)]
pub struct Layer {
    /// Compliance at zero pressure, C0 (displacement per pressure).
    pub compliance: f64,
    /// Relaxation time T.
    pub relaxation_time: f64,
    /// Pressure dependence of the compliance.
    pub law: ComplianceLaw,
    /// Integration of eq. 2 over a cell.
    pub integration: Integration,
}

/// Compliance law evaluated at one pressure.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LawValue {
    /// `C[p]`.
    pub compliance: f64,
    /// `dC/dp`.
    pub slope: f64,
    /// `G(p) = int_0^p C`.
    pub integral: f64,
}

/// `ln(1 + e^x)` without overflow.
fn softplus(x: f64) -> f64 {
    x.max(0.0) + (-x.abs()).exp().ln_1p()
}

/// `1 / (1 + e^-x)` without overflow.
fn logistic(x: f64) -> f64 {
    if x >= 0.0 {
        1.0 / (1.0 + (-x).exp())
    } else {
        let e = x.exp();
        e / (1.0 + e)
    }
}

impl Layer {
    pub(crate) fn validate(&self) -> Result<()> {
        if !matches!(self.law, ComplianceLaw::Table(_)) {
            require_positive("layer.compliance", self.compliance)?;
        }
        require_positive("layer.relaxation_time", self.relaxation_time)?;
        if let ComplianceLaw::Sigmoid { delta, p0 } = self.law {
            if !(0.0..=1.0).contains(&delta) {
                return Err(Error::invalid("layer.delta", delta, "0 <= delta <= 1"));
            }
            require_positive("layer.p0", p0)?;
        }
        Ok(())
    }

    /// Compliance at zero pressure.
    pub fn zero_pressure_compliance(&self) -> f64 {
        match &self.law {
            ComplianceLaw::Table(t) => t.compliances[0],
            _ => self.compliance,
        }
    }

    /// The compliance law at pressure p. For p < 0 (which only solver iterates
    /// visit) the law is continued with the zero-pressure compliance.
    pub fn law_at(&self, p: f64) -> LawValue {
        let c0 = self.zero_pressure_compliance();
        if p <= 0.0 {
            return LawValue {
                compliance: c0,
                slope: 0.0,
                integral: c0 * p,
            };
        }
        match &self.law {
            ComplianceLaw::Linear => LawValue {
                compliance: c0,
                slope: 0.0,
                integral: c0 * p,
            },
            &ComplianceLaw::Sigmoid { delta, p0 } => {
                let x = p / p0;
                let s = logistic(x);
                LawValue {
                    compliance: c0 * (1.0 + delta - 2.0 * delta * s),
                    slope: -2.0 * delta * c0 / p0 * s * (1.0 - s),
                    integral: c0
                        * ((1.0 + delta) * p
                            - 2.0 * delta * p0 * (softplus(x) - std::f64::consts::LN_2)),
                }
            }
            ComplianceLaw::Table(t) => {
                let (c, d, g) = t.eval(p);
                LawValue {
                    compliance: c,
                    slope: d,
                    integral: g,
                }
            }
        }
    }

    /// Instantaneous displacement of a cell and its derivative: `G(p)` (exact) or
    /// `C[p] p` (secant).
    pub fn instantaneous(&self, p: f64) -> (f64, f64) {
        let l = self.law_at(p);
        match self.integration {
            Integration::Exact => (l.integral, l.compliance),
            Integration::Secant => (l.compliance * p, l.compliance + l.slope * p.max(0.0)),
        }
    }

    /// Creep rate density `C[p] p` and its derivative.
    pub fn creep(&self, p: f64) -> (f64, f64) {
        let l = self.law_at(p);
        (l.compliance * p, l.compliance + l.slope * p.max(0.0))
    }
}

/// The layer on a grid row-set: the Maxwell row sweep and its linearisation.
#[derive(Debug, Clone)]
pub struct LayerOperator {
    layer: Layer,
    nx: usize,
    ny: usize,
    /// `h / (V T)`: creep per cell of path, 0 for an infinite velocity.
    creep_per_cell: f64,
}

impl LayerOperator {
    /// The layer on rows of `nx` cells of side `cell`, sliding at `velocity`.
    pub fn new(layer: Layer, nx: usize, ny: usize, cell: f64, velocity: f64) -> Self {
        let creep_per_cell = if velocity.is_infinite() {
            0.0
        } else {
            cell / (velocity * layer.relaxation_time)
        };
        LayerOperator {
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
    pub fn linearise(&self, p: &[f64]) -> LayerJacobian {
        let mut diagonal = vec![0.0; p.len()];
        let mut creep_slope = vec![0.0; p.len()];
        for (k, &pk) in p.iter().enumerate() {
            let (_, d_inst) = self.layer.instantaneous(pk);
            let (_, d_creep) = self.layer.creep(pk);
            creep_slope[k] = self.creep_per_cell * d_creep;
            diagonal[k] = d_inst + 0.5 * creep_slope[k];
        }
        LayerJacobian {
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
pub struct LayerJacobian {
    nx: usize,
    /// `d(instantaneous)/dp + (h / 2VT) d(Cp)/dp`.
    pub diagonal: Vec<f64>,
    /// `(h / VT) d(Cp)/dp`.
    pub creep_slope: Vec<f64>,
}

impl LayerJacobian {
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

#[cfg(test)]
mod tests {
    use super::*;

    fn sigmoid(delta: f64, p0: f64, integration: Integration) -> Layer {
        Layer {
            compliance: 0.02,
            relaxation_time: 1.0,
            law: ComplianceLaw::Sigmoid { delta, p0 },
            integration,
        }
    }

    /// Composite Simpson rule, an independent check of the closed-form G.
    fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
        let h = (b - a) / n as f64;
        let mut s = f(a) + f(b);
        for k in 1..n {
            s += f(a + k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 };
        }
        s * h / 3.0
    }

    #[test]
    fn sigmoid_integral_matches_quadrature_and_is_overflow_safe() {
        let l = sigmoid(0.7, 0.005, Integration::Exact);
        for &p in &[1e-6, 0.001, 0.005, 0.03, 0.2] {
            let q = simpson(|s| l.law_at(s).compliance, 0.0, p, 20_000);
            let g = l.law_at(p).integral;
            assert!(
                (g - q).abs() <= 1e-10 * q.abs().max(1e-12),
                "p={p}: {g} vs {q}"
            );
        }
        // p / p0 = 1e6: G = C0 ((1 + d) p - 2 d p0 (p/p0 - ln 2)) to rounding.
        let p = 0.005 * 1e6;
        let v = l.law_at(p);
        assert!(v.integral.is_finite() && v.compliance.is_finite() && v.slope.is_finite());
        let expect = 0.02 * ((1.7) * p - 1.4 * 0.005 * (1e6 - std::f64::consts::LN_2));
        assert!((v.integral - expect).abs() < 1e-9 * expect);
        assert!((v.compliance - 0.02 * 0.3).abs() < 1e-15);
    }

    #[test]
    fn sigmoid_limits() {
        let l = sigmoid(0.5, 0.01, Integration::Exact);
        assert_eq!(l.law_at(0.0).compliance, 0.02);
        assert!((l.law_at(1e3).compliance - 0.01).abs() < 1e-15);
        // Slope against a centred difference.
        let (p, e) = (0.013, 1e-7);
        let fd = (l.law_at(p + e).compliance - l.law_at(p - e).compliance) / (2.0 * e);
        assert!((l.law_at(p).slope - fd).abs() < 1e-6 * fd.abs());
    }

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
    fn table_is_monotone_and_integrates_exactly() {
        let t = Table::new(vec![0.0, 1.0, 2.0, 4.0], vec![1.0, 0.9, 0.3, 0.2]).unwrap();
        let mut last = f64::INFINITY;
        for k in 0..=400 {
            let p = k as f64 * 0.01;
            let (c, _, g) = t.eval(p);
            assert!(c <= last + 1e-15, "not monotone at {p}");
            last = c;
            let q = simpson(|s| t.eval(s).0, 0.0, p, 2000);
            assert!((g - q).abs() < 1e-9, "integral at {p}: {g} vs {q}");
        }
        // Beyond the table the compliance is constant, so G grows linearly.
        let g4 = t.eval(4.0).2;
        assert!((t.eval(7.5).2 - (g4 + 0.2 * 3.5)).abs() < 1e-14);
        // Knots are reproduced; beyond the table the last value holds.
        assert_eq!(t.eval(2.0).0, 0.3);
        assert_eq!(t.eval(10.0).0, 0.2);
    }

    #[test]
    fn table_errors_name_the_field() {
        let e = Table::new(vec![0.0, 2.0, 1.0], vec![1.0, 1.0, 1.0]).unwrap_err();
        assert!(e.to_string().contains("layer.pressures[2]"), "{e}");
        let e = Table::new(vec![0.1, 2.0], vec![1.0, 1.0]).unwrap_err();
        assert!(e.to_string().contains("layer.pressures[0]"), "{e}");
    }

    #[test]
    fn row_sweep_matches_the_explicit_sum() {
        // Explicit double loop over the definition in the module docs.
        let op = LayerOperator::new(sigmoid(0.5, 0.002, Integration::Exact), 5, 2, 0.1, 0.05);
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
            let op = LayerOperator::new(sigmoid(0.8, 0.002, integration), 6, 2, 0.1, 0.03);
            let p: Vec<f64> = (0..12).map(|k| 0.0007 * (1 + (k * 5) % 7) as f64).collect();
            let jac = op.linearise(&p);
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
