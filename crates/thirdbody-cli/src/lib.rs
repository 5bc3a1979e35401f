//! Library side of the `thirdbody` command-line front end: the pieces the binary, its
//! integration tests and benches share (atomic writes, plots, the VTK writer,
//! height-map files, the summary of a solve, parameter sweeps, the labels of each
//! system of units). Numerics live in the `thirdbody` crate; this crate turns case
//! files into cases and results into files.

#![warn(missing_docs)]

pub mod atomic;
pub mod heightmap;
pub mod plot;
pub mod summary;
pub mod sweep;
pub mod units;
pub mod vtk;
