//! A layered elastic body in Fourier space: any stack of perfectly bonded layers
//! (listed top to bottom) on an elastic half-space or on a rigid base (bonded or
//! frictionless), under a normal surface pressure. For one wavenumber k > 0 it gives
//! the surface compliance factor `A(k)` (for one layer on a half-space, Perriot &
//! Barthel's factor),
//! `w^(k) = 2 (1 - nu_top^2) / (E_top k) * A(k) * p^(k)`,
//! and the stresses and displacements at any depth. Conventions: z into the body,
//! surface z = 0, pressure p >= 0 compressive (sigma_zz(0) = -p), w > 0 into the body, stresses tension-positive,
//! `p^(k) = int p e^{-i k.x}`.
//!
//! # Equations
//! Along the wave vector, `xi = (kx x + ky y) / k`, a Fourier component is a
//! plane-strain problem in the (xi, z) plane. For `p = cos k xi` write
//! `u_xi = U(z) sin k xi`, `w = W(z) cos k xi`, `tau_xiz = T(z) sin k xi`,
//! `sigma_zz = S(z) cos k xi`. With `s = k z`, the state `y = (u, w, T, S)`,
//! `u = k U`, `w = k W`, obeys in a layer (mu, nu), from Hooke's law and equilibrium
//! (`T' = k sigma_xixi`, `S' = -k T`),
//! `du/ds = w + T / mu`, `dw/ds = -a u + b S / (2 mu)`,
//! `dT/ds = 2 mu c u + a S`, `dS/ds = -T`,
//! `a = nu / (1 - nu)`, `b = (1 - 2 nu) / (1 - nu)`, `c = 1 / (1 - nu)`,
//! and `sigma_xixi = 2 mu c u + a S`, `sigma_etaeta = nu (sigma_xixi + sigma_zz)`.
//! `u`, `w`, `T`, `S` are continuous at every interface; `sigma_xixi` jumps. In the
//! scaled state `(u, w, T / 2 mu, S / 2 mu)` the system matrix `M` satisfies
//! `(M^2 - I)^2 = 0` with `M^2 - I = N` of rank two, so the propagator is
//! `exp(s M) = cosh s I + sinh s M + (s sinh s / 2) N + ((s cosh s - sinh s) / 2) M N`
//! (the series of cosh and sinh of `s M` summed with `N^2 = 0`). The same solutions
//! are the Papkovich–Neuber fields `2 mu u = grad phi + z' grad psi - (3 - 4 nu) psi
//! e_z` (Barber, Elasticity, ch. 20) with `phi, psi` in `e^{-s}`, `e^{s}`, where `z'`
//! may be measured from any origin (the shift is a gradient absorbed into phi).
//!
//! # Stable solution
//! The exact propagator grows like `s e^s`: multiplying propagators through a stack
//! (the Thomson–Haskell transfer-matrix method) loses every digit once a layer is a
//! few wavelengths thick. Instead each layer is described by what does not grow:
//! - a layer with `k h > 1` by its 4 x 4 stiffness matrix, mapping the displacements
//!   `(u, w)` of its two faces to the forces on them (Kausel & Roësset, "Stiffness
//!   matrices for layered soils", BSSA 71 (1981) 1743, in the static limit), computed
//!   in a basis of only decaying exponentials: `e^{-k(z - z_top)}` and
//!   `k(z - z_top) e^{-k(z - z_top)}` from the top face, `e^{-k(z_bottom - z)}` and
//!   `k(z_bottom - z) e^{-k(z_bottom - z)}` from the bottom face (Papkovich–Neuber with
//!   the multiplier measured from the face each one decays away from). Every basis
//!   value is below 8 in magnitude (times `1 / 2 mu` for displacements) for any `k h`, and
//!   the displacement matrix of the two faces is well conditioned when `k h > 1`
//!   (its two halves decouple as `e^{-k h} -> 0`); `k h = 1e8` only underflows the
//!   coupling to zero.
//! - a layer with `k h <= 1` by its propagator, whose entries are then `O(1)` and
//!   free of cancellation (`s cosh s - sinh s` by its series). A thin layer's
//!   stiffness would be `O(1 / k h)` and its membrane stiffness `O(k h)` would be
//!   lost in the difference of such numbers; the propagator keeps it.
//!
//! The layers are combined by the recursion of the sub-stack impedance (the 2 x 2
//! `Z` with `-(T, S) = Z (u, w)` on the top face of the part of the body below a
//! depth), from the base up: this is block elimination of the block-tridiagonal
//! global stiffness system, bottom to top, O(layers) per k with 2 x 2 blocks. The
//! base gives the start: a half-space `Z = (2 mu / (3 - 4 nu)) [[2 (1 - nu),
//! 1 - 2 nu], [1 - 2 nu, 2 (1 - nu)]]`; a rigid base the subspace of states its face
//! allows (bonded `u = w = 0`, frictionless `w = T = 0`), carried as a pair
//! `(X, Y)` of 2 x 2 matrices (state `(X e, Y e)`) until the first layer turns it
//! into an impedance. A stiffness layer maps `Z_below` to
//! `K_tt - K_tb (Z_below + K_bb)^{-1} K_bt` (the Schur complement), a thin layer by
//! its propagator `Q = exp(-k h M)`: `Z = -(Q_sd - Q_ss Z_below) (Q_dd - Q_ds
//! Z_below)^{-1}`. At the surface `Z_0 (u, w) = (0, p)` gives the surface
//! displacement and `A = w(0) mu_top / (1 - nu_top)`. The same elimination leaves,
//! per layer, the maps from its top displacement to its bottom state, so one pass
//! down gives the state at every interface; inside a layer the state comes from its
//! top state by the propagator (thin layers) or from its two face displacements in
//! the decaying basis (thick layers, a 4 x 4 pivoted solve), inside a half-space
//! base from its face displacement.
//!
//! # Limits
//! Half-space base: `A(0) = E_top (1 - nu_base^2) / (E_base (1 - nu_top^2))` (the
//! base alone) and `A -> 1` when the top layer is thick. Rigid base: `A -> 0` like k.
//! At long waves a bonded stack is in uniaxial strain, `W = p sum h_i / M_i` with the
//! constrained modulus `M_i = 2 mu_i (1 - nu_i) / (1 - 2 nu_i)`. On a frictionless
//! base the stack slides: its lateral strain `e = k U` is uniform through the
//! thickness (shear makes it so at long waves) and carries no net in-plane force,
//! `sum h_i (2 mu_i e / (1 - nu_i) - p a_i) = 0`, and
//! `W = sum h_i (a_i e + b_i p / (2 mu_i))`; one layer gives `A = k h / 2` whatever
//! the material. [`Stack::long_wave_limit`] returns these.

use realfft::num_complex::Complex;

use crate::case::Elastic;
use crate::error::{require_positive, Error, Result};

/// Stress transfer coefficients in the order `[xx, yy, zz, yz, xz, xy]`: the
/// stresses at a depth under the surface pressure `p^ e^{i (kx x + ky y)}` are these
/// times `p^ e^{i (kx x + ky y)}` (the shears imaginary, the others real).
pub type StressTransfer = [Complex<f64>; 6];

/// Rotates the plane-strain stresses of wave vector (kx, ky) to x, y.
pub(crate) fn rotate(kx: f64, ky: f64, s: [f64; 4]) -> StressTransfer {
    let k = kx.hypot(ky);
    let (c, sn) = if k > 0.0 {
        (kx / k, ky / k)
    } else {
        (1.0, 0.0)
    };
    let [xixi, etaeta, zz, xiz] = s;
    // tau_xiz = -xiz sin(k xi) -> complex coefficient i xiz.
    let shear = Complex::new(0.0, xiz);
    [
        Complex::new(xixi * c * c + etaeta * sn * sn, 0.0),
        Complex::new(xixi * sn * sn + etaeta * c * c, 0.0),
        Complex::new(zz, 0.0),
        shear * sn,
        shear * c,
        Complex::new((xixi - etaeta) * c * sn, 0.0),
    ]
}

/// One layer of a [`Stack`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ply {
    /// Its material.
    pub material: Elastic,
    /// Its thickness, > 0.
    pub thickness: f64,
}

/// How the last layer is attached to a rigid base.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BaseContact {
    /// Perfectly bonded: `u = w = 0` on the base.
    Bonded,
    /// Sliding without friction: `w = 0` and no shear on the base.
    Frictionless,
}

/// What the stack rests on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Base {
    /// An elastic half-space, bonded to the last layer.
    HalfSpace(Elastic),
    /// A rigid base.
    Rigid(BaseContact),
}

