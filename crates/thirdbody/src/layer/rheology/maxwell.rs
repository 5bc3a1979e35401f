//! The paper's Maxwell layer (eq. 2, `dw3/dt = C[p] (p/T + dp/dt)`): a glassy
//! spring and a flow of the same compliance C0 in series, `C(t) = C0 (1 + t / T)`.

use super::{CreepForm, Flow, KeyKind, KeyReader, Preset, Rheology, RheologyModel, SolverUnits};
use crate::error::{require_positive, Result};
use crate::provenance::{self, Reference};

pub(super) const PRESET: Preset = Preset {
    name: "maxwell",
    keys: &[
        ("compliance", KeyKind::Number),
        ("relaxation_time", KeyKind::Number),
    ],
    compliance_from_table: true,
    parse: super::parse::<Maxwell>,
};

/// C0 and T.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Maxwell {
    pub compliance: f64,
    pub relaxation_time: f64,
}

impl From<Maxwell> for Rheology {
    fn from(m: Maxwell) -> Rheology {
        Rheology::Maxwell {
            compliance: m.compliance,
            relaxation_time: m.relaxation_time,
        }
    }
}

impl RheologyModel for Maxwell {
    fn from_keys(keys: &KeyReader) -> Result<Self> {
        Ok(Maxwell {
            compliance: keys.compliance_or_table("its compliance C0")?,
            relaxation_time: keys.need_number(
                "relaxation_time",
                "a [layer] needs its relaxation time T (> 0)",
            )?,
        })
    }

    fn name(&self) -> &'static str {
        PRESET.name
    }

    fn validate(&self) -> Result<()> {
        require_positive("layer.compliance", self.compliance)?;
        require_positive("layer.relaxation_time", self.relaxation_time)
    }

    fn scaled(&self, units: &SolverUnits) -> Rheology {
        Maxwell {
            compliance: units.compliance(self.compliance),
            relaxation_time: units.time(self.relaxation_time),
        }
        .into()
    }

    fn time_scale(&self) -> f64 {
        self.relaxation_time
    }

    fn reference_compliance(&self) -> f64 {
        self.compliance
    }

    fn creep_form(&self) -> CreepForm {
        CreepForm {
            glassy: self.compliance,
            branches: vec![],
            flow: Some(Flow {
                compliance: self.compliance,
                time: self.relaxation_time,
            }),
        }
    }

    fn references(&self) -> Vec<Reference> {
        vec![Reference::new(
            provenance::PAPER,
            "the nonlinear Maxwell layer (eq. 2)",
        )]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn creep_is_the_glassy_spring_plus_the_flow() {
        let m = Maxwell {
            compliance: 0.02,
            relaxation_time: 3.0,
        }
        .creep_form();
        // C(t) = C0 (1 + t / T) (paper eq. 2 under a unit step of pressure).
        assert!((m.creep_compliance(6.0) - 0.02 * 3.0).abs() < 1e-16);
        assert_eq!(m.creep_compliance(0.0), 0.02);
    }
}
