//! Plane-strain (line contact) surface kernel of an elastic half-space: the normal
//! surface displacement at `x` under a unit pressure uniform on the strip
//! `|s| <= h / 2` and along y, per unit plane-strain compliance
//! `J = (1 - nu^2) / E` (Johnson, Contact Mechanics, eq. 2.19b and 2.25b):
//! `g(x) = (2 / pi) int_{-h/2}^{h/2} ln(L / |x - s|) ds`.
//! In plane strain the displacement of a half-space under a load of finite
//! resultant grows logarithmically with distance, so it is defined only against a
//! datum: here the surface at distance `L` (the case's reference distance) from the
//! load, where `g` vanishes for a line load. Every body's plane-strain kernel keeps
//! this datum for its long-wave (relaxed) compliance (`docs/architecture.md`,
//! "Line contacts").

use std::f64::consts::PI;

/// `int_{-b}^{b} ln|x - s| ds` for the half-width `b > 0`: the exact primitive
/// `F(u) = u ln|u| - u` near the strip, the series in `(b / x)^2` beyond `8 b`,
/// where the primitive's two values would cancel.
fn log_integral(x: f64, b: f64) -> f64 {
    let ax = x.abs();
    if ax > 8.0 * b {
        // ln|x - s| = ln|x| - sum_n (s / x)^n / n; the odd powers integrate to zero
        // and s^(2m) to 2 b^(2m+1) / (2m + 1).
        let q = (b / ax) * (b / ax);
        let mut term = 1.0;
        let mut series = 0.0;
        for m in 1..=12 {
            term *= q;
            let m = f64::from(m);
            series += term / ((2.0 * m + 1.0) * 2.0 * m);
            if term < 1e-18 {
                break;
            }
        }
        2.0 * b * (ax.ln() - series)
    } else {
        let primitive = |u: f64| if u == 0.0 { 0.0 } else { u * u.abs().ln() - u };
        primitive(x + b) - primitive(x - b)
    }
}

/// `int_{-b}^{b} ln|x - s| ds` for the half-width `b > 0` (the strip integral of
/// [`strip_displacement`] without its constants), free of cancellation far from
/// the strip.
pub fn strip_log_integral(x: f64, half_width: f64) -> f64 {
    log_integral(x, half_width)
}

/// The displacement at `x` of the surface of a half-space of unit plane-strain
/// compliance under a unit pressure on the strip of width `cell` centred at 0,
/// measured against the surface at distance `reference` from the load (module
/// documentation).
pub fn strip_displacement(x: f64, cell: f64, reference: f64) -> f64 {
    let b = 0.5 * cell;
    2.0 / PI * (cell * reference.ln() - log_integral(x, b))
}

/// The even line kernel of a half-space of plane-strain compliance `compliance`
/// on `nx` cells of width `cell`: `kernel[d]` is the displacement `d` cells from a
/// loaded cell, `0 <= d < nx`.
pub fn homogeneous_line_kernel(compliance: f64, cell: f64, nx: usize, reference: f64) -> Vec<f64> {
    (0..nx)
        .map(|d| compliance * strip_displacement(d as f64 * cell, cell, reference))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `(2 / pi) int_{-b}^{b} ln(L / |x - s|) ds` by composite Gauss–Legendre
    /// quadrature on pieces graded toward the logarithm at `s = x`.
    fn quadrature(x: f64, cell: f64, reference: f64) -> f64 {
        let b = 0.5 * cell;
        // 8-point Gauss–Legendre on [-1, 1].
        let nodes = [
            (0.183_434_642_495_649_8, 0.362_683_783_378_362),
            (0.525_532_409_916_329, 0.313_706_645_877_887_3),
            (0.796_666_477_413_626_7, 0.222_381_034_453_374_5),
            (0.960_289_856_497_536_3, 0.101_228_536_290_376_3),
        ];
        // Geometric grading from both ends toward the point of the strip nearest
        // to the logarithm's singularity at s = x.
        let near = x.clamp(-b, b);
        let mut breaks = vec![-b, near];
        for end in [-b, b] {
            let span = (end - near).abs();
            let mut t = span;
            while t > span * 1e-14 {
                breaks.push(near + (end - near).signum() * t);
                t *= 0.5;
            }
        }
        breaks.push(b);
        breaks.sort_by(f64::total_cmp);
        breaks.dedup();
        let mut sum = 0.0;
        for w in breaks.windows(2) {
            let (lo, hi) = (w[0], w[1]);
            let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
            for &(t, weight) in &nodes {
                for s in [mid - half * t, mid + half * t] {
                    sum += weight * half * (reference / (x - s).abs()).ln();
                }
            }
        }
        2.0 / PI * sum
    }

    #[test]
    fn the_strip_kernel_equals_quadrature_of_the_logarithm() {
        for &(cell, reference) in &[(1.0, 10.0), (0.01, 3.0), (2.0, 0.5)] {
            for &d in &[0.0, 0.3, 0.5, 0.7, 1.0, 3.0, 7.9, 8.1, 40.0, 1e4] {
                let x = d * cell;
                let exact = strip_displacement(x, cell, reference);
                let numeric = quadrature(x, cell, reference);
                let scale = cell * (1.0 + (reference / cell).ln().abs());
                assert!(
                    (exact - numeric).abs() < 1e-13 * scale,
                    "cell {cell} x {x}: {exact} vs {numeric}"
                );
            }
        }
    }

    #[test]
    fn far_away_the_strip_is_a_line_load() {
        // (2 / pi) h ln(L / |x|) with a correction of relative order (h / x)^2.
        let (cell, reference): (f64, f64) = (1.0, 5.0);
        for &x in &[50.0_f64, 500.0, 5e6] {
            let line = 2.0 / PI * cell * (reference / x).ln();
            let strip = strip_displacement(x, cell, reference);
            let correction = 2.0 / PI * cell * cell * cell / (24.0 * x * x);
            assert!(
                (strip - (line + correction)).abs()
                    < 1e-12 * (1.0 + line.abs()) + (cell / x).powi(4),
                "{x}: {strip} vs {line} + {correction}"
            );
        }
        // The datum: a line load does not move the surface at distance L.
        assert!(strip_displacement(5.0, 1e-6, 5.0).abs() < 1e-17);
    }

    #[test]
    fn the_series_and_the_primitive_agree_where_they_meet() {
        let b = 0.5;
        for &x in &[3.99, 4.0, 4.01] {
            let primitive = |u: f64| u * u.abs().ln() - u;
            let direct = primitive(x + b) - primitive(x - b);
            assert!((log_integral(x, b) - direct).abs() < 1e-13);
            assert!((log_integral(-x, b) - direct).abs() < 1e-13);
        }
    }
}
