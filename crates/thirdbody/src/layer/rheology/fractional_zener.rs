//! The fractional Zener layer, `C*(omega) = C_g + C1 / (1 + (i omega tau)^alpha)`
//! (the Cole–Cole form; Mainardi, *Fractional Calculus and Waves in Linear
//! Viscoelasticity*, Imperial College Press 2010, ch. 3), whose retarded part has
//! the creep compliance `C1 (1 - E_alpha(-(t/tau)^alpha))`, discretised into
//! Kelvin–Voigt branches from its closed-form retardation spectrum
//! ([`fractional_zener_branches`]). The number of branches follows from the order
//! ([`fractional_zener_branch_count`]): log-spaced in time at most
//! `min(1, pi (1 - alpha) / (2 alpha))` apart in ln(time) (`0.25 + 1.1 (1 - alpha)`
//! above alpha = 0.9), over the span holding all but 1e-4 of the spectrum, so that
//! the branches' complex compliance is within 0.5 % of the loss peak of the closed
//! form at every frequency and the loss has one maximum, as the closed form does.

use super::{
    require_non_negative, CreepForm, KeyKind, KeyReader, Preset, RetardationBranch, Rheology,
    RheologyModel, SolverUnits, MAX_BRANCHES,
};
use std::f64::consts::PI;

use crate::error::{require_positive, Error, Result};
use crate::provenance::{self, Reference};

pub(super) const PRESET: Preset = Preset {
    name: "fractional_zener",
    keys: &[
        ("glassy_compliance", KeyKind::Number),
        ("compliance", KeyKind::Number),
        ("retardation_time", KeyKind::Number),
        ("order", KeyKind::Number),
        ("branch_count", KeyKind::Count),
    ],
    compliance_from_table: false,
    parse: super::parse::<FractionalZener>,
};

/// C_g, C1, tau, alpha and the number of branches (`None`: the order's rule).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct FractionalZener {
    pub glassy_compliance: f64,
    pub compliance: f64,
    pub retardation_time: f64,
    pub order: f64,
    pub branch_count: Option<usize>,
}

impl From<FractionalZener> for Rheology {
    fn from(f: FractionalZener) -> Rheology {
        Rheology::FractionalZener {
            glassy_compliance: f.glassy_compliance,
            compliance: f.compliance,
            retardation_time: f.retardation_time,
            order: f.order,
            branch_count: f.branch_count,
        }
    }
}

impl RheologyModel for FractionalZener {
    fn from_keys(keys: &KeyReader) -> Result<Self> {
        Ok(FractionalZener {
            glassy_compliance: super::zener::glassy(keys)?,
            compliance: keys.need_number(
                "compliance",
                &keys.needs("the compliance C1 of its retarded part"),
            )?,
            retardation_time: keys
                .need_number("retardation_time", &keys.needs("its retardation time"))?,
            order: keys.need_number(
                "order",
                "a fractional_zener layer needs its order alpha (0 < alpha <= 1)",
            )?,
            branch_count: keys.count("branch_count"),
        })
    }

    fn name(&self) -> &'static str {
        PRESET.name
    }

    fn validate(&self) -> Result<()> {
        require_non_negative("layer.glassy_compliance", self.glassy_compliance)?;
        require_positive("layer.compliance", self.compliance)?;
        require_positive("layer.retardation_time", self.retardation_time)?;
        if !(self.order > 0.0 && self.order <= 1.0) {
            return Err(Error::invalid("layer.order", self.order, "0 < order <= 1"));
        }
        if let Some(n) = self
            .branch_count
            .filter(|n| !(2..=MAX_BRANCHES).contains(n))
        {
            return Err(Error::invalid(
                "layer.branch_count",
                n,
                &format!("an integer from 2 to {MAX_BRANCHES}"),
            ));
        }
        Ok(())
    }

    fn scaled(&self, units: &SolverUnits) -> Rheology {
        FractionalZener {
            glassy_compliance: units.compliance(self.glassy_compliance),
            compliance: units.compliance(self.compliance),
            retardation_time: units.time(self.retardation_time),
            ..*self
        }
        .into()
    }

    /// tau, the centre of the spectrum.
    fn time_scale(&self) -> f64 {
        self.retardation_time
    }

    fn reference_compliance(&self) -> f64 {
        1.0
    }

    fn creep_form(&self) -> CreepForm {
        CreepForm {
            glassy: self.glassy_compliance,
            branches: fractional_zener_branches(
                self.compliance,
                self.retardation_time,
                self.order,
                (self.branch_count).unwrap_or_else(|| fractional_zener_branch_count(self.order)),
            ),
            flow: None,
        }
    }

    fn references(&self) -> Vec<Reference> {
        vec![
            Reference::new(
                provenance::MAINARDI,
                "the fractional Zener body and its closed-form retardation spectrum",
            ),
            Reference::new(
                provenance::TREFETHEN_WEIDEMAN,
                "the fractional Zener spectrum discretised into branches (trapezoidal rule)",
            ),
        ]
    }
}

