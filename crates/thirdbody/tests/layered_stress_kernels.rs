//! Stress kernels of layered stacks (`LayeredStressKernels`: the six stresses per unit
//! pressure on one square surface cell) against references that share nothing with
//! their split into Love's kernels, carriers and a lattice/Hankel remainder:
//! 1. a direct quadrature of the Fourier integral of one cell's stresses,
//!    `K(X, Y) = (1 / 4 pi^2) int T(k, z) h^2 sinc(kx h/2) sinc(ky h/2) e^{i k.X} d^2k`,
//!    with `T` from `LayeredSolver::plane_response` (polar: Gauss–Legendre panels in
//!    |k|, graded towards 0, then one unit wide up to `k z = 36`; the trapezoid rule in
//!    angle, with more points than the angular bandwidth `k (|X| + h)`), for stiff and
//!    soft, thin and thick layers on bonded and frictionless rigid bases and on
//!    half-spaces, in every layer and on both sides of interfaces; the quadrature's
//!    own convergence is checked by doubling its points;
//! 2. window independence: one cell's coefficients on lattices of 9², 65² and 257²
//!    offsets (a stiff thin layer in a three-layer stack);
//! 3. consistency: identical layers on an identical half-space are Love's kernels
//!    (`HomogeneousStressKernels`); splitting a layer into two of the same material
//!    changes nothing; a layer whose thickness goes to zero disappears, linearly;
//! 4. interfaces: sigma_z, tau_xz, tau_yz read on both sides agree, and so do the
//!    in-plane strains computed from each side's stresses in its own material.
//!
//! Components are in the order of `thirdbody::stress::COMPONENTS`: sigma_x, sigma_y,
//! sigma_z, tau_xy, tau_xz, tau_yz. Errors are relative to the largest coefficient
//! of the production table at that depth (its "peak").

use std::f64::consts::PI;
use std::sync::OnceLock;

use rayon::prelude::*;
use thirdbody::body::layered::{Base, BaseContact, LayeredSolver, Ply, Stack};
use thirdbody::stress::{
    HomogeneousStressKernels, InfluenceTable, LayeredStressKernels, OffsetLattice, Side,
    StressKernels,
};
use thirdbody::Elastic;

const NAMES: [&str; 6] = [
    "sigma_x", "sigma_y", "sigma_z", "tau_xy", "tau_xz", "tau_yz",
];

fn elastic(young: f64, poisson: f64) -> Elastic {
    Elastic { young, poisson }
}

fn ply(material: Elastic, thickness: f64) -> Ply {
    Ply {
        material,
        thickness,
    }
}

fn kernels(stack: &Stack, side: Side) -> LayeredStressKernels {
    LayeredStressKernels {
        stack: stack.clone(),
        interface_side: side,
    }
}

/// A centred lattice of `(2 half + 1)^2` offsets.
fn centred(half: usize, cell: f64) -> OffsetLattice {
    let n = 2 * half + 1;
    OffsetLattice {
        cell,
        x_first: -(half as f64),
        cols: n,
        y_first: -(half as f64),
        rows: n,
    }
}

fn fill(k: &dyn StressKernels, z: f64, lattice: &OffsetLattice) -> InfluenceTable {
    let mut t = InfluenceTable::default();
    k.fill(z, lattice, &mut t);
    t
}

fn peak(t: &InfluenceTable) -> f64 {
    t.values
        .iter()
        .flatten()
        .fold(0.0f64, |m, v| m.max(v.abs()))
}

/// The six coefficients at the offset `(x, y)` cells of a table.
fn at(t: &InfluenceTable, x: i64, y: i64) -> [f64; 6] {
    let l = t.lattice.expect("a filled table");
    let col = (x as f64 - l.x_first) as usize;
    let row = (y as f64 - l.y_first) as usize;
    std::array::from_fn(|c| t.get(c, col, row))
}

