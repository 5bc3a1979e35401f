//! The long-wave part of the coated-body stress remainder (see [`super::layered_kernels`]),
//! computed in free space, without the periodic images of a lattice sum:
//! `K(X) = (1 / 4 pi^2) int chi(k) T(k, phi) P(k, phi) e^{i k.X} d^2k`, with the
//! remainder's transfer `T` in wave-frame form, the cell factor `P = h^2 sinc(kx h/2)
//! sinc(ky h/2)` and the band limit `chi(k) = e^{-q} (1 + q + q^2/2 + q^3/6)`, `q = (k/k1)^2`. In polar coordinates
//! each angular Fourier mode `g_n(k) e^{i n phi}` of `chi T P` integrates to a Bessel
//! function, `int e^{i n phi} e^{i k r cos(phi - theta)} dphi = 2 pi i^n J_n(k r)
//! e^{i n theta}` (Watson, Theory of Bessel Functions, §2.22), so
//! `K(r, theta) = (1 / 2 pi) sum_{n >= 0} [cos(n theta) A_n(r) + sin(n theta) B_n(r)]`
//! with the Hankel transforms `A_n = int k a_n(k) J_n(k r) dk`, `a_n = Re(i^n (g_n +
//! g_-n))`, `B_n` likewise with `b_n = Re(i^(n+1) (g_n - g_-n))` (`a_0 = Re g_0`,
//! `b_0 = 0`). The k integral is Gauss–Legendre on panels graded geometrically towards
//! k = 0, where the transfer of a stiff coating varies on the scale of its membrane
//! length, and no wider than the oscillation of `J_n(k r_max)` allows; the angular modes
//! come from a DFT of the integrand on equally spaced angles (spectrally accurate for
//! a smooth periodic function); the `A_n`, `B_n` are tabulated on Chebyshev panels in r
//! (band-limited, so smooth) and summed at every offset. Everything but the transfer
//! itself depends only on the lattice and `k1` ([`LongWaveBasis`], kept by the
//! caller between depths): the modes are linear in the four wave-frame transfers, so
//! a depth combines the modes of the unit transfers at each k node, and the Bessel
//! functions `J_n(k r)` at all node pairs are computed once.

use std::f64::consts::PI;

use rayon::prelude::*;
use realfft::num_complex::Complex;

use super::kernels::{OffsetLattice, RowSource, COMPONENTS};
use crate::body::layered::{LayeredSolver, Stack};
use crate::body::quadrature::{GaussLegendre, SharedPanels};

/// A wave-frame transfer `[xixi, etaeta, zz, xiz / i]` of the wavenumber k (in
/// 1/length), evaluated with a [`LayeredSolver`] of `stack` that the caller owns:
/// parallel loops build one solver per thread (`map_init`) and reuse it for every
/// wavenumber, instead of one per evaluation.
pub(super) struct Radial<'a> {
    /// The stack whose solvers `eval` takes.
    pub stack: &'a Stack,
    /// The transfer at k, with a solver of `stack`.
    pub eval: &'a (dyn Fn(&mut LayeredSolver, f64) -> [f64; 4] + Sync),
}

impl Radial<'_> {
    /// A solver for [`Radial::eval`].
    pub fn solver(&self) -> LayeredSolver {
        LayeredSolver::new(self.stack).expect("a validated stack")
    }

    /// The transfer at every wavenumber of `ks`, in parallel, one solver per thread.
    pub fn eval_all(&self, ks: &[f64]) -> Vec<[f64; 4]> {
        ks.par_iter()
            .map_init(|| self.solver(), |solver, &k| (self.eval)(solver, k))
            .collect()
    }
}

/// Terms of the long waves' share: `chi(k) = e^{-q} sum_{j < TERMS} q^j / j!`, `q =
/// (k / k1)^2`. Then `1 - chi = O(k^16)` at k = 0, so the short-wave complement keeps
/// almost none of the remainder's long-range structure: its kernel is the remainder
/// minus a Gaussian smoothing of width ~1/k1 whose moments vanish up to order 15 (a
/// Gaussian times a Laguerre polynomial), so beyond the remainder's own scales it
/// falls off like `(k1 r)^-16` times the remainder's 16th derivative.
const TERMS: i32 = 8;

