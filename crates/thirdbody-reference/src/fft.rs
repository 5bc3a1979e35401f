//! FFT plans for the tests' own transforms (brute-force quadratures, the time-stepped
//! simulation, the iteration-floor example), behind plain functions: a crate that
//! calls rustfft's or realfft's generic planners compiles their whole `f64` machinery
//! again (about 14 s at `opt-level = 3` for each test crate that did); here it is
//! compiled once, and the plans are used through their trait objects.

use std::sync::Arc;

use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::{Fft, FftPlanner};

/// A forward complex FFT of `len` points (unnormalised, `e^{-i ...}`).
pub fn forward(len: usize) -> Arc<dyn Fft<f64>> {
    FftPlanner::new().plan_fft_forward(len)
}

/// An inverse complex FFT of `len` points (unnormalised, `e^{+i ...}`).
pub fn inverse(len: usize) -> Arc<dyn Fft<f64>> {
    FftPlanner::new().plan_fft_inverse(len)
}

/// A forward real-to-complex FFT of `len` real points (`len / 2 + 1` outputs).
pub fn real_forward(len: usize) -> Arc<dyn RealToComplex<f64>> {
    RealFftPlanner::new().plan_fft_forward(len)
}

/// An inverse complex-to-real FFT of `len` real points (unnormalised).
pub fn real_inverse(len: usize) -> Arc<dyn ComplexToReal<f64>> {
    RealFftPlanner::new().plan_fft_inverse(len)
}

#[cfg(test)]
mod tests {
    use rustfft::num_complex::Complex64;

    #[test]
    fn the_plans_transform_a_single_mode_to_a_single_peak_and_back() {
        let n = 12;
        let mode = 5;
        let mut data: Vec<Complex64> = (0..n)
            .map(|j| {
                Complex64::from_polar(
                    1.0,
                    2.0 * std::f64::consts::PI * (mode * j) as f64 / n as f64,
                )
            })
            .collect();
        super::forward(n).process(&mut data);
        for (k, v) in data.iter().enumerate() {
            let want = if k == mode { n as f64 } else { 0.0 };
            assert!((v - want).norm() < 1e-12, "{k}: {v}");
        }
        super::inverse(n).process(&mut data);
        assert!(
            (data[1]
                - Complex64::from_polar(
                    n as f64,
                    2.0 * std::f64::consts::PI * mode as f64 / n as f64
                ))
            .norm()
                < 1e-12
        );
        let mut real: Vec<f64> = (0..n).map(|j| (j as f64).cos()).collect();
        let kept = real.clone();
        let mut half = vec![Complex64::new(0.0, 0.0); n / 2 + 1];
        super::real_forward(n)
            .process(&mut real, &mut half)
            .unwrap();
        super::real_inverse(n)
            .process(&mut half, &mut real)
            .unwrap();
        for (a, b) in real.iter().zip(&kept) {
            assert!((a / n as f64 - b).abs() < 1e-13);
        }
    }
}
