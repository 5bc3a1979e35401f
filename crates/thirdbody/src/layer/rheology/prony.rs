//! A Prony series of compliances: a glassy spring, N Kelvin–Voigt branches and an
//! optional flow of viscosity eta in series,
//! `C(t) = C_g + sum_k C_k (1 - exp(-t / tau_k)) + t / eta`: the creep form itself.

use super::{
    require_branch_count, require_non_negative, CreepForm, Flow, KeyKind, KeyReader, Preset,
    RetardationBranch, Rheology, RheologyModel, SolverUnits,
};
use crate::error::{require_positive, Result};
use crate::provenance::Reference;

pub(super) const PRESET: Preset = Preset {
    name: "prony",
    keys: &[
        ("glassy_compliance", KeyKind::Number),
        ("branch_compliances", KeyKind::Numbers),
        ("branch_times", KeyKind::Numbers),
        ("viscosity", KeyKind::Number),
    ],
    compliance_from_table: false,
    parse: super::parse::<Prony>,
};

/// C_g, the branches and eta.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Prony {
    pub glassy_compliance: f64,
    pub branches: Vec<RetardationBranch>,
    pub viscosity: Option<f64>,
}

impl From<Prony> for Rheology {
    fn from(p: Prony) -> Rheology {
        Rheology::Prony {
            glassy_compliance: p.glassy_compliance,
            branches: p.branches,
            viscosity: p.viscosity,
        }
    }
}

impl RheologyModel for Prony {
    fn from_keys(keys: &KeyReader) -> Result<Self> {
        let compliances = keys.need_numbers(
            "branch_compliances",
            "a prony layer needs the compliances of its Kelvin–Voigt branches (a list)",
        )?;
        let times = keys.branch_times(compliances.len(), "branch_compliances")?;
        Ok(Prony {
            glassy_compliance: super::zener::glassy(keys)?,
            branches: compliances
                .into_iter()
                .zip(times)
                .map(|(compliance, time)| RetardationBranch { compliance, time })
                .collect(),
            viscosity: keys.number("viscosity"),
        })
    }

    fn name(&self) -> &'static str {
        PRESET.name
    }

    fn validate(&self) -> Result<()> {
        require_non_negative("layer.glassy_compliance", self.glassy_compliance)?;
        require_branch_count("layer.branch_compliances", self.branches.len())?;
        for (k, b) in self.branches.iter().enumerate() {
            require_positive(&format!("layer.branch_compliances[{k}]"), b.compliance)?;
            require_positive(&format!("layer.branch_times[{k}]"), b.time)?;
        }
        if let Some(eta) = self.viscosity {
            require_positive("layer.viscosity", eta)?;
        }
        Ok(())
    }

    fn scaled(&self, units: &SolverUnits) -> Rheology {
        Prony {
            glassy_compliance: units.compliance(self.glassy_compliance),
            branches: self.branches.iter().map(|b| units.retardation(b)).collect(),
            viscosity: self.viscosity.map(|eta| units.viscosity(eta)),
        }
        .into()
    }

    /// The flow's `T` of the creep form (eta, with `C_v = 1`) when the layer flows,
    /// else the first branch's time (1 without branches, which validation rejects).
    fn time_scale(&self) -> f64 {
        self.viscosity
            .or_else(|| self.branches.first().map(|b| b.time))
            .unwrap_or(1.0)
    }

    fn reference_compliance(&self) -> f64 {
        1.0
    }

    fn creep_form(&self) -> CreepForm {
        CreepForm {
            glassy: self.glassy_compliance,
            branches: self.branches.clone(),
            flow: self.viscosity.map(|eta| Flow {
                compliance: 1.0,
                time: eta,
            }),
        }
    }

    fn references(&self) -> Vec<Reference> {
        Vec::new()
    }
}
