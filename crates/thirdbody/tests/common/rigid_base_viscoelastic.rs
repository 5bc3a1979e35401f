//! Semi-analytic reference for a paraboloid slider on a linear Kelvin–Voigt or Zener
//! (standard linear solid) layer over a RIGID base (docs/architecture.md
//! (conventions) with `w_body = 0`). It shares no code with the solver: the layer is
//! derived here from its equations; only `brent`, `gauss_legendre`,
//! `panel_quadrature` and `z_minus_one_minus_exp` come from `rigid_base.rs`.
//!
//! # The layers
//!
//! * Kelvin–Voigt: one branch, `tau dw/dt + w = C p`: no instantaneous part, no flow.
//! * Zener: a glassy spring in series with one Kelvin–Voigt branch,
//!   `w = C_g p + w1`, `tau dw1/dt + w1 = C_1 p`; relaxed compliance `C_r = C_g + C_1`.
//!
//! Kelvin–Voigt is Zener with `C_g = 0`, `C_1 = C`; the formulas below are written
//! for Zener and specialised.
//!
//! # Derivation
//!
//! Frame fixed to the slider, material moves in -x at speed V, so along the
//! material path `d/dt = -V d/dx`. With the creep length `L = V tau` the branch law
//! is `w1 - L w1' = C_1 p` (' = d/dx), and material arriving unloaded from
//! `x = +inf` gives `w1(x) = (C_1 / L) int_x^inf exp(-(s - x) / L) p(s) ds`.
//! On a rigid base the contact condition is `w = D - f` where p > 0 and the gap
//! `w + f - D >= 0` where p = 0, with `f = (x^2 + y^2) / (2R)`. w at x depends on
//! p at `s >= x` only, so rows (fixed y) couple only through D. For a row write
//! `b = sqrt(2 R D - y^2)` and `h(x) = D - f = (b^2 - x^2) / (2R)`.
//!
//! **Leading edge.** Ahead of `x = b`, `h < 0 <= w` (w is a positive combination of
//! upstream p): no contact, p = 0, w = 0. Behind b, `h > 0 = w` would be
//! penetration, so contact starts exactly at `x = b`, where `w1(b) = 0` (w1 is an
//! integral of p; a Dirac mass of p at b would make `w(b-) > h(b) = 0` and open a
//! gap behind it, contradicting `h > w` there).
//!
//! **Zener row.** In contact `C_g p + w1 = h`. At b, `w1 = h = 0` gives `p(b) = 0`:
//! with a glassy spring the pressure rises continuously from the leading edge.
//! Eliminating w1 with the branch law:
//! `L C_g p' - C_r p = L h' - h = (x^2 - 2 L x - b^2) / (2R)`, `p(b) = 0`.
//! With `lambda = L C_g / C_r` and `L1 = L C_1 / C_r = L - lambda`, a quadratic
//! particular solution plus the homogeneous `exp((x - b) / lambda)` (which decays in
//! the direction of integration, -x) give, with `u = b - x`,
//!
//! `p(x) = [b^2 - x^2 + 2 L1 (x + lambda) - 2 L1 (b + lambda) exp(-u / lambda)] / (2 R C_r)`,
//!
//! evaluated as `[u (b + x) + 2 L1 E(u)] / (2 R C_r)` with
//! `E = b (1 - e^-z) - lambda (z - 1 + e^-z)`, `z = u / lambda` (no cancellation of
//! lambda-sized terms when lambda >> b). Its slope at b is `p'(b) = -b / (R C_g)`
//! (the glassy Winkler slope). p is concave in x (a concave quadratic minus a
//! positive multiple of an exponential), `p(b) = 0`, `p'(b) < 0`: it is positive
//! on one interval `(x_t, b)` and its other zero `x_t` is the trailing edge.
//! Bounds: at a zero of p the ODE gives `L C_g p' = (x^2 - 2Lx - b^2) / (2R)`, and
//! the trailing zero needs `p'(x_t) >= 0`, so `x_t <= L - sqrt(L^2 + b^2) < 0`
//! (the Kelvin–Voigt trailing edge, below); and `p(-b) = L1 E(2b) / (R C_r) < 0`
//! because `E(2b) = lambda [(1 + z/2)(1 - e^-z) - z] < 0` for `z = 2b / lambda > 0`,
//! so `-b < x_t`. x_t is found by Brent's method on that bracket.
//!
//! **Gap behind the Zener row.** For `x < x_t`, p = 0 and the branch recovers:
//! `w = w1(x_t) exp((x - x_t) / L)`, so the gap `g(x) = w1(x_t) e^((x - x_t)/L) - h(x)`
//! is convex (exponential plus `x^2 / 2R`), `g(x_t) = 0` (`w1(x_t) = h(x_t)`), and
//! `g'(x_t) = w1(x_t) / L + x_t / R = -C_g p'(x_t) <= 0` (from the branch law at
//! `x_t`, `w1' = w1 / L`, and `w1' = h' - C_g p'` in contact). A convex function
//! with a zero of non-positive slope at x_t is `>= 0` for `x < x_t`: the gap stays
//! open. With p >= 0 on `(x_t, b)` and the gap open elsewhere, this row is a
//! solution of the complementarity problem, and the only one: the map `p -> w` has
//! the symbol `C_g + C_1 / (1 + i k L)` whose real part is positive, so the linear
//! complementarity problem is monotone with a unique solution.
//!
//! **Kelvin–Voigt row** (`C_g = 0`). The contact condition gives p directly:
//! `C p = h - L h' = (b^2 - x^2 + 2 L x) / (2R)`, i.e.
//!
//! `p(x) = [b^2 + L^2 - (x - L)^2] / (2 R C)` on `(x_t, b)`,
//!
//! with a JUMP at the leading edge, `p(b) = L b / (R C)` (the branch cannot deform
//! instantaneously, so the slider meets a layer as stiff as the dashpot; w itself
//! is continuous). This is the `C_g -> 0` limit of the Zener row: the homogeneous
//! term becomes a boundary layer of width `lambda -> 0` at b (the tests check it).
//! Trailing edge: `x_t = L - sqrt(L^2 + b^2) = -b^2 / (L + sqrt(L^2 + b^2))`.
//! Behind it `g(x_t) = 0`, `g'(x_t) = w(x_t) / L + x_t / R = 0` (p(x_t) = 0 means
//! `w(x_t) = L h'(x_t) = -L x_t / R`) and g is strictly convex: the gap is open.
//! The same holds for the leading edge: ahead of b there is no load. Row maximum:
//! at `x = min(L, b)`.
//!
//! **Row load and moment.** Integrating the row ODE over `(x_t, b)`
//! (`p(x_t) = p(b) = 0` for Zener; for Kelvin–Voigt the relation is algebraic):
//! `C_r W = L h(x_t) + int h dx`, i.e.
//!
//! `W = [(b - x_t)^2 (2b + x_t) / 3 + L (b - x_t)(b + x_t)] / (2 R C_r)`,
//!
//! a sum of positive terms because `-b < x_t < 0`. Multiplying by x first:
//! `C_r M = L C_1 W + L h_t (x_t - L) + R h_t^2 / 2`, `h_t = h(x_t)` (checked in the
//! tests; it cancels badly, so the reference integrates `x p` by composite
//! Gauss–Legendre with panels graded from the leading edge, the first no longer than
//! lambda / 2). For Kelvin–Voigt `x_t^2 - 2 L x_t = b^2` turns it into
//! `M = L W - L^2 b^2 / (2 R C)`, and the reference uses the cancellation-free
//! `M = [(b^2 - x_t^2)^2 / 4 + 2 L (b^3 - x_t^3) / 3] / (2 R C)` (direct integration).
//!
//! **Monotonicity in b.** `dp/db` at fixed x is `b / (R C)` (Kelvin–Voigt) or
//! `[b + L1 b e^(-u/lambda) / lambda] / (R C_r)` (Zener): positive. So p grows with
//! b at every x, the trailing edge moves back as b grows (p concave in x), and the
//! row `y = 0` (`b = b0`) holds both the largest pressure and the smallest x_t.
//!
//! **The whole contact.** The leading edges form the half circle `x^2 + y^2 = 2 R D`
//! (for both layers), so `Q(D) = int_{-b0}^{b0} W(b(y)) dy`, `b0 = sqrt(2 R D)`.
//! With `y = b0 sin(theta)` the integrand `W(b0 cos theta) b0 cos theta` is smooth
//! and Gauss–Legendre in theta converges fast. D is found from `Q(D) = Q` by Brent's
//! method on b0 (Q grows with b0). `mu = M / (R Q)` (docs/architecture.md
//! (conventions)); `p_max` and its x are the row `y = 0`'s; `x_max = y_max = b0`,
//! `x_min = x_t(b0)`.
//!
//! **Kelvin–Voigt in closed form** (a check of the row quadrature, used by the tests).
//! `p = [rho^2 - (x - L)^2 - y^2] / (2 R C)` with `rho^2 = b0^2 + L^2`: a paraboloid
//! centred at `(L, 0)` vanishing on the circle of radius rho through `(0, +-b0)`.
//! The contact is the half disc `x >= 0, x^2 + y^2 <= b0^2` plus the segment of that
//! circle with `x <= 0`. With `a = b0`,
//! `2 R C Q = pi a^4 / 4 + 4 L a^3 / 3 + S`, `2 R C M = L (pi a^4 / 4 + S)`,
//! `S = (4/3) int_L^rho (rho^2 - v^2)^(3/2) dv
//!    = (4/3) [(3 rho^4 / 8) atan(a / L) - (L a / 8)(5 rho^2 - 2 L^2)]`,
//! so `mu = (L / R) (1 - 2 L a^3 / (3 R C Q))` exactly.
//!
//! # Limits
//!
//! * Winkler bed of compliance c: `p = (D - f) / c` on a disc of radius
//!   `a = sqrt(2 R D) = (4 R c Q / pi)^(1/4)`, `Q = pi R D^2 / c`, `p_max = D / c` at
//!   the centre, mu = 0.
//! * `L -> inf`: Zener -> Winkler with `c = C_g`; first order
//!   `mu = C_1 a^2 / (3 R L C_g)` (a Maxwell layer of compliance C_g and creep length
//!   `L C_g / C_1`). Kelvin–Voigt -> rigid: the half disc, `p = L x / (R C)`,
//!   `a = (3 R C Q / (2L))^(1/3)`, D -> 0, `p_max = L a / (R C)` at `x = a`,
//!   `mu -> 3 pi a / (16 R)`, `x_min -> 0`.
//! * `L -> 0`: both -> Winkler with the relaxed compliance (C_r, or C), with
//!   `mu = L C_1 / (R C_r)` to first order (`p = (b^2 - x^2 + 2 L1 x) / (2 R C_r)`
//!   away from the leading-edge layer, so `M = L1 Q`).
#![allow(dead_code)]

