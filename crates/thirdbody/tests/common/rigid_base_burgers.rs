//! Closed-form reference for a paraboloid slider on a linear Burgers layer (a glassy
//! spring, one Kelvin–Voigt branch and a viscous flow in series) over a RIGID base,
//! row by row. It shares no code with the solver: the layer is derived here from
//! its equations; only `brent` and `gauss_legendre` come from `rigid_base.rs`, and
//! the [`Reference`] it returns is the one of `rigid_base_viscoelastic.rs`.
//!
//! # Derivation
//!
//! Frame fixed to the slider, material moving in -x at speed V. Along a row (fixed
//! y) measure `u = b - x` from the leading edge b, so that `d/dt = V d/du` along
//! the material path. The layer is
//!
//! `w = C_g p + w1 + wv`, `L w1' + w1 = C_1 p` (`L = V tau`), `wv' = c p`
//! (`c = C_v / (V T)`), `' = d/du`,
//!
//! and in contact `w = H(u) = D - f = (2 b u - u^2) / (2R)` with `b = sqrt(2RD -
//! y^2)`. Material arrives unloaded (`w1 = wv = 0` at u = 0), so `p(0) = H(0) / C_g
//! = 0`: with a glassy spring the pressure rises from the leading edge, which lies
//! where the gap closes, at u = 0, as for the Zener layer.
//!
//! **Particular solution.** With `p = alpha + beta u`, `w1 = gamma + delta u` and
//! `wv = eps + zeta u + eta u^2` the three equations give, power by power,
//! `zeta = c alpha`, `eta = c beta / 2`, `delta = C_1 beta`, `gamma = C_1 (alpha -
//! L beta)`, and from the contact condition `eta = -1 / (2R)`, so `beta = -1 / (R
//! c)`, `alpha = (b / R - (C_g + C_1) beta) / c` and `eps = -(C_g + C_1) alpha + L
//! C_1 beta`.
//!
//! **Homogeneous solutions** `p = A e^(s u)` need `C_g + C_1 / (1 + L s) + c / s =
//! 0`, i.e. `Q(s) = C_g L s^2 + (C_g + C_1 + c L) s + c = 0`. `Q(0) = c > 0`, `Q(-1
//! / L) = -C_1 / L < 0` and `Q(-inf) > 0`: two real roots, one in `(-1/L, 0)` and
//! one below `-1/L`, both decaying along u; with them `w1 = C_1 A / (1 + L s) e^(s
//! u)` and `wv = c A / s e^(s u)`. The two amplitudes follow from `w1(0) = wv(0) =
//! 0`; `p(0) = 0` then holds by the contact condition (checked). Without the glassy
//! spring (`C_g = 0`, a Kelvin–Voigt branch and a flow) `Q(s) = (C_1 + c L) s + c`
//! has one root, its amplitude follows from `w1(0) = 0` (then `wv(0) = H(0) - w1(0)
//! = 0` by the contact condition), and the pressure jumps at the edge to `p(0) =
//! alpha + A`.
//!
//! **Trailing edge.** p rises from 0, and its particular part falls with slope
//! `beta < 0`; the first zero `U` of p after the edge ends the contact. Behind it
//! p = 0, the branch recovers and the flow stays: the gap `w1(U) e^(-(u - U)/L) +
//! wv(U) - H(u)` must stay open, which the solution asserts on a fine sample.
//!
//! **Row integrals** in closed form: `int_0^U p du = alpha U + beta U^2 / 2 + sum A
//! (e^(sU) - 1) / s` and `int_0^U u p du = alpha U^2/2 + beta U^3/3 + sum A (U
//! e^(sU) / s - (e^(sU) - 1) / s^2)`; the moment about x = 0 is `b int p - int u p`.
//! Rows are summed over y by Gauss–Legendre in `y = b0 sin(phi)`, D is found by
//! Brent's method on the load, and `mu = int x p dA / (R Q)` (the pressure's pull
//! on the slope `x / R` of the slider).

#![allow(dead_code)]

use super::rigid_base::{brent, contact_radius, for_each_row};
use super::rigid_base_viscoelastic::Reference;