/// The index of the layer that holds depth z, read on `side` at an interface
/// (`layers.len()`: the half-space base), as `LayeredStressKernels` documents it.
fn layer_at(stack: &Stack, z: f64, side: Side) -> usize {
    let n = stack.layers.len();
    let half_space = matches!(stack.base, Base::HalfSpace(_));
    for (i, &bottom) in stack.interface_depths().iter().enumerate() {
        if z < bottom {
            return i;
        }
        if z == bottom {
            let below = i + 1 < n || half_space;
            return if side == Side::Below && below {
                i + 1
            } else {
                i
            };
        }
    }
    if half_space {
        n
    } else {
        n - 1
    }
}

/// Gauss–Legendre nodes and weights on [-1, 1] (Newton on the Legendre polynomial).
fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let mut x = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut derivative = 0.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, x);
                for j in 2..=n {
                    let j = j as f64;
                    (p0, p1) = (p1, ((2.0 * j - 1.0) * x * p1 - (j - 1.0) * p0) / j);
                }
                derivative = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                let step = p1 / derivative;
                x -= step;
                if step.abs() < 1e-16 {
                    break;
                }
            }
            (x, 2.0 / ((1.0 - x * x) * derivative * derivative))
        })
        .collect()
}

fn sinc(t: f64) -> f64 {
    if t.abs() < 1e-8 {
        1.0 - t * t / 6.0
    } else {
        t.sin() / t
    }
}

/// The shallowest depth the direct quadrature serves, in cells.
const Z_MIN: f64 = 0.05;
/// The quadrature stops at `k z = K_Z`: the transfer, at most `~(k z)^2 e^{-k z}`, is
/// then below 1e-13.
const K_Z: f64 = 36.0;
/// Cell side of the direct quadrature.
const CELL: f64 = 1.0;
/// The offsets of the direct quadrature, in cells.
const OFFSETS: [(i64, i64); 4] = [(0, 0), (1, 0), (2, 3), (5, 1)];

/// The direct quadrature's nodes in |k| and, per offset and node, the angular
/// integrals of the cell factor times the phase (everything that does not depend on
/// the stack or the depth).
struct Quadrature {
    /// `(k, w k / 4 pi^2)`, w the radial weight, ascending in k.
    nodes: Vec<(f64, f64)>,
    /// Per offset, per node: `int_0^{2 pi} P(k, theta) [c^2 cos phi, s^2 cos phi, c s
    /// cos phi, -c sin phi, -s sin phi] d theta`, `(c, s) = (cos, sin) theta`,
    /// `phi = k (X c + Y s)`, `P = h^2 sinc(k c h / 2) sinc(k s h / 2)`.
    angular: Vec<Vec<[f64; 5]>>,
}

impl Quadrature {
    /// `points` Gauss–Legendre points per panel: 20 panels halving from 1 towards 0
    /// (the first [0, 2^-20]), then panels `width` wide up to `K_Z / Z_MIN`; `refine`
    /// times the angular points.
    fn new(points: usize, width: f64, refine: usize) -> Quadrature {
        let rule = gauss_legendre(points);
        let mut bounds = vec![0.0];
        bounds.extend((0..=20).rev().map(|j| 2f64.powi(-j)));
        let k_max = K_Z / Z_MIN;
        while *bounds.last().unwrap() < k_max {
            let b = *bounds.last().unwrap();
            bounds.push(b + width);
        }
        let mut nodes = Vec::new();
        for w in bounds.windows(2) {
            let (half, mid) = (0.5 * (w[1] - w[0]), 0.5 * (w[1] + w[0]));
            for &(u, wt) in &rule {
                let k = mid + half * u;
                nodes.push((k, wt * half * k / (4.0 * PI * PI)));
            }
        }
        let angular = OFFSETS
            .iter()
            .map(|&(x, y)| {
                let (x, y) = (x as f64 * CELL, y as f64 * CELL);
                nodes
                    .par_iter()
                    .map(|&(k, _)| angular_integrals(k, x, y, refine))
                    .collect()
            })
            .collect();
        Quadrature { nodes, angular }
    }

