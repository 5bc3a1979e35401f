//! Compliance laws `C[p]` of a third-body layer: how its compliance depends on the
//! local pressure (paper eq. 1 for the constant law, eq. 11 for the sigmoid,
//! `C[p] = C0 (1 + delta - 2 delta / (1 + exp(-p/p0)))`, and a monotone table),
//! with the slope `dC/dp` and the exact integral `G(p) = int_0^p C[q] dq` that the
//! rheologies of [`super`] integrate along the material path. Pure functions of
//! one pressure; every rheology uses them through [`ComplianceLaw::at`].

use crate::error::{Error, Result};

/// Largest `delta` of the sigmoid law for which the creep rate `C[p] p` rises with p
/// at every pressure. With `x = p / p0` and `s` the logistic function,
/// `d(C p)/dp = C0 (1 + delta - 2 delta m(x))`, `m(x) = s(x) + x s(x) (1 - s(x))`,
/// whose maximum is m* = 1.0998393201 at x = 2.3994 (found numerically, bounded
/// Brent, to 1e-12); so the rate never falls iff `delta <= 1 / (2 m* - 1)`.
pub(crate) const SIGMOID_MONOTONE_DELTA: f64 = 0.833_556_559_6;

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

impl ComplianceLaw {
    /// The law at pressure p for the zero-pressure compliance `c0` (for a table,
    /// its first compliance). For p < 0 (which only solver iterates visit) the law is
    /// continued with the zero-pressure compliance.
    pub fn at(&self, c0: f64, p: f64) -> LawValue {
        if p <= 0.0 {
            return LawValue {
                compliance: c0,
                slope: 0.0,
                integral: c0 * p,
            };
        }
        match self {
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
}

#[cfg(test)]
mod monotone_tests {
    use super::*;

    /// `d(C p)/dp` by central differences of eq. 11 written out here, on 0 < p < 30 p0.
    fn lowest_creep_rate_slope(delta: f64) -> f64 {
        let c = |p: f64| 1.0 + delta - 2.0 * delta / (1.0 + (-p).exp());
        let e = 1e-6;
        (1..30_000)
            .map(|k| k as f64 * 1e-3)
            .map(|p| ((p + e) * c(p + e) - (p - e) * c(p - e)) / (2.0 * e))
            .fold(f64::INFINITY, f64::min)
    }

    #[test]
    fn the_sigmoid_creep_rate_rises_everywhere_exactly_up_to_the_stated_delta() {
        assert!(lowest_creep_rate_slope(SIGMOID_MONOTONE_DELTA - 1e-4) > 0.0);
        assert!(lowest_creep_rate_slope(SIGMOID_MONOTONE_DELTA + 1e-4) < 0.0);
        // The law's own slope agrees: d(C p)/dp = C + p dC/dp at the worst point.
        let law = ComplianceLaw::Sigmoid {
            delta: SIGMOID_MONOTONE_DELTA,
            p0: 1.0,
        };
        let v = law.at(1.0, 2.399_357);
        assert!((v.compliance + 2.399_357 * v.slope).abs() < 1e-9);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layer::tests::sigmoid;
    use crate::layer::Integration;

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
}