use super::rigid_base::{
    brent, contact_radius, for_each_row, panel_quadrature, z_minus_one_minus_exp,
};

/// Gauss–Legendre nodes across the y range (in theta, one half by symmetry).
pub const ROWS: usize = 64;

/// The layer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Rheology {
    /// `tau dw/dt + w = C p`.
    KelvinVoigt {
        /// C.
        compliance: f64,
    },
    /// `w = C_g p + w1`, `tau dw1/dt + w1 = C_1 p`.
    Zener {
        /// C_g (> 0).
        glassy: f64,
        /// C_1 (> 0).
        branch: f64,
    },
}

impl Rheology {
    /// Relaxed compliance `C_r` (C for Kelvin–Voigt).
    pub fn relaxed(&self) -> f64 {
        match *self {
            Rheology::KelvinVoigt { compliance } => compliance,
            Rheology::Zener { glassy, branch } => glassy + branch,
        }
    }

    /// Glassy compliance (0 for Kelvin–Voigt).
    pub fn glassy(&self) -> f64 {
        match *self {
            Rheology::KelvinVoigt { .. } => 0.0,
            Rheology::Zener { glassy, .. } => glassy,
        }
    }

    /// Branch compliance `C_1` (C for Kelvin–Voigt).
    pub fn branch(&self) -> f64 {
        match *self {
            Rheology::KelvinVoigt { compliance } => compliance,
            Rheology::Zener { branch, .. } => branch,
        }
    }
}

