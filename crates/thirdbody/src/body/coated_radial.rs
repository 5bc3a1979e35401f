//! The radial part of the coated-body kernel: the cumulative "mass"
//! `M_D(R) = int_0^R g_D(r) r dr` of the point response `g_D` that must be added
//! to the substrate's Boussinesq response to get the coated body's
//! (see the derivation in [`super::coated`]). In units of `C h / (2 pi)`, with
//! `C = 2 (1 - nu1^2) / E1`, `s = R / h`, `f(t) = A(t) - 1`, `f0 = f(0)`:
//! `mu(s) = s int_0^inf (f(t) - f0) J1(s t) / t dt`, and `M_D(R) = C h mu(R/h) / (2 pi)`.
//!
//! Evaluation:
//! - small and moderate s: the Hankel-type integral, made absolutely convergent by
//!   the exact transform `int_0^inf e^{-c t} J1(s t) / t dt = (sqrt(c^2 + s^2) - c) / s`
//!   (Gradshteyn & Ryzhik 6.611.1):
//!   `mu(s) = f0 (c^2 / (sqrt(c^2 + s^2) + s) - c) + s int_0^T (f(t) - f0 e^{-c t}) J1(s t) / t dt`,
//!   composite Gauss–Legendre with panels shorter than half a period of J1 and than
//!   the scale of f near t = 0 (the radius of convergence of its Taylor series);
//! - large s: the asymptotic series from the Taylor coefficients f_n of f at t = 0,
//!   `mu(s) ~ f1 + sum_{k>=1} c_{2k} f_{2k} s^{1-2k}`, `c_n = int_0^inf x^{n-1} J1(x) dx
//!   = 2^{n-1} Gamma((n+1)/2) / Gamma((3-n)/2)` (G&R 6.561.14, continued analytically;
//!   it vanishes for odd n >= 3): c_2 = 1, c_{2k+2} = -(2k-1)(2k+1) c_{2k}. It is
//!   used only where its terms fall below 1e-16 of the scale before they grow;
//!   beyond all orders its error is `O(exp(-rho s))`, rho the radius of convergence.
//!
//! The function is tabulated once per case on Chebyshev panels in `ln s`.

use rayon::prelude::*;

use super::coated::TransferFactor;
use super::quadrature::{ChebyshevPanels, GaussLegendre};

/// Decay rate of the exponential used to make the Hankel integral converge.
const SUBTRACTION_RATE: f64 = 2.0;
/// Upper limit of the t integral: f(t) ~ 4 b t^2 e^{-2t} < 1e-17 beyond it.
const T_MAX: f64 = 24.0;
/// Taylor coefficients kept for the asymptotic series.
const TAYLOR_ORDER: usize = 90;
/// Width of a Chebyshev panel in ln s, and its degree.
const PANEL_WIDTH: f64 = 0.5;
const PANEL_DEGREE: usize = 20;
/// Gauss–Legendre nodes per panel of the t integral.
const T_NODES: usize = 10;
/// Largest s for which the Hankel integral is evaluated directly (its cost grows
/// like s: about 3000 s evaluations of J1 for the whole table).
pub const MAX_DIRECT_S: f64 = 1e4;

/// `mu(s)` on a range of s, ready for fast evaluation.
#[derive(Debug, Clone)]
pub struct RadialRemainder {
    f0: f64,
    taylor: Vec<f64>,
    /// Radius of convergence of the Taylor series of f (estimate).
    radius: f64,
    /// Above this s the asymptotic series is used.
    s_switch: f64,
    /// Chebyshev table in ln s below `s_switch` (None when not needed).
    table: Option<ChebyshevPanels>,
    /// f is identically zero (same material in coating and substrate).
    zero: bool,
    rule: GaussLegendre,
}

impl RadialRemainder {
    /// Prepares `mu(s)` for `s_lo <= s <= s_hi` (0 < s_lo < s_hi). Fails when the
    /// table would need the direct integral beyond [`MAX_DIRECT_S`] (very stiff,
    /// very thin coatings under a wide window), returning the s it would need.
    pub fn new(factor: &TransferFactor, s_lo: f64, s_hi: f64) -> Result<Self, f64> {
        let taylor = factor.taylor_coefficients(TAYLOR_ORDER);
        let zero = taylor.iter().all(|&c| c == 0.0);
        let radius = convergence_radius(&taylor);
        let mut this = RadialRemainder {
            f0: taylor[0],
            taylor,
            radius,
            s_switch: f64::INFINITY,
            table: None,
            zero,
            rule: GaussLegendre::new(T_NODES),
        };
        if zero {
            return Ok(this);
        }
        this.s_switch = this.find_switch(s_hi);
        let top = this.s_switch.min(s_hi);
        if top > MAX_DIRECT_S {
            return Err(top);
        }
        if s_lo < top {
            let (lo, hi) = (s_lo.ln() - 1e-9, top.ln() + 1e-9);
            let panels = ((hi - lo) / PANEL_WIDTH).ceil().max(1.0) as usize;
            let points = ChebyshevPanels::points(lo, hi, panels, PANEL_DEGREE);
            let values: Vec<f64> = points
                .par_iter()
                .map(|&x| this.mu_direct(factor, x.exp()))
                .collect();
            this.table = Some(ChebyshevPanels::from_values(
                lo,
                hi,
                panels,
                PANEL_DEGREE,
                &values,
            ));
        }
        Ok(this)
    }

