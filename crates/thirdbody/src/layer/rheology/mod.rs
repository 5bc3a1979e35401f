//! Layer rheologies in one creep form. Every linear viscoelastic solid or fluid
//! whose creep compliance is a discrete spectrum,
//! `C(t) = C_g + sum_k C_k (1 - exp(-t / tau_k)) + C_v t / T`,
//! is a glassy spring (`C_g`), Kelvin–Voigt branches (`C_k`, retardation time
//! `tau_k`) and a viscous flow (`C_v / T`) in series ([`CreepForm`]); the layer's
//! pressure dependence multiplies every part by the same shape `phi(p) = C[p] / C[0]`
//! ([`super::law`]). Each named preset is one value implementing [`RheologyModel`],
//! in its own file: the paper's Maxwell body (eq. 2, `maxwell.rs`), Kelvin–Voigt,
//! Zener (standard linear solid), Burgers, a Prony series of compliances, a Prony
//! series of relaxation stiffnesses (converted exactly, [`relaxation_to_creep`]), a
//! fractional Zener body discretised into branches ([`fractional_zener_branches`])
//! and a box retardation spectrum likewise ([`box_spectrum_branches`]). A case
//! holds the data as a [`Rheology`]; [`Rheology::model`] is the one place that picks
//! the implementation, and [`PRESETS`] the one list that maps a case-file name to
//! its keys and its constructor (docs/architecture.md, "How to add a layer
//! rheology").

mod box_spectrum;
mod burgers;
mod creep_form;
mod fractional_zener;
mod kelvin_voigt;
mod keys;
mod maxwell;
mod prony;
mod relaxation_prony;
mod zener;

pub use box_spectrum::{box_spectrum_branch_count, box_spectrum_branches, BOX_SPACING};
pub use creep_form::{CreepForm, Flow, RelaxationBranch, RetardationBranch};
pub use fractional_zener::{
    fractional_zener_branch_count, fractional_zener_branches, fractional_zener_spacing,
};
pub use keys::{KeyKind, KeyReader, KeyValue};
pub use relaxation_prony::relaxation_to_creep;

use crate::error::{Error, Result};
use crate::provenance::Reference;

/// The largest number of branches a layer may have.
pub const MAX_BRANCHES: usize = 1000;

/// The rheology presets a case file can name, in the order error messages list
/// them; the first is the default. This is the one registration list: a new preset
/// adds its `PRESET` here.
pub const PRESETS: [Preset; 8] = [
    maxwell::PRESET,
    kelvin_voigt::PRESET,
    zener::PRESET,
    burgers::PRESET,
    prony::PRESET,
    relaxation_prony::PRESET,
    fractional_zener::PRESET,
    box_spectrum::PRESET,
];

/// A preset as a case file names it: its name, its keys and how to build it from
/// them.
#[derive(Debug, Clone, Copy)]
pub struct Preset {
    /// The name in case files (`rheology = "..."`).
    pub name: &'static str,
    /// The keys it takes, in case-file order, with the kind of their values.
    pub keys: &'static [(&'static str, KeyKind)],
    /// Whether a table law gives its `compliance` (the table's first compliance,
    /// as the paper's layer has it).
    pub compliance_from_table: bool,
    /// Builds the preset from the keys given (missing keys are errors naming them).
    pub parse: fn(&KeyReader) -> Result<Rheology>,
}

impl Preset {
    /// The preset named `name` in case files.
    pub fn named(name: &str) -> Option<&'static Preset> {
        PRESETS.iter().find(|p| p.name == name)
    }

    /// The default preset (a `[layer]` without `rheology`).
    pub fn default_preset() -> &'static Preset {
        &PRESETS[0]
    }

    /// Whether the preset takes the key `key`.
    pub fn takes(&self, key: &str) -> bool {
        self.keys.iter().any(|(k, _)| *k == key)
    }

    /// Its keys' names, in case-file order.
    pub fn key_names(&self) -> Vec<&'static str> {
        self.keys.iter().map(|(k, _)| *k).collect()
    }
}

