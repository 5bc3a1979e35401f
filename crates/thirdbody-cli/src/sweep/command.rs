//! The `thirdbody sweep` and `thirdbody merge` commands: their arguments, a progress
//! bar with ETA on stderr (only when stderr is a terminal), and the summary printed at
//! the end, whose line `computed C (F failed), skipped S already finished` says what
//! this run did. Errors of the sweep's specification are [`SweepError`]s (exit code 2).

use std::io::IsTerminal;
use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

use anyhow::Result;
use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use super::folder::Status;
use super::run::{run, Event, RunOptions, Shard};
use super::{merge, Sweep, SweepError};

/// Arguments of `thirdbody sweep`.
// The field comments are also `--help` text, where `[sweep]` names the case file's
// section; rustdoc would read it as a link.
#[allow(rustdoc::broken_intra_doc_links)]
#[derive(Debug, Args)]
pub struct SweepArgs {
    /// The base case file (TOML, docs/case-file.md); an optional [sweep] section lists
    /// what to vary (docs/sweeps.md).
    pub case: PathBuf,
    /// A key and its values: KEY=V1,V2,... or KEY=A..B:N (N log-spaced values) or
    /// KEY=A..B:N:lin; repeat for more keys (their Cartesian product is run). Replaces
    /// the key's values from [sweep].
    #[arg(long, value_name = "KEY=VALUES")]
    pub vary: Vec<String>,
    /// The sweep folder: records, results.csv, plot. Rerunning the same command there
    /// solves only the cases that are not finished.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Run only every N-th case, starting at case K-1 (1 <= K <= N), e.g. one shard
    /// per job of a cluster job array; join the folders with `thirdbody merge`.
    #[arg(long, value_name = "K/N")]
    pub shard: Option<String>,
    /// Cases solved at once (default: all cores).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..))]
    pub threads: Option<u16>,
    /// Solve again the cases that failed in an earlier run.
    #[arg(long)]
    pub retry_failed: bool,
    /// Check the sweep and list its cases (id and values) without solving or writing.
    #[arg(long)]
    pub dry_run: bool,
    /// Print nothing but errors.
    #[arg(long)]
    pub quiet: bool,
}

/// Arguments of `thirdbody merge`.
#[derive(Debug, Args)]
pub struct MergeArgs {
    /// Sweep folders of one sweep (its shards).
    #[arg(required = true, value_name = "DIR")]
    pub dirs: Vec<PathBuf>,
    /// The merged folder (new, one of the inputs, or an earlier merge).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Print nothing but errors.
    #[arg(long)]
    pub quiet: bool,
}

/// `thirdbody sweep`.
pub fn sweep_command(args: &SweepArgs) -> Result<()> {
    let shard = args.shard.as_deref().map(Shard::parse).transpose()?;
    let sweep = Sweep::from_file(&args.case, &args.vary)?;
    let workers = args
        .threads
        .map(usize::from)
        .unwrap_or_else(rayon::current_num_threads);
    sweep.check_memory(
        |k| shard.is_none_or(|s| s.owns(k)),
        workers,
        crate::memory::available_bytes(),
    )?;
    if args.dry_run {
        if !args.quiet {
            print_cases(&sweep, shard);
        }
        return Ok(());
    }
    let options = RunOptions {
        out: args.out.clone(),
        shard,
        threads: args.threads.map(usize::from),
        retry_failed: args.retry_failed,
    };
    let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden());
    if !args.quiet && std::io::stderr().is_terminal() {
        bar.set_draw_target(ProgressDrawTarget::stderr());
    }
    if let Ok(style) = ProgressStyle::with_template(
        "{bar:32} {pos}/{len} cases  {elapsed} elapsed, ETA {eta}  {msg}",
    ) {
        bar.set_style(style);
    }
    let failed = AtomicUsize::new(0);
    let observer = |event: Event| match event {
        Event::Start { to_solve, .. } => {
            bar.set_length(to_solve as u64);
            bar.enable_steady_tick(Duration::from_millis(500));
        }
        Event::Finished { record, .. } => {
            if record.status == Status::Failed {
                let n = failed.fetch_add(1, Ordering::Relaxed) + 1;
                bar.set_message(format!("{n} failed"));
            }
            bar.inc(1);
        }
    };
    let result = run(&sweep, &options, &observer);
    bar.finish_and_clear();
    let report = result?;
    if !args.quiet {
        let shard = match shard {
            Some(s) => format!(" (shard {}/{}: {} cases)", s.k, s.n, report.shard_cases),
            None => String::new(),
        };
        crate::say!(
            "{}: {} cases{shard}; computed {} ({} failed), skipped {} already finished",
            args.out.display(),
            report.cases,
            report.computed,
            report.computed_failed,
            report.skipped
        );
        crate::say!(
            "results in {} ({} of {} cases finished, {} failed){}",
            report.results.display(),
            report.finished,
            report.cases,
            report.failed,
            report
                .plot
                .map(|p| format!("; plot {}", p.display()))
                .unwrap_or_default()
        );
    }
    Ok(())
}

fn print_cases(sweep: &Sweep, shard: Option<Shard>) {
    let names: Vec<&str> = sweep.axes().iter().map(|a| a.name.as_str()).collect();
    let mine: Vec<usize> = (0..sweep.len())
        .filter(|&k| shard.is_none_or(|s| s.owns(k)))
        .collect();
    crate::say!(
        "{} cases{} (nothing solved or written: --dry-run)",
        sweep.len(),
        shard
            .map(|s| format!(", {} in shard {}/{}", mine.len(), s.k, s.n))
            .unwrap_or_default()
    );
    crate::say!("case\t{}", names.join("\t"));
    for k in mine {
        crate::say!("{}\t{}", sweep.id(k), sweep.labels(k).join("\t"));
    }
}

/// `thirdbody merge`.
pub fn merge_command(args: &MergeArgs) -> Result<()> {
    let report = merge(&args.dirs, &args.out)?;
    if report.missing > 0 {
        eprintln!(
            "warning: {} of {} cases have no result in any folder (rerun their shards, then \
             merge again)",
            report.missing, report.cases
        );
    }
    if !args.quiet {
        crate::say!(
            "{}: merged {} folders; {} of {} cases finished ({} failed, {} missing, {} found \
             twice)",
            args.out.display(),
            args.dirs.len(),
            report.finished,
            report.cases,
            report.failed,
            report.missing,
            report.duplicates
        );
        crate::say!(
            "results in {}{}",
            report.results.display(),
            report
                .plot
                .map(|p| format!("; plot {}", p.display()))
                .unwrap_or_default()
        );
    }
    Ok(())
}

/// Whether an error is a bad sweep, bad arguments or an unusable folder (exit code 2).
pub fn is_bad_input(e: &anyhow::Error) -> bool {
    e.chain().any(|c| c.is::<SweepError>())
}