/// Bonded layers listed top to bottom on a base.
#[derive(Debug, Clone, PartialEq)]
pub struct Stack {
    /// The layers, top to bottom (none: the base half-space alone).
    pub layers: Vec<Ply>,
    /// The base.
    pub base: Base,
}

/// The k -> 0 behaviour of the surface factor `A(k)` (see the module doc).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LongWave {
    /// On a half-space: `A(0)`.
    Factor(f64),
    /// On a rigid base: `lim A(k) / k`, a length.
    Slope(f64),
}

impl Stack {
    /// Checks every layer and the base; the error names the field.
    pub fn validate(&self) -> Result<()> {
        if self.layers.is_empty() && matches!(self.base, Base::Rigid(_)) {
            return Err(Error::invalid(
                "body.layers",
                "[]",
                "at least one layer on a rigid base",
            ));
        }
        for (i, ply) in self.layers.iter().enumerate() {
            ply.material.validate(&format!("body.layers[{i}]"))?;
            require_positive(&format!("body.layers[{i}].thickness"), ply.thickness)?;
        }
        if let Base::HalfSpace(m) = self.base {
            m.validate("body.base")?;
        }
        Ok(())
    }

    /// The modulus that sets the solver's stress unit: the half-space base's Young's
    /// modulus, or on a rigid base the stiffest layer's.
    pub fn reference_modulus(&self) -> f64 {
        match self.base {
            Base::HalfSpace(m) => m.young,
            Base::Rigid(_) => self
                .layers
                .iter()
                .map(|p| p.material.young)
                .fold(0.0, f64::max),
        }
    }

    /// The stack with thicknesses divided by `length` and moduli by `modulus`.
    pub fn scaled(&self, length: f64, modulus: f64) -> Stack {
        Stack {
            layers: self
                .layers
                .iter()
                .map(|p| Ply {
                    material: p.material.scaled(modulus),
                    thickness: p.thickness / length,
                })
                .collect(),
            base: match self.base {
                Base::HalfSpace(m) => Base::HalfSpace(m.scaled(modulus)),
                rigid => rigid,
            },
        }
    }

    /// The total thickness of the layers.
    pub fn thickness(&self) -> f64 {
        self.layers.iter().map(|p| p.thickness).sum()
    }

    /// The material at the surface (the first layer's, or the base's if none);
    /// panics on a rigid base without layers (which `validate` rejects).
    pub fn top_material(&self) -> Elastic {
        match (self.layers.first(), self.base) {
            (Some(ply), _) => ply.material,
            (None, Base::HalfSpace(m)) => m,
            (None, Base::Rigid(_)) => panic!("a stack on a rigid base needs a layer"),
        }
    }

    /// Depths of the bottoms of the layers, top to bottom (the last is the base's).
    pub fn interface_depths(&self) -> Vec<f64> {
        self.layers
            .iter()
            .scan(0.0, |depth, ply| {
                *depth += ply.thickness;
                Some(*depth)
            })
            .collect()
    }

    /// The closed-form k -> 0 limit of `A(k)` (module doc, "Limits").
    pub fn long_wave_limit(&self) -> LongWave {
        let top = Material::new(self.top_material());
        let scale = top.mu / (1.0 - top.nu);
        let mats = || {
            self.layers
                .iter()
                .map(|p| (Material::new(p.material), p.thickness))
        };
        match self.base {
            Base::HalfSpace(base) => {
                let base = Material::new(base);
                // A(0) = scale * (k W)(k -> 0) of the base alone, (1 - nu) / mu.
                LongWave::Factor(scale * (1.0 - base.nu) / base.mu)
            }
            Base::Rigid(BaseContact::Bonded) => {
                LongWave::Slope(scale * mats().map(|(m, h)| h / m.constrained()).sum::<f64>())
            }
            Base::Rigid(BaseContact::Frictionless) => {
                let force: f64 = mats().map(|(m, h)| h * m.a()).sum();
                let stiffness: f64 = mats().map(|(m, h)| h * 2.0 * m.mu * m.c()).sum();
                let strain = force / stiffness;
                let w: f64 = mats()
                    .map(|(m, h)| h * (m.a() * strain + m.b() / (2.0 * m.mu)))
                    .sum();
                LongWave::Slope(scale * w)
            }
        }
    }
}

/// A material as the solve uses it.
#[derive(Debug, Clone, Copy)]
struct Material {
    mu: f64,
    nu: f64,
}

impl Material {
    fn new(m: Elastic) -> Self {
        Material {
            mu: m.young / (2.0 * (1.0 + m.poisson)),
            nu: m.poisson,
        }
    }
    fn a(&self) -> f64 {
        self.nu / (1.0 - self.nu)
    }
    fn b(&self) -> f64 {
        (1.0 - 2.0 * self.nu) / (1.0 - self.nu)
    }
    fn c(&self) -> f64 {
        1.0 / (1.0 - self.nu)
    }
    /// Constrained (oedometric) modulus `lambda + 2 mu`.
    fn constrained(&self) -> f64 {
        2.0 * self.mu * (1.0 - self.nu) / (1.0 - 2.0 * self.nu)
    }
    /// The half-space impedance (module doc).
    fn half_space_impedance(&self) -> Mat2 {
        let f = 2.0 * self.mu / (3.0 - 4.0 * self.nu);
        let (d, o) = (2.0 * (1.0 - self.nu) * f, (1.0 - 2.0 * self.nu) * f);
        [[d, o], [o, d]]
    }
    /// In-plane stresses `(sigma_xixi, sigma_etaeta)` of a state.
    fn in_plane(&self, y: &State) -> (f64, f64) {
        let xixi = 2.0 * self.mu * self.c() * y[0] + self.a() * y[3];
        (xixi, self.nu * (xixi + y[3]))
    }
}

type Mat2 = [[f64; 2]; 2];
type Mat4 = [[f64; 4]; 4];
/// `(u, w, T, S)` per unit pressure, `u = k U`, `w = k W` (module doc).
type State = [f64; 4];

const IDENTITY2: Mat2 = [[1.0, 0.0], [0.0, 1.0]];
const ZERO2: Mat2 = [[0.0; 2]; 2];

fn mul2(p: &Mat2, q: &Mat2) -> Mat2 {
    let mut r = ZERO2;
    for i in 0..2 {
        for j in 0..2 {
            r[i][j] = p[i][0] * q[0][j] + p[i][1] * q[1][j];
        }
    }
    r
}

fn add2(p: &Mat2, q: &Mat2) -> Mat2 {
    [
        [p[0][0] + q[0][0], p[0][1] + q[0][1]],
        [p[1][0] + q[1][0], p[1][1] + q[1][1]],
    ]
}

fn scale2(p: &Mat2, f: f64) -> Mat2 {
    [[p[0][0] * f, p[0][1] * f], [p[1][0] * f, p[1][1] * f]]
}

/// Inverse of a 2 x 2 matrix by its adjugate (written by hand: two lines).
fn inv2(p: &Mat2) -> Mat2 {
    let det = p[0][0] * p[1][1] - p[0][1] * p[1][0];
    [
        [p[1][1] / det, -p[0][1] / det],
        [-p[1][0] / det, p[0][0] / det],
    ]
}

fn apply2(p: &Mat2, v: [f64; 2]) -> [f64; 2] {
    [
        p[0][0] * v[0] + p[0][1] * v[1],
        p[1][0] * v[0] + p[1][1] * v[1],
    ]
}

/// The 2 x 2 block `(r, c)` of a 4 x 4 matrix.
fn block(m: &Mat4, r: usize, c: usize) -> Mat2 {
    [
        [m[2 * r][2 * c], m[2 * r][2 * c + 1]],
        [m[2 * r + 1][2 * c], m[2 * r + 1][2 * c + 1]],
    ]
}

/// Solves `m x = b` for `N` right-hand sides (columns of `b`) by Gaussian elimination
/// with partial pivoting; written by hand because a 4 x 4 solve on the stack is all
/// that is needed and a linear-algebra crate would allocate or add a dependency.
fn solve4<const N: usize>(mut m: Mat4, mut b: [[f64; N]; 4]) -> [[f64; N]; 4] {
    for c in 0..4 {
        let p = (c..4)
            .max_by(|&i, &j| m[i][c].abs().total_cmp(&m[j][c].abs()))
            .unwrap_or(c);
        m.swap(c, p);
        b.swap(c, p);
        let (m_upper, m_lower) = m.split_at_mut(c + 1);
        let (b_upper, b_lower) = b.split_at_mut(c + 1);
        let (pivot, rhs) = (&m_upper[c], &b_upper[c]);
        for (row, b_row) in m_lower.iter_mut().zip(b_lower.iter_mut()) {
            let f = row[c] / pivot[c];
            for (x, p) in row.iter_mut().zip(pivot).skip(c) {
                *x -= f * p;
            }
            for (x, p) in b_row.iter_mut().zip(rhs) {
                *x -= f * p;
            }
        }
    }
    let mut x = [[0.0; N]; 4];
    for i in (0..4).rev() {
        for j in 0..N {
            let s: f64 = (i + 1..4).map(|l| m[i][l] * x[l][j]).sum();
            x[i][j] = (b[i][j] - s) / m[i][i];
        }
    }
    x
}