/// Every key some preset takes, once, with its kind, in the order of [`PRESETS`].
pub fn preset_keys() -> Vec<(&'static str, KeyKind)> {
    let mut all: Vec<(&'static str, KeyKind)> = Vec::new();
    for &(key, kind) in PRESETS.iter().flat_map(|p| p.keys) {
        if !all.iter().any(|(k, _)| *k == key) {
            all.push((key, kind));
        }
    }
    all
}

/// `T::from_keys` as a [`Rheology`]: the constructor a [`Preset`] registers.
fn parse<T: RheologyModel + Into<Rheology>>(keys: &KeyReader) -> Result<Rheology> {
    T::from_keys(keys).map(Into::into)
}

/// The solver's units a rheology is scaled to (each a power of two, so that
/// scaling is exact): a quantity in the case's units is the scaled one times its
/// unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverUnits {
    /// Unit of length.
    pub length: f64,
    /// Unit of pressure (and modulus).
    pub stress: f64,
    /// Unit of time.
    pub time: f64,
}

impl SolverUnits {
    /// A compliance (length per pressure) in these units.
    pub fn compliance(&self, c: f64) -> f64 {
        c / self.length * self.stress
    }

    /// A stiffness (pressure per length) in these units.
    pub fn stiffness(&self, k: f64) -> f64 {
        k / self.stress * self.length
    }

    /// A time in these units.
    pub fn time(&self, t: f64) -> f64 {
        t / self.time
    }

    /// A viscosity of the layer (pressure times time per length) in these units.
    pub fn viscosity(&self, eta: f64) -> f64 {
        self.time(self.stiffness(eta))
    }

    /// A Kelvin–Voigt branch in these units.
    pub fn retardation(&self, b: &RetardationBranch) -> RetardationBranch {
        RetardationBranch {
            compliance: self.compliance(b.compliance),
            time: self.time(b.time),
        }
    }
}

/// One rheology preset: its parameters and everything the rest of the code asks
/// of them. The solvers see only [`RheologyModel::creep_form`] and
/// [`RheologyModel::reference_compliance`] (through [`super::Layer`]).
pub trait RheologyModel: std::fmt::Debug {
    /// Reads the preset from its case-file keys (missing keys are errors naming
    /// them; unused keys were rejected before).
    fn from_keys(keys: &KeyReader) -> Result<Self>
    where
        Self: Sized;
    /// The preset's name in case files.
    fn name(&self) -> &'static str;
    /// Checks the parameters, naming the case-file key of a bad one.
    fn validate(&self) -> Result<()>;
    /// The same preset in the solver's units.
    fn scaled(&self, units: &SolverUnits) -> Rheology;
    /// The time the solver's unit of time is chosen near (units.rs).
    fn time_scale(&self) -> f64;
    /// The compliance `C[0]` a linear or sigmoid law is evaluated with: the
    /// preset's one compliance when it has one (so that the paper's layer is
    /// computed exactly as eq. 8 writes it), else 1 (its parts carry their own).
    fn reference_compliance(&self) -> f64;
    /// The creep form (parameters assumed valid).
    fn creep_form(&self) -> CreepForm;
    /// The works the preset's model or its discretisation comes from (those its
    /// module's documentation cites), with what each gives.
    fn references(&self) -> Vec<Reference>;
}

fn require_non_negative(field: &str, value: f64) -> Result<()> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(field, value, "a finite number >= 0"))
    }
}

fn require_branch_count(field: &str, n: usize) -> Result<()> {
    if (1..=MAX_BRANCHES).contains(&n) {
        Ok(())
    } else {
        Err(Error::invalid(
            field,
            format!("{n} branches"),
            &format!("from 1 to {MAX_BRANCHES} branches"),
        ))
    }
}