/// A slider on a viscoelastic layer over a rigid base.
#[derive(Debug, Clone, Copy)]
pub struct ViscoelasticRigidBase {
    /// Slider radius R (paraboloid).
    pub radius: f64,
    /// Creep length `L = V tau`.
    pub creep_length: f64,
    /// Normal load Q.
    pub load: f64,
    /// The layer.
    pub rheology: Rheology,
}

/// The solution along one row.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Row {
    /// Leading edge b (largest x in contact).
    pub leading_edge: f64,
    /// Trailing edge x_t (smallest x in contact).
    pub trailing_edge: f64,
    /// `int p dx`.
    pub load: f64,
    /// `int x p dx`.
    pub moment: f64,
    /// Largest pressure along the row.
    pub max_pressure: f64,
    /// Where it is.
    pub max_pressure_x: f64,
}

/// The reference for the whole contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reference {
    /// Approach D.
    pub approach: f64,
    /// `b0 = sqrt(2 R D)`: leading edge on y = 0 and half extent in y.
    pub contact_radius: f64,
    /// Largest pressure (on the row y = 0).
    pub max_pressure: f64,
    /// x of the largest pressure (y = 0).
    pub max_pressure_x: f64,
    /// `mu = M / (R Q)`.
    pub friction_coefficient: f64,
    /// Smallest x in contact (trailing edge of the row y = 0).
    pub x_min: f64,
    /// Largest x in contact, `b0`.
    pub x_max: f64,
    /// Half extent in y, `b0`.
    pub y_max: f64,
}

