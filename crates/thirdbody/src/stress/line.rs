//! Plane-strain (line contact) stresses in the XZ plane: the stresses at `(x, z)`
//! per unit pressure uniform on the strip `|x| <= b = h / 2` of the surface (and
//! along all y), and the section `sigma_c(x_i, z) = sum_k K_c(x_i - x_k, z) p_k`
//! of a line case's pressure (one DC-FFT along x per depth and component).
//!
//! Homogeneous half-space, per unit pressure: Johnson, Contact Mechanics (1985),
//! §2.6, eq. 2.21 (uniform pressure on a strip), rederived here by integrating
//! Flamant's line-load stresses (Johnson eq. 2.15) over the strip, with the angles
//! `phi_1,2 = atan((x +- b) / z)` from the z axis to the strip's edges:
//! ```text
//! sigma_x = -(1/2pi) [2 (phi1 - phi2) - (sin 2phi1 - sin 2phi2)]
//! sigma_z = -(1/2pi) [2 (phi1 - phi2) + (sin 2phi1 - sin 2phi2)]
//! tau_xz  =  (1/2pi) (cos 2phi1 - cos 2phi2)
//! ```
//! evaluated without differences of nearly equal numbers (`D_1,2 = (x +- b)^2 + z^2`):
//! `phi1 - phi2 = atan2(2 b z, z^2 + x^2 - b^2)`,
//! `sin 2phi1 - sin 2phi2 = 4 b z (z^2 - x^2 + b^2) / (D1 D2)`,
//! `cos 2phi1 - cos 2phi2 = -8 b x z^2 / (D1 D2)`. Plane
//! strain gives `sigma_y = nu (sigma_x + sigma_z)` and `tau_xy = tau_yz = 0`. The
//! stresses of a half-space under given surface tractions do not depend on its
//! modulus (the traction boundary-value problem's solution, Flamant's, is
//! `sigma = -(2 P / pi) cos(theta) / r` radially whatever E and nu, and only
//! `sigma_y` carries nu): so a viscoelastic half-space of constant Poisson ratio,
//! by the correspondence principle, has the same stresses under the same pressure
//! at every sliding speed, and uses this closed form with its nu.
//!
//! Layered body (the stack's plane-strain transfer `T(k, z) = [T_xixi, T_etaeta,
//! T_zz, T_xiz / i]` per unit surface pressure,
//! [`crate::body::layered::LayeredSolver::plane_response`]; `T_etaeta` is sigma_y for
//! a wave along x): `sigma(x, z) = (1/pi) int_0^inf Re[T(k, z) P(k) e^{ikx}] dk`,
//! `P(k) = 2 sin(k b) / k`. The closed form above with the Poisson ratio of z's
//! layer (Boussinesq's transfer `[-(1 - kz), -2 nu, -(1 + kz), kz] e^{-kz}`) is
//! taken out; the remainder `T - T_hom` decays like `e^{-k lambda}`
//! (`lambda = 2 h1 - z` in the top layer, `z` below) and is summed by the trapezoidal rule on the
//! full k line, `dk = 2 pi / (L h)`, up to `50 / lambda` (where `(k lambda)^3
//! e^{-k lambda}` is below 1e-16), folded onto the `L` wavenumbers of the cell
//! pitch (the alias sum, exact for outputs at whole cells) and inverted by one
//! real FFT of length `L` per component. The normal components' remainder has a
//! kink `r0 + r1 |k|` at k = 0 (in the top layer it does not vanish there: the layer
//! takes the base's surface strains), whose real-space tail `~ r1 / x^2` would reach
//! the images: the carrier `r0 e^{-k mu} + (r1 + mu r0) k e^{-k mu}` (`mu =
//! lambda`, `r1` by a one-sided difference) is taken out of the sum and added in
//! closed form, `(1/pi) [atan((b + x) / mu) + atan((b - x) / mu)]` and `(1/pi) [(b +
//! x) / ((b + x)^2 + mu^2) + (b - x) / ((b - x)^2 + mu^2)]`. By Poisson's formula the trapezoidal sum is
//! the exact remainder plus its images a period `L h` away: `L` is at least 8
//! times the section's cells and 128 times the stack's membrane length `z + sum_i
//! t_i max(1, E_i / E_min)` (capped at 2^20 cells). With 16 membrane lengths the
//! images still cost 2e-5 of the peak (a coating 10 times stiffer than its
//! substrate); with 128, 4e-8 (tests/line_stress.rs, against adaptive quadrature
//! of the Fourier integral). The cost per depth is `25 L h / (pi lambda)`
//! transfers: a coating much thinner than a cell, or very stiff, is slow.

