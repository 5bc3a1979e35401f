//! A layer with a box retardation spectrum: a glassy spring and a continuum of
//! Kelvin–Voigt branches whose compliance `C1` is spread evenly over ln(time)
//! between the retardation times `tau1` and `tau2`, `L(ln tau) = C1 / ln(tau2 /
//! tau1)` (Tobolsky's box distribution: A. V. Tobolsky, *Properties and Structure of
//! Polymers*, Wiley 1960, ch. 3). With `Lambda = ln(tau2 / tau1)` its complex
//! compliance is `C*(omega) = C_g + C1 (1 - ln((1 + i omega tau2) / (1 + i omega
//! tau1)) / Lambda)` and its creep compliance `C(t) = C_g + C1 (1 - (E1(t / tau2) -
//! E1(t / tau1)) / Lambda)` (Tschoegl, *The Phenomenological Theory of Linear
//! Viscoelastic Behavior*, Springer 1989, eq. 3.4-10 and 4.1-10 with this `L`). It is
//! discretised into equal bins of ln(time), one branch of the bin's compliance at
//! each bin's centre ([`box_spectrum_branches`]).

use super::{
    require_non_negative, CreepForm, KeyKind, KeyReader, Preset, RetardationBranch, Rheology,
    RheologyModel, SolverUnits, MAX_BRANCHES,
};
use crate::error::{require_positive, Error, Result};
use crate::provenance::{self, Reference};

pub(super) const PRESET: Preset = Preset {
    name: "box_spectrum",
    keys: &[
        ("glassy_compliance", KeyKind::Number),
        ("compliance", KeyKind::Number),
        ("shortest_time", KeyKind::Number),
        ("longest_time", KeyKind::Number),
    ],
    compliance_from_table: false,
    parse: super::parse::<BoxSpectrum>,
};

/// The widest bin, in ln(time), of the discretisation.
pub const BOX_SPACING: f64 = 0.3;

/// C_g, C1, tau1 and tau2.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct BoxSpectrum {
    pub glassy_compliance: f64,
    pub compliance: f64,
    pub shortest_time: f64,
    pub longest_time: f64,
}

impl From<BoxSpectrum> for Rheology {
    fn from(b: BoxSpectrum) -> Rheology {
        Rheology::BoxSpectrum {
            glassy_compliance: b.glassy_compliance,
            compliance: b.compliance,
            shortest_time: b.shortest_time,
            longest_time: b.longest_time,
        }
    }
}

impl RheologyModel for BoxSpectrum {
    fn from_keys(keys: &KeyReader) -> Result<Self> {
        Ok(BoxSpectrum {
            glassy_compliance: super::zener::glassy(keys)?,
            compliance: keys.need_number(
                "compliance",
                &keys.needs("the compliance C1 of its spectrum"),
            )?,
            shortest_time: keys.need_number(
                "shortest_time",
                &keys.needs("the shortest retardation time of its spectrum"),
            )?,
            longest_time: keys.need_number(
                "longest_time",
                &keys.needs("the longest retardation time of its spectrum"),
            )?,
        })
    }

    fn name(&self) -> &'static str {
        PRESET.name
    }

    fn validate(&self) -> Result<()> {
        require_non_negative("layer.glassy_compliance", self.glassy_compliance)?;
        require_positive("layer.compliance", self.compliance)?;
        require_positive("layer.shortest_time", self.shortest_time)?;
        require_positive("layer.longest_time", self.longest_time)?;
        let span = (self.longest_time / self.shortest_time).ln();
        let widest = BOX_SPACING * MAX_BRANCHES as f64;
        if !(0.0..=widest).contains(&span) {
            return Err(Error::invalid(
                "layer.longest_time",
                self.longest_time,
                &format!(
                    "shortest_time <= longest_time <= shortest_time e^{widest} (at most \
                     {MAX_BRANCHES} branches, {BOX_SPACING} apart in ln(time))"
                ),
            ));
        }
        Ok(())
    }

    fn scaled(&self, units: &SolverUnits) -> Rheology {
        BoxSpectrum {
            glassy_compliance: units.compliance(self.glassy_compliance),
            compliance: units.compliance(self.compliance),
            shortest_time: units.time(self.shortest_time),
            longest_time: units.time(self.longest_time),
        }
        .into()
    }

    /// The shortest retardation time.
    fn time_scale(&self) -> f64 {
        self.shortest_time
    }

    fn reference_compliance(&self) -> f64 {
        1.0
    }

    fn creep_form(&self) -> CreepForm {
        CreepForm {
            glassy: self.glassy_compliance,
            branches: box_spectrum_branches(self.compliance, self.shortest_time, self.longest_time),
            flow: None,
        }
    }

    fn references(&self) -> Vec<Reference> {
        vec![
            Reference::new(provenance::TOBOLSKY, "the box retardation spectrum"),
            Reference::new(
                provenance::TSCHOEGL,
                "the box spectrum's complex and creep compliances",
            ),
        ]
    }
}