/// Kelvin–Voigt layer (`tau dw/dt + w = C p`) on a rigid base.
pub fn kelvin_voigt(
    radius: f64,
    load: f64,
    compliance: f64,
    relaxation_time: f64,
    velocity: f64,
) -> Reference {
    ViscoelasticRigidBase {
        radius,
        creep_length: velocity * relaxation_time,
        load,
        rheology: Rheology::KelvinVoigt { compliance },
    }
    .solve()
}

/// Zener layer (`w = C_g p + w1`, `tau dw1/dt + w1 = C_1 p`) on a rigid base.
pub fn zener(
    radius: f64,
    load: f64,
    glassy: f64,
    branch: f64,
    relaxation_time: f64,
    velocity: f64,
) -> Reference {
    ViscoelasticRigidBase {
        radius,
        creep_length: velocity * relaxation_time,
        load,
        rheology: Rheology::Zener { glassy, branch },
    }
    .solve()
}

impl ViscoelasticRigidBase {
    /// `lambda = L C_g / C_r` and `L1 = L C_1 / C_r` (0 and L for Kelvin–Voigt).
    fn lengths(&self) -> (f64, f64) {
        let c = &self.rheology;
        let l = self.creep_length;
        (l * c.glassy() / c.relaxed(), l * c.branch() / c.relaxed())
    }

    /// The row's closed-form pressure at `x <= b`, NOT clipped at the trailing edge
    /// (negative behind it). For Kelvin–Voigt its value at b is the jump
    /// `L b / (R C)`.
    pub fn pressure_formula(&self, b: f64, x: f64) -> f64 {
        let (r, cr) = (self.radius, self.rheology.relaxed());
        let u = b - x;
        match self.rheology {
            Rheology::KelvinVoigt { .. } => {
                (u * (b + x) + 2.0 * self.creep_length * x) / (2.0 * r * cr)
            }
            Rheology::Zener { .. } => {
                let (lambda, l1) = self.lengths();
                let z = u / lambda;
                let e = b * (-(-z).exp_m1()) - lambda * z_minus_one_minus_exp(z);
                (u * (b + x) + 2.0 * l1 * e) / (2.0 * r * cr)
            }
        }
    }

    /// `dp/dx` of [`Self::pressure_formula`].
    pub fn pressure_slope(&self, b: f64, x: f64) -> f64 {
        let (r, cr) = (self.radius, self.rheology.relaxed());
        match self.rheology {
            Rheology::KelvinVoigt { .. } => (self.creep_length - x) / (r * cr),
            Rheology::Zener { .. } => {
                let (lambda, l1) = self.lengths();
                let z = (b - x) / lambda;
                -(x + l1 * (b / lambda * (-z).exp() + (-z).exp_m1())) / (r * cr)
            }
        }
    }

    /// The row pressure: the closed form on `[x_t, b]`, 0 elsewhere.
    pub fn pressure(&self, b: f64, trailing_edge: f64, x: f64) -> f64 {
        if x > b || x < trailing_edge {
            0.0
        } else {
            self.pressure_formula(b, x).max(0.0)
        }
    }

    /// Trailing edge of the row with leading edge b.
    pub fn trailing_edge(&self, b: f64) -> f64 {
        let l = self.creep_length;
        // The Kelvin–Voigt trailing edge L - sqrt(L^2 + b^2), without cancellation.
        let kv = -b * b / (l + l.hypot(b));
        match self.rheology {
            Rheology::KelvinVoigt { .. } => kv,
            Rheology::Zener { .. } => {
                // -b < x_t <= kv (module comment).
                let p = |x: f64| self.pressure_formula(b, x);
                if p(kv) <= 0.0 {
                    return kv;
                }
                brent(p, -b, kv, 1e-15 * b)
            }
        }
    }

