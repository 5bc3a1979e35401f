//! Semi-analytic reference for a paraboloid slider on a Maxwell layer over a RIGID
//! base (docs/architecture.md (conventions) with `w_body = 0`). It shares no code with the solver: only
//! the compliance law `C[p]` is taken as given (a closure), everything else is
//! derived here.
//!
//! # Derivation
//!
//! Frame fixed to the slider, material moves in -x. On a rigid base the contact
//! condition is `w3(x, y) = D - f(x, y)` with `f = (x^2 + y^2) / (2R)`, and rows
//! (fixed y) couple only through the approach D. Write `L = V T` (the creep length)
//! and, for a row, `b = sqrt(2 R D - y^2)`, so that `D - f = (b^2 - x^2) / (2R)`.
//! Material arrives unloaded: for x > b the slider is above the layer (`f > D`),
//! p = 0 and w3 = 0. At the leading edge x = b, `w3 = 0` forces `p = 0`.
//!
//! **Linear law** (C = C0). With `P(x) = int_x^b p ds` (so `p = -P'`) the layer law
//! `w3 = C0 p + (C0 / L) P` turns the contact condition into the linear ODE
//! `-C0 P' + (C0 / L) P = (b^2 - x^2) / (2R)`, `P(b) = 0`. Differentiating once,
//! `p' = p / L - x / (R C0)`, `p(b) = 0`, whose solution is
//!
//! `p(x) = (L / (R C0)) [x + L - (b + L) exp(-(b - x) / L)]`.
//!
//! `p` is concave with `p(b) = 0` and `p'(b) = -b / (R C0) < 0`, so it is positive on
//! an interval `(x_t, b)` and its second zero, the trailing edge, solves (with
//! `z = (b - x_t) / L`) `(1 - e^-z) / z = L / (b + L)`, which has exactly one root
//! z > 0 (the left side falls from 1 to 0). Since `p(0) > 0`, `x_t < 0`, so behind
//! the trailing edge the frozen creep `w3 = D - f(x_t)` exceeds `D - f(x)`: the gap
//! is open and the row solution is the exact solution of the complementarity
//! problem. Evaluating the contact condition at `x_t` (where p = 0) gives the row
//! load `W = P(x_t) = L (b^2 - x_t^2) / (2 R C0)`. The row's first moment follows
//! from `x = R C0 (p / L - p')` and `p(x_t) = p(b) = 0`:
//! `int x p dx = (R C0 / L) int p^2 dx`, which is positive (so mu > 0) and is
//! integrated by Gauss–Legendre without the cancellation of the closed form of
//! `int x p` when b << L. The row's maximum, where `p' = 0`, is at
//! `x_m = b - L ln(1 + b / L)` with `p(x_m) = L x_m / (R C0)`.
//!
//! **Exact integration, any law.** `w3 = G(p) + (1/L) int_x^inf C[p] p ds` with
//! `G' = C`; differentiating the contact condition along x gives
//! `C[p] p' = C[p] p / L - x / R`, i.e. `p' = p / L - x / (R C[p])`, `p(b) = 0`.
//! It is integrated with classical RK4 from `x = b` towards -x (fixed steps of
//! `min(b, L) / STEPS_PER_LENGTH`) together with the row load and moment, until p
//! returns to 0; the last step is shortened to land on `p = 0` exactly (root of the
//! RK4 step in its length). The row maximum is refined on the step where `p'`
//! changes sign with the cubic Hermite interpolant of `(p, p')`. Where p = 0 and
//! x > 0 the ODE gives `dp/d(-x) = x / (R C0) > 0`, so p cannot return to 0 ahead
//! of x = 0: `x_t <= 0` and, as for the linear law, the gap stays open behind.
//!
//! **Secant integration, any law.** `w3 = q + (1/L) int_x^inf q ds` with
//! `q = C[p] p`: the ODE is linear in q, `q' = q / L - x / R`, so q is the linear
//! solution above with `C0 = 1`: the trailing edge does not depend on the law, and
//! `p = q^{-1}(q(x))` pointwise (q(p) must be increasing). Load and moment are
//! integrated with composite Gauss–Legendre over `(x_t, b)`; the maximum is at
//! `x_m` (p grows with q).
//!
//! **The whole contact.** The leading edges `x = b(y)` form the half circle
//! `x^2 + y^2 = 2 R D`, so `Q(D) = int_{-b0}^{b0} W(b(y)) dy` with `b0 = sqrt(2RD)`.
//! With `y = b0 sin(theta)` the integrand `W(b0 cos theta) b0 cos theta` is smooth
//! (the row load vanishes like `b^3`), and Gauss–Legendre in theta converges fast.
//! D is found from `Q(D) = Q` by Brent's method on b0 (Q grows with b0). Then
//! `mu = (1/Q) int int p df/dx = M / (R Q)` with `M = int int x p`, the maximum
//! pressure is the largest row maximum, and the extents are `x_max = b0`,
//! `|y| <= b0`, `x_min = min over rows of x_t`.
#![allow(dead_code)]

