//! Depth-independent bases of a layered body's remainder along one row of outputs (an
//! XZ section). On the periodic box of [`super::layered_kernels`] the remainder's
//! short waves at depth z give the row
//! `sigma_c(x_i) = sum_j w(j) (1 - chi(|k_j|)) A_c(r(|k_j|, z), k_j / |k_j|) P(j) e^{i k_j x_i}`,
//! with the pressure's spectrum `P`, the cell factor and row phase `w`, the high-pass
//! share `1 - chi` and the four wave-frame functions `r_q(|k|, z)` entering the six
//! components linearly through the angular factors `c^2, s^2, c s, i c, i s`. Only
//! `r_q` depends on the depth. Interpolating it in `theta = |k| h` on Chebyshev panels
//! shared by every depth, `r_q(theta) = sum_b r_q(theta_b) l_b(theta)` (barycentric
//! Lagrange basis `l_b`, Berrut and Trefethen, SIAM Review 46 (2004) 501), gives
//! `sigma_c(x_i) = sum_{q,b} r_q(theta_b, z) Psi_{c,q,b}(x_i)`: the five angular rows
//! `Psi_{a,b}(x_i) = IFFT_x[sum_jy l_b w (1 - chi) f_a P]` (kept as `c^2 + s^2`, `c^2 -
//! s^2`, `c s`, `c`, `s`) are built once per section, and a depth costs the transfer
//! at the nodes and six products per node and column instead of a sum over the box's
//! wavenumbers. A family of rows takes any share of the remainder given as a
//! function of |k| ([`Share`]): the caller splits the short waves over two boxes and
//! a banded depth's part below its bands ([`super::layered_kernels`]). The long
//! waves ([`LongWaveRow`]) are rows per polar node in the same way.
//!
//! The panels grow geometrically (ratio 2 near k = 0, 1.5 beyond): on `[a, rho a]` the
//! degree-19 interpolant of any `e^{-theta L}` is within `e^{-a L} (rho - 1)^20 (a L /
//! 4)^20 / 20!` of it, at most 2e-14 of its value at 0 for `rho = 2` whatever L, so one
//! set of panels serves every depth's decay length.

use std::f64::consts::PI;

use ndarray::linalg::general_mat_mul;
use ndarray::{Array2, ArrayView2, ShapeBuilder};
use rayon::prelude::*;
use realfft::num_complex::Complex;
use realfft::RealFftPlanner;

use super::kernels::{PressureSpectrum, COMPONENTS};
use super::long_wave::BAND_EDGE;

/// Chebyshev points (first kind) per panel: the degree of the former per-depth tables.
const POINTS: usize = 20;
/// Angular rows per node: `c^2, s^2, c s, i c, i s`.
const ANGULAR: usize = 5;
/// Below this theta the panels double; above it they grow by 1.5.
const DOUBLING_BELOW: f64 = 0.05;

/// Panels `[lo, hi]` of theta from 0 to `top`: `[0, first]`, then geometric.
fn geometric_panels(first: f64, top: f64) -> Vec<(f64, f64)> {
    if first >= top {
        return vec![(0.0, top)];
    }
    let mut panels = vec![(0.0, first)];
    let mut lo = first;
    while lo < top {
        let ratio = if lo < DOUBLING_BELOW { 2.0 } else { 1.5 };
        let hi = (lo * ratio).min(top);
        panels.push((lo, hi));
        lo = hi;
    }
    panels
}

/// The Chebyshev points of a panel (as `ChebyshevPanels::points`) and their
/// barycentric weights `(-1)^k sin((k + 1/2) pi / n)`.
fn panel_nodes((lo, hi): (f64, f64)) -> [f64; POINTS] {
    let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
    std::array::from_fn(|k| mid + half * (PI * (k as f64 + 0.5) / POINTS as f64).cos())
}

fn barycentric_weights() -> [f64; POINTS] {
    std::array::from_fn(|k| {
        let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
        sign * (PI * (k as f64 + 0.5) / POINTS as f64).sin()
    })
}