/// The number of branches of a box from `tau1` to `tau2`: bins of ln(time) at most
/// [`BOX_SPACING`] wide, at least one.
///
/// The branches' complex compliance then differs from the closed form by less than
/// 0.5 % of the loss peak `C1 (atan(sqrt(r)) - atan(1 / sqrt(r))) / ln(r)`, `r = tau2 /
/// tau1`, at every frequency (measured for r from 1.01 to 1e20: at most 0.3 %; the
/// error of this midpoint rule falls as the square of the spacing).
pub fn box_spectrum_branch_count(tau1: f64, tau2: f64) -> usize {
    ((tau2 / tau1).ln() / BOX_SPACING).ceil().max(1.0) as usize
}

/// Kelvin–Voigt branches of a box spectrum of compliance `compliance` from `tau1`
/// to `tau2`: [`box_spectrum_branch_count`] equal bins of ln(time), each one branch
/// of the bin's compliance at its centre, so the relaxed compliance is exact. With
/// `tau1 = tau2` it is one branch of time `tau1`: the Zener body.
pub fn box_spectrum_branches(compliance: f64, tau1: f64, tau2: f64) -> Vec<RetardationBranch> {
    let n = box_spectrum_branch_count(tau1, tau2);
    let width = (tau2 / tau1).ln() / n as f64;
    (0..n)
        .map(|k| RetardationBranch {
            compliance: compliance / n as f64,
            time: tau1 * ((k as f64 + 0.5) * width).exp(),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The closed form `1 - ln((1 + i w tau2) / (1 + i w tau1)) / Lambda` for C1 = 1.
    fn closed_form(tau1: f64, tau2: f64, omega: f64) -> (f64, f64) {
        let lambda = (tau2 / tau1).ln();
        let (a, b) = (omega * tau2, omega * tau1);
        let re = 1.0 - 0.5 * ((1.0 + a * a) / (1.0 + b * b)).ln() / lambda;
        let im = -(a.atan() - b.atan()) / lambda;
        (re, im)
    }

    #[test]
    fn branches_match_the_closed_form_complex_compliance() {
        for ratio in [1.3, 2.0, 10.0, 1e3, 1e6, 1e20] {
            let (tau1, tau2) = (0.5, 0.5 * ratio);
            let form = CreepForm {
                glassy: 0.0,
                branches: box_spectrum_branches(1.0, tau1, tau2),
                flow: None,
            };
            assert!((form.relaxed() - 1.0).abs() < 1e-12);
            let peak = (ratio.sqrt().atan() - (1.0 / ratio.sqrt()).atan()) / ratio.ln();
            let mut worst = 0.0f64;
            // Ten decades beyond each end of the spectrum, 40 frequencies a decade.
            let decades = ratio.log10();
            for j in -400..=(40.0 * decades) as i32 + 400 {
                let omega = 10f64.powf(j as f64 / 40.0) / tau1;
                let (cr, ci) = form.complex_compliance(omega);
                let (er, ei) = closed_form(tau1, tau2, omega);
                worst = worst.max((cr - er).hypot(ci - ei));
            }
            eprintln!(
                "tau2/tau1 = {ratio:e}: worst error {:.2e} of the loss peak",
                worst / peak
            );
            assert!(worst < 5e-3 * peak, "tau2/tau1 {ratio}: {worst:e}");
        }
    }

    #[test]
    fn creep_matches_a_quadrature_of_the_spectrum() {
        // C(t) = C_g + C1 / Lambda int (1 - exp(-t / tau)) d ln tau, by Simpson's rule
        // on 2000 intervals (a second method), against the branches.
        let (cg, c1, tau1, tau2) = (0.01, 0.02, 0.1, 100.0);
        let form = BoxSpectrum {
            glassy_compliance: cg,
            compliance: c1,
            shortest_time: tau1,
            longest_time: tau2,
        }
        .creep_form();
        let lambda = (tau2 / tau1).ln();
        for t in [0.01, 0.3, 3.0, 30.0, 1e3] {
            let m = 2000;
            let h = lambda / m as f64;
            let f = |k: usize| -(-t / (tau1 * (k as f64 * h).exp())).exp_m1();
            let simpson = (1..m).fold(f(0) + f(m), |s, k| {
                s + if k % 2 == 1 { 4.0 } else { 2.0 } * f(k)
            }) * h
                / 3.0;
            let exact = cg + c1 * simpson / lambda;
            let c = form.creep_compliance(t);
            assert!((c - exact).abs() < 2e-3 * c1, "t {t}: {c} against {exact}");
        }
        assert_eq!(form.creep_compliance(0.0), cg);
    }

    #[test]
    fn a_box_of_zero_width_is_the_zener_body() {
        let b = box_spectrum_branches(0.7, 3.0, 3.0);
        assert_eq!(
            b,
            vec![RetardationBranch {
                compliance: 0.7,
                time: 3.0
            }]
        );
    }

    #[test]
    fn too_wide_a_box_is_an_error_naming_the_key() {
        let b = BoxSpectrum {
            glassy_compliance: 0.0,
            compliance: 1.0,
            shortest_time: 1.0,
            longest_time: 1e200,
        };
        let e = b.validate().unwrap_err().to_string();
        assert!(e.contains("layer.longest_time"), "{e}");
        let b = BoxSpectrum {
            longest_time: 0.5,
            ..b
        };
        assert!(b.validate().is_err());
    }
}
