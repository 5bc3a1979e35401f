//! Running a sweep: the cases of this shard that have no record yet are solved in
//! parallel on a rayon pool of `threads` threads (one case per thread, each solve's
//! FFTs sequential: cases are independent, so nothing is shared but the pool), each
//! finished case is written at once as its record, and `results.csv` and the mu plot
//! are rebuilt from all records at the end.
//!
//! A case whose solve fails (no convergence, a folding row relation, a contact at the
//! window edge, even a panic) becomes a `failed` record with the message and is not
//! retried on a rerun unless asked (`retry_failed`). Only I/O errors stop the sweep.
//! Kernels and FFT plans are not shared between cases: set-up is 2-7 % of a 128 x 128
//! solve and cases rarely share a window (docs/performance.md, "Sweeps").

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

use anyhow::{Context, Result};
use rayon::prelude::*;
use thirdbody::KernelCache;

use super::folder::{read_record, write_record, Folder, Record, Status, SweepFile};
use super::plot::write_mu_plot;
use super::results::{collect, write_results};
use super::{Sweep, SweepError};
use thirdbody_engine::sweep::record::solve_record;

/// Kernel spectra a sweep worker keeps (cases that share a window and body reuse
/// them; a coated kernel costs up to seconds).
const WORKER_CACHE_CAPACITY: usize = 4;

/// Which part of the cases a run does: case `index` belongs to shard `k` (1-based) of
/// `n` when `index % n == k - 1`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// This shard, 1..=n.
    pub k: usize,
    /// Number of shards.
    pub n: usize,
}

impl Shard {
    /// Parses `K/N`.
    pub fn parse(text: &str) -> Result<Shard, SweepError> {
        let bad = || {
            SweepError::spec(format!(
                "--shard {text}: write K/N with 1 <= K <= N, e.g. --shard 1/4 (runs cases \
                 0, 4, 8, ...)"
            ))
        };
        let (k, n) = text.split_once('/').ok_or_else(bad)?;
        let k: usize = k.trim().parse().map_err(|_| bad())?;
        let n: usize = n.trim().parse().map_err(|_| bad())?;
        if n == 0 || k == 0 || k > n {
            return Err(bad());
        }
        Ok(Shard { k, n })
    }

    /// Whether case `index` is ours.
    pub fn owns(&self, index: usize) -> bool {
        index % self.n == self.k - 1
    }
}

/// How to run.
#[derive(Debug, Clone, PartialEq)]
pub struct RunOptions {
    /// The sweep folder.
    pub out: PathBuf,
    /// Only this shard's cases (all cases when `None`).
    pub shard: Option<Shard>,
    /// Threads (cases solved at once); `None`: all cores.
    pub threads: Option<usize>,
    /// Solve again the cases whose record says `failed`.
    pub retry_failed: bool,
}

/// What a run reports while it runs.
#[derive(Debug, Clone, Copy)]
pub enum Event<'a> {
    /// Before the first solve.
    Start {
        /// Cases of this shard.
        cases: usize,
        /// Of which already finished (skipped).
        skipped: usize,
        /// Of which to solve now.
        to_solve: usize,
    },
    /// A case was solved (or failed) and its record written.
    Finished {
        /// The record.
        record: &'a Record,
        /// Cases solved so far in this run, this one included.
        done: usize,
        /// Cases to solve in this run.
        to_solve: usize,
    },
}

/// What a run did.
#[derive(Debug, Clone, PartialEq)]
pub struct RunReport {
    /// Cases of the whole sweep.
    pub cases: usize,
    /// Cases of this shard.
    pub shard_cases: usize,
    /// Cases solved by this run.
    pub computed: usize,
    /// Of which failed.
    pub computed_failed: usize,
    /// Cases of this shard that were already finished.
    pub skipped: usize,
    /// Records in the folder now (all shards that wrote into it).
    pub finished: usize,
    /// Of which failed.
    pub failed: usize,
    /// `results.csv`.
    pub results: PathBuf,
    /// `mu_vs_<key>.png`, if drawn.
    pub plot: Option<PathBuf>,
}

