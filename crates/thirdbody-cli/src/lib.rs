//! Library side of the `thirdbody` command-line front end: the pieces the binary, its
//! integration tests and benches share (plots, the VTK writer, running parameter
//! sweeps into folders, the labels of each system of units). Numerics live in the
//! `thirdbody` crate; what both front ends need (atomic writes, height-map files, the
//! memory check, the summary of a solve, sweeps' cases and records) in
//! `thirdbody-engine`, re-exported here under the same paths; this crate turns case
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
pub mod plot;
pub mod sweep;
pub mod units;
pub mod vtk;

// Shared with the Python package (crates/thirdbody-engine).
pub use thirdbody_engine::{atomic, heightmap, memory, summary};
