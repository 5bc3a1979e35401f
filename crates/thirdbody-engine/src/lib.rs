//! What thirdbody's front ends (the `thirdbody` command and the Python package)
//! share, so that neither reaches into the other: height maps read from files, the
//! memory check before a solve, atomic writes, the summary of a solve, and sweeps'
//! cases, records and `results.csv`. Numerics live in the `thirdbody` crate; this
//! crate reads and writes files and words refusals, and prints nothing.

#![warn(missing_docs)]

pub mod atomic;
pub mod geometry;
pub mod heightmap;
pub mod memory;
pub mod summary;
pub mod sweep;