/// Runs `sweep` into `options.out`, reporting to `observer` (called from worker
/// threads).
pub fn run(
    sweep: &Sweep,
    options: &RunOptions,
    observer: &(dyn Fn(Event) + Sync),
) -> Result<RunReport> {
    let spec = SweepFile::of(sweep);
    let folder = Folder::open(&options.out, &spec)?;
    let dir = folder.dir();
    let mine: Vec<usize> = (0..sweep.len())
        .filter(|&k| options.shard.is_none_or(|s| s.owns(k)))
        .collect();
    let to_solve: Vec<usize> = mine
        .iter()
        .copied()
        .filter(|&k| match read_record(dir, sweep.id(k)) {
            Some(r) => options.retry_failed && r.status == Status::Failed,
            None => true,
        })
        .collect();
    let total = to_solve.len();
    observer(Event::Start {
        cases: mine.len(),
        skipped: mine.len() - total,
        to_solve: total,
    });
    let done = AtomicUsize::new(0);
    let failed = AtomicUsize::new(0);
    let solve_all = || {
        // One kernel cache per worker thread, owned by this run.
        let caches: Vec<Mutex<KernelCache>> = (0..rayon::current_num_threads())
            .map(|_| Mutex::new(KernelCache::with_capacity(WORKER_CACHE_CAPACITY)))
            .collect();
        to_solve.par_iter().with_max_len(1).try_for_each(|&index| {
            let worker = rayon::current_thread_index().unwrap_or(0) % caches.len();
            let record = match caches[worker].lock() {
                Ok(mut kernels) => solve_case(sweep, index, &mut kernels),
                Err(_) => solve_case(sweep, index, &mut KernelCache::with_capacity(0)),
            };
            write_record(dir, &record)?;
            if record.status == Status::Failed {
                failed.fetch_add(1, Ordering::Relaxed);
            }
            let done = done.fetch_add(1, Ordering::Relaxed) + 1;
            observer(Event::Finished {
                record: &record,
                done,
                to_solve: total,
            });
            Ok::<(), anyhow::Error>(())
        })
    };
    match options.threads {
        Some(n) => rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .context("cannot start the thread pool")?
            .install(solve_all)?,
        None => solve_all()?,
    }
    let (collected, results, plot) = finish(dir, &spec)?;
    Ok(RunReport {
        cases: sweep.len(),
        shard_cases: mine.len(),
        computed: total,
        computed_failed: failed.into_inner(),
        skipped: mine.len() - total,
        finished: collected.records.len(),
        failed: collected.failed(),
        results,
        plot,
    })
}

/// Rebuilds `results.csv` and the plot of `dir` from its records.
pub(crate) fn finish(
    dir: &Path,
    spec: &SweepFile,
) -> Result<(super::results::Collected, PathBuf, Option<PathBuf>)> {
    let collected = collect(dir, spec);
    let results = write_results(dir, spec, &collected.records)?;
    let plot = write_mu_plot(dir, spec, &collected.records)?;
    Ok((collected, results, plot))
}

/// Solves case `index`; every failure becomes a `failed` record.
fn solve_case(sweep: &Sweep, index: usize, kernels: &mut KernelCache) -> Record {
    solve_record(
        sweep.id(index).to_string(),
        index,
        sweep.labels(index),
        || sweep.parse_case(index),
        kernels,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_partition_the_cases() {
        let shards: Vec<Shard> = (1..=3)
            .map(|k| Shard::parse(&format!("{k}/3")).unwrap())
            .collect();
        for index in 0..20 {
            assert_eq!(shards.iter().filter(|s| s.owns(index)).count(), 1);
        }
        assert!(shards[0].owns(0) && shards[0].owns(3) && shards[2].owns(5));
        for bad in ["0/2", "3/2", "1/0", "1", "a/b", "1/2/3"] {
            let e = Shard::parse(bad).unwrap_err().to_string();
            assert!(e.starts_with(&format!("--shard {bad}: write K/N")), "{e}");
        }
    }
}
