//! A linear viscoelastic half-space as a case gives it: a named rheology of its
//! Young's modulus in time (a solid: it stops creeping) and a constant Poisson ratio,
//! reduced to the tensile creep compliance `D(t) = D_g + sum_k D_k (1 - exp(-t /
//! tau_k))` (Tschoegl 1989, ch. 3-4) and, with the constant Poisson ratio, to the
//! plane-strain creep compliance `J(t) = (1 - nu^2) D(t)` the steady-sliding kernel
//! takes ([`super::viscoelastic`]). The rheologies are a Prony series of
//! compliances; a Prony series of relaxation moduli `E(t) = E_inf + sum E_i exp(-t /
//! rho_i)`, converted exactly (the layer's [`relaxation_to_creep`]); the standard
//! linear solid (`zener`: glassy and relaxed moduli and the relaxation time of
//! `E(t) = E_0 + (E_g - E_0) exp(-t / tau)`, whose creep form has one branch of
//! retardation time `tau E_g / E_0`); and the fractional Zener solid
//! `E*(omega) = E_0 + (E_g - E_0) (i omega tau)^a / (1 + (i omega tau)^a)`, whose
//! creep form is exactly `1 / E_g + (1 / E_0 - 1 / E_g) / (1 + (i omega tau_r)^a)`
//! with `tau_r = tau (E_g / E_0)^(1 / a)`, discretised into branches as the layer's
//! ([`fractional_zener_branches`]).
//!
//! Adding a solid rheology: a variant of [`SolidRheology`], its arms in this file
//! (`name`, `validate`, `scaled`, `tensile_creep`, `references`) and its keys in the
//! case file's `[substrate]` (`case_file.rs`, docs/case-file.md).

use super::viscoelastic::{CreepBranch, CreepSeries, ViscoelasticBody};
use crate::error::{require_poisson, require_positive, Error, Result};
use crate::layer::rheology::{
    fractional_zener_branch_count, fractional_zener_branches, relaxation_to_creep,
    RelaxationBranch, MAX_BRANCHES,
};
use crate::provenance::{self, Reference};

/// The time dependence of a viscoelastic solid's Young's modulus.
#[derive(Debug, Clone, PartialEq)]
pub enum SolidRheology {
    /// The standard linear solid: `E(t) = E_0 + (E_g - E_0) exp(-t / tau)`.
    Zener {
        /// `E_g`, the instantaneous modulus (>= `E_0`).
        glassy_modulus: f64,
        /// `E_0`, the long-time modulus (> 0).
        relaxed_modulus: f64,
        /// `tau`, the relaxation time (at constant strain).
        relaxation_time: f64,
    },
    /// The fractional Zener solid of order `a` (0 < a <= 1; 1 is [`Self::Zener`]).
    FractionalZener {
        /// `E_g`.
        glassy_modulus: f64,
        /// `E_0`.
        relaxed_modulus: f64,
        /// `tau`, the relaxation time of the modulus form.
        relaxation_time: f64,
        /// `a`.
        order: f64,
        /// Branches of the discretisation; `None`: as many as the order needs.
        branch_count: Option<usize>,
    },
    /// A Prony series of tensile creep compliances (retardation times).
    Prony {
        /// `D_g >= 0`.
        glassy_compliance: f64,
        /// `D_k >= 0`.
        branch_compliances: Vec<f64>,
        /// `tau_k > 0`.
        branch_times: Vec<f64>,
    },
    /// A Prony series of relaxation moduli, `E(t) = E_inf + sum E_i exp(-t / rho_i)`.
    RelaxationProny {
        /// `E_inf > 0` (a solid).
        equilibrium_modulus: f64,
        /// `E_i >= 0`.
        branch_moduli: Vec<f64>,
        /// `rho_i > 0`.
        branch_times: Vec<f64>,
    },
}