/// A slider on a linear Burgers layer over a rigid base.
#[derive(Debug, Clone, Copy)]
pub struct BurgersRigidBase {
    /// Slider radius R (paraboloid).
    pub radius: f64,
    /// Normal load Q.
    pub load: f64,
    /// Glassy compliance C_g (>= 0).
    pub glassy: f64,
    /// Branch compliance C_1 (> 0).
    pub branch: f64,
    /// The branch's creep length `L = V tau`.
    pub branch_length: f64,
    /// Flow compliance C_v.
    pub flow: f64,
    /// The flow's creep length `V T`.
    pub flow_length: f64,
}

/// One row's closed form: `p(u) = alpha + beta u + sum_m A_m e^(s_m u)`.
#[derive(Debug, Clone, Copy)]
pub struct BurgersRow {
    /// Leading edge b.
    pub leading_edge: f64,
    alpha: f64,
    beta: f64,
    amplitudes: [f64; 2],
    roots: [f64; 2],
    /// Particular parts of w1 (gamma, delta) and wv (eps, zeta, eta).
    branch_particular: [f64; 2],
    flow_particular: [f64; 3],
    /// Their homogeneous factors per root: `C_1 / (1 + L s)` and `c / s`.
    branch_factor: [f64; 2],
    flow_factor: [f64; 2],
    /// The trailing edge's distance from the leading edge, U.
    pub length: f64,
}

impl BurgersRow {
    /// Pressure at u (not clipped: the closed form).
    pub fn pressure(&self, u: f64) -> f64 {
        self.alpha
            + self.beta * u
            + (0..2)
                .map(|m| self.amplitudes[m] * (self.roots[m] * u).exp())
                .sum::<f64>()
    }

    fn slope(&self, u: f64) -> f64 {
        self.beta
            + (0..2)
                .map(|m| self.amplitudes[m] * self.roots[m] * (self.roots[m] * u).exp())
                .sum::<f64>()
    }

    fn branch(&self, u: f64) -> f64 {
        let [g, d] = self.branch_particular;
        g + d * u
            + (0..2)
                .map(|m| self.branch_factor[m] * self.amplitudes[m] * (self.roots[m] * u).exp())
                .sum::<f64>()
    }

    fn flow(&self, u: f64) -> f64 {
        let [e, z, h] = self.flow_particular;
        e + z * u
            + h * u * u
            + (0..2)
                .map(|m| self.flow_factor[m] * self.amplitudes[m] * (self.roots[m] * u).exp())
                .sum::<f64>()
    }

    /// `int_0^U p du`.
    pub fn load(&self) -> f64 {
        let u = self.length;
        self.alpha * u
            + 0.5 * self.beta * u * u
            + (0..2)
                .map(|m| self.amplitudes[m] * (self.roots[m] * u).exp_m1() / self.roots[m])
                .sum::<f64>()
    }

    /// `int x p dx` over the row, x = b - u.
    pub fn moment(&self) -> f64 {
        let u = self.length;
        let first: f64 = self.alpha * u * u / 2.0
            + self.beta * u * u * u / 3.0
            + (0..2)
                .map(|m| {
                    let s = self.roots[m];
                    self.amplitudes[m] * (u * (s * u).exp() / s - (s * u).exp_m1() / (s * s))
                })
                .sum::<f64>();
        self.leading_edge * self.load() - first
    }

    /// Largest pressure and its distance u from the leading edge (at the edge
    /// where the pressure jumps there and falls from it).
    pub fn peak(&self) -> (f64, f64) {
        if self.slope(0.0) <= 0.0 {
            return (self.pressure(0.0), 0.0);
        }
        let u = brent(|u| self.slope(u), 0.0, self.length, 1e-15 * self.length);
        (self.pressure(u), u)
    }
}