/// `s cosh s - sinh s` without cancellation for small s.
fn s_cosh_minus_sinh(s: f64) -> f64 {
    if s.abs() < 1.0 {
        // sum_{n >= 1} 2n s^{2n+1} / (2n+1)!
        let s2 = s * s;
        let mut power = s; // s^{2n+1} / (2n+1)!
        let mut sum = 0.0;
        let mut n = 1.0;
        loop {
            power *= s2 / ((2.0 * n) * (2.0 * n + 1.0));
            let term = 2.0 * n * power;
            sum += term;
            if term.abs() <= 1e-17 * sum.abs() {
                return sum;
            }
            n += 1.0;
        }
    } else {
        s * s.cosh() - s.sinh()
    }
}

/// The propagator `exp(s M)` of the unscaled state `(u, w, T, S)` through a depth
/// `s = k dz` of material `m` (module doc).
fn propagator(m: &Material, s: f64) -> Mat4 {
    let (a, b) = (m.a(), m.b());
    let (ch, sh) = (s.cosh(), s.sinh());
    let p = s * sh * 0.5 * m.c();
    let r = s_cosh_minus_sinh(s) * 0.5 * m.c();
    // Scaled state (u, w, T / 2mu, S / 2mu): ch I + sh M + p Nn + r MNn with
    // N = Nn / (1 - nu), M N = MNn / (1 - nu).
    let e = [
        [ch + p, sh + r, 2.0 * sh + r, p],
        [-a * sh - r, ch - p, -p, b * sh - r],
        [m.c() * sh + r, p, ch + p, a * sh + r],
        [-p, -r, -sh - r, ch - p],
    ];
    let two_mu = 2.0 * m.mu;
    let mut q = e;
    for (i, row) in q.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            // Q = D^{-1} E D, D = diag(1, 1, 1 / 2mu, 1 / 2mu).
            if i >= 2 {
                *v *= two_mu;
            }
            if j >= 2 {
                *v /= two_mu;
            }
        }
    }
    q
}

/// State of one Papkovich–Neuber basis function: `v` its value, `d = ±1` its
/// derivative factor, `zeta` the multiplier of psi (module doc).
fn pn_state(m: &Material, zeta: f64, v: f64, d: f64, psi: bool) -> State {
    let nu = m.nu;
    let q = if psi {
        [
            zeta * v,
            zeta * d * v - (3.0 - 4.0 * nu) * v,
            zeta * v - 2.0 * (1.0 - nu) * d * v,
            zeta * d * v - (1.0 - 2.0 * nu) * v,
        ]
    } else {
        [v, d * v, v, d * v]
    };
    // (2 mu u_xi / (-sin), 2 mu w, sigma_zz, tau / (-sin)) -> (u, w, T, S).
    [-q[0] / (2.0 * m.mu), q[1] / (2.0 * m.mu), -q[3], q[2]]
}

/// The four decaying basis states of a layer of `t = k h` at `s` in [0, t]:
/// two from the top face, two from the bottom face.
fn layer_basis(m: &Material, t: f64, s: f64) -> [State; 4] {
    let r = t - s;
    let (down, up) = ((-s).exp(), (-r).exp());
    [
        pn_state(m, 0.0, down, -1.0, false),
        pn_state(m, s, down, -1.0, true),
        pn_state(m, 0.0, up, 1.0, false),
        pn_state(m, -r, up, 1.0, true),
    ]
}

/// The two decaying states of a half-space at `s >= 0` below its face.
fn half_space_basis(m: &Material, s: f64) -> [State; 2] {
    let down = (-s).exp();
    [
        pn_state(m, 0.0, down, -1.0, false),
        pn_state(m, s, down, -1.0, true),
    ]
}

/// The displacement matrix of a layer's two faces in its decaying basis: rows
/// `(u, w)` at the top, then at the bottom.
fn face_displacements(m: &Material, t: f64) -> (Mat4, [State; 4], [State; 4]) {
    let (top, bottom) = (layer_basis(m, t, 0.0), layer_basis(m, t, t));
    let mut d = [[0.0; 4]; 4];
    for j in 0..4 {
        d[0][j] = top[j][0];
        d[1][j] = top[j][1];
        d[2][j] = bottom[j][0];
        d[3][j] = bottom[j][1];
    }
    (d, top, bottom)
}

/// The stiffness matrix of a layer of `t = k h`: forces on its faces,
/// `(-T, -S)` at the top and `(T, S)` at the bottom, from the displacements
/// `(u, w)` at the top and at the bottom.
fn layer_stiffness(m: &Material, t: f64) -> Mat4 {
    let (d, top, bottom) = face_displacements(m, t);
    // K D = F, so D^T K^T = F^T.
    let mut dt = [[0.0; 4]; 4];
    let mut ft = [[0.0; 4]; 4];
    for j in 0..4 {
        for i in 0..4 {
            dt[j][i] = d[i][j];
        }
        ft[j] = [-top[j][2], -top[j][3], bottom[j][2], bottom[j][3]];
    }
    let kt = solve4(dt, ft);
    let mut k = [[0.0; 4]; 4];
    for i in 0..4 {
        for j in 0..4 {
            k[i][j] = kt[j][i];
        }
    }
    k
}

/// Layers with `k h` above this are described by their stiffness matrix, thinner
/// ones by their propagator (module doc).
const THIN: f64 = 1.0;

#[derive(Debug, Clone, Copy)]
struct Layer {
    material: Material,
    thickness: f64,
    top: f64,
}

/// The solution of a [`Stack`] for one wavenumber at a time. Its buffers are sized
/// once, in [`LayeredSolver::new`]; a solve allocates nothing.
#[derive(Debug, Clone)]
pub struct LayeredSolver {
    layers: Vec<Layer>,
    base: Base,
    top: Material,
    /// The wavenumber of the stored solution (0: none).
    k: f64,
    /// Whether `states` hold the solution at `k`.
    solved: bool,
    /// Impedance of the sub-stack below the top of each layer.
    impedance: Vec<Mat2>,
    /// Per layer, its bottom displacement and traction from its top displacement.
    down_displacement: Vec<Mat2>,
    down_traction: Vec<Mat2>,
    /// The state at the top of each layer and at the base's face.
    states: Vec<State>,
}

/// The plane-strain response at one depth per unit surface pressure, in the
/// wave-vector frame `(xi, eta)`, `xi` along `(kx, ky)`: the transfer of each real
/// entry is itself, of each shear-like entry `i` times it. Rotating to (x, y), with
/// `(c, s) = (kx, ky) / k`: `xx = xixi c^2 + etaeta s^2`, `yy = xixi s^2 + etaeta
/// c^2`, `xy = (xixi - etaeta) c s`, `xz = i T_xiz c`, `yz = i T_xiz s`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneResponse {
    /// `[T_xixi, T_etaeta, T_zz, T_xiz / i]`.
    pub stress: [f64; 4],
    /// The displacement along the wave vector, divided by i (per unit `p^`, a length
    /// per unit stress).
    pub u_xi: f64,
    /// The normal displacement, > 0 into the body (per unit `p^`).
    pub w: f64,
}

impl LayeredSolver {
    /// A solver for `stack` (validated here).
    pub fn new(stack: &Stack) -> Result<Self> {
        stack.validate()?;
        let mut depth = 0.0;
        let layers: Vec<Layer> = stack
            .layers
            .iter()
            .map(|p| {
                let layer = Layer {
                    material: Material::new(p.material),
                    thickness: p.thickness,
                    top: depth,
                };
                depth += p.thickness;
                layer
            })
            .collect();
        let n = layers.len();
        Ok(LayeredSolver {
            layers,
            base: stack.base,
            top: Material::new(stack.top_material()),
            k: 0.0,
            solved: false,
            impedance: vec![ZERO2; n],
            down_displacement: vec![ZERO2; n],
            down_traction: vec![ZERO2; n],
            states: vec![[0.0; 4]; n + 1],
        })
    }

