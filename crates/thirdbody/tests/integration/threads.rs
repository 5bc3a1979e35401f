//! One solve split over threads gives the same bits as on one thread
//! (fixed chunking of every reduction, `crate::passes`, and FFT rows and columns that
//! do not depend on who computes them), for the DC-FFT itself, conjugate gradients
//! (a bare body) and semi-smooth Newton (the paper's layer), on grids large enough
//! (>= 128²) that the parallel paths are taken.

use thirdbody::convolution::{ConvolutionPlan, PARALLEL_MIN_CELLS};
use thirdbody::*;
use thirdbody_reference::direct_convolution;

use crate::bundled::bundled;

fn on_threads<T: Send>(threads: usize, work: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("thread pool")
        .install(work)
}

#[test]
fn parallel_convolution_is_the_sequential_one_and_the_direct_sum() {
    let (nx, ny) = (150, 131);
    assert!(nx * ny >= PARALLEL_MIN_CELLS);
    let kernel = |i: i64, j: i64| 1.0 / (1.0 + (i as f64 - 0.3).powi(2) + 2.0 * (j as f64).powi(2));
    // A field with zero rows (as outside a contact) and a lopsided support.
    let field: Vec<f64> = (0..nx * ny)
        .map(|k| {
            let (i, j) = (k % nx, k / nx);
            if (20..90).contains(&j) && i > 10 {
                ((k * 37) % 11) as f64 - 4.0
            } else {
                0.0
            }
        })
        .collect();
    let run = |parallelism: Parallelism| {
        let plan = ConvolutionPlan::new(nx, ny, parallelism).unwrap();
        let spectrum = plan.kernel_spectrum(kernel).unwrap();
        let mut out = vec![0.0; nx * ny];
        plan.convolver().apply(&spectrum, &field, &mut out).unwrap();
        let mut again = vec![0.0; nx * ny];
        let mut conv = plan.convolver();
        conv.transform_field(&field).unwrap();
        conv.apply_to_transformed(&spectrum, &mut again).unwrap();
        assert_eq!(out, again, "apply and transform + apply agree");
        out
    };
    let sequential = run(Parallelism::Sequential);
    let parallel = on_threads(3, || run(Parallelism::Rayon));
    assert_eq!(sequential, parallel, "same bits on 1 and 3 threads");
    // Against the direct sum on a few rows (the full sum is 4e8 terms).
    let mut direct = vec![0.0; nx * ny];
    let rows = [0usize, 19, 20, 64, 130];
    thirdbody_reference::direct_convolution_rows(nx, ny, kernel, &field, rows, &mut direct)
        .unwrap();
    let scale = direct.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for &j in &rows {
        for i in 0..nx {
            let k = j * nx + i;
            assert!(
                (parallel[k] - direct[k]).abs() < 1e-12 * scale,
                "row {j} cell {i}"
            );
        }
    }
    // The small-grid reference of the unit tests still holds for a tiny grid.
    let (sx, sy) = (9, 7);
    let plan = ConvolutionPlan::new(sx, sy, Parallelism::Rayon).unwrap();
    let spectrum = plan.kernel_spectrum(kernel).unwrap();
    let small: Vec<f64> = (0..sx * sy).map(|k| (k % 5) as f64).collect();
    let (mut fast, mut slow) = (vec![0.0; sx * sy], vec![0.0; sx * sy]);
    plan.convolver()
        .apply(&spectrum, &small, &mut fast)
        .unwrap();
    direct_convolution(sx, sy, kernel, &small, &mut slow).unwrap();
    for k in 0..sx * sy {
        assert!((fast[k] - slow[k]).abs() < 1e-12 * 20.0);
    }
}

fn assert_same_solution(a: &Solution, b: &Solution) {
    assert_eq!(a.info.iterations, b.info.iterations);
    assert_eq!(a.info.linear_iterations, b.info.linear_iterations);
    assert_eq!(a.pressure, b.pressure, "pressure bits");
    assert_eq!(a.gap, b.gap, "gap bits");
    assert_eq!(a.approach.to_bits(), b.approach.to_bits());
}

#[test]
fn a_solve_is_the_same_on_one_thread_and_on_three() {
    for (name, n) in [("hertz_benchmark", 144), ("paper_fig3", 136)] {
        let case = bundled(name, n);
        let params = SolverParams::default();
        let one = on_threads(1, || solve(&case, &params)).expect("solve");
        let three = on_threads(3, || solve(&case, &params)).expect("solve");
        let sequential = solve(
            &case,
            &SolverParams {
                parallelism: Parallelism::Sequential,
                ..params
            },
        )
        .expect("solve");
        assert_same_solution(&one, &three);
        assert_same_solution(&one, &sequential);
        assert!(one.info.operator_products >= one.info.iterations);
    }
}