use std::f64::consts::PI;

use realfft::num_complex::Complex;
use realfft::RealFftPlanner;

use super::kernels::{HomogeneousStressKernels, StressKernels, COMPONENTS};
use super::layered_kernels::LayeredStressKernels;
use super::sections::{per_thread_map, Components};
use crate::body::layered::{Base, LayeredSolver};
use crate::error::Result;
use crate::grid::Grid;

/// The six stresses `[sigma_x, sigma_y, sigma_z, tau_xy, tau_xz, tau_yz]` at `(x, z)`,
/// `z >= 0`, per unit pressure uniform on the strip `|x| <= cell / 2` (all y) of a
/// half-space of Poisson ratio `nu` in plane strain (module documentation). At
/// z = 0 on a strip edge the value is the mean of both sides.
pub fn strip_stresses(x: f64, z: f64, cell: f64, nu: f64) -> [f64; COMPONENTS] {
    let b = 0.5 * cell;
    let (d1, d2) = ((x + b) * (x + b) + z * z, (x - b) * (x - b) + z * z);
    let angle = (2.0 * b * z).atan2(z * z + x * x - b * b);
    let (sin, cos) = if z == 0.0 {
        (0.0, 0.0)
    } else {
        let q = d1 * d2;
        (
            4.0 * b * z * (z * z - x * x + b * b) / q,
            -8.0 * b * x * z * z / q,
        )
    };
    let c = 0.5 / PI;
    let sigma_x = -c * (2.0 * angle - sin);
    let sigma_z = -c * (2.0 * angle + sin);
    [
        sigma_x,
        nu * (sigma_x + sigma_z),
        sigma_z,
        0.0,
        c * cos,
        0.0,
    ]
}

/// Fills `out[c][d + count - 1]`, `-(count - 1) <= d < count`, with the closed-form
/// strip stresses at `(d cell, z)`.
fn closed_form_strip(z: f64, cell: f64, count: usize, nu: f64, out: &mut [Vec<f64>; COMPONENTS]) {
    let n = 2 * count - 1;
    for o in out.iter_mut() {
        o.clear();
        o.resize(n, 0.0);
    }
    for m in 0..n {
        let x = (m as f64 - (count as f64 - 1.0)) * cell;
        for (o, v) in out.iter_mut().zip(strip_stresses(x, z, cell, nu)) {
            o[m] = v;
        }
    }
}

/// [`StressKernels::fill_strip`] of a homogeneous (or viscoelastic) half-space.
pub(crate) fn homogeneous_strip(
    kernels: &HomogeneousStressKernels,
    z: f64,
    cell: f64,
    count: usize,
    out: &mut [Vec<f64>; COMPONENTS],
) {
    closed_form_strip(z, cell, count, kernels.material.poisson, out);
}

/// Largest period of the remainder's trapezoidal sum, in cells.
const MAX_PERIOD_CELLS: usize = 1 << 20;

/// `k lambda` beyond which the remainder is dropped.
const REMAINDER_DECAY: f64 = 50.0;