/// The long waves' share `chi(k)` of the remainder.
pub(super) fn long_wave_share(k: f64, k1: f64) -> f64 {
    let q = (k / k1).powi(2);
    let (mut term, mut sum) = (1.0, 0.0);
    for j in 0..TERMS {
        sum += term;
        term *= q / (j + 1) as f64;
    }
    (-q).exp() * sum
}

/// `1 - chi(k)`, accurate where it is small (`e^{-q} sum_{j >= TERMS} q^j / j!`).
pub(super) fn short_wave_share(k: f64, k1: f64) -> f64 {
    let q = (k / k1).powi(2);
    if q >= 4.0 {
        return 1.0 - long_wave_share(k, k1);
    }
    let mut term = 1.0;
    for j in 1..=TERMS {
        term *= q / j as f64;
    }
    let mut sum = 0.0;
    for j in TERMS + 1..TERMS + 60 {
        sum += term;
        term *= q / j as f64;
    }
    (-q).exp() * sum
}

/// `chi` is below 1e-17 beyond `BAND_EDGE k1`.
pub(super) const BAND_EDGE: f64 = 8.0;
/// Angles of the DFT of the integrand, and the highest angular order kept.
const ANGLES: usize = 64;
const MAX_ORDER: usize = 24;
/// Gauss–Legendre points per k panel; Chebyshev points per r panel.
const K_POINTS: usize = 16;
const R_POINTS: usize = 24;
/// The graded k panels reach down to `k_edge 2^-GRADING` (below it the integrand,
/// O(k^3), adds nothing at double precision).
const GRADING: i32 = 30;

/// The work of [`long_wave_kernels`] that depends on the lattice and the split
/// wavenumber only, not on the transfer (so not on the depth): the k nodes, the
/// angular modes of the four unit wave-frame transfers at each (the modes are
/// linear in the transfer), the r nodes, the Bessel functions `J_n(k r)` at every
/// pair of nodes and the interpolation axes. A section's depths share one lattice,
/// so the caller keeps it between depths (in the [`super::kernels::InfluenceTable`]
/// it fills, one per thread); it is rebuilt when the lattice or the split changes.
#[derive(Clone, Default)]
pub struct LongWaveBasis {
    key: Option<(OffsetLattice, f64)>,
    /// The k nodes.
    ks: Vec<f64>,
    /// Per k node and unit transfer q, the modes (entries as [`angular_modes`]'s):
    /// `unit_modes[(node * 4 + q) * ENTRIES + e]`.
    unit_modes: Vec<f64>,
    r_max: f64,
    panels: usize,
    /// `J_n(k r)`, n up to `MAX_ORDER`: `bessel[(r_node * ks.len() + node) * (MAX_ORDER +
    /// 1) + n]`.
    bessel: Vec<f64>,
    r_count: usize,
    axes: Option<(InterpolationAxis, InterpolationAxis)>,
}

impl std::fmt::Debug for LongWaveBasis {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LongWaveBasis")
            .field("key", &self.key)
            .field("k_nodes", &self.ks.len())
            .field("r_nodes", &self.r_count)
            .finish()
    }
}

/// Entries of the angular modes per k node: `[c][n][cos | sin]`.
const ENTRIES: usize = COMPONENTS * (MAX_ORDER + 1) * 2;