/// A linear viscoelastic half-space: its rheology and its (constant) Poisson ratio.
#[derive(Debug, Clone, PartialEq)]
pub struct ViscoelasticHalfSpace {
    /// How its Young's modulus depends on time.
    pub rheology: SolidRheology,
    /// Poisson's ratio, the same at every time.
    pub poisson: f64,
}

/// The case-file section the body's keys are in.
const SECTION: &str = "substrate";

fn field(key: &str) -> String {
    format!("{SECTION}.{key}")
}

fn require_non_negative(key: &str, value: f64) -> Result<()> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(&field(key), value, "a finite number >= 0"))
    }
}

/// Checks a list of branch values and their times (`values_key`, `branch_times`).
fn check_branches(values_key: &str, values: &[f64], times: &[f64]) -> Result<()> {
    if values.len() != times.len() {
        return Err(Error::invalid(
            &field("branch_times"),
            format!("{} times for {} branches", times.len(), values.len()),
            &format!("one time per entry of {}", field(values_key)),
        ));
    }
    if values.len() > MAX_BRANCHES {
        return Err(Error::invalid(
            &field(values_key),
            format!("{} branches", values.len()),
            &format!("at most {MAX_BRANCHES} branches"),
        ));
    }
    for (k, (&v, &t)) in values.iter().zip(times).enumerate() {
        require_non_negative(&format!("{values_key}[{k}]"), v)?;
        require_positive(&field(&format!("branch_times[{k}]")), t)?;
    }
    Ok(())
}

/// Checks `E_g >= E_0 > 0`.
fn check_moduli(glassy: f64, relaxed: f64) -> Result<()> {
    require_positive(&field("relaxed_modulus"), relaxed)?;
    require_positive(&field("glassy_modulus"), glassy)?;
    if glassy < relaxed {
        return Err(Error::invalid(
            &field("glassy_modulus"),
            glassy,
            &format!(
                "a modulus >= relaxed_modulus ({relaxed}): a solid is stiffest at once (its \
                 glassy compliance is below its relaxed one)"
            ),
        ));
    }
    Ok(())
}