    /// The six coefficients `[sigma_x, sigma_y, sigma_z, tau_xy, tau_xz, tau_yz]` of
    /// `stack` at depth z (read on `side`) at each of `OFFSETS`.
    fn coefficients(&self, stack: &Stack, z: f64, side: Side) -> Vec<[f64; 6]> {
        assert!(z >= Z_MIN, "depth {z} below the quadrature's {Z_MIN}");
        let layer = layer_at(stack, z, side);
        let used = self.nodes.partition_point(|&(k, _)| k * z <= K_Z);
        let transfers: Vec<[f64; 4]> = self.nodes[..used]
            .par_iter()
            .map_init(
                || LayeredSolver::new(stack).expect("a valid stack"),
                |solver, &(k, _)| solver.plane_response(k, layer, z).stress,
            )
            .collect();
        self.angular
            .iter()
            .map(|angular| {
                let mut out = [0.0; 6];
                for ((t, &(_, w)), a) in transfers.iter().zip(&self.nodes).zip(angular) {
                    let [f0, f1, f2, f3] = t.map(|v| v * w);
                    out[0] += f0 * a[0] + f1 * a[1];
                    out[1] += f0 * a[1] + f1 * a[0];
                    out[2] += f2 * (a[0] + a[1]);
                    out[3] += (f0 - f1) * a[2];
                    out[4] += f3 * a[3];
                    out[5] += f3 * a[4];
                }
                out
            })
            .collect()
    }
}

/// The angular integrals of [`Quadrature::angular`] at wavenumber k for the offset
/// `(x, y)`: the trapezoid rule on the half period `[0, pi)` (the integrands are
/// pi-periodic), with more points than the integrand's angular bandwidth `k (r + h)`
/// (its Fourier coefficients in theta fall off like Bessel functions beyond it).
fn angular_integrals(k: f64, x: f64, y: f64, refine: usize) -> [f64; 5] {
    let h = CELL;
    let band = k * (x.hypot(y) + h);
    let n = refine * (0.6 * band + 5.0 * band.cbrt() + 16.0).ceil() as usize;
    let dt = PI / n as f64;
    let mut acc = [0.0; 5];
    for j in 0..n {
        let (s, c) = ((j as f64 + 0.5) * dt).sin_cos();
        let p = h * h * sinc(0.5 * k * c * h) * sinc(0.5 * k * s * h);
        let (sp, cp) = (k * (x * c + y * s)).sin_cos();
        let (pc, ps) = (p * cp, p * sp);
        acc[0] += c * c * pc;
        acc[1] += s * s * pc;
        acc[2] += c * s * pc;
        acc[3] -= c * ps;
        acc[4] -= s * ps;
    }
    // Twice the half period.
    acc.map(|v| 2.0 * dt * v)
}

fn quadrature() -> &'static Quadrature {
    static Q: OnceLock<Quadrature> = OnceLock::new();
    Q.get_or_init(|| Quadrature::new(12, 1.0, 1))
}

/// A named stack and the depths `(z, side)` checked in it.
type Case = (String, Stack, Vec<(f64, Side)>);

