//! Parameter sweeps (docs/sweeps.md): one base case file, some of its keys varied over
//! lists or log-spaced ranges, the Cartesian product of the values solved case by case
//! in parallel (rayon, one thread per case, each solve's FFTs sequential), each
//! finished case written atomically as a record in `DIR/cases/`, and `DIR/results.csv`
//! (one row per case: the varied values, every summary key, the status) assembled from
//! the records at the end of every run. A rerun skips the cases that have a record, so
//! an interrupted sweep loses nothing; `--shard K/N` runs every N-th case and
//! [`merge`](merge()) joins shard folders.
//!
//! The engine ([`run`](run()), [`merge`](merge())) prints nothing: it reports progress to an observer
//! the caller passes. [`command`] is the `thirdbody sweep` / `thirdbody merge` front
//! end (arguments, progress bar, printed summary).

pub mod command;
pub mod merge;
pub mod plot;
pub mod run;

// The cases, records and results.csv, shared with the Python package.
pub use thirdbody_engine::sweep::{cases, folder, plot_scale, record, results, spec, values};
pub use thirdbody_engine::sweep::{Sweep, SweepError};

pub use merge::{merge, MergeReport};
pub use run::{run, Event, RunOptions, RunReport, Shard};
