//! Layer rheologies in one creep form. Every linear viscoelastic solid or fluid
//! whose creep compliance is a discrete spectrum,
//! `C(t) = C_g + sum_k C_k (1 - exp(-t / tau_k)) + C_v t / T`,
//! is a glassy spring (`C_g`), Kelvin–Voigt branches (`C_k`, retardation time
//! `tau_k`) and a viscous flow (`C_v / T`) in series ([`CreepForm`]); the layer's
//! pressure dependence multiplies every part by the same shape `phi(p) = C[p] / C[0]`
//! ([`super::law`]). The named presets ([`Rheology`]) map onto this form: the
//! paper's Maxwell body (eq. 2), Kelvin–Voigt, Zener (standard linear solid),
//! Burgers, a Prony series of compliances, a Prony series of relaxation stiffnesses
//! (converted exactly, [`relaxation_to_creep`]) and a fractional Zener body
//! discretised into branches ([`fractional_zener_branches`]).

use crate::error::{require_positive, Error, Result};

/// The largest number of branches a layer may have.
pub const MAX_BRANCHES: usize = 1000;

/// A Kelvin–Voigt branch: `tau dw/dt + w = C phi(p) p` (linear law: `C p`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RetardationBranch {
    /// Compliance `C_k` at zero pressure (displacement per pressure).
    pub compliance: f64,
    /// Retardation time `tau_k`.
    pub time: f64,
}

/// A Maxwell branch of a relaxation spectrum: a spring of stiffness `K_i`
/// (pressure per displacement) relaxing with time `rho_i`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RelaxationBranch {
    /// Stiffness `K_i` (pressure per displacement; a film of thickness t and
    /// modulus M has K = M / t).
    pub stiffness: f64,
    /// Relaxation time `rho_i`.
    pub time: f64,
}

/// The viscous flow of a layer: `dw_v/dt = C_v phi(p) p / T`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Flow {
    /// `C_v` (only `C_v / T`, the fluidity, matters).
    pub compliance: f64,
    /// `T`.
    pub time: f64,
}

/// The creep form every rheology reduces to: glassy spring, Kelvin–Voigt branches
/// and viscous flow in series.
#[derive(Debug, Clone, PartialEq)]
pub struct CreepForm {
    /// Glassy (instantaneous) compliance `C_g` >= 0.
    pub glassy: f64,
    /// Kelvin–Voigt branches.
    pub branches: Vec<RetardationBranch>,
    /// Viscous flow, if the layer is a fluid.
    pub flow: Option<Flow>,
}

impl CreepForm {
    /// The relaxed compliance `C_g + sum C_k` (the long-time compliance of a solid;
    /// of a fluid without its flow).
    pub fn relaxed(&self) -> f64 {
        self.branches
            .iter()
            .fold(self.glassy, |sum, b| sum + b.compliance)
    }

    /// The creep compliance `C(t)` at zero pressure.
    pub fn creep_compliance(&self, t: f64) -> f64 {
        let flow = self.flow.map_or(0.0, |f| f.compliance * t / f.time);
        self.branches.iter().fold(self.glassy + flow, |sum, b| {
            sum + b.compliance * -(-t / b.time).exp_m1()
        })
    }

    /// The complex compliance `C*(omega) = C_g + sum C_k / (1 + i omega tau_k) +
    /// C_v / (i omega T)` as (real, imaginary).
    pub fn complex_compliance(&self, omega: f64) -> (f64, f64) {
        let (mut re, mut im) = (self.glassy, 0.0);
        for b in &self.branches {
            let wt = omega * b.time;
            let d = 1.0 + wt * wt;
            re += b.compliance / d;
            im -= b.compliance * wt / d;
        }
        if let Some(f) = self.flow {
            im -= f.compliance / (omega * f.time);
        }
        (re, im)
    }
}

/// A layer rheology as a case names it.
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
    /// discretised into `branch_count` Kelvin–Voigt branches.
    FractionalZener {
        /// C_g >= 0.
        glassy_compliance: f64,
        /// C1 (the relaxed compliance is C_g + C1).
        compliance: f64,
        /// tau.
        retardation_time: f64,
        /// alpha, 0 < alpha <= 1 (1: the Zener body).
        order: f64,
        /// Number of branches of the discretisation, 2 ..= 1000.
        branch_count: usize,
    },
}