impl BurgersRigidBase {
    /// The row with leading edge `b > 0`.
    pub fn row(&self, b: f64) -> BurgersRow {
        let (r, cg, c1, l) = (self.radius, self.glassy, self.branch, self.branch_length);
        let c = self.flow / self.flow_length;
        let beta = -1.0 / (r * c);
        let alpha = (b / r - (cg + c1) * beta) / c;
        let gamma = c1 * (alpha - l * beta);
        let delta = c1 * beta;
        let eps = -(cg + c1) * alpha + l * c1 * beta;
        // Q(s) = cg L s^2 + B s + c, B = cg + c1 + c L: the roots without
        // cancellation.
        let big_b = cg + c1 + c * l;
        let (roots, amplitudes, branch_factor, flow_factor);
        if cg > 0.0 {
            let q = -0.5 * (big_b + (big_b * big_b - 4.0 * cg * l * c).sqrt());
            roots = [q / (cg * l), c / q];
            branch_factor = roots.map(|s| c1 / (1.0 + l * s));
            flow_factor = roots.map(|s| c / s);
            // w1(0) = 0 and wv(0) = 0.
            let det = branch_factor[0] * flow_factor[1] - branch_factor[1] * flow_factor[0];
            amplitudes = [
                (-gamma * flow_factor[1] + eps * branch_factor[1]) / det,
                (-eps * branch_factor[0] + gamma * flow_factor[0]) / det,
            ];
        } else {
            // One root; the second term unused (amplitude 0, any decaying root).
            roots = [-c / big_b, -1.0];
            branch_factor = roots.map(|s| c1 / (1.0 + l * s));
            flow_factor = roots.map(|s| c / s);
            amplitudes = [-gamma / branch_factor[0], 0.0];
            assert!((eps + flow_factor[0] * amplitudes[0]).abs() <= 1e-9 * eps.abs());
        }
        let mut row = BurgersRow {
            leading_edge: b,
            alpha,
            beta,
            amplitudes,
            roots,
            branch_particular: [gamma, delta],
            flow_particular: [eps, c * alpha, 0.5 * c * beta],
            branch_factor,
            flow_factor,
            length: 0.0,
        };
        let scale = alpha.abs() + amplitudes[0].abs() + amplitudes[1].abs();
        assert!(
            cg == 0.0 || row.pressure(0.0).abs() < 1e-9 * scale,
            "p(0) = {} (scale {scale})",
            row.pressure(0.0)
        );
        // The first zero after the edge: the particular part's zero bounds it.
        let end = -alpha / beta + 10.0 * (1.0 / roots[0].abs()).max(1.0 / roots[1].abs());
        let n = 4000;
        let mut lo = 0.0;
        let mut found = None;
        for k in 1..=n {
            let u = end * k as f64 / n as f64;
            if row.pressure(u) < 0.0 {
                found = Some((lo, u));
                break;
            }
            lo = u;
        }
        let (lo, hi) = found.expect("the row's pressure returns to zero");
        row.length = brent(|u| row.pressure(u), lo, hi, 1e-15 * end);
        // Behind the trailing edge the gap stays open.
        let (w1, wv) = (row.branch(row.length), row.flow(row.length));
        let h = |u: f64| (2.0 * b * u - u * u) / (2.0 * r);
        for k in 1..=n {
            let u = row.length + (2.0 * b + 4.0 * l) * k as f64 / n as f64;
            let gap = w1 * (-(u - row.length) / l).exp() + wv - h(u);
            assert!(
                gap >= -1e-9 * h(b),
                "the gap closes again behind the row b = {b} at u = {u}: {gap}"
            );
        }
        row
    }

    /// Load and moment of a contact of radius b0, and the row y = 0.
    pub fn contact(&self, b0: f64, rows: usize) -> (f64, f64, BurgersRow) {
        let (mut load, mut moment) = (0.0, 0.0);
        for_each_row(b0, rows, |b, weight| {
            let row = self.row(b);
            load += weight * row.load();
            moment += weight * row.moment();
        });
        (load, moment, self.row(b0))
    }

    /// The reference: D from the load, then mu, the peak and the extents.
    pub fn solve(&self) -> Reference {
        let rows = 64;
        let excess = |b0: f64| self.contact(b0, rows).0 / self.load - 1.0;
        // The slow limit's half disc, `Q = (4/3) V T b0^3 / (2 R C_v)`, as a start.
        let b0 = contact_radius(
            excess,
            (3.0 * self.load * 2.0 * self.radius * self.flow / (4.0 * self.flow_length)).cbrt(),
        );
        let (load, moment, centre) = self.contact(b0, rows);
        let (peak, at) = centre.peak();
        Reference {
            approach: b0 * b0 / (2.0 * self.radius),
            contact_radius: b0,
            max_pressure: peak,
            max_pressure_x: b0 - at,
            friction_coefficient: moment / (self.radius * load),
            x_min: b0 - centre.length,
            x_max: b0,
            y_max: b0,
        }
    }
}