/// The Lagrange basis of `nodes` at t (barycentric formula; exact at a node).
fn lagrange(nodes: &[f64; POINTS], bary: &[f64; POINTS], t: f64) -> [f64; POINTS] {
    let mut l = [0.0; POINTS];
    if let Some(k) = nodes.iter().position(|&x| x == t) {
        l[k] = 1.0;
        return l;
    }
    let mut total = 0.0;
    for ((lk, &x), &w) in l.iter_mut().zip(nodes).zip(bary) {
        *lk = w / (t - x);
        total += *lk;
    }
    for lk in l.iter_mut() {
        *lk /= total;
    }
    l
}

/// A share of the remainder as a function of `theta = |k| h` (a difference of the
/// smooth steps `1 - chi`), and the theta beyond which a family of rows ends.
pub(super) struct Share<'a> {
    pub share: &'a (dyn Fn(f64) -> f64 + Sync),
    pub top: f64,
}

/// The short waves of a layered body's remainder along a row, as rows per
/// interpolation node (module doc).
pub(super) struct ShortWaveRow {
    panels: Vec<(f64, f64)>,
    /// Theta of each node, panel after panel.
    nodes: Vec<f64>,
    /// `psi[(node * ANGULAR + a) * nx + i]`.
    psi: Vec<f64>,
    /// The band family's nodes (the first of `nodes`; 0 without the family).
    band_nodes: usize,
    /// The band family's rows, as `psi` with the share `chi(k / kx) - chi(k / k1)`
    /// instead of `1 - chi(k / k1)`.
    psi_band: Vec<f64>,
    nx: usize,
}

