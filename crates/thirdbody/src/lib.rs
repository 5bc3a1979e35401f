//! thirdbody: quasi-static sliding contact of a smooth slider over a thin nonlinear
//! viscoelastic "third-body" layer lying on a homogeneous or coated elastic
//! half-space (Lubricants 2023, 11, 333).
//!
//! Conventions (design.md §1): the frame is fixed to the slider, which moves in +x
//! over the body, so body material flows through the contact in -x. z points into
//! the body. Pressure is positive in compression; stresses are positive in tension.
//! Fields on the grid are row-major with rows along y (`field[j * nx + i]`).
//! Any consistent units work; the paper's dimensionless variables are R = E2 = T = 1.
#![warn(missing_docs)]

pub mod body;
pub mod case;
pub mod case_file;
pub mod contact;
pub mod convolution;
pub mod error;
pub mod grid;
pub mod krylov;
pub mod layer;
pub mod operator;
pub mod reference;
pub mod shape;
pub mod solution;
pub mod stress;

pub use case::{Body, Case, Elastic, GridSpec, Loading, Units};
pub use contact::{solve, solve_observed, Progress, SolverParams};
pub use convolution::Parallelism;
pub use error::{Error, Result};
pub use grid::Grid;
pub use layer::{ComplianceLaw, Integration, Layer};
pub use shape::{HeightMap, Slider};
pub use solution::{Method, Solution, SolveInfo, Summary};