impl Rheology {
    /// The preset's name in case files.
    pub fn name(&self) -> &'static str {
        match self {
            Rheology::Maxwell { .. } => "maxwell",
            Rheology::KelvinVoigt { .. } => "kelvin_voigt",
            Rheology::Zener { .. } => "zener",
            Rheology::Burgers { .. } => "burgers",
            Rheology::Prony { .. } => "prony",
            Rheology::RelaxationProny { .. } => "relaxation_prony",
            Rheology::FractionalZener { .. } => "fractional_zener",
        }
    }

    /// Checks the parameters, naming the case-file key of a bad one.
    pub fn validate(&self) -> Result<()> {
        match self {
            Rheology::Maxwell {
                compliance,
                relaxation_time,
            } => {
                require_positive("layer.compliance", *compliance)?;
                require_positive("layer.relaxation_time", *relaxation_time)
            }
            Rheology::KelvinVoigt {
                compliance,
                retardation_time,
            } => {
                require_positive("layer.compliance", *compliance)?;
                require_positive("layer.retardation_time", *retardation_time)
            }
            Rheology::Zener {
                glassy_compliance,
                compliance,
                retardation_time,
            } => {
                require_positive("layer.glassy_compliance", *glassy_compliance)?;
                require_positive("layer.compliance", *compliance)?;
                require_positive("layer.retardation_time", *retardation_time)
            }
            Rheology::Burgers {
                glassy_compliance,
                relaxation_time,
                compliance,
                retardation_time,
            } => {
                require_positive("layer.glassy_compliance", *glassy_compliance)?;
                require_positive("layer.relaxation_time", *relaxation_time)?;
                require_positive("layer.compliance", *compliance)?;
                require_positive("layer.retardation_time", *retardation_time)
            }
            Rheology::Prony {
                glassy_compliance,
                branches,
                viscosity,
            } => {
                require_non_negative("layer.glassy_compliance", *glassy_compliance)?;
                require_branch_count("layer.branch_compliances", branches.len())?;
                for (k, b) in branches.iter().enumerate() {
                    require_positive(&format!("layer.branch_compliances[{k}]"), b.compliance)?;
                    require_positive(&format!("layer.branch_times[{k}]"), b.time)?;
                }
                if let Some(eta) = viscosity {
                    require_positive("layer.viscosity", *eta)?;
                }
                Ok(())
            }
            Rheology::RelaxationProny {
                equilibrium_stiffness,
                branches,
            } => {
                require_non_negative("layer.equilibrium_stiffness", *equilibrium_stiffness)?;
                require_branch_count("layer.branch_stiffnesses", branches.len())?;
                for (k, b) in branches.iter().enumerate() {
                    require_positive(&format!("layer.branch_stiffnesses[{k}]"), b.stiffness)?;
                    require_positive(&format!("layer.branch_times[{k}]"), b.time)?;
                }
                let glassy = branches
                    .iter()
                    .fold(*equilibrium_stiffness, |s, b| s + b.stiffness);
                if !glassy.is_finite() {
                    return Err(Error::invalid(
                        "layer.branch_stiffnesses",
                        glassy,
                        "stiffnesses whose sum (the glassy stiffness) is finite",
                    ));
                }
                Ok(())
            }
            Rheology::FractionalZener {
                glassy_compliance,
                compliance,
                retardation_time,
                order,
                branch_count,
            } => {
                require_non_negative("layer.glassy_compliance", *glassy_compliance)?;
                require_positive("layer.compliance", *compliance)?;
                require_positive("layer.retardation_time", *retardation_time)?;
                if !(*order > 0.0 && *order <= 1.0) {
                    return Err(Error::invalid("layer.order", *order, "0 < order <= 1"));
                }
                if !(2..=MAX_BRANCHES).contains(branch_count) {
                    return Err(Error::invalid(
                        "layer.branch_count",
                        *branch_count,
                        &format!("an integer from 2 to {MAX_BRANCHES}"),
                    ));
                }
                Ok(())
            }
        }
    }

    /// The creep form of the preset (parameters assumed valid).
    pub fn creep_form(&self) -> CreepForm {
        let branch = |compliance, time| RetardationBranch { compliance, time };
        match self {
            &Rheology::Maxwell {
                compliance,
                relaxation_time,
            } => CreepForm {
                glassy: compliance,
                branches: vec![],
                flow: Some(Flow {
                    compliance,
                    time: relaxation_time,
                }),
            },
            &Rheology::KelvinVoigt {
                compliance,
                retardation_time,
            } => CreepForm {
                glassy: 0.0,
                branches: vec![branch(compliance, retardation_time)],
                flow: None,
            },
            &Rheology::Zener {
                glassy_compliance,
                compliance,
                retardation_time,
            } => CreepForm {
                glassy: glassy_compliance,
                branches: vec![branch(compliance, retardation_time)],
                flow: None,
            },
            &Rheology::Burgers {
                glassy_compliance,
                relaxation_time,
                compliance,
                retardation_time,
            } => CreepForm {
                glassy: glassy_compliance,
                branches: vec![branch(compliance, retardation_time)],
                flow: Some(Flow {
                    compliance: glassy_compliance,
                    time: relaxation_time,
                }),
            },
            Rheology::Prony {
                glassy_compliance,
                branches,
                viscosity,
            } => CreepForm {
                glassy: *glassy_compliance,
                branches: branches.clone(),
                flow: viscosity.map(|eta| Flow {
                    compliance: 1.0,
                    time: eta,
                }),
            },
            Rheology::RelaxationProny {
                equilibrium_stiffness,
                branches,
            } => relaxation_to_creep(*equilibrium_stiffness, branches),
            &Rheology::FractionalZener {
                glassy_compliance,
                compliance,
                retardation_time,
                order,
                branch_count,
            } => CreepForm {
                glassy: glassy_compliance,
                branches: fractional_zener_branches(
                    compliance,
                    retardation_time,
                    order,
                    branch_count,
                ),
                flow: None,
            },
        }
    }
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

    #[test]
    fn presets_map_onto_the_creep_form() {
        let z = Rheology::Zener {
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
        let m = Rheology::Maxwell {
            compliance: 0.02,
            relaxation_time: 3.0,
        }
        .creep_form();
        assert!((m.creep_compliance(6.0) - 0.02 * 3.0).abs() < 1e-16);
        let bu = Rheology::Burgers {
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