/// The stacks of the direct-quadrature test: a stiff (E ratio 30) or soft (1/30)
/// layer, thin (0.05 cell) or thick (20 cells), over a unit layer, on a bonded or
/// frictionless rigid base, and two on a half-space; with the depths `(z, side)`
/// checked in each.
fn quadrature_cases() -> Vec<Case> {
    let a = elastic(1.0, 0.3);
    let stiff = elastic(30.0, 0.25);
    let soft = elastic(1.0 / 30.0, 0.4);
    let depths = |t: f64, half_space: bool| {
        let mut d = if t < 1.0 {
            vec![
                (t, Side::Above),
                (t, Side::Below),
                (t + 0.03, Side::Above),
                (t + 0.5, Side::Above),
                (t + 1.0, Side::Above),
            ]
        } else {
            vec![
                (0.3 * t, Side::Above),
                (t, Side::Above),
                (t, Side::Below),
                (t + 0.1, Side::Above),
                (t + 0.5, Side::Above),
                (t + 1.0, Side::Above),
            ]
        };
        if half_space {
            d.push((t + 1.0, Side::Below));
            d.push((t + 2.0, Side::Above));
        }
        d
    };
    let mut cases = Vec::new();
    for (name, x) in [("stiff", stiff), ("soft", soft)] {
        for t in [0.05, 20.0] {
            for contact in [BaseContact::Bonded, BaseContact::Frictionless] {
                cases.push((
                    format!("{name} {t} over 1, rigid {contact:?}"),
                    Stack {
                        layers: vec![ply(x, t), ply(a, 1.0)],
                        base: Base::Rigid(contact),
                    },
                    depths(t, false),
                ));
            }
        }
    }
    let base = elastic(3.0, 0.2);
    cases.push((
        "stiff 0.05 over 1, half-space 3".into(),
        Stack {
            layers: vec![ply(stiff, 0.05), ply(a, 1.0)],
            base: Base::HalfSpace(base),
        },
        depths(0.05, true),
    ));
    cases.push((
        "soft 20 over 1, half-space 3".into(),
        Stack {
            layers: vec![ply(soft, 20.0), ply(a, 1.0)],
            base: Base::HalfSpace(base),
        },
        depths(20.0, true),
    ));
    cases
}

/// The largest difference, relative to `peak`, between the production table and the
/// quadrature's coefficients at the offsets of `OFFSETS`, and where.
fn worst_against(table: &InfluenceTable, reference: &[[f64; 6]], peak: f64) -> (f64, String) {
    let mut worst = (0.0, String::new());
    for (&(x, y), want) in OFFSETS.iter().zip(reference) {
        let got = at(table, x, y);
        for c in 0..6 {
            let e = (got[c] - want[c]).abs() / peak;
            if e > worst.0 {
                worst = (
                    e,
                    format!("({x}, {y}) {}: {:.9e} vs {:.9e}", NAMES[c], got[c], want[c]),
                );
            }
        }
    }
    worst
}

/// Test 1: the production kernels against the direct quadrature, to 1e-6 of the
/// peak at that depth.
#[test]
fn kernels_match_a_direct_fourier_quadrature() {
    let q = quadrature();
    let lattice = centred(5, CELL);
    let mut failures = Vec::new();
    let mut overall = 0.0f64;
    for (name, stack, depths) in quadrature_cases() {
        for (z, side) in depths {
            let k = kernels(&stack, side);
            let method = k.method_at(z, &lattice);
            let table = fill(&k, z, &lattice);
            let p = peak(&table);
            let reference = q.coefficients(&stack, z, side);
            let (e, at) = worst_against(&table, &reference, p);
            overall = overall.max(e);
            eprintln!(
                "{name}, z {z} {side:?} ({method:?}): {e:.1e} of the peak {p:.3e}; worst {at}"
            );
            if e > 1e-6 {
                failures.push(format!(
                    "{name}, z {z} {side:?} ({method:?}): {e:.1e}, {at}"
                ));
            }
        }
    }
    eprintln!("largest difference: {overall:.1e} of the peak");
    assert!(
        failures.is_empty(),
        "kernels off the direct quadrature by more than 1e-6 of the peak:\n{}",
        failures.join("\n")
    );
}