/// RK4 steps per `min(b, L)` in the exact-integration rows.
pub const STEPS_PER_LENGTH: f64 = 400.0;

/// Gauss–Legendre nodes across the y range (in theta, one half by symmetry).
pub const ROWS: usize = 64;

/// How the layer is modelled.
pub enum Law<'a> {
    /// Constant compliance: closed form.
    Linear {
        /// C0.
        compliance: f64,
    },
    /// Exact integration of eq. 2 with compliance `C[p]`: RK4.
    Exact(&'a dyn Fn(f64) -> f64),
    /// Secant integration with compliance `C[p]`: closed form for `C[p] p`, inverted.
    Secant(&'a dyn Fn(f64) -> f64),
}

/// A slider on a layer over a rigid base.
#[derive(Debug, Clone, Copy)]
pub struct RigidBase {
    /// Slider radius R (paraboloid).
    pub radius: f64,
    /// Creep length `L = V T`.
    pub creep_length: f64,
    /// Normal load Q.
    pub load: f64,
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
    /// `int C[p] p dx`: by the contact condition at the trailing edge (p = 0 there)
    /// it equals `L (b^2 - x_t^2) / (2R)`, a check of the integrated form.
    pub creep_integral: f64,
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
    /// Largest pressure.
    pub max_pressure: f64,
    /// `mu = M / (R Q)`.
    pub friction_coefficient: f64,
    /// Smallest x in contact (trailing edge).
    pub x_min: f64,
    /// Largest x in contact, `b0`.
    pub x_max: f64,
    /// Half extent in y, `b0`.
    pub y_max: f64,
}

/// Linear-law pressure along a row with leading edge b (closed form).
pub fn linear_pressure(x: f64, b: f64, creep_length: f64, radius: f64, compliance: f64) -> f64 {
    let l = creep_length;
    if x >= b {
        return 0.0;
    }
    // x + L - (b + L) e^{-u/L} = (b + L)(1 - e^{-u/L}) - u, written without the
    // cancellation of the two large terms when L >> b.
    let u = b - x;
    l / (radius * compliance) * ((b + l) * (-(-u / l).exp_m1()) - u)
}

/// `z > 0` with `(1 + beta)(1 - e^-z) = z`, beta = b / L > 0: the trailing edge of
/// a linear row is at `b - L z` (equivalently `(1 - e^-z) / z = L / (b + L)`).
pub fn trailing_edge_depth(beta: f64) -> f64 {
    // beta (1 - e^-z) - (z - (1 - e^-z)): positive just above 0, negative at
    // z = 1 + beta (where it equals -(1 + beta) e^-(1 + beta)).
    let g = |z: f64| beta * (-(-z).exp_m1()) - z_minus_one_minus_exp(z);
    let hi = 1.0 + beta;
    // Near 0, g = beta z - (1 + beta) z^2 / 2 + ..., positive below 2 beta / (1 + beta).
    let lo = 1e-3 * beta / (1.0 + beta);
    if g(hi) >= 0.0 {
        // beta >~ 30: the root is within rounding of 1 + beta.
        return hi;
    }
    brent(g, lo, hi, 1e-16 * hi)
}

/// `x_t = b - L z`, which also equals `-L + (b + L) e^-z` (the root's equation);
/// the second form keeps x_t's digits when b >> L.
fn trailing_edge(b: f64, l: f64, z: f64) -> f64 {
    if z < 1.0 {
        b - l * z
    } else {
        -l + (b + l) * (-z).exp()
    }
}

/// `z - (1 - e^-z)` without cancellation for small z.
pub fn z_minus_one_minus_exp(z: f64) -> f64 {
    if z < 0.05 {
        // z^2/2 - z^3/6 + z^4/24 - ...: terms to z^9 leave < 1e-17 relative.
        let mut term = z * z / 2.0;
        let mut sum = 0.0;
        for k in 3..12 {
            sum += term;
            term *= -z / k as f64;
        }
        sum
    } else {
        z + (-z).exp_m1()
    }
}

impl RigidBase {
    /// One row with leading edge `b` > 0.
    pub fn row(&self, law: &Law, b: f64) -> Row {
        match *law {
            Law::Linear { compliance } => self.linear_row(b, compliance),
            Law::Exact(c) => self.exact_row(b, c),
            Law::Secant(c) => self.secant_row(b, c),
        }
    }

    fn linear_row(&self, b: f64, compliance: f64) -> Row {
        let (l, r) = (self.creep_length, self.radius);
        let s = l / (r * compliance);
        let z = trailing_edge_depth(b / l);
        let xt = trailing_edge(b, l, z);
        // b^2 - x_t^2 factored through b - x_t = L z.
        let load = s * l * z * (b + xt) / 2.0;
        // The moment from x = R C0 (p / L - p') and p(x_t) = p(b) = 0:
        // int x p = (R C0 / L) int p^2, a positive integrand (the closed form of
        // int x p cancels badly when b << L).
        let p = |x: f64| linear_pressure(x, b, l, r, compliance);
        let moment = r * compliance / l * panel_quadrature(|x| p(x) * p(x), xt, b, 0.5 * l);
        let xm = b - l * (b / l).ln_1p();
        Row {
            leading_edge: b,
            trailing_edge: xt,
            load,
            moment,
            creep_integral: compliance * load,
            max_pressure: s * xm,
            max_pressure_x: xm,
        }
    }

    fn exact_row(&self, b: f64, compliance: &dyn Fn(f64) -> f64) -> Row {
        let (l, r) = (self.creep_length, self.radius);
        // State along s = b - x: (p, int p, int x p, int C p); d/ds = (-p', p, x p, C p).
        let rhs = |s: f64, y: [f64; 4]| -> [f64; 4] {
            let x = b - s;
            let c = compliance(y[0].max(0.0));
            [x / (r * c) - y[0] / l, y[0], x * y[0], c * y[0]]
        };
        let step = |s: f64, y: [f64; 4], h: f64| -> [f64; 4] {
            let k1 = rhs(s, y);
            let k2 = rhs(s + h / 2.0, add(y, k1, h / 2.0));
            let k3 = rhs(s + h / 2.0, add(y, k2, h / 2.0));
            let k4 = rhs(s + h, add(y, k3, h));
            let mut out = y;
            for k in 0..4 {
                out[k] += h / 6.0 * (k1[k] + 2.0 * k2[k] + 2.0 * k3[k] + k4[k]);
            }
            out
        };
        let h = b.min(l) / STEPS_PER_LENGTH;
        let (mut s, mut y) = (0.0, [0.0; 4]);
        let (mut pmax, mut xmax) = (0.0, b);
        let mut slope = rhs(0.0, y)[0];
        loop {
            let next = step(s, y, h);
            if next[0] <= 0.0 && s > 0.0 {
                // Land on p = 0: root of the RK4 step in its length.
                let sigma = brent(|t| step(s, y, t)[0], 0.0, h, 1e-15 * h);
                let end = step(s, y, sigma);
                return Row {
                    leading_edge: b,
                    trailing_edge: b - s - sigma,
                    load: end[1],
                    moment: end[2],
                    creep_integral: end[3],
                    max_pressure: pmax,
                    max_pressure_x: xmax,
                };
            }
            let next_slope = rhs(s + h, next)[0];
            if slope > 0.0 && next_slope <= 0.0 {
                // The maximum is inside this step: cubic Hermite of (p, dp/ds).
                let cubic = |t: f64| hermite(y[0], next[0], slope * h, next_slope * h, t);
                let t = golden_max(cubic, 0.0, 1.0);
                if cubic(t) > pmax {
                    pmax = cubic(t);
                    xmax = b - s - t * h;
                }
            }
            if next[0] > pmax {
                pmax = next[0];
                xmax = b - s - h;
            }
            s += h;
            y = next;
            slope = next_slope;
            assert!(s < 1e3 * (b + l), "row did not close: b = {b}");
        }
    }

    fn secant_row(&self, b: f64, compliance: &dyn Fn(f64) -> f64) -> Row {
        let (l, r) = (self.creep_length, self.radius);
        // q = C[p] p is the linear solution with C0 = 1.
        let z = trailing_edge_depth(b / l);
        let xt = trailing_edge(b, l, z);
        let invert = |q: f64| -> f64 {
            if q <= 0.0 {
                return 0.0;
            }
            let c0 = compliance(0.0);
            let mut hi = q / c0;
            while compliance(hi) * hi < q {
                hi *= 2.0;
            }
            brent(|p| compliance(p) * p - q, 0.0, hi, 1e-15 * hi)
        };
        let creep = |x: f64| linear_pressure(x, b, l, r, 1.0);
        let pressure = |x: f64| invert(creep(x));
        // Composite Gauss-Legendre, panels no longer than L/2 (p varies on L).
        let [load, moment, creep_integral] = panel_quadrature(
            |x| {
                let p = pressure(x);
                [p, x * p, compliance(p) * p]
            },
            xt,
            b,
            0.5 * l,
        );
        let xm = b - l * (b / l).ln_1p();
        Row {
            leading_edge: b,
            trailing_edge: xt,
            load,
            moment,
            creep_integral,
            max_pressure: pressure(xm),
            max_pressure_x: xm,
        }
    }

    /// Load, moment, largest pressure and smallest trailing edge for a contact of
    /// radius b0, by Gauss–Legendre in theta (`y = b0 sin theta`), plus the row y = 0.
    pub fn contact(&self, law: &Law, b0: f64, rows: usize) -> (f64, f64, f64, f64) {
        let centre = self.row(law, b0);
        let (mut load, mut moment) = (0.0, 0.0);
        let (mut pmax, mut xmin) = (centre.max_pressure, centre.trailing_edge);
        for_each_row(b0, rows, |b, weight| {
            let row = self.row(law, b);
            load += weight * row.load;
            moment += weight * row.moment;
            pmax = pmax.max(row.max_pressure);
            xmin = xmin.min(row.trailing_edge);
        });
        (load, moment, pmax, xmin)
    }

    /// The reference solution: D from the load, then mu, max pressure and extents.
    pub fn solve(&self, law: &Law) -> Reference {
        self.solve_with(law, ROWS)
    }

    /// As [`RigidBase::solve`] with a given number of Gauss–Legendre rows.
    pub fn solve_with(&self, law: &Law, rows: usize) -> Reference {
        let excess = |b0: f64| self.contact(law, b0, rows).0 / self.load - 1.0;
        // The load grows without bound with b0.
        let b0 = contact_radius(excess, self.creep_length.max(1e-6 * self.radius));
        let (load, moment, pmax, xmin) = self.contact(law, b0, rows);
        Reference {
            approach: b0 * b0 / (2.0 * self.radius),
            contact_radius: b0,
            max_pressure: pmax,
            friction_coefficient: moment / (self.radius * load),
            x_min: xmin,
            x_max: b0,
            y_max: b0,
        }
    }
}

/// Composite 16-point Gauss–Legendre quadrature of `f` on [a, b] with panels graded
/// away from the leading edge b: the first no longer than `panel` (and than a
/// quarter of the interval), each next one as long as the distance already
/// covered. Row pressures vary on the creep length only near the leading edge
/// (the `exp(-(b - x) / L)` term); further back they are nearly polynomial.
/// `f` may return a number or an array of numbers.
pub fn panel_quadrature<T: Quadrand>(f: impl Fn(f64) -> T, a: f64, b: f64, panel: f64) -> T {
    let (nodes, weights) = gauss_legendre(16);
    let length = b - a;
    let first = panel.min(length / 4.0);
    let (mut sum, mut covered) = (T::zero(), 0.0);
    while covered < length {
        let width = covered.max(first).min(length - covered);
        let mid = b - covered - 0.5 * width;
        for (t, w) in nodes.iter().zip(&weights) {
            sum = sum.add_scaled(f(mid + 0.5 * width * t), 0.5 * width * w);
        }
        covered += width;
    }
    sum
}

/// What [`panel_quadrature`] can sum.
pub trait Quadrand: Copy {
    fn zero() -> Self;
    fn add_scaled(self, other: Self, weight: f64) -> Self;
}

impl Quadrand for f64 {
    fn zero() -> Self {
        0.0
    }
    fn add_scaled(self, other: Self, weight: f64) -> Self {
        self + weight * other
    }
}

impl<const N: usize> Quadrand for [f64; N] {
    fn zero() -> Self {
        [0.0; N]
    }
    fn add_scaled(self, other: Self, weight: f64) -> Self {
        std::array::from_fn(|i| self[i] + weight * other[i])
    }
}

fn add(y: [f64; 4], k: [f64; 4], h: f64) -> [f64; 4] {
    std::array::from_fn(|i| y[i] + h * k[i])
}

/// Cubic Hermite on t in [0, 1] with end values and end slopes (per unit t).
fn hermite(y0: f64, y1: f64, m0: f64, m1: f64, t: f64) -> f64 {
    let (t2, t3) = (t * t, t * t * t);
    (2.0 * t3 - 3.0 * t2 + 1.0) * y0
        + (t3 - 2.0 * t2 + t) * m0
        + (-2.0 * t3 + 3.0 * t2) * y1
        + (t3 - t2) * m1
}

/// Maximiser of a unimodal function on [a, b] by golden-section search.
fn golden_max(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    let g = (5f64.sqrt() - 1.0) / 2.0;
    let (mut c, mut d) = (b - g * (b - a), a + g * (b - a));
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..80 {
        if fc > fd {
            b = d;
            d = c;
            fd = fc;
            c = b - g * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + g * (b - a);
            fd = f(d);
        }
    }
    (a + b) / 2.0
}

/// Visits the rows of a contact of radius `b0` (leading edges `b = b0 cos theta`)
/// at `rows` Gauss–Legendre nodes in theta over (0, pi/2) (`y = b0 sin theta`),
/// each with its weight in `int dy` over both halves of y (by symmetry).
pub fn for_each_row(b0: f64, rows: usize, mut visit: impl FnMut(f64, f64)) {
    let (nodes, weights) = gauss_legendre(rows);
    let half_pi = std::f64::consts::FRAC_PI_2;
    for (t, w) in nodes.iter().zip(&weights) {
        let theta = half_pi * (t + 1.0) / 2.0;
        let b = b0 * theta.cos();
        visit(b, 2.0 * (half_pi / 2.0) * w * b);
    }
}

/// The contact radius where `excess(b0)`, increasing (the load over its target,
/// less 1), vanishes: bracketed by doubling and halving from `start`, then Brent's
/// method.
pub fn contact_radius(excess: impl Fn(f64) -> f64, start: f64) -> f64 {
    let mut hi = start;
    while excess(hi) < 0.0 {
        hi *= 2.0;
    }
    let mut lo = hi / 2.0;
    while excess(lo) > 0.0 {
        hi = lo;
        lo /= 2.0;
    }
    brent(excess, lo, hi, 1e-14 * hi)
}

/// Root of f in [a, b] (f(a), f(b) of opposite signs or zero) by Brent's method
/// (Brent, Algorithms for Minimization without Derivatives, 1973, ch. 4).
pub fn brent(f: impl Fn(f64) -> f64, a: f64, b: f64, tol: f64) -> f64 {
    let (mut a, mut b) = (a, b);
    let (mut fa, mut fb) = (f(a), f(b));
    if fa == 0.0 {
        return a;
    }
    if fb == 0.0 {
        return b;
    }
    assert!(
        fa * fb < 0.0,
        "root not bracketed: f({a}) = {fa}, f({b}) = {fb}"
    );
    let (mut c, mut fc) = (a, fa);
    let (mut d, mut e) = (b - a, b - a);
    for _ in 0..200 {
        if fb * fc > 0.0 {
            c = a;
            fc = fa;
            d = b - a;
            e = d;
        }
        if fc.abs() < fb.abs() {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        let tol1 = 2.0 * f64::EPSILON * b.abs() + 0.5 * tol;
        let m = 0.5 * (c - b);
        if m.abs() <= tol1 || fb == 0.0 {
            return b;
        }
        if e.abs() >= tol1 && fa.abs() > fb.abs() {
            // Inverse quadratic interpolation or secant.
            let s = fb / fa;
            let (mut p, mut q);
            if a == c {
                p = 2.0 * m * s;
                q = 1.0 - s;
            } else {
                let qa = fa / fc;
                let r = fb / fc;
                p = s * (2.0 * m * qa * (qa - r) - (b - a) * (r - 1.0));
                q = (qa - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if p > 0.0 {
                q = -q;
            } else {
                p = -p;
            }
            if 2.0 * p < (3.0 * m * q - (tol1 * q).abs()).min((e * q).abs()) {
                e = d;
                d = p / q;
            } else {
                d = m;
                e = m;
            }
        } else {
            d = m;
            e = m;
        }
        a = b;
        fa = fb;
        b += if d.abs() > tol1 { d } else { tol1.copysign(m) };
        fb = f(b);
    }
    b
}

/// Gauss–Legendre nodes and weights on [-1, 1] (Newton on the three-term
/// recurrence; Abramowitz & Stegun 25.4.29).
pub fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut nodes = vec![0.0; n];
    let mut weights = vec![0.0; n];
    for i in 0..n.div_ceil(2) {
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 0.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            // P_n = p1, P_{n-1} = p0 (also for n = 1).
            dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
            let dx = p1 / dp;
            x -= dx;
            if dx.abs() < 1e-16 {
                break;
            }
        }
        nodes[i] = -x;
        nodes[n - 1 - i] = x;
        let w = 2.0 / ((1.0 - x * x) * dp * dp);
        weights[i] = w;
        weights[n - 1 - i] = w;
    }
    (nodes, weights)
}