    /// Number of layers.
    pub fn layer_count(&self) -> usize {
        self.layers.len()
    }

    /// The depth of the top of layer `i` (`i = layer_count()`: the base's face).
    pub fn depth(&self, i: usize) -> f64 {
        match self.layers.get(i) {
            Some(l) => l.top,
            None => self.layers.last().map_or(0.0, |l| l.top + l.thickness),
        }
    }

    /// The surface factor `A(k)` for `k > 0` (module doc; panics unless k is finite
    /// and positive).
    pub fn surface_factor(&mut self, k: f64) -> f64 {
        let z0 = self.eliminate(k);
        let d0 = apply2(&inv2(&z0), [0.0, 1.0]);
        d0[1] * self.top.mu / (1.0 - self.top.nu)
    }

    /// Solves for the state at every interface at wavenumber `k > 0`.
    pub fn solve(&mut self, k: f64) {
        if self.solved && self.k == k {
            return;
        }
        let z0 = self.eliminate(k);
        let d0 = apply2(&inv2(&z0), [0.0, 1.0]);
        self.states[0] = [d0[0], d0[1], 0.0, -1.0];
        for i in 0..self.layers.len() {
            let d = [self.states[i][0], self.states[i][1]];
            let below = apply2(&self.down_displacement[i], d);
            let traction = apply2(&self.down_traction[i], d);
            self.states[i + 1] = [below[0], below[1], traction[0], traction[1]];
        }
        self.solved = true;
    }

    /// Bottom-up elimination at `k`: fills the impedances and the downward maps,
    /// returns the impedance at the surface.
    fn eliminate(&mut self, k: f64) -> Mat2 {
        assert!(k > 0.0 && k.is_finite(), "wavenumber {k} must be > 0");
        self.k = k;
        self.solved = false;
        // The base's subspace of states (X e, Y e).
        let (mut x, mut y) = match self.base {
            Base::HalfSpace(m) => (
                IDENTITY2,
                scale2(&Material::new(m).half_space_impedance(), -1.0),
            ),
            Base::Rigid(BaseContact::Bonded) => (ZERO2, IDENTITY2),
            Base::Rigid(BaseContact::Frictionless) => {
                ([[1.0, 0.0], [0.0, 0.0]], [[0.0, 0.0], [0.0, 1.0]])
            }
        };
        if self.layers.is_empty() {
            return scale2(&y, -1.0);
        }
        for i in (0..self.layers.len()).rev() {
            let layer = self.layers[i];
            let t = k * layer.thickness;
            let (z, map) = if t <= THIN {
                let q = propagator(&layer.material, -t);
                let (qdd, qds, qsd, qss) = (
                    block(&q, 0, 0),
                    block(&q, 0, 1),
                    block(&q, 1, 0),
                    block(&q, 1, 1),
                );
                let xt = add2(&mul2(&qdd, &x), &mul2(&qds, &y));
                let yt = add2(&mul2(&qsd, &x), &mul2(&qss, &y));
                let inverse = inv2(&xt);
                (scale2(&mul2(&yt, &inverse), -1.0), inverse)
            } else {
                let s = layer_stiffness(&layer.material, t);
                let (ktt, ktb, kbt, kbb) = (
                    block(&s, 0, 0),
                    block(&s, 0, 1),
                    block(&s, 1, 0),
                    block(&s, 1, 1),
                );
                // Bottom face: force K_bt d_top + K_bb X e = Y e.
                let w = add2(&y, &scale2(&mul2(&kbb, &x), -1.0));
                let map = mul2(&inv2(&w), &kbt);
                (add2(&ktt, &mul2(&ktb, &mul2(&x, &map))), map)
            };
            self.down_displacement[i] = mul2(&x, &map);
            self.down_traction[i] = mul2(&y, &map);
            self.impedance[i] = z;
            x = IDENTITY2;
            y = scale2(&z, -1.0);
        }
        self.impedance[0]
    }

    /// The state `(u, w, T, S)` at depth `z` in layer `layer` from that layer's
    /// representation, after [`Self::solve`].
    fn layer_state(&self, layer: usize, z: f64) -> State {
        let k = self.k;
        match self.layers.get(layer) {
            Some(l) => {
                let t = k * l.thickness;
                let s = (k * (z - l.top)).clamp(0.0, t);
                let top = self.states[layer];
                if t <= THIN {
                    let q = propagator(&l.material, s);
                    let mut y = [0.0; 4];
                    for (i, out) in y.iter_mut().enumerate() {
                        *out = (0..4).map(|j| q[i][j] * top[j]).sum();
                    }
                    y
                } else {
                    let bottom = self.states[layer + 1];
                    let (d, _, _) = face_displacements(&l.material, t);
                    let c = solve4(d, [[top[0]], [top[1]], [bottom[0]], [bottom[1]]]);
                    let basis = layer_basis(&l.material, t, s);
                    let mut y = [0.0; 4];
                    for (j, b) in basis.iter().enumerate() {
                        for q in 0..4 {
                            y[q] += c[j][0] * b[q];
                        }
                    }
                    y
                }
            }
            None => {
                let Base::HalfSpace(m) = self.base else {
                    panic!("layer {layer} is below the last layer on a rigid base");
                };
                let m = Material::new(m);
                let face = self.states[layer];
                let s = (k * (z - self.depth(layer))).max(0.0);
                let at_face = half_space_basis(&m, 0.0);
                let dm = [
                    [at_face[0][0], at_face[1][0]],
                    [at_face[0][1], at_face[1][1]],
                ];
                let c = apply2(&inv2(&dm), [face[0], face[1]]);
                let basis = half_space_basis(&m, s);
                let mut y = [0.0; 4];
                for q in 0..4 {
                    y[q] = c[0] * basis[0][q] + c[1] * basis[1][q];
                }
                y
            }
        }
    }

    fn material(&self, layer: usize) -> Material {
        match (self.layers.get(layer), self.base) {
            (Some(l), _) => l.material,
            (None, Base::HalfSpace(m)) if layer == self.layers.len() => Material::new(m),
            _ => panic!(
                "layer {layer} does not exist ({} layers on {:?})",
                self.layers.len(),
                self.base
            ),
        }
    }

    /// The plane-strain response at wavenumber `k > 0` and depth `z` read in layer
    /// `layer` (`layer_count()`: the half-space base), which must contain z (its
    /// top and bottom depths included: at an interface the index picks the side).
    /// At a layer's faces the interface states of the solve are used, so `u`, `w`,
    /// `sigma_zz`, `tau_xiz` are the same on both sides and `sigma_zz(0) = -1`.
    /// Panics for a layer index or depth outside the stack, or `k <= 0`.
    pub fn plane_response(&mut self, k: f64, layer: usize, z: f64) -> PlaneResponse {
        self.solve(k);
        self.solved_response(layer, z)
    }

    /// [`LayeredSolver::plane_response`] at the wavenumber of the last
    /// [`LayeredSolver::solve`], without solving again: a solver solved once per
    /// wavenumber serves every depth. Panics if it holds no solution.
    pub fn solved_response(&self, layer: usize, z: f64) -> PlaneResponse {
        assert!(self.solved, "solve before reading a response");
        let k = self.k;
        let m = self.material(layer);
        let (top, bottom) = (
            self.depth(layer),
            self.layers
                .get(layer)
                .map_or(f64::INFINITY, |l| l.top + l.thickness),
        );
        let slack = 1e-12 * (bottom.min(1e300).abs() + top.abs());
        assert!(
            z >= top - slack && z <= bottom + slack,
            "depth {z} is outside layer {layer} ({top} to {bottom})"
        );
        let y = if z <= top {
            self.states[layer]
        } else if z >= bottom {
            self.states[layer + 1]
        } else {
            self.layer_state(layer, z)
        };
        let (xixi, etaeta) = m.in_plane(&y);
        PlaneResponse {
            stress: [xixi, etaeta, y[3], -y[2]],
            u_xi: -y[0] / k,
            w: y[1] / k,
        }
    }

    /// The stress transfer `[xx, yy, zz, yz, xz, xy]` at depth `z` in layer `layer`
    /// for the wave vector `(kx, ky) != 0`: [`LayeredSolver::plane_response`] rotated.
    pub fn stress_transfer(&mut self, kx: f64, ky: f64, layer: usize, z: f64) -> StressTransfer {
        let r = self.plane_response(kx.hypot(ky), layer, z);
        rotate(kx, ky, r.stress)
    }

