//! The error type of `brdf-solve`: misuse and impossible input, each naming
//! what is at fault. Non-convergence is never an error: it is a termination
//! reason in a solver's report.

use thiserror::Error;

/// Errors of the solvers.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum SolveError {
    /// Two dimensions that must agree do not.
    #[error("dimension mismatch: {what} ({left} vs {right})")]
    Dimension {
        /// what was compared
        what: &'static str,
        /// first size
        left: usize,
        /// second size
        right: usize,
    },
    /// The problem has no rows or no columns.
    #[error("empty problem: {what}")]
    Empty {
        /// what is empty
        what: &'static str,
    },
    /// An input value is NaN or infinite.
    #[error("non-finite value {value} in {what} at row {row}, column {col}")]
    NonFinite {
        /// which input
        what: &'static str,
        /// row
        row: usize,
        /// column
        col: usize,
        /// the value
        value: f64,
    },
    /// An option or weight is outside its allowed range.
    #[error("invalid {name} = {value}: {reason}")]
    InvalidOption {
        /// option name
        name: &'static str,
        /// value given
        value: f64,
        /// what is allowed
        reason: &'static str,
    },
    /// A factorisation failed (e.g. Cholesky of a matrix that is not
    /// numerically positive definite in the normal equations).
    #[error("{method} failed: {reason}")]
    Factorisation {
        /// the method
        method: &'static str,
        /// why
        reason: String,
    },
}
