//! Scaling table: solve time (median of repeats) and peak
//! resident memory for 64..1024 cells a side, each size in a fresh process so that
//! the peak belongs to that size alone, and the dense reference (the paper's method)
//! at 32 and 64 cells a side for the ratio.
//!
//! Run: `cargo run --release -p thirdbody --example scaling`

use std::process::Command;
use std::time::Instant;
use thirdbody::*;
use thirdbody_reference::solve_dense;

#[path = "../tests/bundled/mod.rs"]
mod bundled;
use bundled::bundled as case;

/// Peak resident set size of this process, from /proc (Linux), in MiB.
fn peak_rss_mib() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<f64>().ok())
        })
        .map_or(f64::NAN, |kib| kib / 1024.0)
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn child(kind: &str, n: usize, method: &str) {
    let c = case(kind, n);
    let params = SolverParams::default();
    let repeats = if n >= 512 || method == "dense" { 3 } else { 7 };
    let mut times = Vec::new();
    let mut info = String::new();
    for _ in 0..repeats {
        let t = Instant::now();
        let s = solve(&c, &params).expect("solve");
        let fft_time = t.elapsed().as_secs_f64();
        if method == "dense" {
            let t = Instant::now();
            let d = solve_dense(&c, &s.grid, 1e-10).expect("dense");
            times.push(t.elapsed().as_secs_f64());
            info = format!("{} active-set steps", d.info.iterations);
        } else {
            times.push(fft_time);
            info = format!(
                "{:?}, {} iterations, residual {:.1e}",
                s.info.method, s.info.iterations, s.info.residual
            );
        }
    }
    println!(
        "{kind}|{n}|{method}|{:.4}|{:.1}|{info}",
        median(times),
        peak_rss_mib()
    );
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.len() == 4 {
        child(&args[1], args[2].parse().unwrap(), &args[3]);
        return;
    }
    let me = std::env::current_exe().unwrap();
    println!("| case | cells a side | method | median solve (s) | peak RSS (MiB) | notes |");
    println!("|---|---|---|---|---|---|");
    let mut runs = Vec::new();
    for kind in ["hertz_benchmark", "paper_fig3"] {
        for n in [64, 128, 256, 512, 1024] {
            runs.push((kind, n, "fft"));
        }
        for n in [32, 64] {
            runs.push((kind, n, "dense"));
        }
    }
    for (kind, n, method) in runs {
        let out = Command::new(&me)
            .args([kind, &n.to_string(), method])
            .output()
            .unwrap();
        let line = String::from_utf8_lossy(&out.stdout);
        let line = line.trim();
        let cols: Vec<&str> = line.split('|').collect();
        if cols.len() == 6 {
            println!(
                "| {} | {} | {} | {} | {} | {} |",
                cols[0], cols[1], cols[2], cols[3], cols[4], cols[5]
            );
        } else {
            println!(
                "| {kind} | {n} | {method} | failed | | {} |",
                String::from_utf8_lossy(&out.stderr)
                    .lines()
                    .last()
                    .unwrap_or("")
            );
        }
    }
}
