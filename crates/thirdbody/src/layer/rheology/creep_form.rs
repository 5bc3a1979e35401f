//! The creep form every layer rheology reduces to: a glassy spring, Kelvin–Voigt
//! branches and a viscous flow in series, whose creep compliance is
//! `C(t) = C_g + sum_k C_k (1 - exp(-t / tau_k)) + C_v t / T` and complex compliance
//! `C*(omega) = C_g + sum_k C_k / (1 + i omega tau_k) + C_v / (i omega T)` (Tschoegl,
//! *The Phenomenological Theory of Linear Viscoelastic Behavior*, Springer 1989,
//! ch. 3-4). Compliances are displacement per pressure at zero pressure; the layer's
//! law multiplies every part by the same shape `phi(p) = C[p] / C[0]`.

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
