//! The Zener layer (standard linear solid): a glassy spring and one Kelvin–Voigt
//! branch in series, `C(t) = C_g + C1 (1 - exp(-t / tau))`.

use super::{
    CreepForm, KeyKind, KeyReader, Preset, RetardationBranch, Rheology, RheologyModel, SolverUnits,
};
use crate::error::{require_positive, Result};
use crate::provenance::Reference;

pub(super) const PRESET: Preset = Preset {
    name: "zener",
    keys: &[
        ("glassy_compliance", KeyKind::Number),
        ("compliance", KeyKind::Number),
        ("retardation_time", KeyKind::Number),
    ],
    compliance_from_table: false,
    parse: super::parse::<Zener>,
};

/// C_g, C1 and tau1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Zener {
    pub glassy_compliance: f64,
    pub compliance: f64,
    pub retardation_time: f64,
}

impl From<Zener> for Rheology {
    fn from(z: Zener) -> Rheology {
        Rheology::Zener {
            glassy_compliance: z.glassy_compliance,
            compliance: z.compliance,
            retardation_time: z.retardation_time,
        }
    }
}

/// `glassy_compliance`, or the error every preset with a glassy spring gives.
pub(super) fn glassy(keys: &KeyReader) -> Result<f64> {
    keys.need_number(
        "glassy_compliance",
        &format!(
            "a {} layer needs its glassy (instantaneous) compliance C_g",
            keys.name()
        ),
    )
}

impl RheologyModel for Zener {
    fn from_keys(keys: &KeyReader) -> Result<Self> {
        Ok(Zener {
            glassy_compliance: glassy(keys)?,
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
        require_positive("layer.compliance", self.compliance)?;
        require_positive("layer.retardation_time", self.retardation_time)
    }

    fn scaled(&self, units: &SolverUnits) -> Rheology {
        Zener {
            glassy_compliance: units.compliance(self.glassy_compliance),
            compliance: units.compliance(self.compliance),
            retardation_time: units.time(self.retardation_time),
        }
        .into()
    }

    fn time_scale(&self) -> f64 {
        self.retardation_time
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
            flow: None,
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
    fn creep_is_the_standard_linear_solid() {
        let z = Zener {
            glassy_compliance: 1.0,
            compliance: 2.0,
            retardation_time: 0.5,
        }
        .creep_form();
        // C(t) = 1 + 2 (1 - exp(-t / 0.5)).
        for t in [0.0, 0.1, 1.0, 10.0] {
            let c = 1.0 + 2.0 * (1.0 - (-t / 0.5f64).exp());
            assert!((z.creep_compliance(t) - c).abs() < 1e-14);
        }
    }
}
