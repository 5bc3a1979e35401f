//! thirdbody: quasi-static sliding contact of a smooth slider over a thin nonlinear
//! viscoelastic "third-body" layer lying on a homogeneous or coated elastic
//! half-space (Lubricants 2023, 11, 333).
//!
//! Conventions (docs/architecture.md (conventions)): the frame is fixed to the slider, which moves in +x
//! over the body, so body material flows through the contact in -x. z points into
//! the body. Pressure is positive in compression; stresses are positive in tension.
//! Fields on the grid are row-major with rows along y (`field[j * nx + i]`).
//! Any consistent units work; the paper's dimensionless variables are R = E2 = T = 1.
//!
//! The data flow (docs/architecture.md): a [`Case`] (plain data, from code or from
//! a case file with [`case_file::parse_case_file`]) is assembled on a window into a
//! [`ContactProblem`] ([`Case::assemble`]: the body's influence operator, the layer's
//! response, the slider's gap and slope, the load), which a solver turns into a
//! [`Solution`]; a solution knows its body and gives its stresses
//! ([`Solution::stress_results`]) and its [`Report`] (what `summary.json` holds).
//! [`solve_with`] does the whole chain with an automatic window; costly state
//! (FFT plans, kernel spectra) lives in a [`KernelCache`] the caller owns.
//!
//! ```
//! use std::ops::ControlFlow;
//! use thirdbody::{solve_with, KernelCache, Progress, SolverParams};
//! let text = "[slider]\nshape = \"sphere\"\nradius = 1.0\n[substrate]\nyoung = 1.0\n\
//!             poisson = 0.3\n[loading]\nnormal_load = 5e-6\n[grid]\ncells = [32, 32]\n";
//! let case = thirdbody::case_file::parse_case_file(text, &mut |_, _| unreachable!())
//!     .unwrap()
//!     .case;
//! let mut kernels = KernelCache::new();
//! let mut keep_going = |_: Progress| ControlFlow::Continue(());
//! let solution = solve_with(&case, &SolverParams::default(), &mut kernels, &mut keep_going).unwrap();
//! // Hertz: p_max = (6 Q E*^2 / pi^3 R^2)^(1/3) to the grid's accuracy.
//! let e_star = 1.0 / (1.0 - 0.09);
//! let hertz = (6.0 * 5e-6 * e_star * e_star / std::f64::consts::PI.powi(3)).cbrt();
//! assert!((solution.summary().max_pressure / hertz - 1.0).abs() < 0.02);
//! ```
#![warn(missing_docs)]

pub mod body;
pub mod case;
pub mod case_file;
pub mod contact;
#[doc(hidden)]
pub mod convolution;
pub mod error;
pub mod grid;
mod kernel_cache;
pub(crate) mod krylov;
pub mod layer;
pub mod operator;
mod passes;
pub mod problem;
pub mod provenance;
pub mod report;
pub mod shape;
pub mod solution;
pub mod stress;
#[cfg(test)]
mod test_cases;
mod units;

pub use case::{Body, Case, Elastic, GridSpec, Loading, Units};
pub use contact::{solve, solve_observed, solve_problem, solve_with, Progress, SolverParams};
pub use convolution::Parallelism;
pub use error::{Error, Result};
pub use grid::{Geometry, Grid};
pub use kernel_cache::KernelCache;
pub use layer::{
    ComplianceLaw, CreepForm, Integration, Layer, RelaxationBranch, RetardationBranch, Rheology,
};
pub use problem::ContactProblem;
pub use report::Report;
pub use shape::{HeightMap, Profile, Slider};
pub use solution::{Method, Solution, SolveInfo, Summary};