/// The direct quadrature is converged: twice the points per radial panel and twice
/// the angular points change no coefficient by 1e-8 of the peak, on the hardest cases (the shallowest depth, the widest offset, a thick stiff
/// layer's deep field).
#[test]
fn direct_quadrature_is_converged() {
    let coarse = quadrature();
    let fine = Quadrature::new(24, 1.0, 2);
    let lattice = centred(5, CELL);
    let cases = quadrature_cases();
    let mut worst = 0.0f64;
    for (name, stack, depths) in &cases {
        if !(name.starts_with("stiff 0.05 over 1, rigid Bonded")
            || name.starts_with("stiff 20 over 1, rigid Frictionless")
            || name.starts_with("soft 20 over 1, half-space"))
        {
            continue;
        }
        for &(z, side) in depths {
            let p = peak(&fill(&kernels(stack, side), z, &lattice));
            let a = coarse.coefficients(stack, z, side);
            let b = fine.coefficients(stack, z, side);
            let e = a
                .iter()
                .flatten()
                .zip(b.iter().flatten())
                .fold(0.0f64, |m, (u, v)| m.max((u - v).abs()))
                / p;
            eprintln!("{name}, z {z} {side:?}: doubling changes {e:.1e} of the peak");
            worst = worst.max(e);
        }
    }
    eprintln!("largest change on doubling: {worst:.1e} of the peak");
    assert!(worst < 1e-8, "quadrature not converged: {worst:.1e}");
}

/// Test 2: one cell's coefficients do not depend on the window: lattices of 9², 65²
/// and 257² offsets agree on their common offsets to 1e-8 of the peak, for a stiff
/// thin layer (E ratio 30, 0.1 cell) on two more layers and a half-space.
#[test]
fn coefficients_do_not_depend_on_the_window() {
    let stack = Stack {
        layers: vec![
            ply(elastic(30.0, 0.25), 0.1),
            ply(elastic(1.0, 0.3), 1.0),
            ply(elastic(0.2, 0.4), 2.0),
        ],
        base: Base::HalfSpace(elastic(3.0, 0.2)),
    };
    let halves = [4usize, 32, 128];
    let mut worst_all = 0.0f64;
    for (z, side) in [
        (0.0, Side::Above),
        (0.05, Side::Above),
        (0.1, Side::Above),
        (0.1, Side::Below),
        (0.6, Side::Above),
        (1.1, Side::Above),
        (1.1, Side::Below),
        (3.1, Side::Above),
        (3.1, Side::Below),
        (5.0, Side::Above),
    ] {
        let k = kernels(&stack, side);
        let tables: Vec<InfluenceTable> = halves
            .iter()
            .map(|&h| fill(&k, z, &centred(h, 1.0)))
            .collect();
        let big = &tables[2];
        let p = peak(big);
        let mut worst = 0.0f64;
        for (&half, t) in halves.iter().zip(&tables).take(2) {
            let n = 2 * half + 1;
            let shift = halves[2] - half;
            for c in 0..6 {
                for m in 0..n {
                    for i in 0..n {
                        let d = t.get(c, i, m) - big.get(c, i + shift, m + shift);
                        worst = worst.max(d.abs() / p);
                    }
                }
            }
        }
        let method = k.method_at(z, &centred(halves[0], 1.0));
        eprintln!("z {z} {side:?} ({method:?} on 9²): {worst:.1e} of the peak");
        worst_all = worst_all.max(worst);
    }
    eprintln!("largest window dependence: {worst_all:.1e} of the peak");
    assert!(worst_all < 1e-8, "window dependence {worst_all:.1e}");
}

/// Test 3a: identical layers on an identical half-space are Love's half-space, to
/// 1e-12 of the peak, in each layer, on both sides of each interface and in the base.
#[test]
fn identical_layers_are_a_half_space() {
    let m = elastic(1.0, 0.3);
    let stack = Stack {
        layers: vec![ply(m, 0.3), ply(m, 1.0), ply(m, 0.5)],
        base: Base::HalfSpace(m),
    };
    let lattice = centred(8, 1.0);
    let love = HomogeneousStressKernels { material: m };
    let mut worst_all = 0.0f64;
    for (z, side) in [
        (0.0, Side::Above),
        (0.1, Side::Above),
        (0.3, Side::Above),
        (0.3, Side::Below),
        (0.8, Side::Above),
        (1.3, Side::Above),
        (1.3, Side::Below),
        (1.8, Side::Above),
        (1.8, Side::Below),
        (2.5, Side::Above),
    ] {
        let k = kernels(&stack, side);
        let got = fill(&k, z, &lattice);
        let want = fill(&love, z, &lattice);
        let p = peak(&want);
        let e = max_difference(&got, &want) / p;
        eprintln!(
            "z {z} {side:?} ({:?}): {e:.1e} of the peak",
            k.method_at(z, &lattice)
        );
        worst_all = worst_all.max(e);
    }
    eprintln!("largest difference from Love's: {worst_all:.1e} of the peak");
    assert!(
        worst_all < 1e-12,
        "identical layers off Love's by {worst_all:.1e}"
    );
}

