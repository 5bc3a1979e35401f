//! The oracles' own checks: the FFT plans against a single mode, and the direct
//! convolution sum against a value summed by hand and against fields of the wrong
//! size. (Integration tests, not unit tests: the crate's library is then compiled
//! once for the test run instead of twice, about 27 s of a clean build.)

use rustfft::num_complex::Complex64;
use thirdbody::error::{Error, Result};
use thirdbody_reference::{direct_convolution, direct_convolution_rows, fft};

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
    fft::forward(n).process(&mut data);
    for (k, v) in data.iter().enumerate() {
        let want = if k == mode { n as f64 } else { 0.0 };
        assert!((v - want).norm() < 1e-12, "{k}: {v}");
    }
    fft::inverse(n).process(&mut data);
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
    fft::real_forward(n).process(&mut real, &mut half).unwrap();
    fft::real_inverse(n).process(&mut half, &mut real).unwrap();
    for (a, b) in real.iter().zip(&kept) {
        assert!((a / n as f64 - b).abs() < 1e-13);
    }
}

#[test]
fn the_direct_sum_refuses_fields_of_another_size_naming_them_and_writes_nothing() {
    let kernel = |i: i64, j: i64| (1 + i.abs() + 2 * j.abs()) as f64;
    let field: Vec<f64> = (0..30).map(|k| k as f64).collect();
    let mut out = vec![0.0; 30];
    let names = |r: Result<()>, name: &str| matches!(r, Err(Error::InvalidValue { field, .. }) if field == name);
    assert!(names(
        direct_convolution(6, 5, kernel, &field[1..], &mut out),
        "field"
    ));
    assert!(names(
        direct_convolution(6, 5, kernel, &field, &mut out[1..]),
        "out"
    ));
    let rows = direct_convolution_rows(6, 5, kernel, &field, [1, 5], &mut out);
    assert!(names(rows, "rows"));
    assert!(out.iter().all(|&v| v == 0.0));
    // One value by hand: the corner cell (0, 0) sums K(-k, -l) f(k, l).
    direct_convolution(6, 5, kernel, &field, &mut out).unwrap();
    let by_hand: f64 = (0..5)
        .flat_map(|l| (0..6).map(move |k| (l, k)))
        .map(|(l, k)| kernel(-k, -l) * field[(l * 6 + k) as usize])
        .sum();
    assert_eq!(out[0], by_hand);
}