impl ShortWaveRow {
    /// The rows for outputs at x offsets `0..nx` cells (cell centres) from the
    /// pressure's spectrum on a box of `len` cells whose row phase has the fraction
    /// `frac_y` (cells), for the share `main` of the remainder up to its top (`theta =
    /// |k| h`, below pi: no aliases) and optionally a second family with the share
    /// `band`, up to its top. The first panel ends at `first` (a share is negligible
    /// below it).
    pub(super) fn new(
        spectrum: &PressureSpectrum,
        len: usize,
        frac_y: f64,
        nx: usize,
        first: f64,
        main: Share,
        band: Option<Share>,
    ) -> Self {
        let theta_top = main.top;
        assert!(theta_top < PI, "the row basis sums no aliases");
        let panels = geometric_panels(first, theta_top);
        let panel_points: Vec<[f64; POINTS]> = panels.iter().map(|&p| panel_nodes(p)).collect();
        let nodes: Vec<f64> = panel_points.iter().flatten().copied().collect();
        let bary = barycentric_weights();
        let count = nodes.len() * ANGULAR;
        // The band family's wavenumbers end at its top, within the rows.
        let band_edge = band.as_ref().map_or(0.0, |b| b.top.min(theta_top));
        let band_nodes = panels.partition_point(|&(lo, _)| lo < band_edge) * POINTS;
        let total = count + band_nodes * ANGULAR;
        let base = |j: usize| {
            let j = if j <= len / 2 {
                j as f64
            } else {
                j as f64 - len as f64
            };
            2.0 * PI * j / len as f64
        };
        let sinc = |t: f64| {
            if t.abs() < 1e-8 {
                1.0 - t * t / 6.0
            } else {
                t.sin() / t
            }
        };
        let weight_y: Vec<Complex<f64>> = (0..len)
            .map(|j| {
                let t = base(j);
                Complex::from_polar(sinc(0.5 * t), t * frac_y)
            })
            .collect();
        let norm = 1.0 / (len * len) as f64;
        let half = len / 2 + 1;
        let locate = |theta: f64| -> usize {
            panels
                .partition_point(|&(_, hi)| hi < theta)
                .min(panels.len() - 1)
        };
        // Per column jx: sum_jy l_b w (1 - chi) f_a P, `[node * ANGULAR + a]`.
        let columns: Vec<Vec<f64>> = (0..half)
            .into_par_iter()
            .map(|jx| {
                let tx = base(jx);
                if tx.abs() > theta_top {
                    return Vec::new();
                }
                let wx = sinc(0.5 * tx) * norm;
                // Real and imaginary parts apart, `[((panel * ANGULAR + a) * 2 + part) *
                // POINTS + b]` per family, so that a point's update of its panel is ten
                // contiguous rank-one updates that vectorise.
                let mut sums = vec![0.0; 2 * total];
                let column = spectrum.column(jx);
                // Rows +ty and -ty share theta, c and the Lagrange weights, and s
                // changes sign: their sum takes the even factors, their difference the
                // odd ones.
                for jy in 0..=len / 2 {
                    let ty = base(jy);
                    let theta = (tx * tx + ty * ty).sqrt();
                    if theta > theta_top {
                        break;
                    }
                    let high_pass = (main.share)(theta);
                    let band_share = match &band {
                        Some(b) if theta < band_edge => (b.share)(theta),
                        _ => 0.0,
                    };
                    if high_pass == 0.0 && band_share == 0.0 {
                        continue;
                    }
                    let (c, s) = if theta > 0.0 {
                        (tx / theta, ty / theta)
                    } else {
                        (1.0, 0.0)
                    };
                    let plus = column[jy] * weight_y[jy] * wx;
                    let partner = len - jy;
                    let minus = if jy == 0 || partner == jy {
                        Complex::default()
                    } else {
                        column[partner] * weight_y[partner] * wx
                    };
                    let (even, odd) = (plus + minus, plus - minus);
                    let panel = locate(theta);
                    let l = lagrange(&panel_points[panel], &bary, theta);
                    let (cc, ss, cs) = (c * c, s * s, c * s);
                    let mut accumulate = |first: usize, scale: f64| {
                        let (e, o) = (even * scale, odd * scale);
                        let parts = [
                            e.re * cc,
                            e.im * cc,
                            e.re * ss,
                            e.im * ss,
                            o.re * cs,
                            o.im * cs,
                            e.re * c,
                            e.im * c,
                            o.re * s,
                            o.im * s,
                        ];
                        let at = &mut sums[2 * first + panel * 2 * ANGULAR * POINTS..]
                            [..2 * ANGULAR * POINTS];
                        for (line, &part) in at.chunks_exact_mut(POINTS).zip(&parts) {
                            for (v, &lb) in line.iter_mut().zip(&l) {
                                *v += part * lb;
                            }
                        }
                    };
                    if high_pass != 0.0 {
                        accumulate(0, high_pass);
                    }
                    if band_share != 0.0 {
                        accumulate(count, band_share);
                    }
                }
                sums
            })
            .collect();
        // Along x: one inverse transform per node and angular row, a panel of a
        // family at a time (its sums are contiguous in every column).
        let inverse = RealFftPlanner::<f64>::new().plan_fft_inverse(len);
        let block = 2 * ANGULAR * POINTS;
        let panels_of = |nodes: usize| nodes / POINTS;
        let tasks: Vec<usize> = (0..panels_of(nodes.len()))
            .map(|p| p * block)
            .chain((0..panels_of(band_nodes)).map(|p| 2 * count + p * block))
            .collect();
        let mut psi: Vec<f64> = tasks
            .par_iter()
            .flat_map_iter(|&first| {
                // spec[k][jx], k = (a * 2 + part) * POINTS + b as in the columns.
                let mut gathered = vec![0.0; block * half];
                for (jx, col) in columns.iter().enumerate() {
                    if col.is_empty() {
                        continue;
                    }
                    for (k, &v) in col[first..first + block].iter().enumerate() {
                        gathered[k * half + jx] = v;
                    }
                }
                let mut out = vec![0.0; POINTS * ANGULAR * nx];
                let mut spec = vec![Complex::default(); half];
                let mut line = vec![0.0; len];
                for b in 0..POINTS {
                    for a in 0..ANGULAR {
                        let re = &gathered[((a * 2) * POINTS + b) * half..][..half];
                        let im = &gathered[((a * 2 + 1) * POINTS + b) * half..][..half];
                        let shear = a >= 3;
                        for ((s, &r), &i) in spec.iter_mut().zip(re).zip(im) {
                            *s = if shear {
                                Complex::new(-i, r)
                            } else {
                                Complex::new(r, i)
                            };
                        }
                        spec[0].im = 0.0;
                        spec[half - 1].im = 0.0;
                        inverse
                            .process(&mut spec, &mut line)
                            .expect("FFT lengths are fixed by the plan");
                        out[(b * ANGULAR + a) * nx..][..nx].copy_from_slice(&line[..nx]);
                    }
                }
                out
            })
            .collect();
        to_sum_and_difference(&mut psi, nx);
        let psi_band = psi.split_off(count * nx);
        ShortWaveRow {
            panels,
            nodes,
            psi,
            band_nodes,
            psi_band,
            nx,
        }
    }