fn max_difference(a: &InfluenceTable, b: &InfluenceTable) -> f64 {
    a.values
        .iter()
        .flatten()
        .zip(b.values.iter().flatten())
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
}

/// Test 3b: splitting a layer into two of the same material changes nothing:
/// `[A 1.0, B 0.5]` on C against `[A 0.4, A 0.6, B 0.5]` on C, cell 0.25, to 1e-10 of
/// the peak (the two stacks' kernels are split differently: the carriers' depth in
/// the lower A part is `2 h1 - z` in one and z in the other).
#[test]
fn splitting_a_layer_changes_nothing() {
    let (a, b, c) = (elastic(1.0, 0.3), elastic(5.0, 0.25), elastic(0.5, 0.35));
    let whole = Stack {
        layers: vec![ply(a, 1.0), ply(b, 0.5)],
        base: Base::HalfSpace(c),
    };
    let split = Stack {
        layers: vec![ply(a, 0.4), ply(a, 0.6), ply(b, 0.5)],
        base: Base::HalfSpace(c),
    };
    let lattice = centred(8, 0.25);
    let mut worst_all = 0.0f64;
    for (z, side) in [
        (0.0, Side::Above),
        (0.2, Side::Above),
        (0.4, Side::Above),
        (0.4, Side::Below),
        (0.7, Side::Above),
        (1.0, Side::Above),
        (1.0, Side::Below),
        (1.2, Side::Above),
        (1.5, Side::Above),
        (1.5, Side::Below),
        (2.0, Side::Above),
    ] {
        let (kw, ks) = (kernels(&whole, side), kernels(&split, side));
        let tw = fill(&kw, z, &lattice);
        let ts = fill(&ks, z, &lattice);
        let e = max_difference(&tw, &ts) / peak(&tw);
        eprintln!(
            "z {z} {side:?} ({:?} / {:?}): {e:.1e} of the peak",
            kw.method_at(z, &lattice),
            ks.method_at(z, &lattice)
        );
        worst_all = worst_all.max(e);
    }
    eprintln!("largest change on splitting: {worst_all:.1e} of the peak");
    assert!(
        worst_all < 1e-10,
        "splitting a layer changed the kernels by {worst_all:.1e}"
    );
}

/// Test 3c: a layer whose thickness t goes to zero disappears: the kernels of `[X t,
/// A 1]` on C approach those of `[A 1]` on C, the difference falling linearly in t:
/// ratio ~2 per halving of t = 4e-3 ... 5e-4, within 0.15, and closer to 2 at each
/// halving (the second-order term, about 28 t relative here, halves with t).
#[test]
fn a_vanishing_layer_disappears_linearly() {
    let (x, a, c) = (elastic(5.0, 0.2), elastic(1.0, 0.3), elastic(0.5, 0.35));
    let without = Stack {
        layers: vec![ply(a, 1.0)],
        base: Base::HalfSpace(c),
    };
    let lattice = centred(4, 1.0);
    let thicknesses = [4e-3, 2e-3, 1e-3, 5e-4];
    let mut failures = Vec::new();
    for z in [0.3, 0.7, 1.5] {
        let want = fill(&kernels(&without, Side::Above), z, &lattice);
        let p = peak(&want);
        let d: Vec<f64> = thicknesses
            .iter()
            .map(|&t| {
                let with = Stack {
                    layers: vec![ply(x, t), ply(a, 1.0)],
                    base: Base::HalfSpace(c),
                };
                max_difference(&fill(&kernels(&with, Side::Above), z, &lattice), &want) / p
            })
            .collect();
        let ratios: Vec<f64> = d.windows(2).map(|w| w[0] / w[1]).collect();
        let list =
            |v: &[f64], f: fn(&f64) -> String| v.iter().map(f).collect::<Vec<_>>().join(", ");
        eprintln!(
            "z {z}: difference {} of the peak for t = {thicknesses:?}; ratios {}",
            list(&d, |v| format!("{v:.2e}")),
            list(&ratios, |v| format!("{v:.3}"))
        );
        let approaching = ratios
            .windows(2)
            .all(|w| (w[1] - 2.0).abs() < (w[0] - 2.0).abs());
        if ratios.iter().any(|r| (r - 2.0).abs() > 0.15) || !approaching {
            failures.push(format!("z {z}: {d:?}, ratios {ratios:?}"));
        }
    }
    assert!(
        failures.is_empty(),
        "the vanishing layer's effect does not fall linearly:\n{}",
        failures.join("\n")
    );
}