impl SolidRheology {
    /// The name in case files (`[substrate] rheology = "..."`).
    pub fn name(&self) -> &'static str {
        match self {
            SolidRheology::Zener { .. } => "zener",
            SolidRheology::FractionalZener { .. } => "fractional_zener",
            SolidRheology::Prony { .. } => "prony",
            SolidRheology::RelaxationProny { .. } => "relaxation_prony",
        }
    }

    /// Checks every value; the error names the `[substrate]` key.
    pub fn validate(&self) -> Result<()> {
        match self {
            SolidRheology::Zener {
                glassy_modulus,
                relaxed_modulus,
                relaxation_time,
            } => {
                check_moduli(*glassy_modulus, *relaxed_modulus)?;
                require_positive(&field("relaxation_time"), *relaxation_time)
            }
            SolidRheology::FractionalZener {
                glassy_modulus,
                relaxed_modulus,
                relaxation_time,
                order,
                branch_count,
            } => {
                check_moduli(*glassy_modulus, *relaxed_modulus)?;
                require_positive(&field("relaxation_time"), *relaxation_time)?;
                if !(*order > 0.0 && *order <= 1.0) {
                    return Err(Error::invalid(&field("order"), order, "0 < order <= 1"));
                }
                if let Some(n) = branch_count {
                    if !(2..=MAX_BRANCHES).contains(n) {
                        return Err(Error::invalid(
                            &field("branch_count"),
                            n,
                            &format!("2 to {MAX_BRANCHES} branches"),
                        ));
                    }
                }
                Ok(())
            }
            SolidRheology::Prony {
                glassy_compliance,
                branch_compliances,
                branch_times,
            } => {
                require_non_negative("glassy_compliance", *glassy_compliance)?;
                check_branches("branch_compliances", branch_compliances, branch_times)?;
                let relaxed = glassy_compliance + branch_compliances.iter().sum::<f64>();
                if !(relaxed.is_finite() && relaxed > 0.0) {
                    return Err(Error::invalid(
                        &field("branch_compliances"),
                        relaxed,
                        "a finite relaxed compliance > 0 (glassy_compliance plus the \
                         branches' compliances)",
                    ));
                }
                Ok(())
            }
            SolidRheology::RelaxationProny {
                equilibrium_modulus,
                branch_moduli,
                branch_times,
            } => {
                if *equilibrium_modulus == 0.0 {
                    return Err(Error::invalid(
                        &field("equilibrium_modulus"),
                        0.0,
                        "a modulus > 0: a body with none flows without end under a \
                         steady load (a fluid has no steady sliding contact)",
                    ));
                }
                require_positive(&field("equilibrium_modulus"), *equilibrium_modulus)?;
                check_branches("branch_moduli", branch_moduli, branch_times)?;
                let glassy = equilibrium_modulus + branch_moduli.iter().sum::<f64>();
                require_positive(&field("branch_moduli"), glassy)
            }
        }
    }

    /// The same rheology with moduli divided by `modulus` and times by `time` (the
    /// solver's units).
    pub fn scaled(&self, modulus: f64, time: f64) -> SolidRheology {
        match self {
            SolidRheology::Zener {
                glassy_modulus,
                relaxed_modulus,
                relaxation_time,
            } => SolidRheology::Zener {
                glassy_modulus: glassy_modulus / modulus,
                relaxed_modulus: relaxed_modulus / modulus,
                relaxation_time: relaxation_time / time,
            },
            SolidRheology::FractionalZener {
                glassy_modulus,
                relaxed_modulus,
                relaxation_time,
                order,
                branch_count,
            } => SolidRheology::FractionalZener {
                glassy_modulus: glassy_modulus / modulus,
                relaxed_modulus: relaxed_modulus / modulus,
                relaxation_time: relaxation_time / time,
                order: *order,
                branch_count: *branch_count,
            },
            SolidRheology::Prony {
                glassy_compliance,
                branch_compliances,
                branch_times,
            } => SolidRheology::Prony {
                glassy_compliance: glassy_compliance * modulus,
                branch_compliances: branch_compliances.iter().map(|c| c * modulus).collect(),
                branch_times: branch_times.iter().map(|t| t / time).collect(),
            },
            SolidRheology::RelaxationProny {
                equilibrium_modulus,
                branch_moduli,
                branch_times,
            } => SolidRheology::RelaxationProny {
                equilibrium_modulus: equilibrium_modulus / modulus,
                branch_moduli: branch_moduli.iter().map(|m| m / modulus).collect(),
                branch_times: branch_times.iter().map(|t| t / time).collect(),
            },
        }
    }

    /// The tensile creep compliance `D(t)` as a Prony series (retardation times).
    pub fn tensile_creep(&self) -> CreepSeries {
        let branch = |compliance: f64, retardation_time: f64| CreepBranch {
            compliance,
            retardation_time,
        };
        match self {
            SolidRheology::Zener {
                glassy_modulus,
                relaxed_modulus,
                relaxation_time,
            } => CreepSeries {
                glassy: 1.0 / glassy_modulus,
                branches: vec![branch(
                    1.0 / relaxed_modulus - 1.0 / glassy_modulus,
                    relaxation_time * (glassy_modulus / relaxed_modulus),
                )],
            },
            SolidRheology::FractionalZener {
                glassy_modulus,
                relaxed_modulus,
                relaxation_time,
                order,
                branch_count,
            } => {
                let retarded = 1.0 / relaxed_modulus - 1.0 / glassy_modulus;
                let tau = relaxation_time * (glassy_modulus / relaxed_modulus).powf(1.0 / order);
                let n = branch_count.unwrap_or_else(|| fractional_zener_branch_count(*order));
                CreepSeries {
                    glassy: 1.0 / glassy_modulus,
                    branches: fractional_zener_branches(retarded, tau, *order, n)
                        .into_iter()
                        .map(|b| branch(b.compliance, b.time))
                        .collect(),
                }
            }
            SolidRheology::Prony {
                glassy_compliance,
                branch_compliances,
                branch_times,
            } => CreepSeries {
                glassy: *glassy_compliance,
                branches: branch_compliances
                    .iter()
                    .zip(branch_times)
                    .map(|(&c, &t)| branch(c, t))
                    .collect(),
            },
            SolidRheology::RelaxationProny {
                equilibrium_modulus,
                branch_moduli,
                branch_times,
            } => {
                let relaxation: Vec<RelaxationBranch> = branch_moduli
                    .iter()
                    .zip(branch_times)
                    .filter(|(&m, _)| m > 0.0)
                    .map(|(&stiffness, &time)| RelaxationBranch { stiffness, time })
                    .collect();
                if relaxation.is_empty() {
                    return CreepSeries {
                        glassy: 1.0 / equilibrium_modulus,
                        branches: Vec::new(),
                    };
                }
                let creep = relaxation_to_creep(*equilibrium_modulus, &relaxation);
                CreepSeries {
                    glassy: creep.glassy,
                    branches: creep
                        .branches
                        .iter()
                        .map(|b| branch(b.compliance, b.time))
                        .collect(),
                }
            }
        }
    }

    /// The works its creep form comes from.
    pub fn references(&self) -> Vec<Reference> {
        let mut works = vec![Reference::new(
            provenance::TSCHOEGL,
            "the body's creep compliance as a Prony series (creep form of a linear \
             viscoelastic solid)",
        )];
        match self {
            SolidRheology::RelaxationProny { .. } => works.push(Reference::new(
                provenance::PARK_SCHAPERY,
                "the body's relaxation Prony series converted to creep form",
            )),
            SolidRheology::FractionalZener { .. } => works.extend([
                Reference::new(
                    provenance::MAINARDI,
                    "the body's fractional Zener rheology and its retardation spectrum",
                ),
                Reference::new(
                    provenance::TREFETHEN_WEIDEMAN,
                    "the body's fractional Zener spectrum discretised into branches",
                ),
            ]),
            SolidRheology::Zener { .. } | SolidRheology::Prony { .. } => {}
        }
        works
    }
}

