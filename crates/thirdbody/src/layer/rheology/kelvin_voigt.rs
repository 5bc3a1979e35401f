//! The Kelvin–Voigt layer: one spring and dashpot in parallel,
//! `tau dw/dt + w = C1 phi(p) p`, so `C(t) = C1 (1 - exp(-t / tau))`: no glassy
//! part, no flow.

use super::{
    CreepForm, KeyKind, KeyReader, Preset, RetardationBranch, Rheology, RheologyModel, SolverUnits,
};
use crate::error::{require_positive, Result};
use crate::provenance::Reference;

pub(super) const PRESET: Preset = Preset {
    name: "kelvin_voigt",
    keys: &[
        ("compliance", KeyKind::Number),
        ("retardation_time", KeyKind::Number),
    ],
    compliance_from_table: true,
    parse: super::parse::<KelvinVoigt>,
};

/// C1 and tau1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct KelvinVoigt {
    pub compliance: f64,
    pub retardation_time: f64,
}

impl From<KelvinVoigt> for Rheology {
    fn from(k: KelvinVoigt) -> Rheology {
        Rheology::KelvinVoigt {
            compliance: k.compliance,
            retardation_time: k.retardation_time,
        }
    }
}

impl RheologyModel for KelvinVoigt {
    fn from_keys(keys: &KeyReader) -> Result<Self> {
        Ok(KelvinVoigt {
            compliance: keys.compliance_or_table("its compliance C1")?,
            retardation_time: keys
                .need_number("retardation_time", &keys.needs("its retardation time"))?,
        })
    }

    fn name(&self) -> &'static str {
        PRESET.name
    }

    fn validate(&self) -> Result<()> {
        require_positive("layer.compliance", self.compliance)?;
        require_positive("layer.retardation_time", self.retardation_time)
    }

    fn scaled(&self, units: &SolverUnits) -> Rheology {
        KelvinVoigt {
            compliance: units.compliance(self.compliance),
            retardation_time: units.time(self.retardation_time),
        }
        .into()
    }

    fn time_scale(&self) -> f64 {
        self.retardation_time
    }

    fn reference_compliance(&self) -> f64 {
        self.compliance
    }

    fn creep_form(&self) -> CreepForm {
        CreepForm {
            glassy: 0.0,
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
