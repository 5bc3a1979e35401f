//! Library side of the `thirdbody` command-line front end: the pieces the binary, its
//! integration tests and benches share (atomic writes, plots, the VTK writer,
//! height-map files, the summary of a solve, parameter sweeps, the labels of each
//! system of units). Numerics live in the `thirdbody` crate; this crate turns case
//! files into cases and results into files.

#![warn(missing_docs)]

/// Prints a line to stdout like `println!`, but a closed stdout (`thirdbody solve ...
/// | head -1`) is not an error: the line is dropped instead of panicking, and the
/// command goes on to finish its work and exit as it would have.
#[macro_export]
macro_rules! say {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stdout(), $($arg)*);
    }};
}

pub mod app;
pub mod atomic;
pub mod heightmap;
pub mod memory;
pub mod plot;
pub mod summary;
pub mod sweep;
pub mod units;
pub mod vtk;
