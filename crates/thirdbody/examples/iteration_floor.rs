//! The iteration-floor benchmark: for the Hertz benchmark case and the paper's Fig. 3 case at
//! 256² to 2048² cells, the solve's time per iteration and per operator product (one
//! DC-FFT convolution) on one thread, against the *minimal DC-FFT convolution*, and
//! the speed-up of N threads over one.
//!
//! The floor is written here independently of the library (realfft rows, a blocked
//! transpose, rustfft columns): the zero-padded `2nx x 2ny` convolution of an
//! `nx x ny` field that transforms only the `ny` rows holding data, keeps only the
//! `ny` output rows that are needed, and does nothing else. The machine is shared
//! and its speed drifts over seconds, so each repeat is a round of the floor (median
//! of a few), a one-thread solve and an N-thread solve; `it/fl` is the median over
//! the rounds of the solve's time per iteration over the round's floor, `speedup`
//! the median of the rounds' one-thread over N-thread times. `conv ms` is the
//! library's own full-padding convolution on one thread. Every other time is a
//! median of the rounds.
//!
//! Run: `cargo run --release -p thirdbody --example iteration_floor -- [--sizes 256,512]
//! [--threads N] [--cases hertz,fig3] [--repeats R] [--convolution-only]`

use std::sync::Arc;
use std::time::Instant;

use realfft::num_complex::Complex;
use thirdbody::*;
use thirdbody_reference::fft;

#[path = "../tests/bundled/mod.rs"]
mod bundled;
use bundled::bundled;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// The minimal DC-FFT convolution of an `n x n` field, sequential.
struct Floor {
    n: usize,
    row_forward: Arc<dyn realfft::RealToComplex<f64>>,
    row_inverse: Arc<dyn realfft::ComplexToReal<f64>>,
    column_forward: Arc<dyn rustfft::Fft<f64>>,
    column_inverse: Arc<dyn rustfft::Fft<f64>>,
    kernel: Vec<Complex<f64>>,
    rows: Vec<Complex<f64>>,
    columns: Vec<Complex<f64>>,
    real: Vec<f64>,
    scratch: Vec<Complex<f64>>,
}

/// Transposes an `r x c` row-major block into `dst` with row length `dst_stride`, in
/// tiles so both sides stay in cache.
fn transpose(src: &[Complex<f64>], r: usize, c: usize, dst: &mut [Complex<f64>], stride: usize) {
    const TILE: usize = 16;
    for i0 in (0..r).step_by(TILE) {
        for j0 in (0..c).step_by(TILE) {
            for i in i0..(i0 + TILE).min(r) {
                for j in j0..(j0 + TILE).min(c) {
                    dst[j * stride + i] = src[i * c + j];
                }
            }
        }
    }
}

impl Floor {
    fn new(n: usize) -> Self {
        let row_forward = fft::real_forward(2 * n);
        let row_inverse = fft::real_inverse(2 * n);
        let column_forward = fft::forward(2 * n);
        let column_inverse = fft::inverse(2 * n);
        let scratch = row_forward
            .get_scratch_len()
            .max(row_inverse.get_scratch_len())
            .max(column_forward.get_inplace_scratch_len())
            .max(column_inverse.get_inplace_scratch_len());
        let half = n + 1;
        Floor {
            n,
            row_forward,
            row_inverse,
            column_forward,
            column_inverse,
            kernel: (0..half * 2 * n)
                .map(|k| Complex::new(1.0 / (1.0 + k as f64), 0.0))
                .collect(),
            rows: vec![Complex::default(); half * n],
            columns: vec![Complex::default(); half * 2 * n],
            real: vec![0.0; 2 * n],
            scratch: vec![Complex::default(); scratch],
        }
    }

    fn convolve(&mut self, field: &[f64], out: &mut [f64]) {
        let (n, half) = (self.n, self.n + 1);
        for (src, dst) in field.chunks_exact(n).zip(self.rows.chunks_exact_mut(half)) {
            self.real[..n].copy_from_slice(src);
            self.real[n..].fill(0.0);
            self.row_forward
                .process_with_scratch(&mut self.real, dst, &mut self.scratch)
                .unwrap();
        }
        for col in self.columns.chunks_exact_mut(2 * n) {
            col[n..].fill(Complex::default());
        }
        transpose(&self.rows, n, half, &mut self.columns, 2 * n);
        self.column_forward
            .process_with_scratch(&mut self.columns, &mut self.scratch);
        self.columns
            .iter_mut()
            .zip(&self.kernel)
            .for_each(|(c, k)| *c *= k);
        self.column_inverse
            .process_with_scratch(&mut self.columns, &mut self.scratch);
        // The first n entries of each column back into rows.
        const TILE: usize = 16;
        for c0 in (0..half).step_by(TILE) {
            for r0 in (0..n).step_by(TILE) {
                for c in c0..(c0 + TILE).min(half) {
                    for r in r0..(r0 + TILE).min(n) {
                        self.rows[r * half + c] = self.columns[c * 2 * n + r];
                    }
                }
            }
        }
        for (src, dst) in self
            .rows
            .chunks_exact_mut(half)
            .zip(out.chunks_exact_mut(n))
        {
            src[0].im = 0.0;
            src[n].im = 0.0;
            self.row_inverse
                .process_with_scratch(src, &mut self.real, &mut self.scratch)
                .unwrap();
            dst.copy_from_slice(&self.real[..n]);
        }
    }
}