impl ViscoelasticHalfSpace {
    /// Checks the rheology and the Poisson ratio; errors name the `[substrate]` key.
    pub fn validate(&self) -> Result<()> {
        self.rheology.validate()?;
        require_poisson(&field("poisson"), self.poisson)
    }

    /// The same body in the solver's units (moduli over `modulus`, times over
    /// `time`).
    pub fn scaled(&self, modulus: f64, time: f64) -> ViscoelasticHalfSpace {
        ViscoelasticHalfSpace {
            rheology: self.rheology.scaled(modulus, time),
            poisson: self.poisson,
        }
    }

    /// The plane-strain creep compliance `J(t) = (1 - nu^2) D(t)`.
    pub fn plane_strain_creep(&self) -> CreepSeries {
        let factor = 1.0 - self.poisson * self.poisson;
        let tensile = self.rheology.tensile_creep();
        CreepSeries {
            glassy: factor * tensile.glassy,
            branches: tensile
                .branches
                .iter()
                .map(|b| CreepBranch {
                    compliance: factor * b.compliance,
                    retardation_time: b.retardation_time,
                })
                .collect(),
        }
    }

    /// The relaxed (long-time) Young's modulus.
    pub fn relaxed_modulus(&self) -> f64 {
        1.0 / self.rheology.tensile_creep().relaxed()
    }

