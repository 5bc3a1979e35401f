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

pub mod cases;
pub mod command;
pub mod folder;
pub mod merge;
pub mod plot;
pub mod results;
pub mod run;
pub mod spec;
pub mod values;

pub use cases::Sweep;
pub use merge::{merge, MergeReport};
pub use run::{run, Event, RunOptions, RunReport, Shard};

/// A sweep the user asked for that cannot be run as given: a bad `--vary` or
/// `[sweep]` entry, a case of the product that the case-file rules refuse, or an
/// output folder that holds another sweep. The command exits with code 2 and writes
/// nothing.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SweepError {
    /// A bad sweep specification; the message names the key or section.
    #[error("{0}")]
    Spec(String),
    /// A case of the product is not a valid case.
    #[error("sweep case {index} ({settings}): {message}")]
    Case {
        /// Index of the case in the product.
        index: usize,
        /// Its varied values, `key = value, ...`.
        settings: String,
        /// The case-file error.
        message: String,
    },
    /// The output folder (or a folder to merge) cannot be used.
    #[error("{0}")]
    Folder(String),
}

impl SweepError {
    pub(crate) fn spec(message: impl Into<String>) -> Self {
        SweepError::Spec(message.into())
    }

    pub(crate) fn key(place: &str, message: impl std::fmt::Display) -> Self {
        SweepError::Spec(format!("{place}: {message}"))
    }
}