/// The strains `[eps_xx, eps_yy, eps_xy]` of the stresses `s` (kernel order) in the
/// material m.
fn in_plane_strains(s: [f64; 6], m: Elastic) -> [f64; 3] {
    let (e, nu) = (m.young, m.poisson);
    [
        (s[0] - nu * (s[1] + s[2])) / e,
        (s[1] - nu * (s[0] + s[2])) / e,
        (1.0 + nu) * s[3] / e,
    ]
}

/// Test 4: at every interface of a three-layer stack (on a half-space, and on a
/// bonded rigid base), the tractions sigma_z, tau_xz, tau_yz read above and below
/// agree to 1e-8 of the peak, and so do the in-plane strains, each side's from its
/// own stresses and material, to 1e-8 of the peak strain; then the sigma_x below
/// predicted from the strains above and the continuous sigma_z is the one read below.
#[test]
fn interfaces_carry_tractions_and_strains() {
    let layers = vec![
        ply(elastic(1.0, 0.3), 0.5),
        ply(elastic(10.0, 0.2), 0.3),
        ply(elastic(0.2, 0.4), 1.0),
    ];
    let base = elastic(2.0, 0.25);
    let lattice = centred(8, 1.0);
    let mut worst = [0.0f64; 3];
    for stack in [
        Stack {
            layers: layers.clone(),
            base: Base::HalfSpace(base),
        },
        Stack {
            layers: layers.clone(),
            base: Base::Rigid(BaseContact::Bonded),
        },
    ] {
        let half_space = matches!(stack.base, Base::HalfSpace(_));
        let depths = stack.interface_depths();
        let interfaces = if half_space {
            depths.len()
        } else {
            depths.len() - 1
        };
        for (i, &z) in depths.iter().take(interfaces).enumerate() {
            let above_m = stack.layers[i].material;
            let below_m = stack.layers.get(i + 1).map_or(base, |p| p.material);
            let above = fill(&kernels(&stack, Side::Above), z, &lattice);
            let below = fill(&kernels(&stack, Side::Below), z, &lattice);
            let p = peak(&above).max(peak(&below));
            let (mut traction, mut strain, mut jump) = (0.0f64, 0.0f64, 0.0f64);
            let mut strain_peak = 0.0f64;
            let cells = lattice.cols * lattice.rows;
            let mut pairs = Vec::with_capacity(cells);
            for n in 0..cells {
                let sa: [f64; 6] = std::array::from_fn(|c| above.values[c][n]);
                let sb: [f64; 6] = std::array::from_fn(|c| below.values[c][n]);
                for c in [2, 4, 5] {
                    traction = traction.max((sa[c] - sb[c]).abs() / p);
                }
                let (ea, eb) = (in_plane_strains(sa, above_m), in_plane_strains(sb, below_m));
                for q in 0..3 {
                    strain_peak = strain_peak.max(ea[q].abs()).max(eb[q].abs());
                }
                // sigma_x below from the strains above and sigma_z:
                // sigma_x = E (e_xx + nu e_yy) / (1 - nu^2) + nu sigma_z / (1 - nu).
                let (e, nu) = (below_m.young, below_m.poisson);
                let predicted =
                    e * (ea[0] + nu * ea[1]) / (1.0 - nu * nu) + nu * sa[2] / (1.0 - nu);
                jump = jump.max((predicted - sb[0]).abs() / p);
                pairs.push((ea, eb));
            }
            for (ea, eb) in pairs {
                for q in 0..3 {
                    strain = strain.max((ea[q] - eb[q]).abs() / strain_peak);
                }
            }
            eprintln!(
                "{} base, interface {i} (z {z}): tractions {traction:.1e} of the peak, \
                 in-plane strains {strain:.1e} of the peak strain, sigma_x below from the \
                 strains above {jump:.1e} of the peak",
                if half_space {
                    "half-space"
                } else {
                    "bonded rigid"
                }
            );
            worst = [
                worst[0].max(traction),
                worst[1].max(strain),
                worst[2].max(jump),
            ];
        }
    }
    eprintln!(
        "largest: tractions {:.1e}, strains {:.1e}, sigma_x jump {:.1e}",
        worst[0], worst[1], worst[2]
    );
    assert!(
        worst[0] < 1e-8,
        "tractions jump by {:.1e} of the peak",
        worst[0]
    );
    assert!(worst[1] < 1e-8, "in-plane strains jump by {:.1e}", worst[1]);
    assert!(
        worst[2] < 1e-8,
        "sigma_x jump off by {:.1e} of the peak",
        worst[2]
    );
}