    /// One row with leading edge `b > 0`.
    pub fn row(&self, b: f64) -> Row {
        let (r, cr, l) = (self.radius, self.rheology.relaxed(), self.creep_length);
        let xt = self.trailing_edge(b);
        let (d, s) = (b - xt, b + xt);
        let load = (d * d * (2.0 * b + xt) / 3.0 + l * d * s) / (2.0 * r * cr);
        match self.rheology {
            Rheology::KelvinVoigt { .. } => {
                let moment = ((d * s) * (d * s) / 4.0 + 2.0 * l * (b.powi(3) - xt.powi(3)) / 3.0)
                    / (2.0 * r * cr);
                let xm = l.min(b);
                Row {
                    leading_edge: b,
                    trailing_edge: xt,
                    load,
                    moment,
                    max_pressure: self.pressure_formula(b, xm),
                    max_pressure_x: xm,
                }
            }
            Rheology::Zener { .. } => {
                let (lambda, _) = self.lengths();
                let moment =
                    panel_quadrature(|x| x * self.pressure_formula(b, x), xt, b, 0.5 * lambda);
                // p is concave: its slope falls from >= 0 at x_t to -b / (R C_g) at b.
                let slope = |x: f64| self.pressure_slope(b, x);
                let xm = if slope(xt) <= 0.0 {
                    xt
                } else {
                    brent(slope, xt, b, 1e-15 * b)
                };
                Row {
                    leading_edge: b,
                    trailing_edge: xt,
                    load,
                    moment,
                    max_pressure: self.pressure_formula(b, xm),
                    max_pressure_x: xm,
                }
            }
        }
    }

    /// Load and moment of a contact of radius b0, by Gauss–Legendre in theta
    /// (`y = b0 sin theta`), and the row y = 0.
    pub fn contact(&self, b0: f64, rows: usize) -> (f64, f64, Row) {
        let (mut load, mut moment) = (0.0, 0.0);
        for_each_row(b0, rows, |b, weight| {
            let row = self.row(b);
            load += weight * row.load;
            moment += weight * row.moment;
        });
        (load, moment, self.row(b0))
    }

    /// The reference solution: D from the load, then mu, max pressure and extents.
    pub fn solve(&self) -> Reference {
        self.solve_with(ROWS)
    }

    /// As [`Self::solve`] with a given number of Gauss–Legendre rows.
    pub fn solve_with(&self, rows: usize) -> Reference {
        let excess = |b0: f64| self.contact(b0, rows).0 / self.load - 1.0;
        // Start from the relaxed Winkler radius and bracket.
        let winkler = (4.0 * self.radius * self.rheology.relaxed() * self.load
            / std::f64::consts::PI)
            .powf(0.25);
        let b0 = contact_radius(excess, winkler);
        let (load, moment, centre) = self.contact(b0, rows);
        Reference {
            approach: b0 * b0 / (2.0 * self.radius),
            contact_radius: b0,
            max_pressure: centre.max_pressure,
            max_pressure_x: centre.max_pressure_x,
            friction_coefficient: moment / (self.radius * load),
            x_min: centre.trailing_edge,
            x_max: b0,
            y_max: b0,
        }
    }
}

/// Kelvin–Voigt load and moment of a contact of radius `a` in closed form (half
/// disc plus circular segment; module comment): `(Q, M)`.
pub fn kelvin_voigt_closed_form(
    radius: f64,
    compliance: f64,
    creep_length: f64,
    a: f64,
) -> (f64, f64) {
    let (l, pi) = (creep_length, std::f64::consts::PI);
    let rho2 = a * a + l * l;
    let segment = 4.0 / 3.0
        * (3.0 * rho2 * rho2 / 8.0 * (a / l).atan() - l * a / 8.0 * (5.0 * rho2 - 2.0 * l * l));
    let scale = 2.0 * radius * compliance;
    let quarter = pi * a.powi(4) / 4.0;
    (
        (quarter + 4.0 * l * a.powi(3) / 3.0 + segment) / scale,
        l * (quarter + segment) / scale,
    )
}