impl LongWaveBasis {
    /// Builds the basis for `lattice` and `k1` unless it holds it already.
    fn prepare(&mut self, lattice: &OffsetLattice, k1: f64) {
        if self.key == Some((*lattice, k1)) {
            return;
        }
        let h = lattice.cell;
        let k_edge = k1 * BAND_EDGE;
        let extent = |first: f64, count: usize| {
            let (a, b) = (first * h, (first + count as f64 - 1.0) * h);
            a.abs().max(b.abs())
        };
        let r_max = extent(lattice.x_first, lattice.cols)
            .hypot(extent(lattice.y_first, lattice.rows))
            .max(h);

        let nodes = polar_nodes(k_edge, r_max, 0.0);

        // Angular modes per k node of the unit transfers (times the weight).
        let dft = rustfft::FftPlanner::<f64>::new().plan_fft_forward(ANGLES);
        let unit_modes: Vec<f64> = nodes
            .par_iter()
            .flat_map_iter(|&(k, weight)| {
                let dft = dft.as_ref();
                (0..4).flat_map(move |q| {
                    let t = std::array::from_fn(|i| if i == q { 1.0 } else { 0.0 });
                    angular_modes(k, h, k1, weight, t, dft)
                })
            })
            .collect();

        // Bessel functions at the Chebyshev points in r.
        let panels = ((r_max * k_edge / 8.0).ceil() as usize).max(1);
        let r_nodes =
            crate::body::quadrature::ChebyshevPanels::points(0.0, r_max, panels, R_POINTS);
        let bessel: Vec<f64> = r_nodes
            .par_iter()
            .flat_map_iter(|&r| {
                let mut j = vec![0.0; MAX_ORDER + 1];
                nodes.iter().flat_map(move |&(k, _)| {
                    bessel_j_upto(k * r, &mut j);
                    j.clone()
                })
            })
            .collect();
        let x_axis = InterpolationAxis::new(lattice.x_first * h, lattice.cols, h, k_edge);
        let y_axis = InterpolationAxis::new(lattice.y_first * h, lattice.rows, h, k_edge);
        *self = LongWaveBasis {
            key: Some((*lattice, k1)),
            ks: nodes.iter().map(|&(k, _)| k).collect(),
            unit_modes,
            r_max,
            panels,
            bessel,
            r_count: r_nodes.len(),
            axes: Some((x_axis, y_axis)),
        };
    }
}

/// The k nodes of a polar integral over `k < k_edge` whose integrand holds `e^{i k.X}`
/// for `|X|` up to `r_max`, and their weights times k (the polar Jacobian):
/// Gauss–Legendre on panels graded geometrically towards k = 0 and no wider than `8 /
/// r_max`. The grading stops at `k_edge 2^-GRADING`, or above it at `floor` (> 0): a
/// first panel `[0, floor]` integrates the transfer exactly to rounding once `floor`
/// is far below the inverse of its longest length.
pub(super) fn polar_nodes(k_edge: f64, r_max: f64, floor: f64) -> Vec<(f64, f64)> {
    let rule = GaussLegendre::new(K_POINTS);
    let widest = 8.0 / r_max;
    let mut bounds = vec![0.0];
    let levels = if floor > 0.0 {
        ((k_edge / floor).log2().ceil() as i32).clamp(0, GRADING)
    } else {
        GRADING
    };
    for i in (0..=levels).rev() {
        let hi = k_edge * 2f64.powi(-i);
        let lo = *bounds.last().unwrap_or(&0.0);
        let pieces = ((hi - lo) / widest).ceil().max(1.0) as usize;
        for p in 1..=pieces {
            bounds.push(lo + (hi - lo) * p as f64 / pieces as f64);
        }
    }
    let mut nodes = Vec::new();
    for w in bounds.windows(2) {
        let (lo, hi) = (w[0], w[1]);
        let (half, mid) = (0.5 * (hi - lo), 0.5 * (hi + lo));
        for (x, wt) in rule.nodes.iter().zip(&rule.weights) {
            let k = mid + half * x;
            nodes.push((k, wt * half * k));
        }
    }
    nodes
}