    /// The interpolation nodes (theta), panel after panel.
    pub(super) fn nodes(&self) -> &[f64] {
        &self.nodes
    }

    /// The nodes a depth whose transfer is negligible beyond `theta_cut` takes:
    /// those of the panels that start below it (of the band family's with `band`).
    pub(super) fn used(&self, theta_cut: f64, band: bool) -> usize {
        let used = self.panels.partition_point(|&(lo, _)| lo < theta_cut) * POINTS;
        if band {
            used.min(self.band_nodes)
        } else {
            used
        }
    }

    /// Adds to `rows[d]` the short waves of depth d from the wave-frame functions
    /// `[xixi, etaeta, zz, xiz / i]` at its [`Self::used`] nodes: with the rows of the
    /// share `1 - chi(k / k1)`, or where `band` with the band family's `chi(k / kx) -
    /// chi(k / k1)` (the part of a banded depth's remainder below the bands it sums on
    /// small boxes). The depths are taken together, each node's rows read once for
    /// all of them.
    pub(super) fn add_many(
        &self,
        depths: &[(bool, &[[f64; 4]])],
        rows: &mut [[Vec<f64>; COMPONENTS]],
    ) {
        let jobs: Vec<(&[f64], &[[f64; 4]])> = depths
            .iter()
            .map(|&(band, values)| {
                let psi: &[f64] = if band { &self.psi_band } else { &self.psi };
                (psi, values)
            })
            .collect();
        add_rows_many(&jobs, self.nx, rows);
    }
}

/// Points per axis of the Lagrange stencil that interpolates the pressure's
/// spectrum, and the oversampling of its grid: the centred spectrum's frequencies
/// are at most `n / 2` cells, so on a grid of `2 pi / (OVERSAMPLING n)` the stencil's
/// error is about `(pi / OVERSAMPLING)^q ((q / 2)!)^2 / q!`, 5e-14 of its largest
/// value.
const STENCIL: usize = 14;
const OVERSAMPLING: f64 = 16.0;

/// The long waves of a layered body's remainder along a row, as rows per polar k
/// node: `sigma_c(x_i) = (1 / 4 pi^2) int chi(k) T_c(k) S(k) E(k) e^{i k.(x_i, y)} d^2k`
/// (theta units, h = 1), with the cell factor `S = sinc(kx / 2) sinc(ky / 2)` and the
/// pressure's spectrum `E(k) = sum p_lm e^{-i (kx m + ky l)}`, in polar coordinates:
/// Gauss–Legendre in |k| ([`super::long_wave::polar_nodes`], as the Hankel
/// transforms of the kernel tables), the trapezoidal rule in the angle over as
/// many angles as `e^{i k r_max cos}` needs (half of them: the other half gives the
/// complex conjugate). `E` at the polar points is interpolated from a fine grid of
/// the centred spectrum computed directly. As for the short waves, only the
/// wave-frame transfer depends on the depth, so a depth costs the transfer at the k
/// nodes and `nodes x 9 x nx` products.
pub(super) struct LongWaveRow {
    /// The k nodes (theta units).
    thetas: Vec<f64>,
    /// `psi[(node * ANGULAR + a) * nx + i]`.
    psi: Vec<f64>,
    nx: usize,
}