/// A layer rheology as a case names it: the data of one preset. [`Rheology::model`]
/// gives the preset's implementation of [`RheologyModel`].
#[derive(Debug, Clone, PartialEq)]
pub enum Rheology {
    /// The paper's nonlinear Maxwell body (eq. 2): `C_g = C_v = C0`, `T`.
    Maxwell {
        /// C0.
        compliance: f64,
        /// T.
        relaxation_time: f64,
    },
    /// One Kelvin–Voigt branch, no glassy part, no flow.
    KelvinVoigt {
        /// C1.
        compliance: f64,
        /// tau1.
        retardation_time: f64,
    },
    /// The standard linear solid: glassy spring and one Kelvin–Voigt branch.
    Zener {
        /// C_g.
        glassy_compliance: f64,
        /// C1 (the relaxed compliance is C_g + C1).
        compliance: f64,
        /// tau1.
        retardation_time: f64,
    },
    /// Burgers: a Maxwell element (`C_g`, `T`, so `C_v = C_g`) and a Kelvin–Voigt
    /// branch in series.
    Burgers {
        /// C_g.
        glassy_compliance: f64,
        /// T of the Maxwell element.
        relaxation_time: f64,
        /// C1.
        compliance: f64,
        /// tau1.
        retardation_time: f64,
    },
    /// A Prony series of compliances: glassy spring, N Kelvin–Voigt branches and
    /// an optional flow of viscosity eta (`dw_v/dt = phi(p) p / eta`).
    Prony {
        /// C_g >= 0.
        glassy_compliance: f64,
        /// The branches.
        branches: Vec<RetardationBranch>,
        /// eta (pressure times time per displacement), if the layer flows.
        viscosity: Option<f64>,
    },
    /// A Prony series of relaxation stiffnesses `K(t) = K_inf + sum K_i
    /// exp(-t / rho_i)`, converted exactly to the creep form.
    RelaxationProny {
        /// K_inf >= 0 (0: the layer flows).
        equilibrium_stiffness: f64,
        /// The Maxwell branches.
        branches: Vec<RelaxationBranch>,
    },
    /// The fractional Zener body `C*(omega) = C_g + C1 / (1 + (i omega tau)^alpha)`,
    /// discretised into Kelvin–Voigt branches (by default as many as the order
    /// needs: [`fractional_zener_branch_count`]).
    FractionalZener {
        /// C_g >= 0.
        glassy_compliance: f64,
        /// C1 (the relaxed compliance is C_g + C1).
        compliance: f64,
        /// tau.
        retardation_time: f64,
        /// alpha, 0 < alpha <= 1 (1: the Zener body).
        order: f64,
        /// Number of branches of the discretisation, 2 ..= 1000; `None`: the
        /// order's rule.
        branch_count: Option<usize>,
    },
    /// A box retardation spectrum: `C1` spread evenly over ln(time) from `tau1` to
    /// `tau2`, after a glassy spring; discretised into Kelvin–Voigt branches at most
    /// [`BOX_SPACING`] apart in ln(time).
    BoxSpectrum {
        /// C_g >= 0.
        glassy_compliance: f64,
        /// C1 (the relaxed compliance is C_g + C1).
        compliance: f64,
        /// tau1.
        shortest_time: f64,
        /// tau2 >= tau1 (equal: the Zener body).
        longest_time: f64,
    },
}

impl Rheology {
    /// The preset's implementation: the one place that maps a preset's data to its
    /// code (every arm names its variant; there is no catch-all).
    pub fn model(&self) -> Box<dyn RheologyModel> {
        match self {
            &Rheology::Maxwell {
                compliance,
                relaxation_time,
            } => Box::new(maxwell::Maxwell {
                compliance,
                relaxation_time,
            }),
            &Rheology::KelvinVoigt {
                compliance,
                retardation_time,
            } => Box::new(kelvin_voigt::KelvinVoigt {
                compliance,
                retardation_time,
            }),
            &Rheology::Zener {
                glassy_compliance,
                compliance,
                retardation_time,
            } => Box::new(zener::Zener {
                glassy_compliance,
                compliance,
                retardation_time,
            }),
            &Rheology::Burgers {
                glassy_compliance,
                relaxation_time,
                compliance,
                retardation_time,
            } => Box::new(burgers::Burgers {
                glassy_compliance,
                relaxation_time,
                compliance,
                retardation_time,
            }),
            Rheology::Prony {
                glassy_compliance,
                branches,
                viscosity,
            } => Box::new(prony::Prony {
                glassy_compliance: *glassy_compliance,
                branches: branches.clone(),
                viscosity: *viscosity,
            }),
            Rheology::RelaxationProny {
                equilibrium_stiffness,
                branches,
            } => Box::new(relaxation_prony::RelaxationProny {
                equilibrium_stiffness: *equilibrium_stiffness,
                branches: branches.clone(),
            }),
            &Rheology::FractionalZener {
                glassy_compliance,
                compliance,
                retardation_time,
                order,
                branch_count,
            } => Box::new(fractional_zener::FractionalZener {
                glassy_compliance,
                compliance,
                retardation_time,
                order,
                branch_count,
            }),
            &Rheology::BoxSpectrum {
                glassy_compliance,
                compliance,
                shortest_time,
                longest_time,
            } => Box::new(box_spectrum::BoxSpectrum {
                glassy_compliance,
                compliance,
                shortest_time,
                longest_time,
            }),
        }
    }