/// Test 5: a stack of isotropic layers is symmetric about the plane y = 0, so its
/// kernels have Love's parity in y (declared by `parity_in_y`; XZ sections tabulate
/// only the offsets `|y|`): `K(x, -y) = +-K(x, y)` to 1e-13 of the peak (rounding
/// in the remainder's lattice sums), under the thick-coating limit, the sub-cell
/// split and the full expansion.
#[test]
fn kernels_have_loves_parity_in_y() {
    let love = HomogeneousStressKernels {
        material: elastic(1.0, 0.3),
    };
    let stacks = [
        (
            Stack {
                layers: vec![ply(elastic(3.0, 0.3), 1e6)],
                base: Base::HalfSpace(elastic(1.0, 0.3)),
            },
            vec![0.0, 2.0],
        ),
        (
            Stack {
                layers: vec![ply(elastic(30.0, 0.25), 0.1), ply(elastic(1.0, 0.3), 1.0)],
                base: Base::HalfSpace(elastic(0.2, 0.4)),
            },
            vec![0.0, 0.05, 0.3, 1.1, 4.0],
        ),
        (
            Stack {
                layers: vec![ply(elastic(1.0 / 30.0, 0.45), 3.0)],
                base: Base::Rigid(BaseContact::Bonded),
            },
            vec![0.0, 1.0, 3.0],
        ),
    ];
    let lattice = centred(24, 1.0);
    let mut worst_all = 0.0f64;
    for (stack, depths) in &stacks {
        let k = kernels(stack, Side::Above);
        let even = k.parity_in_y().expect("a stack declares its parity");
        assert_eq!(Some(even), love.parity_in_y());
        for &z in depths {
            let t = fill(&k, z, &lattice);
            let p = peak(&t);
            let mut worst = 0.0f64;
            for y in 1..=24 {
                for x in -24..=24 {
                    let (a, b) = (at(&t, x, y), at(&t, x, -y));
                    for c in 0..6 {
                        let d = if even[c] { a[c] - b[c] } else { a[c] + b[c] };
                        worst = worst.max(d.abs() / p);
                    }
                }
            }
            eprintln!(
                "z {z} ({:?}): {worst:.1e} of the peak",
                k.method_at(z, &lattice)
            );
            worst_all = worst_all.max(worst);
        }
    }
    assert!(worst_all < 1e-13, "asymmetry {worst_all:.1e} of the peak");
}