/// The minimal convolution and the library's, built once per size and timed in
/// turns, so that both see the same machine (it is shared and its speed drifts).
struct Convolutions {
    floor: Floor,
    library: thirdbody::convolution::Convolver,
    spectrum: thirdbody::convolution::KernelSpectrum,
    field: Vec<f64>,
    out: Vec<f64>,
}

impl Convolutions {
    fn new(n: usize) -> Self {
        use thirdbody::convolution::ConvolutionPlan;
        let plan = ConvolutionPlan::new(n, n, Parallelism::Sequential).expect("n > 0");
        let spectrum = plan
            .kernel_spectrum(|i, j| 1.0 / (1.0 + (i * i + j * j) as f64).sqrt())
            .expect("a full plan");
        let mut c = Convolutions {
            floor: Floor::new(n),
            library: plan.convolver(),
            spectrum,
            field: (0..n * n).map(|k| ((k * 37) % 11) as f64).collect(),
            out: vec![0.0; n * n],
        };
        c.floor_seconds(1);
        c.library_seconds(1);
        c
    }

    /// Median of `repeats` minimal convolutions.
    fn floor_seconds(&mut self, repeats: usize) -> f64 {
        median(
            (0..repeats)
                .map(|_| {
                    let t = Instant::now();
                    self.floor.convolve(&self.field, &mut self.out);
                    t.elapsed().as_secs_f64()
                })
                .collect(),
        )
    }

    /// Median of `repeats` of the library's own convolution (one thread).
    fn library_seconds(&mut self, repeats: usize) -> f64 {
        median(
            (0..repeats)
                .map(|_| {
                    let t = Instant::now();
                    self.library
                        .apply(&self.spectrum, &self.field, &mut self.out)
                        .expect("the plan's sizes");
                    t.elapsed().as_secs_f64()
                })
                .collect(),
        )
    }
}

/// Convolutions per timing of the floor: about 30 ms of them.
fn floor_repeats(n: usize) -> usize {
    (30_000_000 / (n * n * 30)).clamp(3, 51)
}

/// `repeats` rounds of: the minimal convolution (median of a few), a solve of
/// `case` on one thread, the same solve on `threads` threads. The machine is shared
/// and its speed drifts over seconds, so each ratio is formed within a round and
/// their medians are reported.
fn rounds(threads: usize, case: &Case, repeats: usize, floor: &mut Convolutions) -> Rounds {
    let pools: Vec<rayon::ThreadPool> = [1, threads]
        .iter()
        .map(|&t| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(t)
                .build()
                .expect("thread pool")
        })
        .collect();
    let params = SolverParams::default();
    let n = case.grid.cells[0];
    let mut r = Rounds::default();
    for _ in 0..repeats {
        let f = floor.floor_seconds(floor_repeats(n));
        let mut timed = pools.iter().map(|pool| {
            let t = Instant::now();
            let s = pool.install(|| solve(case, &params)).expect("solve");
            (t.elapsed().as_secs_f64(), s)
        });
        let (one, s1) = timed.next().expect("one thread");
        let (many, sn) = timed.next().expect("n threads");
        r.floors.push(f);
        r.over_floor.push(one / s1.info.iterations as f64 / f);
        r.speed_ups.push(one / many);
        r.one.push(one);
        r.many.push(many);
        r.solutions = Some((s1, sn));
    }
    r
}

#[derive(Default)]
struct Rounds {
    one: Vec<f64>,
    many: Vec<f64>,
    floors: Vec<f64>,
    over_floor: Vec<f64>,
    speed_ups: Vec<f64>,
    solutions: Option<(Solution, Solution)>,
}