/// Orders above which the spectrum is too narrow for sampled densities: the
/// branches carry the exact mass of their bins.
const NARROW_ORDER: f64 = 0.9;

/// The spectrum's mass left out at each end of the span (it goes to the end
/// branches).
const TAIL: f64 = 0.5e-4;

/// Half the span of `v = ln(tau / tau_k)` that holds all but `2 TAIL` of the
/// spectrum: the mass above `v` is about `sin(alpha pi) e^(-alpha v) / (alpha pi)`,
/// and the same below `-v` by symmetry.
fn half_span(alpha: f64) -> f64 {
    let s = (alpha * PI).sin();
    ((s / (alpha * PI * TAIL)).ln() / alpha).max(1.0)
}

/// The rule's spacing of the branches in ln(time) for the order `alpha < 1`:
/// `min(1, pi (1 - alpha) / (2 alpha))` up to alpha = 0.9 (half the distance
/// of the spectrum's poles from the real axis), `0.25 + 1.1 (1 - alpha)` above.
pub fn fractional_zener_spacing(alpha: f64) -> f64 {
    if alpha <= NARROW_ORDER {
        (PI * (1.0 - alpha) / (2.0 * alpha)).min(1.0)
    } else {
        0.25 + 1.1 * (1.0 - alpha)
    }
}

/// The default number of branches for the order `alpha`: the span holding all
/// but 1e-4 of the spectrum divided by [`fractional_zener_spacing`], rounded up to
/// an odd number (one branch at `tau` itself), at most [`MAX_BRANCHES`]; 1 for
/// `alpha = 1` (the Zener body).
///
/// With these branches the complex compliance is within 0.5 % of the loss peak
/// `C1 tan(alpha pi / 4) / 2` of the closed form at every frequency (measured for
/// orders 0.05 to 0.995: at most 0.32 %, at alpha = 0.92; 0.005 % to 0.11 % for
/// orders 0.1 to 0.9, where the error is the tails' 1e-4 lumped into the end
/// branches), and the loss compliance has a single maximum (counting those above
/// 1 % of the peak) for orders from 0.07: 199 branches at alpha = 0.1, 99 at 0.2,
/// 39 at 0.5, 99 at 0.9, 49 at 0.95. Below an order of about 0.015 the rule would
/// need more than 1000 branches; they are then further apart.
pub fn fractional_zener_branch_count(alpha: f64) -> usize {
    if alpha >= 1.0 {
        return 1;
    }
    let n = (2.0 * half_span(alpha) / fractional_zener_spacing(alpha)).ceil() as usize;
    (n | 1).min(MAX_BRANCHES)
}

