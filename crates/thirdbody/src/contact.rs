//! The contact solver (design.md §2): finds the contact area, pressure p >= 0 and
//! approach D such that `w_body(p) + w_layer(p) + f - D = 0` where p > 0, the gap is
//! >= 0 where p = 0, and `sum(p) h^2 = Q` (paper eq. 3-4, system 6).
//! (Implementation in progress.)

use crate::case::Case;
use crate::convolution::Parallelism;
use crate::error::{Error, Result};
use crate::grid::Grid;
use crate::solution::Solution;

/// Stopping criteria and resources of a solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverParams {
    /// Relative complementarity residual at which the solve stops.
    pub tolerance: f64,
    /// Most outer iterations per window.
    pub max_iterations: usize,
    /// Threads for one solve's FFTs.
    pub parallelism: Parallelism,
    /// Most windows the automatic window may try.
    pub max_windows: usize,
}

impl Default for SolverParams {
    fn default() -> Self {
        SolverParams {
            tolerance: 1e-10,
            max_iterations: 2000,
            parallelism: Parallelism::Rayon,
            max_windows: 6,
        }
    }
}

/// What a solve reports while it runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Progress {
    /// A new window is being solved.
    Window {
        /// 1 for the first window.
        attempt: usize,
        /// The window.
        grid: Grid,
    },
    /// An outer iteration finished.
    Iteration {
        /// Iteration number in this window.
        iteration: usize,
        /// Relative residual after it.
        residual: f64,
    },
}

/// Solves a case.
pub fn solve(case: &Case, params: &SolverParams) -> Result<Solution> {
    solve_observed(case, params, &mut |_| {})
}

/// Solves a case, reporting progress to `observer`.
pub fn solve_observed(
    case: &Case,
    params: &SolverParams,
    observer: &mut dyn FnMut(Progress),
) -> Result<Solution> {
    case.validate()?;
    let _ = (params, observer);
    Err(Error::Parse("solver not implemented yet".into()))
}