impl LongWaveRow {
    /// The rows for outputs at x offsets `0..nx` cells from source column 0 and `offset`
    /// cells along y from source row 0, of the pressure `p[l * nx + m]` on `ny` rows,
    /// for the long-wave share `chi(theta / k1h)` (band-limited to `BAND_EDGE k1h`), with
    /// offsets at most `r_max` cells from a source, for transfers whose longest length
    /// is `longest` cells (their panels graded down to a sixteenth of its inverse).
    pub(super) fn new(
        pressure: &[f64],
        nx: usize,
        ny: usize,
        offset: f64,
        k1h: f64,
        r_max: f64,
        longest: f64,
    ) -> Self {
        let k_edge = BAND_EDGE * k1h;
        let nodes = super::long_wave::polar_nodes(k_edge, r_max, 1.0 / (16.0 * longest));
        let spectrum = CentredSpectrum::new(pressure, nx, ny, k_edge);
        let (cx, cy) = (0.5 * (nx as f64 - 1.0), 0.5 * (ny as f64 - 1.0));
        let sinc = |t: f64| {
            if t.abs() < 1e-8 {
                1.0 - t * t / 6.0
            } else {
                t.sin() / t
            }
        };
        let psi: Vec<f64> = nodes
            .par_iter()
            .flat_map_iter(|&(kappa, weight)| {
                let mut rows = vec![0.0; ANGULAR * nx];
                let chi = super::long_wave::long_wave_share(kappa, k1h);
                if chi == 0.0 || weight == 0.0 {
                    return rows;
                }
                let kr = kappa * r_max;
                let angles = 4 * ((kr + 12.0 * kr.cbrt() + 12.0) / 4.0).ceil() as usize;
                let step = 2.0 * PI / angles as f64;
                // 2 Re over the half circle kx > 0, times the angle's and k's weights.
                let scale = 2.0 * weight * step * chi / (4.0 * PI * PI);
                let (ccs, rest) = rows.split_at_mut(nx);
                let (sss, rest) = rest.split_at_mut(nx);
                let (css, rest) = rest.split_at_mut(nx);
                let (cs_, ss_) = rest.split_at_mut(nx);
                for j in 0..angles / 2 {
                    let phi = -0.5 * PI + (j as f64 + 0.5) * step;
                    let (s, c) = phi.sin_cos();
                    let (tx, ty) = (kappa * c, kappa * s);
                    let value = spectrum.at(tx, ty)
                        * Complex::from_polar(
                            scale * sinc(0.5 * tx) * sinc(0.5 * ty),
                            ty * (offset - cy) - tx * cx,
                        );
                    // e^{i tx i} along the row, by recurrence (renormalised).
                    let turn = Complex::from_polar(1.0, tx);
                    let mut u = value;
                    for i in 0..nx {
                        if i % 64 == 0 {
                            u = value * Complex::from_polar(1.0, tx * i as f64);
                        }
                        let (re, im) = (u.re, u.im);
                        ccs[i] += c * c * re;
                        sss[i] += s * s * re;
                        css[i] += c * s * re;
                        cs_[i] -= c * im;
                        ss_[i] -= s * im;
                        u *= turn;
                    }
                }
                rows
            })
            .collect();
        let mut psi = psi;
        to_sum_and_difference(&mut psi, nx);
        LongWaveRow {
            thetas: nodes.iter().map(|&(k, _)| k).collect(),
            psi,
            nx,
        }
    }

    /// The k nodes (theta units).
    pub(super) fn nodes(&self) -> &[f64] {
        &self.thetas
    }

    /// Adds to `rows[d]` the long waves of depth d from its wave-frame functions at
    /// every node, `values[d]` (the depths taken together, as the short waves').
    pub(super) fn add_many(&self, values: &[&[[f64; 4]]], rows: &mut [[Vec<f64>; COMPONENTS]]) {
        let jobs: Vec<(&[f64], &[[f64; 4]])> =
            values.iter().map(|&v| (self.psi.as_slice(), v)).collect();
        add_rows_many(&jobs, self.nx, rows);
    }
}

