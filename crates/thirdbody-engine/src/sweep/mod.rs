//! Parameter sweeps (docs/sweeps.md), the parts every front end needs: the cases of
//! a sweep ([`Sweep`]: the base case, its varied keys, ids and labels), the record
//! of one solved case ([`record::solve_record`]), the records' folder and
//! `results.csv`. Running a sweep into a folder, merging shards and plotting are the
//! command line's (`thirdbody_cli::sweep`); a Python executor runs the cases itself.

pub mod cases;
pub mod folder;
pub mod plot_scale;
pub mod record;
pub mod results;
pub mod spec;
pub mod values;

pub use cases::Sweep;

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
    /// A bad sweep specification.
    pub fn spec(message: impl Into<String>) -> Self {
        SweepError::Spec(message.into())
    }

    /// A bad sweep specification at `place` (a key or section).
    pub fn key(place: &str, message: impl std::fmt::Display) -> Self {
        SweepError::Spec(format!("{place}: {message}"))
    }
}