    /// The displacement transfer `[u_x, u_y, w]` at depth `z` in layer `layer` for
    /// the wave vector `(kx, ky) != 0` (`u_x`, `u_y` imaginary).
    pub fn displacement_transfer(
        &mut self,
        kx: f64,
        ky: f64,
        layer: usize,
        z: f64,
    ) -> [Complex<f64>; 3] {
        let k = kx.hypot(ky);
        let r = self.plane_response(k, layer, z);
        let along = Complex::new(0.0, r.u_xi);
        [along * (kx / k), along * (ky / k), Complex::new(r.w, 0.0)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::body::two_layer_oracle::{
        coated_stress_transfer, interface_stress_transfer, TransferFactor,
    };

    fn elastic(young: f64, poisson: f64) -> Elastic {
        Elastic { young, poisson }
    }

    fn ply(young: f64, poisson: f64, thickness: f64) -> Ply {
        Ply {
            material: elastic(young, poisson),
            thickness,
        }
    }

    fn log_space(lo: f64, hi: f64, n: usize) -> impl Iterator<Item = f64> {
        (0..n).map(move |i| lo * (hi / lo).powf(i as f64 / (n - 1) as f64))
    }

    fn close(a: Complex<f64>, b: Complex<f64>, tol: f64) -> bool {
        (a - b).norm() <= tol
    }

    #[test]
    fn one_layer_on_a_half_space_is_perriot_barthel() {
        let substrate = elastic(1.0, 0.3);
        let mut worst: f64 = 0.0;
        for ratio in [100.0, 10.0, 0.1, 0.01] {
            for (nu1, nu2) in [(0.3, 0.3), (0.2, 0.45), (0.45, 0.1), (-0.3, 0.25)] {
                let coating = elastic(ratio, nu1);
                let substrate = elastic(substrate.young, nu2);
                let h = 0.37;
                let stack = Stack {
                    layers: vec![Ply {
                        material: coating,
                        thickness: h,
                    }],
                    base: Base::HalfSpace(substrate),
                };
                let mut solver = LayeredSolver::new(&stack).unwrap();
                let closed = TransferFactor::new(coating, substrate);
                for t in log_space(1e-4, 1e4, 81) {
                    let a = solver.surface_factor(t / h);
                    // The closed form overflows (NaN) beyond t ~ 700, where its excess
                    // 4 b t^2 e^{-2t} is far below 1e-200.
                    let expected = if t < 300.0 { closed.factor(t) } else { 1.0 };
                    let error = ((a - expected) / expected).abs();
                    worst = worst.max(error);
                    assert!(
                        error < 1e-12,
                        "{ratio} {nu1} {nu2} kh = {t}: {a} vs {expected}"
                    );
                }
            }
        }
        eprintln!("one layer vs Perriot-Barthel: worst relative difference {worst:.1e}");
    }

    #[test]
    fn one_layer_stresses_are_the_coated_ones() {
        let mut worst: f64 = 0.0;
        for (c, s) in [
            (elastic(10.0, 0.25), elastic(1.0, 0.35)),
            (elastic(0.1, 0.45), elastic(1.0, 0.2)),
            (elastic(100.0, 0.3), elastic(1.0, 0.3)),
        ] {
            let h = 0.7;
            let stack = Stack {
                layers: vec![Ply {
                    material: c,
                    thickness: h,
                }],
                base: Base::HalfSpace(s),
            };
            let mut solver = LayeredSolver::new(&stack).unwrap();
            for (kx, ky) in [(0.006, 0.008), (0.3, 0.4), (1.2, -1.6), (18.0, 24.0)] {
                for (layer, z) in [(0, 0.0), (0, 0.2), (0, 0.5), (1, 1.0), (1, 2.5)] {
                    let got = solver.stress_transfer(kx, ky, layer, z);
                    let expected = coated_stress_transfer(c, h, s, kx, ky, z);
                    for q in 0..6 {
                        worst = worst.max((got[q] - expected[q]).norm());
                        assert!(
                            close(got[q], expected[q], 1e-10),
                            "({kx}, {ky}) z = {z} component {q}: {} vs {}",
                            got[q],
                            expected[q]
                        );
                    }
                }
                let (above, below) = interface_stress_transfer(c, h, s, kx, ky);
                let (top, bottom) = (
                    solver.stress_transfer(kx, ky, 0, h),
                    solver.stress_transfer(kx, ky, 1, h),
                );
                for q in 0..6 {
                    worst = worst.max((top[q] - above[q]).norm());
                    worst = worst.max((bottom[q] - below[q]).norm());
                    assert!(close(top[q], above[q], 1e-10), "coating side {q}");
                    assert!(close(bottom[q], below[q], 1e-10), "substrate side {q}");
                }
            }
        }
        eprintln!("one layer vs coated stresses: worst difference {worst:.1e} p");
    }

    /// Boussinesq's response of a half-space to `p = cos k xi` (module doc of
    /// coated_stress): `[T_xixi, T_etaeta, T_zz, T_xiz / i]` and
    /// `W = (2 (1 - nu) + kz) e^{-kz} / (2 mu k)`.
    fn boussinesq(m: Elastic, k: f64, z: f64) -> ([f64; 4], f64) {
        let (kz, nu) = (k * z, m.poisson);
        let e = (-kz).exp();
        let mu = m.young / (2.0 * (1.0 + nu));
        (
            [-(1.0 - kz) * e, -2.0 * nu * e, -(1.0 + kz) * e, kz * e],
            (2.0 * (1.0 - nu) + kz) * e / (2.0 * mu * k),
        )
    }

    #[test]
    fn identical_layers_are_the_half_space() {
        let m = elastic(2.0, 0.3);
        let mut worst: f64 = 0.0;
        for n in [1, 3, 8] {
            let stack = Stack {
                layers: (0..n)
                    .map(|i| ply(2.0, 0.3, 0.1 + 0.3 * i as f64))
                    .collect(),
                base: Base::HalfSpace(m),
            };
            let depths = stack.interface_depths();
            let mut solver = LayeredSolver::new(&stack).unwrap();
            for k in log_space(1e-3, 1e3, 25) {
                let a = solver.surface_factor(k);
                worst = worst.max((a - 1.0).abs());
                assert!((a - 1.0).abs() < 1e-12, "{n} layers, k = {k}: A = {a}");
                for layer in 0..=n {
                    let top = if layer == 0 { 0.0 } else { depths[layer - 1] };
                    let bottom = depths.get(layer).copied().unwrap_or(top + 2.0);
                    for f in [0.0, 0.3, 1.0] {
                        let z = top + f * (bottom - top);
                        let r = solver.plane_response(k, layer, z);
                        let (stress, w) = boussinesq(m, k, z);
                        for (q, (got, want)) in r.stress.iter().zip(stress).enumerate() {
                            worst = worst.max((got - want).abs());
                            assert!(
                                (got - want).abs() < 1e-12,
                                "{n} layers, k = {k}, z = {z}, {q}: {got} vs {want}"
                            );
                        }
                        let w0 = boussinesq(m, k, 0.0).1;
                        assert!((r.w - w).abs() < 1e-12 * w0, "w at {z}: {} vs {w}", r.w);
                    }
                }
            }
        }
        eprintln!("identical layers vs Boussinesq: worst {worst:.1e}");
    }

    #[test]
    fn splitting_a_layer_changes_nothing() {
        let whole = Stack {
            layers: vec![ply(5.0, 0.2, 0.3), ply(0.5, 0.4, 0.5)],
            base: Base::HalfSpace(elastic(1.0, 0.3)),
        };
        let split = Stack {
            layers: vec![ply(5.0, 0.2, 0.1), ply(5.0, 0.2, 0.2), ply(0.5, 0.4, 0.5)],
            base: Base::HalfSpace(elastic(1.0, 0.3)),
        };
        for base in [
            Base::HalfSpace(elastic(1.0, 0.3)),
            Base::Rigid(BaseContact::Bonded),
            Base::Rigid(BaseContact::Frictionless),
        ] {
            let mut a = LayeredSolver::new(&Stack {
                base,
                ..whole.clone()
            })
            .unwrap();
            let mut b = LayeredSolver::new(&Stack {
                base,
                ..split.clone()
            })
            .unwrap();
            for k in log_space(1e-3, 1e3, 19) {
                let (fa, fb) = (a.surface_factor(k), b.surface_factor(k));
                assert!((fa - fb).abs() < 1e-12 * fa, "k = {k}: {fa} vs {fb}");
                // Depths in the whole stack's layer 0 / 1 and the split one's 0, 1 / 2.
                for (za, la, lb) in [(0.05, 0, 0), (0.1, 0, 1), (0.2, 0, 1), (0.6, 1, 2)] {
                    let (ra, rb) = (a.plane_response(k, la, za), b.plane_response(k, lb, za));
                    for q in 0..4 {
                        assert!(
                            (ra.stress[q] - rb.stress[q]).abs() < 1e-12,
                            "k = {k}, z = {za}, {q}: {} vs {}",
                            ra.stress[q],
                            rb.stress[q]
                        );
                    }
                    let scale = a.plane_response(k, 0, 0.0).w.abs();
                    assert!((ra.w - rb.w).abs() < 1e-12 * scale);
                    assert!((ra.u_xi - rb.u_xi).abs() < 1e-12 * scale);
                }
            }
        }
    }

    /// Dense Gaussian elimination with partial pivoting (test oracle).
    fn solve_dense(mut m: Vec<Vec<f64>>, mut r: Vec<f64>) -> Vec<f64> {
        let n = r.len();
        for c in 0..n {
            let p = (c..n)
                .max_by(|&i, &j| m[i][c].abs().total_cmp(&m[j][c].abs()))
                .unwrap();
            m.swap(c, p);
            r.swap(c, p);
            let (upper, lower) = m.split_at_mut(c + 1);
            let pivot = &upper[c];
            for (i, row) in lower.iter_mut().enumerate() {
                let f = row[c] / pivot[c];
                for (x, p) in row.iter_mut().zip(pivot).skip(c) {
                    *x -= f * p;
                }
                r[c + 1 + i] -= f * r[c];
            }
        }
        let mut x = vec![0.0; n];
        for i in (0..n).rev() {
            let s: f64 = (i + 1..n).map(|j| m[i][j] * x[j]).sum();
            x[i] = (r[i] - s) / m[i][i];
        }
        x
    }

    /// The second method: the Papkovich–Neuber potentials of every layer in one
    /// dense boundary-value system, in the basis of the two-layer oracle (`e^{-(kz -
    /// k z_top)}`, `e^{kz - k z_bottom}`, psi multiplied by the absolute `kz`), solved
    /// with partial pivoting. Fine for moderate k times the depths.
    struct Dense {
        materials: Vec<Elastic>,
        tops: Vec<f64>,
        base: Base,
        k: f64,
        x: Vec<f64>,
    }

    impl Dense {
        fn new(stack: &Stack, k: f64) -> Self {
            let n = stack.layers.len();
            let mut materials: Vec<Elastic> = stack.layers.iter().map(|p| p.material).collect();
            let mut tops = vec![0.0];
            for p in &stack.layers {
                tops.push(tops.last().unwrap() + p.thickness);
            }
            if let Base::HalfSpace(m) = stack.base {
                materials.push(m);
            }
            let mut dense = Dense {
                materials,
                tops,
                base: stack.base,
                k,
                x: Vec::new(),
            };
            let unknowns = 4 * n + if n < dense.materials.len() { 2 } else { 0 };
            let mut m = Vec::new();
            let mut r = Vec::new();
            let row = |dense: &Dense, body: usize, z: f64, q: usize, scale: f64| {
                let mut out = vec![0.0; unknowns];
                for (j, v) in dense.rows(body, z)[q].iter().enumerate() {
                    out[4 * body + j] = v * scale;
                }
                out
            };
            m.push(row(&dense, 0, 0.0, 2, 1.0));
            r.push(-1.0);
            m.push(row(&dense, 0, 0.0, 3, 1.0));
            r.push(0.0);
            for i in 0..n {
                let z = dense.tops[i + 1];
                if i + 1 < dense.materials.len() {
                    for q in 0..4 {
                        let (s1, s2) = if q < 2 {
                            (1.0 / dense.mu(i), 1.0 / dense.mu(i + 1))
                        } else {
                            (1.0, 1.0)
                        };
                        let upper = row(&dense, i, z, q, s1);
                        let lower = row(&dense, i + 1, z, q, s2);
                        m.push(upper.iter().zip(&lower).map(|(a, b)| a - b).collect());
                        r.push(0.0);
                    }
                } else {
                    let conditions = match dense.base {
                        Base::Rigid(BaseContact::Bonded) => [0, 1],
                        _ => [1, 3],
                    };
                    for q in conditions {
                        m.push(row(&dense, i, z, q, 1.0));
                        r.push(0.0);
                    }
                }
            }
            dense.x = solve_dense(m, r);
            dense
        }

        fn mu(&self, body: usize) -> f64 {
            let m = self.materials[body];
            m.young / (2.0 * (1.0 + m.poisson))
        }

        /// (is_psi, value, d/dzeta factor) of the body's basis at depth z.
        fn basis(&self, body: usize, z: f64) -> Vec<(bool, f64, f64)> {
            let k = self.k;
            let down = (-k * (z - self.tops[body])).exp();
            if body + 1 < self.tops.len() {
                let up = (k * (z - self.tops[body + 1])).exp();
                vec![
                    (false, down, -1.0),
                    (false, up, 1.0),
                    (true, down, -1.0),
                    (true, up, 1.0),
                ]
            } else {
                vec![(false, down, -1.0), (true, down, -1.0)]
            }
        }

        /// `[2 mu u_xi / i, 2 mu w, sigma_zz, tau_xiz / i]`-rows per basis function
        /// (the two-layer oracle's `quantities`, per unit p / k^2).
        fn rows(&self, body: usize, z: f64) -> [Vec<f64>; 4] {
            let nu = self.materials[body].poisson;
            let zeta = self.k * z;
            let g = 3.0 - 4.0 * nu;
            let mut q: [Vec<f64>; 4] = Default::default();
            for (psi, v, d) in self.basis(body, z) {
                let column = if psi {
                    [
                        zeta * v,
                        zeta * d * v - g * v,
                        zeta * v - 2.0 * (1.0 - nu) * d * v,
                        zeta * d * v - (1.0 - 2.0 * nu) * v,
                    ]
                } else {
                    [v, d * v, v, d * v]
                };
                for (row, value) in q.iter_mut().zip(column) {
                    row.push(value);
                }
            }
            q
        }

        /// `([T_xixi, T_etaeta, T_zz, T_xiz / i], u_xi / i, w)` at depth z in `body`.
        fn response(&self, body: usize, z: f64) -> ([f64; 4], f64, f64) {
            let nu = self.materials[body].poisson;
            let zeta = self.k * z;
            let c = &self.x[4 * body..];
            let (mut phi, mut dphi, mut psi, mut dpsi) = (0.0, 0.0, 0.0, 0.0);
            for (&c, (is_psi, v, d)) in c.iter().zip(self.basis(body, z)) {
                if is_psi {
                    psi += c * v;
                    dpsi += c * d * v;
                } else {
                    phi += c * v;
                    dphi += c * d * v;
                }
            }
            let stress = [
                -phi - zeta * psi - 2.0 * nu * dpsi,
                -2.0 * nu * dpsi,
                phi + zeta * psi - 2.0 * (1.0 - nu) * dpsi,
                dphi + zeta * dpsi - (1.0 - 2.0 * nu) * psi,
            ];
            let two_mu_k = 2.0 * self.mu(body) * self.k;
            let u = (phi + zeta * psi) / two_mu_k;
            let w = (dphi + zeta * dpsi - (3.0 - 4.0 * nu) * psi) / two_mu_k;
            (stress, u, w)
        }
    }

    const BASES: [Base; 3] = [
        Base::HalfSpace(Elastic {
            young: 1.0,
            poisson: 0.3,
        }),
        Base::Rigid(BaseContact::Bonded),
        Base::Rigid(BaseContact::Frictionless),
    ];

    /// Compares the solver with the dense method at `k`: A relative, stresses
    /// absolute (per unit p), displacements relative to w(0); returns the worst.
    fn against_dense(stack: &Stack, k: f64, tol: f64) -> f64 {
        let dense = Dense::new(stack, k);
        let mut solver = LayeredSolver::new(stack).unwrap();
        let a = solver.surface_factor(k);
        let top = stack.top_material();
        let expected =
            dense.response(0, 0.0).2 * k * top.young / (2.0 * (1.0 - top.poisson.powi(2)));
        let mut worst = ((a - expected) / expected).abs();
        assert!(worst < tol, "{stack:?} k = {k}: A = {a} vs {expected}");
        let w0 = dense.response(0, 0.0).2.abs();
        let n = stack.layers.len();
        let bodies = n + usize::from(matches!(stack.base, Base::HalfSpace(_)));
        for body in 0..bodies {
            let z0 = dense.tops[body];
            let h = if body < n {
                stack.layers[body].thickness
            } else {
                1.0
            };
            for f in [0.0, 0.25, 0.5, 0.9, 1.0] {
                let z = z0 + f * h;
                let (stress, u, w) = dense.response(body, z);
                let r = solver.plane_response(k, body, z);
                for (q, (got, want)) in r.stress.iter().zip(stress).enumerate() {
                    let e = (got - want).abs();
                    worst = worst.max(e);
                    assert!(
                        e < tol,
                        "k = {k}, body {body}, z = {z}, {q}: {got} vs {want}"
                    );
                }
                let e = (r.u_xi - u).abs().max((r.w - w).abs()) / w0;
                worst = worst.max(e);
                assert!(
                    e < tol,
                    "k = {k}, body {body}, z = {z}: u {} vs {u}, w {} vs {w}",
                    r.u_xi,
                    r.w
                );
            }
        }
        worst
    }

    #[test]
    fn three_layers_agree_with_the_dense_boundary_value_problem() {
        let layers = vec![ply(3.0, 0.25, 0.4), ply(0.2, 0.4, 0.3), ply(8.0, 0.15, 0.6)];
        let mut worst: f64 = 0.0;
        for base in BASES {
            let stack = Stack {
                layers: layers.clone(),
                base,
            };
            for k in [0.05, 0.3, 1.0, 2.5, 6.0] {
                worst = worst.max(against_dense(&stack, k, 1e-10));
            }
        }
        eprintln!("three layers vs dense: worst {worst:.1e}");
    }

    #[test]
    fn near_incompressible_layers_on_a_rigid_base_are_finite_and_agree() {
        let mut worst: f64 = 0.0;
        for nu in [0.49, 0.499] {
            for layers in [
                vec![ply(1.0, nu, 0.5)],
                vec![ply(2.0, 0.3, 0.2), ply(1.0, nu, 0.5), ply(0.1, nu, 0.3)],
            ] {
                for contact in [BaseContact::Bonded, BaseContact::Frictionless] {
                    let stack = Stack {
                        layers: layers.clone(),
                        base: Base::Rigid(contact),
                    };
                    for k in [0.05, 0.4, 2.0, 5.0] {
                        worst = worst.max(against_dense(&stack, k, 1e-10));
                    }
                    let mut solver = LayeredSolver::new(&stack).unwrap();
                    // One layer on a rigid base is stiffer than its own half-space; the
                    // stack's soft lower layers make it more compliant than its top's.
                    let most = if layers.len() == 1 {
                        1.0 + 1e-12
                    } else {
                        100.0
                    };
                    for k in log_space(1e-6, 1e6, 49) {
                        let a = solver.surface_factor(k);
                        assert!(a.is_finite() && a > 0.0 && a <= most, "nu {nu}, k {k}: {a}");
                    }
                }
            }
        }
        eprintln!("near-incompressible vs dense: worst {worst:.1e}");
    }

    /// `E_top / (2 (1 - nu_top^2))`: A = that times k W per unit p.
    fn normaliser(m: Elastic) -> f64 {
        m.young / (2.0 * (1.0 - m.poisson * m.poisson))
    }

    #[test]
    fn long_waves_on_a_half_space_see_the_base_and_short_waves_the_top_layer() {
        let base = elastic(1.0, 0.35);
        for layers in [
            vec![ply(100.0, 0.2, 0.3)],
            vec![ply(0.01, 0.45, 0.3)],
            vec![ply(3.0, 0.25, 0.4), ply(0.2, 0.4, 0.3), ply(8.0, 0.15, 0.6)],
        ] {
            let stack = Stack {
                layers,
                base: Base::HalfSpace(base),
            };
            let top = stack.top_material();
            let alone = top.young * (1.0 - base.poisson.powi(2))
                / (base.young * (1.0 - top.poisson.powi(2)));
            let LongWave::Factor(limit) = stack.long_wave_limit() else {
                panic!("a half-space base has a factor at k = 0");
            };
            assert!((limit - alone).abs() < 1e-14 * alone);
            let mut solver = LayeredSolver::new(&stack).unwrap();
            let a = solver.surface_factor(1e-9);
            assert!((a - alone).abs() < 1e-6 * alone, "{a} vs {alone}");
            // Top layer 60 wavelengths / 2 pi thick: A - 1 ~ t^2 e^{-2t} < 1e-48.
            let k = 60.0 / stack.layers[0].thickness;
            assert!((solver.surface_factor(k) - 1.0).abs() < 1e-13);
        }
    }

    #[test]
    fn long_waves_on_a_rigid_base_follow_the_closed_forms() {
        for layers in [
            vec![ply(1.0, 0.3, 0.5)],
            vec![ply(1.0, 0.499, 0.5)],
            vec![ply(1.0, -0.5, 0.5)],
            vec![ply(3.0, 0.25, 0.4), ply(0.2, 0.4, 0.3), ply(8.0, 0.15, 0.6)],
        ] {
            let top = layers[0].material;
            let total: f64 = layers.iter().map(|p| p.thickness).sum();
            // Bonded: uniaxial strain, W / p = sum h / (lambda + 2 mu).
            let constrained = |m: Elastic| {
                let nu = m.poisson;
                m.young * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu))
            };
            let bonded: f64 = normaliser(top)
                * layers
                    .iter()
                    .map(|p| p.thickness / constrained(p.material))
                    .sum::<f64>();
            // Frictionless: a common lateral strain e with no net in-plane force.
            let e = layers
                .iter()
                .map(|p| p.thickness * p.material.poisson / (1.0 - p.material.poisson))
                .sum::<f64>()
                / layers
                    .iter()
                    .map(|p| p.thickness * p.material.plane_strain_modulus())
                    .sum::<f64>();
            let frictionless = normaliser(top)
                * layers
                    .iter()
                    .map(|p| {
                        let (y, nu) = (p.material.young, p.material.poisson);
                        p.thickness
                            * (nu / (1.0 - nu) * e
                                + (1.0 - 2.0 * nu) * (1.0 + nu) / (y * (1.0 - nu)))
                    })
                    .sum::<f64>();
            if layers.len() == 1 {
                // One layer: h (1 - 2 nu) / (2 (1 - nu)^2) bonded, h / 2 sliding.
                let (h, nu) = (layers[0].thickness, top.poisson);
                let one = h * (1.0 - 2.0 * nu) / (2.0 * (1.0 - nu).powi(2));
                assert!((bonded - one).abs() < 1e-14 * one);
                assert!((frictionless - h / 2.0).abs() < 1e-14 * h);
            }
            for (contact, slope) in [
                (BaseContact::Bonded, bonded),
                (BaseContact::Frictionless, frictionless),
            ] {
                let stack = Stack {
                    layers: layers.clone(),
                    base: Base::Rigid(contact),
                };
                let LongWave::Slope(limit) = stack.long_wave_limit() else {
                    panic!("a rigid base has a slope at k = 0");
                };
                assert!((limit - slope).abs() < 1e-14 * slope, "{limit} vs {slope}");
                let mut solver = LayeredSolver::new(&stack).unwrap();
                let k = 1e-7 / total;
                let got = solver.surface_factor(k) / k;
                assert!(
                    (got - slope).abs() < 1e-6 * slope,
                    "{contact:?} {layers:?}: {got} vs {slope}"
                );
            }
        }
    }