/// [`StressKernels::fill_strip`] of a layered body (module documentation).
pub(crate) fn layered_strip(
    kernels: &LayeredStressKernels,
    z: f64,
    cell: f64,
    count: usize,
    out: &mut [Vec<f64>; COMPONENTS],
) {
    let layer = kernels.layer(z);
    let nu = kernels.material(layer).poisson;
    closed_form_strip(z, cell, count, nu, out);
    let stack = &kernels.stack;
    let lambda = kernels.decay_length(layer, z);
    let softest = stack
        .layers
        .iter()
        .map(|p| p.material.young)
        .chain(match stack.base {
            Base::HalfSpace(m) => Some(m.young),
            Base::Rigid(_) => None,
        })
        .fold(f64::INFINITY, f64::min);
    let membrane: f64 = z + stack
        .layers
        .iter()
        .map(|p| p.thickness * (p.material.young / softest).max(1.0))
        .sum::<f64>();
    let period = (8 * count)
        .max(
            (128.0 * membrane / cell)
                .ceil()
                .min(MAX_PERIOD_CELLS as f64) as usize,
        )
        .next_power_of_two()
        .min(MAX_PERIOD_CELLS);
    let dk = 2.0 * PI / (period as f64 * cell);
    let top = ((REMAINDER_DECAY / lambda) / dk).ceil().min(1e9) as usize;
    let b = 0.5 * cell;
    let mut solver: LayeredSolver = kernels.solver();
    let mut remainder = |k: f64| {
        let t = kernels.transfer(&mut solver, k, layer, z);
        let kz = k * z;
        let e = (-kz).exp();
        let hom = [-(1.0 - kz) * e, -2.0 * nu * e, -(1.0 + kz) * e, kz * e];
        std::array::from_fn::<f64, 4, _>(|q| t[q] - hom[q])
    };
    // The carriers of the normal components' value r0 and slope r1 at k = 0, whose
    // kink in |k| would leave a 1 / x^2 tail in the periodic images:
    // `r0 e^{-k mu} + (r1 + mu r0) k e^{-k mu}` is summed in closed form instead.
    let mu = lambda;
    let step = 1e-3 / membrane;
    let (r0, r_1, r_2) = (remainder(0.0), remainder(step), remainder(2.0 * step));
    let r1: [f64; 3] =
        std::array::from_fn(|q| (4.0 * r_1[q] - r_2[q] - 3.0 * r0[q]) / (2.0 * step));
    let mut bins = vec![[Complex::<f64>::default(); 4]; period];
    for i in 0..=top {
        let k = i as f64 * dk;
        let r = remainder(k);
        let p = if i == 0 {
            cell
        } else {
            2.0 * (k * b).sin() / k
        };
        let e = (-k * mu).exp();
        let carried = |q: usize| r0[q] * e + (r1[q] + mu * r0[q]) * k * e;
        let f = [
            Complex::new((r[0] - carried(0)) * p, 0.0),
            Complex::new((r[1] - carried(1)) * p, 0.0),
            Complex::new((r[2] - carried(2)) * p, 0.0),
            Complex::new(0.0, r[3] * p),
        ];
        let j = i % period;
        for (bin, v) in bins[j].iter_mut().zip(f) {
            *bin += v;
        }
        if i > 0 {
            let j = (period - j) % period;
            for (bin, v) in bins[j].iter_mut().zip(f) {
                *bin += v.conj();
            }
        }
    }
    let inverse = RealFftPlanner::<f64>::new().plan_fft_inverse(period);
    let half = period / 2 + 1;
    let mut spectrum = vec![Complex::default(); half];
    let mut values = vec![0.0; period];
    let scale = dk / (2.0 * PI);
    for (q, c) in [0, 1, 2, 4].into_iter().enumerate() {
        for (s, bin) in spectrum.iter_mut().zip(&bins) {
            *s = bin[q] * scale;
        }
        spectrum[0].im = 0.0;
        spectrum[half - 1].im = 0.0;
        inverse
            .process(&mut spectrum, &mut values)
            .expect("a Hermitian spectrum");
        for (m, o) in out[c].iter_mut().enumerate() {
            let d = m as i64 - (count as i64 - 1);
            *o += values[d.rem_euclid(period as i64) as usize];
            if q < 3 {
                // (1/pi) int_0^inf {1, k} e^{-k mu} P(k) cos(kx) dk.
                let x = d as f64 * cell;
                let (u, v) = (b + x, b - x);
                let angles = ((u / mu).atan() + (v / mu).atan()) / PI;
                let slopes = (u / (u * u + mu * mu) + v / (v * v + mu * mu)) / PI;
                *o += r0[q] * angles + (r1[q] + mu * r0[q]) * slopes;
            }
        }
    }
}