/// The rows of many depths, `jobs[d] = (rows per node, transfer per node)`,
/// into `rows[d]`, as matrix products: depths sharing the same rows (`psi`) form,
/// per component, a matrix of coefficients (depth x node) that multiplies the nodes'
/// angular row of that component (node x column). The products go through
/// `ndarray`'s `general_mat_mul` (`matrixmultiply`: cache-blocked kernels with the
/// processor's vector instructions, chosen at run time).
fn add_rows_many(jobs: &[(&[f64], &[[f64; 4]])], nx: usize, rows: &mut [[Vec<f64>; COMPONENTS]]) {
    // Groups of depths by their rows (the main family's or the band family's).
    let mut groups: Vec<(&[f64], Vec<usize>)> = Vec::new();
    for (d, &(psi, _)) in jobs.iter().enumerate() {
        match groups.iter_mut().find(|(p, _)| std::ptr::eq(*p, psi)) {
            Some((_, members)) => members.push(d),
            None => groups.push((psi, vec![d])),
        }
    }
    for (psi, members) in groups {
        let nodes = members.iter().map(|&d| jobs[d].1.len()).max().unwrap_or(0);
        if nodes == 0 {
            continue;
        }
        // Component c (of `[A, B, sigma_z, tau_xy, tau_xz, tau_yz]`, [`finish_rows`])
        // takes angular row `ANGULAR_OF[c]` (`c^2 + s^2, c^2 - s^2, c s, i c, i s`)
        // times `coefficient(c, r)`: `sigma_x = r0 c^2 + r1 s^2 = A + B` and `sigma_y =
        // A - B` with `A = (r0 + r1) / 2 (c^2 + s^2)`, `B = (r0 - r1) / 2 (c^2 - s^2)`.
        const ANGULAR_OF: [usize; COMPONENTS] = [0, 1, 0, 2, 3, 4];
        let coefficient = |c: usize, [r0, r1, r2, r3]: [f64; 4]| match c {
            0 => 0.5 * (r0 + r1),
            1 => 0.5 * (r0 - r1),
            2 => r2,
            3 => r0 - r1,
            _ => r3,
        };
        let products: Vec<Array2<f64>> = (0..COMPONENTS)
            .into_par_iter()
            .map(|c| {
                let mut coefficients = Array2::<f64>::zeros((members.len(), nodes));
                for (i, &d) in members.iter().enumerate() {
                    for (b, &value) in jobs[d].1.iter().enumerate() {
                        coefficients[[i, b]] = coefficient(c, value);
                    }
                }
                let angular = ArrayView2::from_shape(
                    (nodes, nx).strides((ANGULAR * nx, 1)),
                    &psi[ANGULAR_OF[c] * nx..],
                )
                .expect("each node holds its angular rows");
                let mut out = Array2::<f64>::zeros((members.len(), nx));
                general_mat_mul(1.0, &coefficients, &angular, 0.0, &mut out);
                out
            })
            .collect();
        for (c, product) in products.iter().enumerate() {
            for (i, &d) in members.iter().enumerate() {
                for (o, v) in rows[d][c].iter_mut().zip(product.row(i)) {
                    *o += v;
                }
            }
        }
    }
}

/// Replaces each node's first two angular rows `c^2, s^2` by their sum and
/// difference ([`add_rows_many`] then takes six products per node and column instead
/// of nine).
fn to_sum_and_difference(psi: &mut [f64], nx: usize) {
    for node in psi.chunks_exact_mut(ANGULAR * nx) {
        let (cc, rest) = node.split_at_mut(nx);
        for (a, b) in cc.iter_mut().zip(&mut rest[..nx]) {
            let (sum, difference) = (*a + *b, *a - *b);
            *a = sum;
            *b = difference;
        }
    }
}