    #[test]
    fn propagator_is_the_matrix_exponential() {
        for (mu, nu) in [(1.0, 0.3), (250.0, 0.499), (0.01, -0.7)] {
            let m = Material { mu, nu };
            let (a, b, c) = (
                nu / (1.0 - nu),
                (1.0 - 2.0 * nu) / (1.0 - nu),
                1.0 / (1.0 - nu),
            );
            let system = [
                [0.0, 1.0, 1.0 / mu, 0.0],
                [-a, 0.0, 0.0, b / (2.0 * mu)],
                [2.0 * mu * c, 0.0, 0.0, a],
                [0.0, 0.0, -1.0, 0.0],
            ];
            for s in [-1.0, -0.3, -1e-3, 1e-6, 0.05, 0.7, 1.0] {
                // Taylor series of exp(s M), 60 terms.
                let mut term = [[0.0; 4]; 4];
                let mut sum = [[0.0; 4]; 4];
                for i in 0..4 {
                    term[i][i] = 1.0;
                    sum[i][i] = 1.0;
                }
                for n in 1..60 {
                    let mut next = [[0.0; 4]; 4];
                    for i in 0..4 {
                        for j in 0..4 {
                            next[i][j] = (0..4).map(|l| term[i][l] * system[l][j]).sum::<f64>() * s
                                / n as f64;
                        }
                    }
                    term = next;
                    for i in 0..4 {
                        for j in 0..4 {
                            sum[i][j] += term[i][j];
                        }
                    }
                }
                let q = propagator(&m, s);
                for i in 0..4 {
                    for j in 0..4 {
                        // Entries scale with the units of (u, w, T, S).
                        let unit = [1.0, 1.0, mu, mu];
                        let tol = 1e-14 * unit[i] / unit[j] + 1e-15 * sum[i][j].abs();
                        assert!(
                            (q[i][j] - sum[i][j]).abs() < tol.max(1e-15 * sum[i][j].abs()),
                            "mu {mu} nu {nu} s {s} ({i}, {j}): {} vs {}",
                            q[i][j],
                            sum[i][j]
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn eight_contrasting_layers_stay_finite_and_continuous() {
        let thickness = [1e-6, 1e-3, 1e3, 1e-1, 1e-5, 10.0, 1e-2, 1e2];
        let layers: Vec<Ply> = thickness
            .iter()
            .enumerate()
            .map(|(i, &h)| {
                let (young, nu) = if i % 2 == 0 { (1e3, 0.2) } else { (1.0, 0.45) };
                ply(young, nu, h)
            })
            .collect();
        let mut worst: f64 = 0.0;
        for base in BASES {
            let stack = Stack {
                layers: layers.clone(),
                base,
            };
            let depths = stack.interface_depths();
            let mut solver = LayeredSolver::new(&stack).unwrap();
            for k in log_space(1e-6, 1e6, 25) {
                let a = solver.surface_factor(k);
                assert!(
                    a.is_finite() && a > 0.0 && a < 1e5,
                    "{base:?} k = {k}: A = {a}"
                );
                let surface = solver.plane_response(k, 0, 0.0);
                assert_eq!(surface.stress[2], -1.0);
                assert_eq!(surface.stress[3], 0.0);
                for (i, &z) in depths.iter().enumerate() {
                    let upper = solver.layer_state(i, z);
                    let below = i + 1 < layers.len() || matches!(base, Base::HalfSpace(_));
                    if below {
                        let lower = solver.layer_state(i + 1, z);
                        for (range, what) in [(0..2, "displacement"), (2..4, "traction")] {
                            let scale = range
                                .clone()
                                .map(|q| upper[q].abs().max(lower[q].abs()))
                                .fold(0.0, f64::max);
                            for q in range {
                                let e = (upper[q] - lower[q]).abs() / scale.max(1e-300);
                                worst = worst.max(e);
                                assert!(
                                    e < 1e-10,
                                    "{base:?} k = {k} interface {i} {what} {q}: {} vs {}",
                                    upper[q],
                                    lower[q]
                                );
                            }
                        }
                        // The in-plane strain e_xixi = ((1 - nu^2) s_xx - nu (1 + nu) s_zz) / E
                        // is continuous while sigma_xixi jumps; Hooke's law recovers it to
                        // rounding of the stresses over E (`size`).
                        let mut strain = |layer: usize, m: Elastic| {
                            let r = solver.plane_response(k, layer, z).stress;
                            let nu = m.poisson;
                            let e = ((1.0 - nu * nu) * r[0] - nu * (1.0 + nu) * r[2]) / m.young;
                            (e, (r[0].abs() + r[2].abs()) / m.young)
                        };
                        let lower_material = match (layers.get(i + 1), base) {
                            (Some(p), _) => p.material,
                            (None, Base::HalfSpace(m)) => m,
                            _ => unreachable!(),
                        };
                        let ((ea, sa), (eb, sb)) =
                            (strain(i, layers[i].material), strain(i + 1, lower_material));
                        let scale = ea.abs().max(eb.abs()).max(sa).max(sb).max(1e-300);
                        let e = (ea - eb).abs() / scale;
                        worst = worst.max(e);
                        assert!(
                            e < 1e-10,
                            "{base:?} k = {k} interface {i} strain: {ea} vs {eb}"
                        );
                    } else {
                        // The rigid base's conditions.
                        let scale = upper.iter().map(|v| v.abs()).fold(0.0, f64::max);
                        let held = match base {
                            Base::Rigid(BaseContact::Bonded) => [0, 1],
                            _ => [1, 2],
                        };
                        for q in held {
                            assert!(
                                upper[q].abs() <= 1e-10 * scale,
                                "{base:?} k = {k}: {upper:?}"
                            );
                        }
                    }
                }
            }
        }
        eprintln!("eight layers: worst interface mismatch {worst:.1e}");
    }

    #[test]
    fn validation_names_the_field() {
        let good = ply(1.0, 0.3, 1.0);
        let check = |layers: Vec<Ply>, base: Base, field: &str| {
            let error = Stack { layers, base }.validate().unwrap_err();
            let text = error.to_string();
            assert!(text.starts_with(field), "{text}");
            assert!(!text.contains('\n'));
        };
        check(vec![], Base::Rigid(BaseContact::Bonded), "body.layers =");
        check(
            vec![good, ply(1.0, 0.3, 0.0)],
            BASES[0],
            "body.layers[1].thickness",
        );
        check(
            vec![ply(1.0, 0.3, f64::NAN)],
            BASES[1],
            "body.layers[0].thickness",
        );
        check(
            vec![ply(1.0, 0.3, f64::INFINITY)],
            BASES[1],
            "body.layers[0].thickness",
        );
        check(vec![ply(1.0, 0.5, 1.0)], BASES[2], "body.layers[0].poisson");
        check(
            vec![ply(1.0, -1.0, 1.0)],
            BASES[2],
            "body.layers[0].poisson",
        );
        check(vec![ply(0.0, 0.3, 1.0)], BASES[2], "body.layers[0].young");
        check(
            vec![good],
            Base::HalfSpace(elastic(-1.0, 0.3)),
            "body.base.young",
        );
        check(
            vec![good],
            Base::HalfSpace(elastic(1.0, 0.6)),
            "body.base.poisson",
        );
        assert!(Stack {
            layers: vec![],
            base: BASES[0]
        }
        .validate()
        .is_ok());
        assert!(LayeredSolver::new(&Stack {
            layers: vec![],
            base: BASES[1]
        })
        .is_err());
    }

    #[test]
    fn extreme_contrasts_and_thicknesses_keep_the_closed_form() {
        let mut worst: f64 = 0.0;
        for ratio in [1e4, 1e-4] {
            let (coating, substrate) = (elastic(ratio, 0.3), elastic(1.0, 0.25));
            let stack = Stack {
                layers: vec![Ply {
                    material: coating,
                    thickness: 1.0,
                }],
                base: Base::HalfSpace(substrate),
            };
            let mut solver = LayeredSolver::new(&stack).unwrap();
            let closed = TransferFactor::new(coating, substrate);
            for t in log_space(1e-8, 1e8, 65) {
                let a = solver.surface_factor(t);
                let expected = if t < 300.0 { closed.factor(t) } else { 1.0 };
                let error = ((a - expected) / expected).abs();
                worst = worst.max(error);
                assert!(
                    error < 1e-10,
                    "E1/E2 = {ratio}, kh = {t}: {a} vs {expected}"
                );
            }
        }
        eprintln!("E ratio 1e4 and 1e-4 vs Perriot-Barthel: worst {worst:.1e}");
    }

    #[test]
    fn displacement_transfer_is_along_the_wave_vector() {
        let stack = Stack {
            layers: vec![ply(3.0, 0.25, 0.4), ply(0.2, 0.4, 0.3)],
            base: BASES[0],
        };
        let mut solver = LayeredSolver::new(&stack).unwrap();
        let (kx, ky) = (0.6, -0.8);
        for (layer, z) in [(0, 0.0), (0, 0.2), (1, 0.5), (2, 1.5)] {
            let r = solver.plane_response(1.0, layer, z);
            let [ux, uy, w] = solver.displacement_transfer(kx, ky, layer, z);
            assert_eq!(w, Complex::new(r.w, 0.0));
            assert_eq!(ux, Complex::new(0.0, r.u_xi * kx));
            assert_eq!(uy, Complex::new(0.0, r.u_xi * ky));
        }
        // At the surface w is the compliance of A: 2 (1 - nu^2) / (E k) A.
        let a = solver.surface_factor(1.0);
        let w = solver.plane_response(1.0, 0, 0.0).w;
        assert!((w - 2.0 * (1.0 - 0.0625) / 3.0 * a).abs() < 1e-15 * w);
    }
}
