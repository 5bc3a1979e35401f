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
