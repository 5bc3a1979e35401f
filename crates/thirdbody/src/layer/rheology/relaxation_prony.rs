//! A Prony series of relaxation stiffnesses, `K(t) = K_inf + sum_i K_i exp(-t /
//! rho_i)` (a generalized Maxwell body: springs `K_i` with dashpots of relaxation
//! times `rho_i`, in parallel with `K_inf`), converted exactly to the creep form by
//! the reciprocity of the operational stiffness and compliance
//! ([`relaxation_to_creep`]).

use super::{
    require_branch_count, require_non_negative, CreepForm, Flow, KeyKind, KeyReader, Preset,
    RelaxationBranch, RetardationBranch, Rheology, RheologyModel, SolverUnits,
};
use crate::error::{require_positive, Error, Result};
use crate::provenance::{self, Reference};

pub(super) const PRESET: Preset = Preset {
    name: "relaxation_prony",
    keys: &[
        ("equilibrium_stiffness", KeyKind::Number),
        ("branch_stiffnesses", KeyKind::Numbers),
        ("branch_times", KeyKind::Numbers),
    ],
    compliance_from_table: false,
    parse: super::parse::<RelaxationProny>,
};

/// K_inf and the Maxwell branches.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct RelaxationProny {
    pub equilibrium_stiffness: f64,
    pub branches: Vec<RelaxationBranch>,
}

impl From<RelaxationProny> for Rheology {
    fn from(r: RelaxationProny) -> Rheology {
        Rheology::RelaxationProny {
            equilibrium_stiffness: r.equilibrium_stiffness,
            branches: r.branches,
        }
    }
}

impl RheologyModel for RelaxationProny {
    fn from_keys(keys: &KeyReader) -> Result<Self> {
        let stiffnesses = keys.need_numbers(
            "branch_stiffnesses",
            "a relaxation_prony layer needs the stiffnesses of its Maxwell branches (a list)",
        )?;
        let times = keys.branch_times(stiffnesses.len(), "branch_stiffnesses")?;
        Ok(RelaxationProny {
            equilibrium_stiffness: keys.need_number(
                "equilibrium_stiffness",
                "a relaxation_prony layer needs its equilibrium stiffness K_inf (>= 0; 0 for a \
                 layer that flows)",
            )?,
            branches: stiffnesses
                .into_iter()
                .zip(times)
                .map(|(stiffness, time)| RelaxationBranch { stiffness, time })
                .collect(),
        })
    }

    fn name(&self) -> &'static str {
        PRESET.name
    }

    fn validate(&self) -> Result<()> {
        require_non_negative("layer.equilibrium_stiffness", self.equilibrium_stiffness)?;
        require_branch_count("layer.branch_stiffnesses", self.branches.len())?;
        for (k, b) in self.branches.iter().enumerate() {
            require_positive(&format!("layer.branch_stiffnesses[{k}]"), b.stiffness)?;
            require_positive(&format!("layer.branch_times[{k}]"), b.time)?;
        }
        let glassy = self
            .branches
            .iter()
            .fold(self.equilibrium_stiffness, |s, b| s + b.stiffness);
        if !glassy.is_finite() {
            return Err(Error::invalid(
                "layer.branch_stiffnesses",
                glassy,
                "stiffnesses whose sum (the glassy stiffness) is finite",
            ));
        }
        Ok(())
    }

    fn scaled(&self, units: &SolverUnits) -> Rheology {
        RelaxationProny {
            equilibrium_stiffness: units.stiffness(self.equilibrium_stiffness),
            branches: self
                .branches
                .iter()
                .map(|b| RelaxationBranch {
                    stiffness: units.stiffness(b.stiffness),
                    time: units.time(b.time),
                })
                .collect(),
        }
        .into()
    }

    /// The creep form's flow `T` (eta, with `C_v = 1`) when the layer flows, else its
    /// first retardation time.
    fn time_scale(&self) -> f64 {
        let form = self.creep_form();
        form.flow
            .map(|f| f.time)
            .or_else(|| form.branches.first().map(|b| b.time))
            .unwrap_or(1.0)
    }

    fn reference_compliance(&self) -> f64 {
        1.0
    }

    fn creep_form(&self) -> CreepForm {
        relaxation_to_creep(self.equilibrium_stiffness, &self.branches)
    }

    fn references(&self) -> Vec<Reference> {
        vec![
            Reference::new(
                provenance::TSCHOEGL,
                "the exact conversion of a relaxation Prony series to the creep form",
            ),
            Reference::new(
                provenance::PARK_SCHAPERY,
                "the exact conversion of a relaxation Prony series to the creep form",
            ),
        ]
    }
}

