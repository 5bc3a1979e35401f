//! The fractional Zener layer, `C*(omega) = C_g + C1 / (1 + (i omega tau)^alpha)`
//! (the Cole–Cole form; Mainardi, *Fractional Calculus and Waves in Linear
//! Viscoelasticity*, Imperial College Press 2010, ch. 3), whose retarded part has
//! the creep compliance `C1 (1 - E_alpha(-(t/tau)^alpha))`, discretised into
//! Kelvin–Voigt branches from its closed-form retardation spectrum
//! ([`fractional_zener_branches`]).

use super::{
    require_non_negative, CreepForm, KeyKind, KeyReader, Preset, RetardationBranch, Rheology,
    RheologyModel, SolverUnits, MAX_BRANCHES,
};
use crate::error::{require_positive, Error, Result};

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

/// Default number of branches.
const DEFAULT_BRANCHES: usize = 24;

/// C_g, C1, tau, alpha and the number of branches.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct FractionalZener {
    pub glassy_compliance: f64,
    pub compliance: f64,
    pub retardation_time: f64,
    pub order: f64,
    pub branch_count: usize,
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
            branch_count: keys.count("branch_count").unwrap_or(DEFAULT_BRANCHES),
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
        if !(2..=MAX_BRANCHES).contains(&self.branch_count) {
            return Err(Error::invalid(
                "layer.branch_count",
                self.branch_count,
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
                self.branch_count,
            ),
            flow: None,
        }
    }
}

/// Kelvin–Voigt branches of the fractional Zener body's retarded part,
/// `C1 (1 - E_alpha(-(t/tau)^alpha))`, `E_alpha` the Mittag-Leffler function.
///
/// Its retardation spectrum is known in closed form (Mainardi, *Fractional
/// Calculus and Waves in Linear Viscoelasticity*, Imperial College Press 2010,
/// eq. 3.32-3.33; Gorenflo, Kilbas, Mainardi & Rogosin, *Mittag-Leffler
/// Functions*, Springer 2014, §3.7): `E_alpha(-(t/tau)^alpha) = int_0^inf K(r)
/// exp(-r t / tau) dr` with `K(r) = sin(alpha pi) r^(alpha-1) / (pi (r^(2 alpha) +
/// 2 r^alpha cos(alpha pi) + 1))`. In `v = ln r` the density is `sin(alpha pi) /
/// (pi (2 cosh(alpha v) + 2 cos(alpha pi)))`, whose integral is
/// `atan((e^(alpha v) + cos(alpha pi)) / sin(alpha pi)) / (alpha pi)`. The v axis is
/// cut into `n` equal bins over the span that holds all but 1e-4 of the spectrum
/// (the two end bins take the tails); each bin is one branch of time
/// `tau exp(-v_centre)` with the spectrum's exact mass in the bin, so the glassy
/// and relaxed compliances are exact and the branches are `n / span` per unit of
/// ln(time) — the log-spaced collocation of Schapery-type Prony fits (Park &
/// Schapery 1999). `alpha = 1` is the Zener body: one branch of time tau.
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
    let (s, c) = (alpha * std::f64::consts::PI).sin_cos();
    // Cumulative mass below v, from 0 at -inf to 1 at +inf.
    let cumulative = |v: f64| {
        let x = (alpha * v).exp();
        (((x + c) / s).atan() - (c / s).atan()) / (alpha * std::f64::consts::PI)
    };
    // Tails: mass above v is about s e^(-alpha v) / (alpha pi) (and the same below
    // -v by symmetry); keep all but 1e-4 in total.
    let tail = 0.5e-4;
    let half_span = ((s / (alpha * std::f64::consts::PI * tail)).ln() / alpha).max(1.0);
    let width = 2.0 * half_span / n as f64;
    (0..n)
        .map(|k| {
            let lo = -half_span + k as f64 * width;
            let hi = lo + width;
            let mass_lo = if k == 0 { 0.0 } else { cumulative(lo) };
            let mass_hi = if k + 1 == n { 1.0 } else { cumulative(hi) };
            RetardationBranch {
                compliance: compliance * (mass_hi - mass_lo),
                time: tau * (-(0.5 * (lo + hi))).exp(),
            }
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
}