    /// The geometric mean of the retardation times (a time scale for the solver's
    /// units).
    pub fn time_scale(&self) -> f64 {
        let creep = self.rheology.tensile_creep();
        let times: Vec<f64> = creep
            .branches
            .iter()
            .map(|b| b.retardation_time)
            .filter(|t| t.is_finite() && *t > 0.0)
            .collect();
        if times.is_empty() {
            return 1.0;
        }
        (times.iter().map(|t| t.ln()).sum::<f64>() / times.len() as f64).exp()
    }

    /// Its model for the solvers.
    pub fn model(&self) -> ViscoelasticBody {
        ViscoelasticBody {
            creep: self.plane_strain_creep(),
            poisson: self.poisson,
            references: self.rheology.references(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn zener(eg: f64, e0: f64, tau: f64) -> SolidRheology {
        SolidRheology::Zener {
            glassy_modulus: eg,
            relaxed_modulus: e0,
            relaxation_time: tau,
        }
    }

    /// The creep compliance at time t of a series.
    fn creep_at(c: &CreepSeries, t: f64) -> f64 {
        c.branches.iter().fold(c.glassy, |s, b| {
            s + b.compliance * (1.0 - (-t / b.retardation_time).exp())
        })
    }

    #[test]
    fn zener_creep_form_inverts_its_relaxation_modulus() {
        // The Laplace-domain identity s E~(s) s D~(s) = 1 of a linear solid
        // (Tschoegl ch. 4), checked on the real axis: with E(t) = E0 + (Eg - E0)
        // exp(-t / tau), s E~(s) = E0 + (Eg - E0) s tau / (1 + s tau); with the creep
        // series, s D~(s) = Dg + sum Dk / (1 + s tau_k).
        let (eg, e0, tau) = (10.0, 2.0, 0.3);
        let creep = zener(eg, e0, tau).tensile_creep();
        for s in [1e-3, 0.1, 1.0, 3.7, 100.0, 1e4] {
            let se = e0 + (eg - e0) * s * tau / (1.0 + s * tau);
            let sd = creep.branches.iter().fold(creep.glassy, |acc, b| {
                acc + b.compliance / (1.0 + s * b.retardation_time)
            });
            assert!((se * sd - 1.0).abs() < 1e-14, "s {s}: {}", se * sd);
        }
        // The retardation time is tau Eg / E0 (closed form).
        assert!((creep.branches[0].retardation_time - tau * eg / e0).abs() < 1e-15);
        assert!((creep_at(&creep, 1e9) - 1.0 / e0).abs() < 1e-15);
    }

    #[test]
    fn a_one_branch_relaxation_series_is_the_zener_solid() {
        let (eg, e0, tau) = (7.0, 1.5, 2.0);
        let series = SolidRheology::RelaxationProny {
            equilibrium_modulus: e0,
            branch_moduli: vec![eg - e0],
            branch_times: vec![tau],
        }
        .tensile_creep();
        let z = zener(eg, e0, tau).tensile_creep();
        assert!((series.glassy - z.glassy).abs() < 1e-15);
        let (a, b) = (series.branches[0], z.branches[0]);
        assert!((a.compliance - b.compliance).abs() < 1e-14 * b.compliance);
        assert!((a.retardation_time - b.retardation_time).abs() < 1e-13 * b.retardation_time);
    }

    #[test]
    fn fractional_zener_of_order_one_is_the_zener_solid_and_keeps_its_limits() {
        let (eg, e0, tau) = (20.0, 1.0, 0.01);
        let one = SolidRheology::FractionalZener {
            glassy_modulus: eg,
            relaxed_modulus: e0,
            relaxation_time: tau,
            order: 1.0,
            branch_count: None,
        }
        .tensile_creep();
        assert_eq!(one, zener(eg, e0, tau).tensile_creep());
        // Order 0.4: the complex compliance of the branches against the closed form
        // 1/Eg + (1/E0 - 1/Eg) / (1 + (i w tau_r)^a) at a few frequencies, and the
        // glassy and relaxed compliances exact.
        let a = 0.4;
        let half = SolidRheology::FractionalZener {
            glassy_modulus: eg,
            relaxed_modulus: e0,
            relaxation_time: tau,
            order: a,
            branch_count: None,
        }
        .tensile_creep();
        assert!((half.glassy - 1.0 / eg).abs() < 1e-15);
        assert!((half.relaxed() - 1.0 / e0).abs() < 1e-12);
        let tau_r = tau * (eg / e0).powf(1.0 / a);
        for w in [1e-2 / tau_r, 1.0 / tau_r, 1e2 / tau_r] {
            // (i w tau_r)^a = (w tau_r)^a (cos(a pi/2) + i sin(a pi/2)).
            let m = (w * tau_r).powf(a);
            let (re, im) = (
                1.0 + m * (a * std::f64::consts::FRAC_PI_2).cos(),
                m * (a * std::f64::consts::FRAC_PI_2).sin(),
            );
            let d1 = 1.0 / e0 - 1.0 / eg;
            let exact = (
                1.0 / eg + d1 * re / (re * re + im * im),
                -d1 * im / (re * re + im * im),
            );
            let (mut sr, mut si) = (half.glassy, 0.0);
            for b in &half.branches {
                let x = w * b.retardation_time;
                sr += b.compliance / (1.0 + x * x);
                si -= b.compliance * x / (1.0 + x * x);
            }
            // The discretisation's accuracy (the layer's rule: 1 % of the loss peak).
            assert!(
                (sr - exact.0).abs() < 0.01 * d1,
                "w {w}: {sr} vs {}",
                exact.0
            );
            assert!(
                (si - exact.1).abs() < 0.01 * d1,
                "w {w}: {si} vs {}",
                exact.1
            );
        }
    }

    #[test]
    fn bad_solids_name_the_key() {
        let err = |r: SolidRheology| {
            ViscoelasticHalfSpace {
                rheology: r,
                poisson: 0.3,
            }
            .validate()
            .unwrap_err()
            .to_string()
        };
        assert!(err(zener(1.0, 2.0, 1.0)).contains("substrate.glassy_modulus"));
        assert!(err(zener(2.0, 1.0, -1.0)).contains("substrate.relaxation_time"));
        assert!(err(zener(2.0, 0.0, 1.0)).contains("substrate.relaxed_modulus"));
        let prony = |g: f64, c: Vec<f64>, t: Vec<f64>| SolidRheology::Prony {
            glassy_compliance: g,
            branch_compliances: c,
            branch_times: t,
        };
        assert!(err(prony(-1.0, vec![1.0], vec![1.0])).contains("substrate.glassy_compliance"));
        assert!(err(prony(1.0, vec![-1.0], vec![1.0])).contains("substrate.branch_compliances[0]"));
        assert!(err(prony(1.0, vec![1.0], vec![0.0])).contains("substrate.branch_times[0]"));
        assert!(err(prony(1.0, vec![1.0], vec![1.0, 2.0])).contains("substrate.branch_times"));
        assert!(err(prony(0.0, vec![0.0], vec![1.0])).contains("substrate.branch_compliances"));
        let fluid = SolidRheology::RelaxationProny {
            equilibrium_modulus: 0.0,
            branch_moduli: vec![1.0],
            branch_times: vec![1.0],
        };
        assert!(err(fluid).contains("substrate.equilibrium_modulus"));
        let order = SolidRheology::FractionalZener {
            glassy_modulus: 2.0,
            relaxed_modulus: 1.0,
            relaxation_time: 1.0,
            order: 1.5,
            branch_count: None,
        };
        assert!(err(order).contains("substrate.order"));
        let poisson = ViscoelasticHalfSpace {
            rheology: zener(2.0, 1.0, 1.0),
            poisson: 0.5,
        };
        assert!(poisson
            .validate()
            .unwrap_err()
            .to_string()
            .contains("substrate.poisson"));
    }
}
