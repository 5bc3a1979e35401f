//! The Burgers layer: a Maxwell element (glassy spring `C_g`, flow `C_g t / T`) and
//! a Kelvin–Voigt branch in series,
//! `C(t) = C_g (1 + t / T) + C1 (1 - exp(-t / tau))`.

use super::{
    CreepForm, Flow, KeyKind, KeyReader, Preset, RetardationBranch, Rheology, RheologyModel,
    SolverUnits,
};
use crate::error::{require_positive, Result};
use crate::provenance::Reference;

pub(super) const PRESET: Preset = Preset {
    name: "burgers",
    keys: &[
        ("glassy_compliance", KeyKind::Number),
        ("relaxation_time", KeyKind::Number),
        ("compliance", KeyKind::Number),
        ("retardation_time", KeyKind::Number),
    ],
    compliance_from_table: false,
    parse: super::parse::<Burgers>,
};

/// C_g, T, C1 and tau1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Burgers {
    pub glassy_compliance: f64,
    pub relaxation_time: f64,
    pub compliance: f64,
    pub retardation_time: f64,
}

impl From<Burgers> for Rheology {
    fn from(b: Burgers) -> Rheology {
        Rheology::Burgers {
            glassy_compliance: b.glassy_compliance,
            relaxation_time: b.relaxation_time,
            compliance: b.compliance,
            retardation_time: b.retardation_time,
        }
    }
}

impl RheologyModel for Burgers {
    fn from_keys(keys: &KeyReader) -> Result<Self> {
        Ok(Burgers {
            glassy_compliance: super::zener::glassy(keys)?,
            relaxation_time: keys.need_number(
                "relaxation_time",
                &keys.needs("the relaxation time T of its Maxwell element"),
            )?,
            compliance: keys.need_number(
                "compliance",
                &keys.needs("the compliance C1 of its Kelvin–Voigt branch"),
            )?,
            retardation_time: keys
                .need_number("retardation_time", &keys.needs("its retardation time"))?,
        })
    }

    fn name(&self) -> &'static str {
        PRESET.name
    }

    fn validate(&self) -> Result<()> {
        require_positive("layer.glassy_compliance", self.glassy_compliance)?;
        require_positive("layer.relaxation_time", self.relaxation_time)?;
        require_positive("layer.compliance", self.compliance)?;
        require_positive("layer.retardation_time", self.retardation_time)
    }

    fn scaled(&self, units: &SolverUnits) -> Rheology {
        Burgers {
            glassy_compliance: units.compliance(self.glassy_compliance),
            relaxation_time: units.time(self.relaxation_time),
            compliance: units.compliance(self.compliance),
            retardation_time: units.time(self.retardation_time),
        }
        .into()
    }

    /// The Maxwell element's T (the flow's time).
    fn time_scale(&self) -> f64 {
        self.relaxation_time
    }

    fn reference_compliance(&self) -> f64 {
        1.0
    }

    fn creep_form(&self) -> CreepForm {
        CreepForm {
            glassy: self.glassy_compliance,
            branches: vec![RetardationBranch {
                compliance: self.compliance,
                time: self.retardation_time,
            }],
            flow: Some(Flow {
                compliance: self.glassy_compliance,
                time: self.relaxation_time,
            }),
        }
    }

    fn references(&self) -> Vec<Reference> {
        Vec::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn creep_is_a_maxwell_and_a_kelvin_voigt_element_in_series() {
        let bu = Burgers {
            glassy_compliance: 1.0,
            relaxation_time: 4.0,
            compliance: 2.0,
            retardation_time: 0.5,
        }
        .creep_form();
        let t = 2.0;
        let c = 1.0 + t / 4.0 + 2.0 * (1.0 - (-t / 0.5f64).exp());
        assert!((bu.creep_compliance(t) - c).abs() < 1e-14);
    }
}