/// The band-limited long-wave part of a remainder with wave-frame transfer
/// `radial(k) = [xixi, etaeta, zz, xiz / i]` (k in 1/length), at every offset of
/// `lattice`: `[sigma_x, ..., tau_yz]`, offsets row-major as in the influence tables.
/// `basis` holds (or is given) the work that does not depend on the transfer.
pub(super) fn long_wave_kernels(
    lattice: &OffsetLattice,
    k1: f64,
    radial: &Radial,
    basis: &mut LongWaveBasis,
) -> [Vec<f64>; COMPONENTS] {
    basis.prepare(lattice, k1);
    let Some(samples) = long_wave_samples(radial, basis) else {
        return std::array::from_fn(|_| vec![0.0; lattice.cols * lattice.rows]);
    };
    let (x_axis, y_axis) = basis.axes.as_ref().expect("prepared above");
    let (nx, ny, cols) = (x_axis.nodes.len(), y_axis.nodes.len(), lattice.cols);
    let mut out: [Vec<f64>; COMPONENTS] = std::array::from_fn(|_| Vec::new());
    for (c, o) in out.iter_mut().enumerate() {
        // Along x: u[j][col] = sum_i G[j][i] Wx[i][col].
        let u: Vec<Vec<f64>> = (0..ny)
            .into_par_iter()
            .map(|j| x_axis.interpolate(|i| samples[j * nx + i][c]))
            .collect();
        // Along y: out[row][col] = sum_j Wy[j][row] u[j][col].
        let rows: Vec<Vec<f64>> = (0..lattice.rows)
            .into_par_iter()
            .map(|m| {
                let mut line = vec![0.0; cols];
                y_axis.accumulate(m, &u, &mut line);
                line
            })
            .collect();
        *o = rows.concat();
    }
    out
}

/// The long waves' stresses along the row of `source` (added to `row`), for the
/// offsets of `lattice` (the section's: columns `-(nx - 1) ..= nx - 1`, one row per
/// loaded source row): with the kernel's tensor interpolant `K(x, y) = sum_{a,b}
/// G_ab Wx_a(x) Wy_b(y)` (the samples G of [`long_wave_kernels`] at the Chebyshev
/// nodes, the barycentric weights W), `sigma(x_i) = sum_{k,l} p_kl K(x_i - x_k, y -
/// y_l) = sum_{a,b} G_ab Q_ab(i)`, where the pressure's moments `Q_ab(i) = sum_{k,l}
/// p_kl Wx_a(x_i - x_k) Wy_b(y - y_l)` depend on the lattice and the pressure only
/// (`source` keeps them for all depths): per depth `(a, b, i)` products instead of
/// the interpolation to every offset and the row transforms.
pub(super) fn long_wave_on_row(
    lattice: &OffsetLattice,
    k1: f64,
    radial: &Radial,
    basis: &mut LongWaveBasis,
    source: &RowSource,
    row: &mut [Vec<f64>; COMPONENTS],
) {
    basis.prepare(lattice, k1);
    let Some(samples) = long_wave_samples(radial, basis) else {
        return;
    };
    let (x_axis, y_axis) = basis.axes.as_ref().expect("prepared above");
    let moments = source.moments(lattice, k1, || {
        pressure_moments(lattice, x_axis, y_axis, source)
    });
    let nx = source.nx;
    for (g, q) in samples.iter().zip(moments.chunks_exact(nx)) {
        for (out, &gc) in row.iter_mut().zip(g) {
            for (o, &v) in out.iter_mut().zip(q) {
                *o += gc * v;
            }
        }
    }
}