fn max_relative_difference(a: &[f64], b: &[f64]) -> f64 {
    let scale = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs() / scale))
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let value = |flag: &str| {
        args.iter()
            .position(|a| a == flag)
            .and_then(|i| args.get(i + 1).cloned())
    };
    let sizes: Vec<usize> = value("--sizes")
        .unwrap_or_else(|| "256,512,1024,2048".into())
        .split(',')
        .map(|s| s.parse().expect("--sizes: comma-separated cell counts"))
        .collect();
    let threads: usize = value("--threads")
        .map(|s| s.parse().expect("--threads: a count"))
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(2, |n| n.get()));
    let cases: Vec<String> = value("--cases")
        .unwrap_or_else(|| "hertz,fig3".into())
        .split(',')
        .map(str::to_owned)
        .collect();
    let repeats_override: Option<usize> =
        value("--repeats").map(|s| s.parse().expect("--repeats: a count"));
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    println!("load average at start: {}", load.trim());
    if args.iter().any(|a| a == "--convolution-only") {
        for &n in &sizes {
            let mut c = Convolutions::new(n);
            let repeats = repeats_override.unwrap_or(15);
            let (mut floors, mut libraries, mut ratios) = (Vec::new(), Vec::new(), Vec::new());
            for _ in 0..repeats {
                let f = c.floor_seconds(floor_repeats(n));
                let l = c.library_seconds(floor_repeats(n));
                floors.push(f);
                libraries.push(l);
                ratios.push(l / f);
            }
            println!(
                "{n:>5}: floor {:.3} ms, library {:.3} ms, ratio {:.3} (median of {repeats} paired ratios)",
                median(floors) * 1e3,
                median(libraries) * 1e3,
                median(ratios)
            );
        }
        return;
    }
    // What two cores give this machine now: the library's one-thread convolution
    // alone, and two of them at once on two threads (their own data). On a shared
    // host two vCPUs can share a core or its memory bandwidth; then no solve gets
    // 2x from a second thread, and this line says by how much less.
    for &n in &sizes {
        let alone = Convolutions::new(n).library_seconds(15);
        let both: Vec<f64> = std::thread::scope(|scope| {
            let runs: Vec<_> = (0..2)
                .map(|_| scope.spawn(move || Convolutions::new(n).library_seconds(15)))
                .collect();
            runs.into_iter()
                .map(|r| r.join().expect("thread"))
                .collect()
        });
        let together = both.iter().sum::<f64>() / 2.0;
        println!(
            "{n:>5}: one-thread convolution alone {:.3} ms, two at once {:.3} ms each: two cores give {:.2}x one",
            alone * 1e3,
            together * 1e3,
            2.0 * alone / together
        );
    }
    println!(
        "{:<6} {:>5} {:>5} {:>8} {:>10} {:>10} {:>10} {:>8} {:>6} {:>6} {:>9} {:>9} {:>7} {:>9}",
        "case",
        "cells",
        "iter",
        "products",
        "t/iter ms",
        "t/prod ms",
        "floor ms",
        "conv ms",
        "it/fl",
        "pr/fl",
        "1 thr s",
        format!("{threads} thr s"),
        "speedup",
        "max diff"
    );
    for name in &cases {
        let file = match name.as_str() {
            "hertz" => "hertz_benchmark",
            "fig3" => "paper_fig3",
            other => panic!("unknown case {other}: hertz or fig3"),
        };
        for &n in &sizes {
            let case = bundled(file, n);
            let repeats = repeats_override.unwrap_or(if n >= 2048 {
                1
            } else if n >= 1024 {
                3
            } else {
                5
            });
            let mut convolutions = Convolutions::new(n);
            let library = convolutions.library_seconds(floor_repeats(n));
            let r = rounds(threads, &case, repeats, &mut convolutions);
            let (s1, sn) = r.solutions.as_ref().expect("at least one round");
            let (one, many, floor) = (
                median(r.one.clone()),
                median(r.many.clone()),
                median(r.floors.clone()),
            );
            let products = s1.info.operator_products;
            let per_product = one / products as f64;
            let per_iteration = one / s1.info.iterations as f64;
            println!(
                "{:<6} {:>5} {:>5} {:>8} {:>10.2} {:>10.2} {:>10.2} {:>8.2} {:>6.2} {:>6.2} {:>9.3} {:>9.3} {:>7.2} {:>9.1e}",
                name,
                n,
                s1.info.iterations,
                products,
                per_iteration * 1e3,
                per_product * 1e3,
                floor * 1e3,
                library * 1e3,
                median(r.over_floor.clone()),
                per_product / floor,
                one,
                many,
                median(r.speed_ups.clone()),
                max_relative_difference(&s1.pressure, &sn.pressure),
            );
        }
    }
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    println!("load average at end: {}", load.trim());
}
