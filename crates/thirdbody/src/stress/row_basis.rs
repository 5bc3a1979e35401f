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
//! `Psi_{a,b}(x_i) = IFFT_x[sum_jy l_b w (1 - chi) f_a P]` are built once per section,
//! and a depth costs the transfer at the nodes and `nodes x 9 x nx` products instead
//! of a sum over the box's wavenumbers.
//!
//! The panels grow geometrically (ratio 2 near k = 0, 1.5 beyond): on `[a, rho a]` the
//! degree-19 interpolant of any `e^{-theta L}` is within `e^{-a L} (rho - 1)^20 (a L /
//! 4)^20 / 20!` of it, at most 2e-14 of its value at 0 for `rho = 2` whatever L, so one
//! set of panels serves every depth's decay length.

use std::f64::consts::PI;

use rayon::prelude::*;
use realfft::num_complex::Complex;
use realfft::RealFftPlanner;

use super::kernels::{PressureSpectrum, COMPONENTS};
use super::long_wave::{short_wave_share, BAND_EDGE};

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

/// The short waves of a layered body's remainder along a row, as rows per
/// interpolation node (module doc).
pub(super) struct ShortWaveRow {
    panels: Vec<(f64, f64)>,
    /// Theta of each node, panel after panel.
    nodes: Vec<f64>,
    /// `psi[(node * ANGULAR + a) * nx + i]`.
    psi: Vec<f64>,
    nx: usize,
}

impl ShortWaveRow {
    /// The rows for outputs at x offsets `0..nx` cells (cell centres) from the
    /// pressure's spectrum on a box of `len` cells whose row phase has the fraction
    /// `frac_y` (cells), split at `k1h = k1 h`, for every wavenumber up to `theta_top`
    /// (`|k| h`, below pi: no aliases).
    pub(super) fn new(
        spectrum: &PressureSpectrum,
        len: usize,
        frac_y: f64,
        nx: usize,
        k1h: f64,
        theta_top: f64,
    ) -> Self {
        assert!(theta_top < PI, "the row basis sums no aliases");
        let panels = geometric_panels(0.01 * k1h, theta_top);
        let panel_points: Vec<[f64; POINTS]> = panels.iter().map(|&p| panel_nodes(p)).collect();
        let nodes: Vec<f64> = panel_points.iter().flatten().copied().collect();
        let bary = barycentric_weights();
        let count = nodes.len() * ANGULAR;
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
        let columns: Vec<Vec<Complex<f64>>> = (0..half)
            .into_par_iter()
            .map(|jx| {
                let tx = base(jx);
                if tx.abs() > theta_top {
                    return Vec::new();
                }
                let wx = sinc(0.5 * tx) * norm;
                let mut sums = vec![Complex::default(); count];
                for (jy, (&p, &wy)) in spectrum.column(jx).iter().zip(&weight_y).enumerate() {
                    let ty = base(jy);
                    let theta = (tx * tx + ty * ty).sqrt();
                    if theta > theta_top {
                        continue;
                    }
                    let high_pass = if theta > BAND_EDGE * k1h {
                        1.0
                    } else {
                        short_wave_share(theta, k1h)
                    };
                    if high_pass == 0.0 {
                        continue;
                    }
                    let (c, s) = if theta > 0.0 {
                        (tx / theta, ty / theta)
                    } else {
                        (1.0, 0.0)
                    };
                    let v = p * wy * (wx * high_pass);
                    let factors = [c * c, s * s, c * s, c, s];
                    let panel = locate(theta);
                    let l = lagrange(&panel_points[panel], &bary, theta);
                    let at = &mut sums[panel * POINTS * ANGULAR..][..POINTS * ANGULAR];
                    for (slot, &lb) in at.chunks_exact_mut(ANGULAR).zip(&l) {
                        let u = v * lb;
                        for (o, &f) in slot.iter_mut().zip(&factors) {
                            *o += u * f;
                        }
                    }
                }
                sums
            })
            .collect();
        // Along x: one inverse transform per node and angular row.
        let inverse = RealFftPlanner::<f64>::new().plan_fft_inverse(len);
        let psi: Vec<f64> = (0..count)
            .into_par_iter()
            .flat_map_iter(|na| {
                let shear = na % ANGULAR >= 3;
                let mut spec: Vec<Complex<f64>> = columns
                    .iter()
                    .map(|col| {
                        let v = col.get(na).copied().unwrap_or_default();
                        if shear {
                            Complex::new(-v.im, v.re)
                        } else {
                            v
                        }
                    })
                    .collect();
                spec[0].im = 0.0;
                spec[half - 1].im = 0.0;
                let mut line = vec![0.0; len];
                inverse
                    .process(&mut spec, &mut line)
                    .expect("FFT lengths are fixed by the plan");
                line.truncate(nx);
                line
            })
            .collect();
        ShortWaveRow {
            panels,
            nodes,
            psi,
            nx,
        }
    }

    /// The largest theta the rows hold.
    pub(super) fn top(&self) -> f64 {
        self.panels.last().map_or(0.0, |p| p.1)
    }

    /// Adds to `row` the short waves of the wave-frame functions `transfer(theta)`
    /// (`[xixi, etaeta, zz, xiz / i]`), negligible beyond `theta_cut`.
    pub(super) fn add(
        &self,
        theta_cut: f64,
        mut transfer: impl FnMut(f64) -> [f64; 4],
        row: &mut [Vec<f64>; COMPONENTS],
    ) {
        let used = self.panels.partition_point(|&(lo, _)| lo < theta_cut) * POINTS;
        let nx = self.nx;
        for (b, &theta) in self.nodes.iter().enumerate().take(used) {
            let [r0, r1, r2, r3] = transfer(theta);
            if r0 == 0.0 && r1 == 0.0 && r2 == 0.0 && r3 == 0.0 {
                continue;
            }
            let rows = &self.psi[b * ANGULAR * nx..][..ANGULAR * nx];
            let (cc, rest) = rows.split_at(nx);
            let (ss, rest) = rest.split_at(nx);
            let (cs, rest) = rest.split_at(nx);
            let (c, s) = rest.split_at(nx);
            let [o0, o1, o2, o3, o4, o5] = row;
            for i in 0..nx {
                o0[i] += r0 * cc[i] + r1 * ss[i];
                o1[i] += r0 * ss[i] + r1 * cc[i];
                o2[i] += r2 * (cc[i] + ss[i]);
                o3[i] += (r0 - r1) * cs[i];
                o4[i] += r3 * c[i];
                o5[i] += r3 * s[i];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