/// The pressure's moments `Q_ab(i)` of [`long_wave_on_row`], `[(b * nodes_x + a) *
/// nx + i]` (b the y node, a the x node): `R_b(k) = sum_l p_kl Wy_b(row of l)`, then
/// along x the convolution `Q_ab(i) = sum_k Wx_a(column of i - k) R_b(k)` by FFT.
fn pressure_moments(
    lattice: &OffsetLattice,
    x_axis: &InterpolationAxis,
    y_axis: &InterpolationAxis,
    source: &RowSource,
) -> Vec<f64> {
    let (nx, ny) = (source.nx, source.rows());
    let pressure = source.pressure();
    assert_eq!(lattice.cols, 2 * nx - 1, "the section's columns");
    assert_eq!(lattice.x_first, -(nx as f64 - 1.0), "the section's columns");
    // Source row l sits at lattice row m = offset - l - y_first.
    let lattice_row = |l: usize| -> Option<usize> {
        let m = (source.offset - l as f64 - lattice.y_first).round();
        (m >= 0.0 && m < lattice.rows as f64).then_some(m as usize)
    };
    let (nodes_x, nodes_y) = (x_axis.nodes.len(), y_axis.nodes.len());
    let along_y: Vec<Vec<f64>> = (0..nodes_y)
        .map(|b| {
            let mut r = vec![0.0; nx];
            for l in 0..ny {
                let line = &pressure[l * nx..(l + 1) * nx];
                match lattice_row(l) {
                    Some(m) => {
                        let w = y_axis.weights[b * y_axis.count + m];
                        for (acc, &p) in r.iter_mut().zip(line) {
                            *acc += w * p;
                        }
                    }
                    None => assert!(
                        line.iter().all(|&p| p == 0.0),
                        "a loaded source row outside the lattice"
                    ),
                }
            }
            r
        })
        .collect();
    // Linear convolution of the columns' weights (2 nx - 1) with R_b (nx).
    let len = (3 * nx).next_power_of_two();
    let mut planner = realfft::RealFftPlanner::<f64>::new();
    let forward = planner.plan_fft_forward(len);
    let inverse = planner.plan_fft_inverse(len);
    let transform = |values: &[f64]| {
        let mut real = vec![0.0; len];
        real[..values.len()].copy_from_slice(values);
        let mut spec = vec![Complex::default(); len / 2 + 1];
        forward
            .process(&mut real, &mut spec)
            .expect("FFT lengths are fixed by the plan");
        spec
    };
    let weights_x: Vec<Vec<Complex<f64>>> = (0..nodes_x)
        .into_par_iter()
        .map(|a| transform(&x_axis.weights[a * x_axis.count..(a + 1) * x_axis.count]))
        .collect();
    let scale = 1.0 / len as f64;
    (0..nodes_y)
        .into_par_iter()
        .flat_map_iter(|b| {
            let r = transform(&along_y[b]);
            let mut spec = vec![Complex::default(); len / 2 + 1];
            let mut real = vec![0.0; len];
            let mut out = Vec::with_capacity(nodes_x * nx);
            for w in &weights_x {
                for ((s, a), c) in spec.iter_mut().zip(w).zip(&r) {
                    *s = a * c;
                }
                inverse
                    .process(&mut spec, &mut real)
                    .expect("FFT lengths are fixed by the plan");
                // Q(i) = (W * R)(i + nx - 1).
                out.extend(real[nx - 1..2 * nx - 1].iter().map(|v| v * scale));
            }
            out
        })
        .collect()
}