/// Turns rows summed by [`add_rows_many`] (`[A, B, sigma_z, tau_xy, tau_xz, tau_yz]`, A and B
/// the halves of the sum and difference of `sigma_x` and `sigma_y`) into the six
/// stresses.
pub(super) fn finish_rows(row: &mut [Vec<f64>; COMPONENTS]) {
    let (a, rest) = row.split_at_mut(1);
    for (x, y) in a[0].iter_mut().zip(rest[0].iter_mut()) {
        let (sum, difference) = (*x, *y);
        *x = sum + difference;
        *y = sum - difference;
    }
}

/// The pressure's centred spectrum `E~(k) = sum p_lm e^{-i (kx (m - cx) + ky (l - cy))}`
/// (`cx, cy` the window's centre, so its frequencies are at most half the window) on a
/// grid of step `2 pi / (OVERSAMPLING max(nx, ny))` covering `|k| <= top`, `kx >= 0`,
/// with the stencil's margin, computed directly (one pass per axis), and interpolated
/// between grid points by a tensor Lagrange stencil.
struct CentredSpectrum {
    step: f64,
    /// Grid index of kx = 0 and ky = 0.
    x0: i64,
    y0: i64,
    /// `values[a * ny_grid + b]`.
    values: Vec<Complex<f64>>,
    ny_grid: usize,
    /// Barycentric weights of equispaced points, `(-1)^m C(q - 1, m)`.
    bary: [f64; STENCIL],
}

impl CentredSpectrum {
    fn new(pressure: &[f64], nx: usize, ny: usize, top: f64) -> Self {
        let step = 2.0 * PI / (OVERSAMPLING * nx.max(ny) as f64);
        let margin = (STENCIL / 2 + 1) as i64;
        let reach = (top / step).ceil() as i64 + margin;
        let (x0, y0) = (margin, reach);
        let xs: Vec<f64> = (-margin..=reach).map(|a| a as f64 * step).collect();
        let ys: Vec<f64> = (-reach..=reach).map(|b| b as f64 * step).collect();
        let (cx, cy) = (0.5 * (nx as f64 - 1.0), 0.5 * (ny as f64 - 1.0));
        // Along x, each loaded row: R[l][a], with the phases tabulated once.
        let loaded: Vec<usize> = (0..ny)
            .filter(|&l| pressure[l * nx..(l + 1) * nx].iter().any(|&p| p != 0.0))
            .collect();
        let phases = |ts: &[f64], n: usize, centre: f64| -> Vec<Complex<f64>> {
            ts.iter()
                .flat_map(|&t| {
                    (0..n).map(move |m| Complex::from_polar(1.0, -t * (m as f64 - centre)))
                })
                .collect()
        };
        let phase_x = phases(&xs, nx, cx);
        let along_x: Vec<Vec<Complex<f64>>> = loaded
            .par_iter()
            .map(|&l| {
                let line = &pressure[l * nx..(l + 1) * nx];
                phase_x
                    .chunks_exact(nx)
                    .map(|ph| {
                        let mut sum = Complex::default();
                        for (e, &p) in ph.iter().zip(line) {
                            sum += e * p;
                        }
                        sum
                    })
                    .collect()
            })
            .collect();
        // Along y, per kx: E~[a][b].
        let phase_y = phases(&ys, ny, cy);
        let ny_grid = ys.len();
        let values: Vec<Complex<f64>> = (0..xs.len())
            .into_par_iter()
            .flat_map_iter(|a| {
                let along_x = &along_x;
                let loaded = &loaded;
                phase_y.chunks_exact(ny).map(move |ph| {
                    let mut sum = Complex::default();
                    for (r, &l) in along_x.iter().zip(loaded) {
                        sum += r[a] * ph[l];
                    }
                    sum
                })
            })
            .collect();
        let bary = std::array::from_fn(|m| {
            let mut binomial = 1.0;
            for j in 0..m {
                binomial = binomial * (STENCIL - 1 - j) as f64 / (j + 1) as f64;
            }
            if m % 2 == 0 {
                binomial
            } else {
                -binomial
            }
        });
        CentredSpectrum {
            step,
            x0,
            y0,
            values,
            ny_grid,
            bary,
        }
    }

