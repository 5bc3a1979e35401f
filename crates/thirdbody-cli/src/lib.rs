//! Library side of the `thirdbody` command-line front end: the pieces the binary and its
//! integration tests share (plots and the VTK writer). Numerics live in the `thirdbody` crate; this
//! crate only turns its results into files.

#![warn(missing_docs)]

pub mod plot;
pub mod vtk;