/// The long waves' kernel at the tensor nodes of `basis` (`[j * nodes_x + i]`, j the
/// y node): the transfer at the k nodes, the Hankel transforms at the r nodes and the
/// kernel at the tensor nodes. `None` if the transfer vanishes.
fn long_wave_samples(radial: &Radial, basis: &LongWaveBasis) -> Option<Vec<[f64; COMPONENTS]>> {
    let (r_max, panels) = (basis.r_max, basis.panels);
    let n_nodes = basis.ks.len();

    // Angular modes per k node: `[c][n][cos | sin]` radial functions (times weight),
    // the transfer's combination of the unit transfers' modes.
    let transfers = radial.eval_all(&basis.ks);
    let per_node: Vec<Vec<f64>> = transfers
        .iter()
        .enumerate()
        .map(|(node, t)| {
            let mut f = vec![0.0; ENTRIES];
            for (q, &tq) in t.iter().enumerate() {
                if tq == 0.0 {
                    continue;
                }
                let unit = &basis.unit_modes[(node * 4 + q) * ENTRIES..][..ENTRIES];
                for (a, u) in f.iter_mut().zip(unit) {
                    *a += tq * u;
                }
            }
            f
        })
        .collect();
    let entries_all = ENTRIES;
    // Keep the modes that matter (bounded by the sum of |f| since |J_n| <= 1).
    let size: Vec<f64> = (0..entries_all)
        .map(|e| per_node.iter().map(|f| f[e].abs()).sum())
        .collect();
    let largest = size.iter().fold(0.0f64, |m, &v| m.max(v));
    let kept: Vec<usize> = (0..entries_all)
        .filter(|&e| size[e] > 1e-15 * largest && largest > 0.0)
        .collect();
    if kept.is_empty() {
        return None;
    }
    let order_of = |e: usize| (e / 2) % (MAX_ORDER + 1);
    let top_order = kept.iter().map(|&e| order_of(e)).max().unwrap_or(0);

    // Hankel transforms at the Chebyshev points in r.
    let orders = MAX_ORDER + 1;
    // The kept entries of each node, contiguous, and the nodes that matter: a node
    // whose every kept entry is below 1e-18 of the largest sum bound adds less than
    // that to any transform (|J_n| <= 1); near k = 0 the graded panels hold many.
    let kept_order: Vec<usize> = kept.iter().map(|&e| order_of(e)).collect();
    let floor = 1e-18 * largest;
    let nodes: Vec<(usize, Vec<f64>)> = per_node
        .iter()
        .enumerate()
        .filter(|(_, f)| kept.iter().any(|&e| f[e].abs() > floor))
        .map(|(node, f)| (node, kept.iter().map(|&e| f[e]).collect()))
        .collect();
    let transforms: Vec<Vec<f64>> = (0..basis.r_count)
        .into_par_iter()
        .map(|ri| {
            let mut sums = vec![0.0; kept.len()];
            let row = &basis.bessel[ri * n_nodes * orders..][..n_nodes * orders];
            for (node, f) in &nodes {
                let j = &row[node * orders..][..orders];
                for ((s, &fe), &n) in sums.iter_mut().zip(f).zip(&kept_order) {
                    *s += fe * j[n];
                }
            }
            sums
        })
        .collect();
    let columns: Vec<Vec<f64>> = (0..kept.len())
        .map(|q| transforms.iter().map(|t| t[q]).collect())
        .collect();
    let table = SharedPanels::from_values(0.0, r_max, panels, R_POINTS, &columns);

    // The band-limited kernel at one point.
    let at = |x: f64, y: f64, h_values: &mut [f64], trig: &mut [(f64, f64)]| {
        let r = x.hypot(y);
        let (c, s) = if r > 0.0 { (x / r, y / r) } else { (1.0, 0.0) };
        trig[0] = (1.0, 0.0);
        for n in 1..trig.len() {
            let (cp, sp) = trig[n - 1];
            trig[n] = (cp * c - sp * s, sp * c + cp * s);
        }
        table.eval_into(r, h_values);
        let mut v = [0.0; COMPONENTS];
        for (&e, hv) in kept.iter().zip(h_values.iter()) {
            let (cn, sn) = trig[order_of(e)];
            let factor = if e % 2 == 0 { cn } else { sn };
            v[e / (2 * (MAX_ORDER + 1))] += factor * hv;
        }
        v.map(|t| t / (2.0 * PI))
    };
    // It is an entire function of exponential type k_edge, so on the offsets'
    // rectangle it is a tensor Chebyshev interpolant of modest degree: sample it at
    // the Chebyshev points and interpolate to the offsets (barycentric formula;
    // Trefethen, Approximation Theory and Approximation Practice, ch. 5), or take the
    // offsets themselves where there are fewer of them.
    let (x_axis, y_axis) = basis.axes.as_ref().expect("prepared above");
    let samples: Vec<[f64; COMPONENTS]> = y_axis
        .nodes
        .par_iter()
        .flat_map_iter(|&y| {
            let mut h_values = vec![0.0; kept.len()];
            let mut trig = vec![(0.0, 0.0); top_order + 1];
            x_axis
                .nodes
                .iter()
                .map(move |&x| at(x, y, &mut h_values, &mut trig))
                .collect::<Vec<_>>()
        })
        .collect();
    Some(samples)
}