    /// The stencil's first grid index and weights at position `u` (grid units).
    fn stencil(&self, u: f64) -> (i64, [f64; STENCIL]) {
        let first = u.floor() as i64 - (STENCIL as i64 / 2 - 1);
        let mut w = [0.0; STENCIL];
        let offset = u - first as f64;
        if offset == offset.floor() {
            w[offset as usize] = 1.0;
            return (first, w);
        }
        let mut total = 0.0;
        for (m, (wm, &b)) in w.iter_mut().zip(&self.bary).enumerate() {
            *wm = b / (offset - m as f64);
            total += *wm;
        }
        for wm in w.iter_mut() {
            *wm /= total;
        }
        (first, w)
    }

    /// `E~` at `(tx, ty)`, `tx >= 0`, `|k|` within the grid's top.
    fn at(&self, tx: f64, ty: f64) -> Complex<f64> {
        let (ax, wx) = self.stencil(tx / self.step);
        let (ay, wy) = self.stencil(ty / self.step);
        let mut sum = Complex::default();
        for (i, &w1) in wx.iter().enumerate() {
            let a = (ax + i as i64 + self.x0) as usize;
            let column = &self.values[a * self.ny_grid..][..self.ny_grid];
            let mut inner = Complex::default();
            for (j, &w2) in wy.iter().enumerate() {
                inner += column[(ay + j as i64 + self.y0) as usize] * w2;
            }
            sum += inner * w1;
        }
        sum
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The interpolated centred spectrum equals its direct sum between grid points.
    #[test]
    fn centred_spectrum_interpolates_to_its_direct_sum() {
        let (nx, ny) = (23, 17);
        let pressure: Vec<f64> = (0..nx * ny)
            .map(|n| ((n * 7919) % 101) as f64 / 101.0 - 0.3)
            .collect();
        let top = 1.3;
        let spectrum = CentredSpectrum::new(&pressure, nx, ny, top);
        let (cx, cy) = (0.5 * (nx as f64 - 1.0), 0.5 * (ny as f64 - 1.0));
        let scale: f64 = pressure.iter().map(|p| p.abs()).sum();
        let mut worst: f64 = 0.0;
        for (tx, ty) in [
            (0.0, 0.0),
            (0.013, -0.4),
            (0.9, 0.77),
            (1.29, 0.0),
            (0.31, 1.27),
        ] {
            let mut direct = Complex::default();
            for l in 0..ny {
                for m in 0..nx {
                    let phase = -(tx * (m as f64 - cx) + ty * (l as f64 - cy));
                    direct += Complex::from_polar(pressure[l * nx + m], phase);
                }
            }
            worst = worst.max((spectrum.at(tx, ty) - direct).norm() / scale);
        }
        assert!(worst < 1e-13, "{worst:e}");
    }

    /// The interpolant on the shared panels reproduces exponentials of every decay
    /// length to the bound of the module doc.
    #[test]
    fn geometric_panels_hold_every_exponential() {
        let panels = geometric_panels(1e-4, 3.0);
        let bary = barycentric_weights();
        for length in [0.3, 1.0, 10.0, 100.0, 1e3, 1e4] {
            let mut worst: f64 = 0.0;
            for &p in &panels {
                let nodes = panel_nodes(p);
                let values: Vec<f64> = nodes.iter().map(|&t| (-t * length).exp()).collect();
                for m in 0..=40 {
                    let t = p.0 + (p.1 - p.0) * m as f64 / 40.0;
                    let l = lagrange(&nodes, &bary, t);
                    let v: f64 = l.iter().zip(&values).map(|(a, b)| a * b).sum();
                    worst = worst.max((v - (-t * length).exp()).abs());
                }
            }
            assert!(worst < 5e-14, "L = {length}: {worst:e}");
        }
    }
}
