//! Errors of the library: every bad input names the offending field and the
//! allowed range, and every solver failure carries its residual, so that a caller
//! can print one line that tells the user what to change.

use thiserror::Error;

/// Everything that can go wrong in thirdbody.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum Error {
    /// A case field has a value outside its allowed range.
    #[error("{field} = {value} is not allowed: {allowed}")]
    InvalidValue {
        /// Dotted path of the field, e.g. `layer.delta`.
        field: String,
        /// The offending value, as written.
        value: String,
        /// What is allowed, e.g. `0 <= delta <= 1`.
        allowed: String,
    },
    /// A field needed by the chosen options is absent.
    #[error("missing field {field}: {why}")]
    MissingField {
        /// Dotted path of the field.
        field: String,
        /// Why it is needed.
        why: String,
    },
    /// A field was given that the chosen options do not use.
    #[error("field {field} is not used here: {why}")]
    UnusedField {
        /// Dotted path of the field.
        field: String,
        /// Why it is not used.
        why: String,
    },
    /// The case text could not be parsed (syntax, unknown key, missing section).
    #[error("{0}")]
    Parse(String),
    /// The contact solver did not reach the requested residual.
    #[error(
        "the contact solver did not converge: residual {residual:.3e} after {iterations} \
         iterations (tolerance {tolerance:.1e}); {hint}"
    )]
    NoConvergence {
        /// Iterations done.
        iterations: usize,
        /// Final relative complementarity residual.
        residual: f64,
        /// The tolerance asked for.
        tolerance: f64,
        /// Residual after each outer iteration.
        history: Vec<f64>,
        /// What the user can try.
        hint: String,
    },
    /// The case's values are out of double precision's range together: the solver's
    /// numbers overflow or underflow (an input error, like an invalid value).
    #[error("the case cannot be computed in double precision: {why}")]
    OutOfRange {
        /// What overflowed and which keys to check.
        why: String,
    },
    /// The case is far outside the model (a contact much larger than a small
    /// fraction of the slider's radius) and the solve failed there: an input error.
    #[error("the case is outside the model: {why}")]
    OutsideModel {
        /// What is outside, by how much, and which keys set it.
        why: String,
    },
    /// The progress observer asked the solve to stop (a user's interrupt).
    #[error("the solve was interrupted")]
    Interrupted,
    /// The contact reached the edge of the computational window: an input error (the
    /// window is the case's, or the automatic window ran out of `solver.max_windows`).
    #[error(
        "the contact reaches the edge of the window (half widths {half_width_x:.4e} x \
         {half_width_y:.4e}); enlarge grid.half_width, or omit it for an automatic window \
         (enlarged up to solver.max_windows times)"
    )]
    ContactAtWindowEdge {
        /// Window half width along x.
        half_width_x: f64,
        /// Window half width along y.
        half_width_y: f64,
    },
}

/// Result with the library's error.
pub type Result<T> = std::result::Result<T, Error>;

impl Error {
    /// Whether the error is in the user's input (a case, a request, a height map),
    /// as opposed to a solve that failed: front ends classify errors by it (the CLI
    /// exits with 2 for input errors, 1 otherwise).
    pub fn is_input(&self) -> bool {
        matches!(
            self,
            Error::InvalidValue { .. }
                | Error::MissingField { .. }
                | Error::UnusedField { .. }
                | Error::Parse(_)
                | Error::OutOfRange { .. }
                | Error::OutsideModel { .. }
                | Error::ContactAtWindowEdge { .. }
        )
    }

    /// Shorthand for [`Error::InvalidValue`].
    pub fn invalid(field: &str, value: impl std::fmt::Display, allowed: &str) -> Self {
        let value = value.to_string();
        // f64's Display writes 1e308 as 309 digits: a long number reads better in
        // exponent form.
        let value = match value.parse::<f64>() {
            Ok(v) if value.len() > 16 => format!("{v:e}"),
            _ => value,
        };
        Error::InvalidValue {
            field: field.to_string(),
            value,
            allowed: allowed.to_string(),
        }
    }
}

/// Checks that `value` is finite and strictly positive.
pub(crate) fn require_positive(field: &str, value: f64) -> Result<()> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(field, value, "a finite number > 0"))
    }
}

/// Checks a Poisson ratio: the thermodynamic range of an isotropic solid, excluding
/// the incompressible limit (the half-space kernels use 1 - nu^2 and 1 - 2 nu).
pub(crate) fn require_poisson(field: &str, value: f64) -> Result<()> {
    if value.is_finite() && value > -1.0 && value < 0.5 {
        Ok(())
    } else {
        Err(Error::invalid(field, value, "-1 < poisson < 0.5"))
    }
}