/// One axis of the tensor interpolation: the sample points (Chebyshev points of the
/// second kind spanning the offsets, or the offsets themselves) and the barycentric
/// weights of every offset, `weights[i * count + m]` for sample i and offset m.
#[derive(Clone)]
struct InterpolationAxis {
    nodes: Vec<f64>,
    count: usize,
    weights: Vec<f64>,
}

impl InterpolationAxis {
    fn new(first: f64, count: usize, h: f64, k_edge: f64) -> Self {
        let (lo, hi) = (first, first + (count as f64 - 1.0) * h);
        let half = 0.5 * (hi - lo);
        // Chebyshev coefficients of e^{i k x} on a half-width w decay like J_n(k w):
        // negligible (1e-16) beyond n ~ k w + 10 (k w)^(1/3) + 12.
        let kw = k_edge * half;
        let degree = (kw + 10.0 * kw.cbrt() + 12.0).ceil() as usize;
        if count <= degree + 1 {
            let nodes: Vec<f64> = (0..count).map(|m| first + m as f64 * h).collect();
            let mut weights = vec![0.0; count * count];
            for m in 0..count {
                weights[m * count + m] = 1.0;
            }
            return InterpolationAxis {
                nodes,
                count,
                weights,
            };
        }
        let n = degree + 1;
        let mid = 0.5 * (hi + lo);
        let nodes: Vec<f64> = (0..n)
            .map(|i| mid + half * (PI * i as f64 / degree as f64).cos())
            .collect();
        let bary: Vec<f64> = (0..n)
            .map(|i| {
                let sign = if i % 2 == 0 { 1.0 } else { -1.0 };
                if i == 0 || i == degree {
                    0.5 * sign
                } else {
                    sign
                }
            })
            .collect();
        let mut weights = vec![0.0; n * count];
        for m in 0..count {
            let t = first + m as f64 * h;
            if let Some(i) = nodes.iter().position(|&x| x == t) {
                weights[i * count + m] = 1.0;
                continue;
            }
            let terms: Vec<f64> = nodes.iter().zip(&bary).map(|(x, w)| w / (t - x)).collect();
            let total: f64 = terms.iter().sum();
            for (i, term) in terms.iter().enumerate() {
                weights[i * count + m] = term / total;
            }
        }
        InterpolationAxis {
            nodes,
            count,
            weights,
        }
    }

    /// The interpolant at every offset of the values `sample(i)` at the nodes.
    fn interpolate(&self, sample: impl Fn(usize) -> f64) -> Vec<f64> {
        let mut line = vec![0.0; self.count];
        for i in 0..self.nodes.len() {
            let g = sample(i);
            for (l, w) in line.iter_mut().zip(&self.weights[i * self.count..]) {
                *l += g * w;
            }
        }
        line
    }

    /// `line += sum_j w_j(offset m) u[j]`.
    fn accumulate(&self, m: usize, u: &[Vec<f64>], line: &mut [f64]) {
        for (j, uj) in u.iter().enumerate() {
            let w = self.weights[j * self.count + m];
            if w != 0.0 {
                for (l, v) in line.iter_mut().zip(uj) {
                    *l += w * v;
                }
            }
        }
    }
}

/// `sin(t) / t`.
fn sinc(t: f64) -> f64 {
    if t.abs() < 1e-8 {
        1.0 - t * t / 6.0
    } else {
        t.sin() / t
    }
}