    /// The preset's name in case files.
    pub fn name(&self) -> &'static str {
        self.model().name()
    }

    /// Checks the parameters, naming the case-file key of a bad one.
    pub fn validate(&self) -> Result<()> {
        self.model().validate()
    }

    /// The creep form of the preset (parameters assumed valid).
    pub fn creep_form(&self) -> CreepForm {
        self.model().creep_form()
    }

    /// See [`RheologyModel::references`].
    pub fn references(&self) -> Vec<Reference> {
        self.model().references()
    }

    /// See [`RheologyModel::reference_compliance`].
    pub fn reference_compliance(&self) -> f64 {
        self.model().reference_compliance()
    }

    /// See [`RheologyModel::time_scale`].
    pub fn time_scale(&self) -> f64 {
        self.model().time_scale()
    }

    /// The same rheology in the solver's units.
    pub fn scaled(&self, units: &SolverUnits) -> Rheology {
        self.model().scaled(units)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_preset_is_registered_once_with_one_kind_per_key() {
        for (i, p) in PRESETS.iter().enumerate() {
            assert!(
                PRESETS[..i].iter().all(|q| q.name != p.name),
                "{} is registered twice",
                p.name
            );
            for &(key, kind) in p.keys {
                let first = preset_keys().into_iter().find(|(k, _)| *k == key);
                assert_eq!(first, Some((key, kind)), "{}: {key}", p.name);
            }
        }
        assert_eq!(Preset::default_preset().name, "maxwell");
    }

    #[test]
    fn every_variant_names_a_registered_preset() {
        let branch = RetardationBranch {
            compliance: 1.0,
            time: 1.0,
        };
        let all = [
            Rheology::Maxwell {
                compliance: 1.0,
                relaxation_time: 1.0,
            },
            Rheology::KelvinVoigt {
                compliance: 1.0,
                retardation_time: 1.0,
            },
            Rheology::Zener {
                glassy_compliance: 1.0,
                compliance: 1.0,
                retardation_time: 1.0,
            },
            Rheology::Burgers {
                glassy_compliance: 1.0,
                relaxation_time: 1.0,
                compliance: 1.0,
                retardation_time: 1.0,
            },
            Rheology::Prony {
                glassy_compliance: 1.0,
                branches: vec![branch],
                viscosity: None,
            },
            Rheology::RelaxationProny {
                equilibrium_stiffness: 1.0,
                branches: vec![RelaxationBranch {
                    stiffness: 1.0,
                    time: 1.0,
                }],
            },
            Rheology::FractionalZener {
                glassy_compliance: 1.0,
                compliance: 1.0,
                retardation_time: 1.0,
                order: 0.5,
                branch_count: Some(10),
            },
            Rheology::BoxSpectrum {
                glassy_compliance: 1.0,
                compliance: 1.0,
                shortest_time: 1.0,
                longest_time: 10.0,
            },
        ];
        let mut names: Vec<&str> = all.iter().map(Rheology::name).collect();
        names.sort_unstable();
        let mut registered: Vec<&str> = PRESETS.iter().map(|p| p.name).collect();
        registered.sort_unstable();
        assert_eq!(names, registered);
    }
}