    /// The s above which the asymptotic series is used.
    #[cfg(test)]
    pub fn switch_point(&self) -> f64 {
        self.s_switch
    }

    /// `mu(s)` (table or asymptotic series).
    pub fn mu(&self, s: f64) -> f64 {
        if self.zero {
            return 0.0;
        }
        if s > self.s_switch {
            if let Some(v) = self.mu_asymptotic(s) {
                return v;
            }
        }
        match &self.table {
            Some(t) => t.eval(s.ln()),
            None => self.mu_asymptotic(s).unwrap_or(f64::NAN),
        }
    }

    /// The smallest s (on a geometric ladder) from which the asymptotic series
    /// converges to 1e-16 of the scale, times a safety factor; infinity if not
    /// below `s_hi`.
    fn find_switch(&self, s_hi: f64) -> f64 {
        let mut s = 4.0 / self.radius;
        while s <= s_hi {
            if self.mu_asymptotic(s).is_some() {
                return 1.25 * s;
            }
            s *= 1.2;
        }
        f64::INFINITY
    }

    /// The asymptotic series, or None where it does not reach 1e-16 of the scale.
    pub fn mu_asymptotic(&self, s: f64) -> Option<f64> {
        let f = &self.taylor;
        let tolerance = 1e-16 * (f[0].abs() + f[1].abs());
        let mut sum = f[1];
        // r = c_{2k} s^{1-2k}
        let mut r = 1.0 / s;
        let mut previous = f64::INFINITY;
        let mut k = 1;
        while 2 * k < f.len() {
            let term = r * f[2 * k];
            if !term.is_finite() {
                return None;
            }
            if term.abs() < tolerance {
                return Some(sum + term);
            }
            if term.abs() > previous {
                return None;
            }
            sum += term;
            previous = term.abs();
            let m = 2.0 * k as f64;
            r *= -(m - 1.0) * (m + 1.0) / (s * s);
            k += 1;
        }
        None
    }

    /// `mu(s)` from the Hankel integral (any s > 0; cost grows like s).
    pub fn mu_direct(&self, factor: &TransferFactor, s: f64) -> f64 {
        if self.zero {
            return 0.0;
        }
        let c = SUBTRACTION_RATE;
        let f0 = self.f0;
        let near_zero = (0.5 * self.radius).clamp(1e-5, 0.5);
        let mut integral = 0.0;
        let mut t = 0.0;
        while t < T_MAX {
            let width = (std::f64::consts::PI / s)
                .min(near_zero + 0.25 * t)
                .min(0.5);
            let end = (t + width).min(T_MAX);
            integral += self.rule.integrate(t, end, |x| {
                let d = factor.excess(x) - f0 * (-c * x).exp();
                d * libm::j1(s * x) / x
            });
            t = end;
        }
        f0 * (c * c / ((c * c + s * s).sqrt() + s) - c) + s * integral
    }
}

/// Radius of convergence of a power series from its coefficients (root test on
/// the upper half), clamped to [1e-6, 2].
fn convergence_radius(c: &[f64]) -> f64 {
    let mut radius = f64::INFINITY;
    for (n, &cn) in c.iter().enumerate().skip(c.len() / 3) {
        if cn != 0.0 && cn.is_finite() {
            radius = radius.min(cn.abs().powf(-1.0 / n as f64));
        }
    }
    radius.clamp(1e-6, 2.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::case::Elastic;

    fn factor(ratio: f64) -> TransferFactor {
        TransferFactor::new(
            Elastic {
                young: ratio,
                poisson: 0.3,
            },
            Elastic {
                young: 1.0,
                poisson: 0.25,
            },
        )
    }

    #[test]
    fn asymptotic_series_matches_the_integral_past_the_switch() {
        for ratio in [10.0, 3.0, 0.1] {
            let f = factor(ratio);
            let r = RadialRemainder::new(&f, 0.01, 1e5).unwrap();
            let s0 = r.switch_point();
            assert!(s0.is_finite() && s0 < 2e3, "{ratio}: switch {s0}");
            for s in [s0, 1.5 * s0] {
                let direct = r.mu_direct(&f, s);
                let series = r.mu_asymptotic(s).unwrap();
                assert!(
                    (direct - series).abs() < 1e-11 * (1.0 + series.abs()),
                    "E1/E2 = {ratio}, s = {s}: {direct} vs {series}"
                );
            }
        }
    }

    #[test]
    fn table_matches_direct_evaluation_between_nodes() {
        for ratio in [10.0, 0.1] {
            let f = factor(ratio);
            let r = RadialRemainder::new(&f, 0.02, 300.0).unwrap();
            for k in 0..60 {
                let s = 0.02 * (1.1f64).powf(k as f64 + 0.37);
                if s > 300.0 {
                    break;
                }
                let (a, b) = (r.mu(s), r.mu_direct(&f, s));
                assert!(
                    (a - b).abs() < 1e-11 * (1.0 + b.abs()),
                    "{ratio} {s}: {a} {b}"
                );
            }
        }
    }

    #[test]
    fn small_s_behaves_like_minus_f0_s() {
        // M_D(R) -> -(f0) R C / 2 pi near the load: the coating's own 1/r response
        // replaces the substrate's there.
        let f = factor(3.0);
        let r = RadialRemainder::new(&f, 1e-4, 10.0).unwrap();
        let s = 1e-4;
        let f0 = f.excess(0.0);
        assert!(((r.mu(s) + f0 * s) / (f0 * s)).abs() < 1e-3);
    }
}