/// The radial functions `a_n`, `b_n` of the six components at wavenumber k, times
/// `weight`: entry `(c (MAX_ORDER + 1) + n) 2 + {0: cos, 1: sin}`.
fn angular_modes(
    k: f64,
    h: f64,
    k1: f64,
    weight: f64,
    t: [f64; 4],
    dft: &dyn rustfft::Fft<f64>,
) -> Vec<f64> {
    let chi = long_wave_share(k, k1);
    let [xixi, etaeta, zz, xiz] = t.map(|v| v * chi * h * h);
    // The integrand of each component at the DFT angles.
    let mut samples = [[Complex::<f64>::default(); ANGLES]; COMPONENTS];
    #[allow(clippy::needless_range_loop)] // j indexes six arrays and sets the angle.
    for j in 0..ANGLES {
        let phi = 2.0 * PI * j as f64 / ANGLES as f64;
        let (s, c) = phi.sin_cos();
        let p = sinc(0.5 * k * h * c) * sinc(0.5 * k * h * s);
        samples[0][j] = Complex::new((xixi * c * c + etaeta * s * s) * p, 0.0);
        samples[1][j] = Complex::new((xixi * s * s + etaeta * c * c) * p, 0.0);
        samples[2][j] = Complex::new(zz * p, 0.0);
        samples[3][j] = Complex::new((xixi - etaeta) * c * s * p, 0.0);
        samples[4][j] = Complex::new(0.0, xiz * c * p);
        samples[5][j] = Complex::new(0.0, xiz * s * p);
    }
    for g in samples.iter_mut() {
        dft.process(g);
    }
    // Mode n of the samples (the DFT's bin n mod ANGLES, over ANGLES).
    let mode = |g: &[Complex<f64>; ANGLES], n: i64| -> Complex<f64> {
        g[n.rem_euclid(ANGLES as i64) as usize] / ANGLES as f64
    };
    let i_pow = |n: usize| {
        [
            Complex::new(1.0, 0.0),
            Complex::i(),
            -Complex::new(1.0, 0.0),
            -Complex::i(),
        ][n % 4]
    };
    let mut out = vec![0.0; COMPONENTS * (MAX_ORDER + 1) * 2];
    for (c, g) in samples.iter().enumerate() {
        for n in 0..=MAX_ORDER {
            let (a, b) = if n == 0 {
                (mode(g, 0).re, 0.0)
            } else {
                let (plus, minus) = (mode(g, n as i64), mode(g, -(n as i64)));
                (
                    (i_pow(n) * (plus + minus)).re,
                    (i_pow(n + 1) * (plus - minus)).re,
                )
            };
            let e = (c * (MAX_ORDER + 1) + n) * 2;
            out[e] = a * weight;
            out[e + 1] = b * weight;
        }
    }
    out
}

/// `J_0(x) .. J_{n-1}(x)` into `j` (x >= 0): forward recurrence from libm's J_0 and
/// J_1 where it is stable (orders below x), downward recurrence from libm's two
/// highest orders where that is stable (orders above x), libm's `jn` per order where
/// the highest orders underflow.
fn bessel_j_upto(x: f64, j: &mut [f64]) {
    let n = j.len();
    j[0] = libm::j0(x);
    if n == 1 {
        return;
    }
    j[1] = libm::j1(x);
    let stable = (x.floor() as usize).clamp(2, n);
    for q in 2..stable {
        j[q] = 2.0 * (q - 1) as f64 / x * j[q - 1] - j[q - 2];
    }
    if stable >= n {
        return;
    }
    let (top, below) = (libm::jn(n as i32 - 1, x), libm::jn(n as i32 - 2, x));
    if top.abs() < 1e-290 || below.abs() < 1e-290 {
        for (q, v) in j.iter_mut().enumerate().skip(stable) {
            *v = libm::jn(q as i32, x);
        }
        return;
    }
    j[n - 1] = top;
    j[n - 2] = below;
    for q in (stable..n - 2).rev() {
        j[q] = 2.0 * (q + 1) as f64 / x * j[q + 1] - j[q + 2];
    }
}