/// The exact creep form of a Prony series of relaxation stiffnesses,
/// `K(t) = K_inf + sum_i K_i exp(-t / rho_i)`.
///
/// In the Laplace domain the operational stiffness `K*(s) = K_inf + sum_i K_i s
/// rho_i / (1 + s rho_i)` and the operational compliance `C*(s) = C_g + sum_k C_k /
/// (1 + s tau_k) + 1 / (s eta)` are reciprocal (Tschoegl, *The Phenomenological
/// Theory of Linear Viscoelastic Behavior*, Springer 1989, ch. 4; Park & Schapery,
/// Int. J. Solids Struct. 36 (1999) 1653-1675). `K*` increases on the real axis
/// between its poles `-1/rho_i`, so it has exactly one zero `s_k = -1/tau_k` between
/// consecutive poles and one in `(-1/rho_max, 0)` when `K_inf > 0` (at `s = 0` when
/// `K_inf = 0`: the layer flows with `eta = sum K_i rho_i`). Then `C_g = 1 / K*(inf)`
/// and each residue gives `C_k = -1 / (s_k K*'(s_k))`. The zeros are found by
/// bisection on their brackets (written here: a bracketed scalar root needs no
/// crate), to the last bit.
pub fn relaxation_to_creep(equilibrium: f64, branches: &[RelaxationBranch]) -> CreepForm {
    let mut b = branches.to_vec();
    b.sort_by(|x, y| x.time.total_cmp(&y.time));
    let stiffness = |s: f64| {
        b.iter().fold(equilibrium, |sum, r| {
            sum + r.stiffness * s * r.time / (1.0 + s * r.time)
        })
    };
    let slope = |s: f64| {
        b.iter().fold(0.0, |sum, r| {
            let d = 1.0 + s * r.time;
            sum + r.stiffness * r.time / (d * d)
        })
    };
    let glassy = b.iter().fold(equilibrium, |s, r| s + r.stiffness);
    // Brackets (lo, hi) of the zeros in s, from the most negative pole.
    let poles: Vec<f64> = b.iter().map(|r| -1.0 / r.time).collect();
    let mut brackets: Vec<(f64, f64)> = poles.windows(2).map(|w| (w[0], w[1])).collect();
    if equilibrium > 0.0 {
        brackets.push((poles[poles.len() - 1], 0.0));
    }
    let mut out = Vec::with_capacity(brackets.len());
    for (lo, hi) in brackets {
        if lo == hi {
            // Two equal times are one branch: no zero between them.
            continue;
        }
        let (mut lo, mut hi) = (lo, hi);
        // K* rises from -inf just right of `lo` to +inf (or K_inf) at `hi`.
        loop {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if stiffness(mid) < 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let s = 0.5 * (lo + hi);
        out.push(RetardationBranch {
            compliance: -1.0 / (s * slope(s)),
            time: -1.0 / s,
        });
    }
    let flow = (equilibrium == 0.0).then(|| Flow {
        compliance: 1.0,
        time: b.iter().map(|r| r.stiffness * r.time).sum(),
    });
    CreepForm {
        glassy: 1.0 / glassy,
        branches: out,
        flow,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn relaxation_spectrum_converts_to_the_reciprocal_compliance() {
        // Independent check: K*(i omega) C*(i omega) = 1 at every frequency, with
        // K*(i omega) summed from the relaxation branches directly.
        let cases: Vec<(f64, Vec<RelaxationBranch>)> = vec![
            (
                1.0,
                vec![RelaxationBranch {
                    stiffness: 2.0,
                    time: 0.5,
                }],
            ),
            (
                0.3,
                (0..10)
                    .map(|k| RelaxationBranch {
                        stiffness: 1.0 + (k % 3) as f64,
                        time: 10f64.powi(k - 5),
                    })
                    .collect(),
            ),
            (
                0.0,
                (0..4)
                    .map(|k| RelaxationBranch {
                        stiffness: 0.5 * (k + 1) as f64,
                        time: 3f64.powi(k),
                    })
                    .collect(),
            ),
        ];
        for (k_inf, branches) in cases {
            let form = relaxation_to_creep(k_inf, &branches);
            assert_eq!(form.flow.is_some(), k_inf == 0.0);
            for e in -8..=8 {
                let omega = 10f64.powf(e as f64 * 0.75);
                let (mut kr, mut ki) = (k_inf, 0.0);
                for b in &branches {
                    let wt = omega * b.time;
                    let d = 1.0 + wt * wt;
                    kr += b.stiffness * wt * wt / d;
                    ki += b.stiffness * wt / d;
                }
                let (cr, ci) = form.complex_compliance(omega);
                let (pr, pi) = (kr * cr - ki * ci, kr * ci + ki * cr);
                assert!(
                    (pr - 1.0).abs() < 1e-10 && pi.abs() < 1e-10,
                    "K_inf {k_inf}, omega {omega}: {pr} + {pi} i"
                );
            }
            if k_inf > 0.0 {
                assert!((form.relaxed() * k_inf - 1.0).abs() < 1e-12);
            }
        }
    }
}