/// Stresses along x (cell centres) at each depth under the strips' pressure
/// `pressure` (one value per cell of the line grid `grid`): `out[c][k * nx + i]`.
pub(crate) fn section(
    grid: &Grid,
    pressure: &[f64],
    kernels: &dyn StressKernels,
    depths: &[f64],
    depth_done: &(dyn Fn() + Sync),
) -> Result<Components> {
    let (nx, h) = (grid.nx, grid.cell);
    let width = 2 * nx;
    let mut planner = RealFftPlanner::<f64>::new();
    let forward = planner.plan_fft_forward(width);
    let inverse = planner.plan_fft_inverse(width);
    let mut padded = vec![0.0; width];
    padded[..nx].copy_from_slice(&pressure[..nx]);
    let mut source = forward.make_output_vec();
    forward
        .process(&mut padded, &mut source)
        .expect("lengths of the plan");
    let per_depth = per_thread_map(
        depths,
        || {
            let table: Components = Default::default();
            (
                table,
                vec![0.0; width],
                forward.make_output_vec(),
                vec![0.0; width],
            )
        },
        |(table, wrapped, spectrum, row), &z| -> Result<Components> {
            kernels.fill_strip(z, h, nx, table)?;
            let mut out: Components = Default::default();
            for (c, o) in out.iter_mut().enumerate() {
                if table[c].iter().all(|&v| v == 0.0) {
                    *o = vec![0.0; nx];
                    continue;
                }
                // Offset d at index d (d >= 0) or width + d (d < 0); index nx unused.
                wrapped.fill(0.0);
                for (m, &v) in table[c].iter().enumerate() {
                    let d = m as i64 - (nx as i64 - 1);
                    wrapped[d.rem_euclid(width as i64) as usize] = v;
                }
                forward
                    .process(wrapped, spectrum)
                    .expect("lengths of the plan");
                for (s, p) in spectrum.iter_mut().zip(&source) {
                    *s *= p / width as f64;
                }
                spectrum[0].im = 0.0;
                if let Some(last) = spectrum.last_mut() {
                    last.im = 0.0;
                }
                inverse.process(spectrum, row).expect("lengths of the plan");
                *o = row[..nx].to_vec();
            }
            depth_done();
            Ok(out)
        },
    );
    let mut out: Components = std::array::from_fn(|_| Vec::with_capacity(nx * depths.len()));
    for depth in per_depth {
        for (o, d) in out.iter_mut().zip(depth?) {
            o.extend_from_slice(&d);
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Flamant's line load (Johnson eq. 2.15) in Cartesian components, per unit
    /// load: `-(2 / pi) (x^2 z, z^3, x z^2) / r^4` for (sigma_x, sigma_z, tau_xz).
    fn flamant(x: f64, z: f64) -> [f64; 3] {
        let r2 = x * x + z * z;
        let c = -2.0 / PI / (r2 * r2);
        [c * x * x * z, c * z * z * z, c * x * z * z]
    }

    /// The strip's stresses by composite Gauss–Legendre quadrature of Flamant's
    /// stresses over the strip, on pieces graded toward the point nearest (x, z).
    fn flamant_strip(x: f64, z: f64, cell: f64) -> [f64; 3] {
        let nodes = [
            (0.183_434_642_495_649_8, 0.362_683_783_378_362),
            (0.525_532_409_916_329, 0.313_706_645_877_887_3),
            (0.796_666_477_413_626_7, 0.222_381_034_453_374_5),
            (0.960_289_856_497_536_3, 0.101_228_536_290_376_3),
        ];
        let b = 0.5 * cell;
        let near = x.clamp(-b, b);
        let mut breaks = vec![-b, near, b];
        for end in [-b, b] {
            let span = (end - near).abs();
            let mut t = span;
            while t > span * 1e-6 && t > 0.02 * z {
                breaks.push(near + (end - near).signum() * t);
                t *= 0.5;
            }
        }
        breaks.sort_by(f64::total_cmp);
        breaks.dedup();
        let mut sum = [0.0; 3];
        for w in breaks.windows(2) {
            let (mid, half) = (0.5 * (w[0] + w[1]), 0.5 * (w[1] - w[0]));
            // Each piece subdivided so that it is at most z / 4 long.
            let pieces = ((2.0 * half) / (0.25 * z)).ceil().max(1.0) as usize;
            let step = 2.0 * half / pieces as f64;
            for q in 0..pieces {
                let c = mid - half + (q as f64 + 0.5) * step;
                for &(t, weight) in &nodes {
                    for s in [c - 0.5 * step * t, c + 0.5 * step * t] {
                        let f = flamant(x - s, z);
                        for (a, v) in sum.iter_mut().zip(f) {
                            *a += weight * 0.5 * step * v;
                        }
                    }
                }
            }
        }
        sum
    }

    #[test]
    fn the_strip_is_flamant_integrated() {
        let (cell, nu) = (0.7, 0.3);
        let mut worst: f64 = 0.0;
        for &z in &[0.01, 0.1, 0.35, 1.0, 5.0, 40.0] {
            for &x in &[0.0, 0.2, 0.35, 0.5, 1.0, 3.3, -2.0, 50.0] {
                let s = strip_stresses(x, z, cell, nu);
                let f = flamant_strip(x, z, cell);
                for (got, want) in [s[0], s[2], s[4]].into_iter().zip(f) {
                    worst = worst.max((got - want).abs());
                    assert!((got - want).abs() < 1e-12, "({x}, {z}): {got} vs {want}");
                }
                assert_eq!(s[1], nu * (s[0] + s[2]));
            }
        }
        eprintln!("strip vs Flamant quadrature: worst {worst:.1e}");
        // The surface: -1 under the strip in sigma_x and sigma_z, 0 outside.
        let s = strip_stresses(0.2, 0.0, cell, nu);
        assert!((s[0] + 1.0).abs() < 1e-15 && (s[2] + 1.0).abs() < 1e-15);
        let s = strip_stresses(2.0, 0.0, cell, nu);
        assert!(s.iter().all(|v| *v == 0.0));
    }
}