/// `n` Kelvin–Voigt branches of the fractional Zener body's retarded part,
/// `C1 (1 - E_alpha(-(t/tau)^alpha))`, `E_alpha` the Mittag-Leffler function.
///
/// Its retardation spectrum is known in closed form (Mainardi, *Fractional
/// Calculus and Waves in Linear Viscoelasticity*, Imperial College Press 2010,
/// eq. 3.32-3.33; Gorenflo, Kilbas, Mainardi & Rogosin, *Mittag-Leffler
/// Functions*, Springer 2014, §3.7): `E_alpha(-(t/tau)^alpha) = int_0^inf K(r)
/// exp(-r t / tau) dr` with `K(r) = sin(alpha pi) r^(alpha-1) / (pi (r^(2 alpha) +
/// 2 r^alpha cos(alpha pi) + 1))`. In `v = ln r` the density is `rho(v) = sin(alpha
/// pi) / (pi (2 cosh(alpha v) + 2 cos(alpha pi)))`, whose integral is
/// `atan((e^(alpha v) + cos(alpha pi)) / sin(alpha pi)) / (alpha pi)`. The v axis is
/// cut into `n` equal bins over the span that holds all but 1e-4 of the spectrum,
/// one branch of time `tau exp(-v_centre)` per bin (log-spaced, as Schapery-type
/// Prony fits place them: Park & Schapery 1999). The two end bins take the tails
/// with their exact mass. For `alpha <= 0.9` the other branches carry
/// `width rho(v_centre)` (the trapezoidal rule on the line, whose error falls as
/// `exp(-2 pi d / width)` for a density analytic in a strip of half-width `d`:
/// Trefethen & Weideman, SIAM Review 56 (2014) 385-458; here `d = min(pi (1 -
/// alpha) / alpha, pi / 2)` from the poles of `rho` and of the kernel `1 / (1 + i
/// omega tau e^-v)`), scaled to hold exactly the mass between the end bins; above,
/// where `rho` narrows to the Zener body's single time faster than such nodes can
/// follow, each carries its bin's exact mass (error of order `width^2`). So the
/// glassy and relaxed compliances are exact. `alpha = 1` is the Zener body: one
/// branch of time tau. [`fractional_zener_branch_count`] is the default `n`.
pub fn fractional_zener_branches(
    compliance: f64,
    tau: f64,
    alpha: f64,
    n: usize,
) -> Vec<RetardationBranch> {
    if alpha >= 1.0 {
        return vec![RetardationBranch {
            compliance,
            time: tau,
        }];
    }
    let (s, c) = (alpha * PI).sin_cos();
    // Cumulative mass below v, from 0 at -inf to 1 at +inf.
    let cumulative = |v: f64| {
        let x = (alpha * v).exp();
        (((x + c) / s).atan() - (c / s).atan()) / (alpha * PI)
    };
    let density = |v: f64| s / (PI * (2.0 * (alpha * v).cosh() + 2.0 * c));
    let half_span = half_span(alpha);
    let width = 2.0 * half_span / n as f64;
    let centre = |k: usize| -half_span + (k as f64 + 0.5) * width;
    let mass: Vec<f64> = if alpha > NARROW_ORDER {
        (0..n)
            .map(|k| {
                let lo = -half_span + k as f64 * width;
                let mass_lo = if k == 0 { 0.0 } else { cumulative(lo) };
                let mass_hi = if k + 1 == n {
                    1.0
                } else {
                    cumulative(lo + width)
                };
                mass_hi - mass_lo
            })
            .collect()
    } else {
        let (inner_lo, inner_hi) = (-half_span + width, half_span - width);
        let mut m: Vec<f64> = (0..n).map(|k| width * density(centre(k))).collect();
        m[0] = cumulative(inner_lo);
        m[n - 1] = 1.0 - cumulative(inner_hi);
        let inner: f64 = m[1..n - 1].iter().sum();
        if inner > 0.0 {
            let scale = (cumulative(inner_hi) - cumulative(inner_lo)) / inner;
            m[1..n - 1].iter_mut().for_each(|x| *x *= scale);
        }
        m
    };
    mass.iter()
        .enumerate()
        .map(|(k, m)| RetardationBranch {
            compliance: compliance * m,
            time: tau * (-centre(k)).exp(),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fractional_zener_matches_its_complex_compliance() {
        // Closed form C1 / (1 + (i omega tau)^alpha) against the branches, over the
        // decades the spectrum is resolved in.
        for (alpha, n, tol) in [(0.5, 40, 5e-3), (0.8, 30, 5e-3), (0.3, 60, 1e-2)] {
            let b = fractional_zener_branches(1.0, 2.0, alpha, n);
            let sum: f64 = b.iter().map(|x| x.compliance).sum();
            assert!((sum - 1.0).abs() < 1e-12, "relaxed compliance {sum}");
            let form = CreepForm {
                glassy: 0.0,
                branches: b,
                flow: None,
            };
            for e in -6..=6 {
                let wt: f64 = 10f64.powf(e as f64 * 0.5);
                let omega = wt / 2.0;
                let phase = alpha * std::f64::consts::FRAC_PI_2;
                let m = wt.powf(alpha);
                let (dr, di) = (1.0 + m * phase.cos(), m * phase.sin());
                let d2 = dr * dr + di * di;
                let (er, ei) = (dr / d2, -di / d2);
                let (cr, ci) = form.complex_compliance(omega);
                let err = ((cr - er).powi(2) + (ci - ei).powi(2)).sqrt();
                assert!(err < tol, "alpha {alpha}, omega tau {wt}: error {err}");
            }
        }
    }

    #[test]
    fn fractional_zener_of_order_one_is_the_zener_body() {
        let b = fractional_zener_branches(0.7, 3.0, 1.0, 20);
        assert_eq!(
            b,
            vec![RetardationBranch {
                compliance: 0.7,
                time: 3.0
            }]
        );
    }

    /// `1 / (1 + (i wt)^alpha)` as (real, imaginary), from `(i wt)^alpha = wt^alpha
    /// (cos(alpha pi / 2) + i sin(alpha pi / 2))`.
    fn closed_form(alpha: f64, wt: f64) -> (f64, f64) {
        let m = wt.powf(alpha);
        let (si, co) = (alpha * std::f64::consts::FRAC_PI_2).sin_cos();
        let (dr, di) = (1.0 + m * co, m * si);
        let d2 = dr * dr + di * di;
        (dr / d2, -di / d2)
    }

    /// The default branches' largest error in `C*` over the decades holding all
    /// but 1e-4 of the spectrum and a tenth more each side (40 frequencies a
    /// decade), and the loss compliance's maxima above 1 % of its peak there.
    fn default_branches(alpha: f64, n: usize) -> (f64, usize) {
        let tau = 2.0;
        let form = CreepForm {
            glassy: 0.0,
            branches: fractional_zener_branches(1.0, tau, alpha, n),
            flow: None,
        };
        assert!((form.relaxed() - 1.0).abs() < 1e-12);
        let half = 1.1 * (2e4 * (alpha * PI).sin() / (alpha * PI)).ln() / alpha;
        let steps = (half / std::f64::consts::LN_10 * 40.0) as i32;
        let mut worst = 0.0f64;
        let mut loss = Vec::new();
        for j in -steps..=steps {
            let wt = (half * j as f64 / steps as f64).exp();
            let (er, ei) = closed_form(alpha, wt);
            let (cr, ci) = form.complex_compliance(wt / tau);
            worst = worst.max((cr - er).hypot(ci - ei));
            loss.push(-ci);
        }
        let top = loss.iter().fold(0.0f64, |m, &x| m.max(x));
        let maxima = (1..loss.len() - 1)
            .filter(|&k| loss[k] > loss[k - 1] && loss[k] >= loss[k + 1] && loss[k] > 0.01 * top)
            .count();
        (worst, maxima)
    }

    #[test]
    fn the_orders_branches_match_the_closed_form_over_the_spectrum() {
        for alpha in [0.1, 0.2, 0.3, 0.5, 0.8, 0.95] {
            let n = fractional_zener_branch_count(alpha);
            let (worst, maxima) = default_branches(alpha, n);
            let peak = (alpha * PI / 4.0).tan() / 2.0;
            eprintln!(
                "alpha {alpha}: {n} branches, largest error {:.2e} of the loss peak, {maxima} \
                 loss maxima",
                worst / peak
            );
            assert!(worst < 5e-3 * peak, "alpha {alpha}: {worst:e}");
            assert_eq!(maxima, 1, "alpha {alpha}");
            assert_eq!(n % 2, 1);
        }
        // The former fixed 24 branches: 2 decades apart at alpha = 0.2, a rippled loss.
        let (worst, maxima) = default_branches(0.2, 24);
        eprintln!(
            "alpha 0.2, 24 branches: largest error {:.2e} of the loss peak, {maxima} loss \
             maxima",
            worst / ((0.2 * PI / 4.0).tan() / 2.0)
        );
        assert!(
            worst > 5e-2 * (0.2 * PI / 4.0).tan() / 2.0 && maxima > 1,
            "{worst} {maxima}"
        );
        assert_eq!(fractional_zener_branch_count(1.0), 1);
    }
}
