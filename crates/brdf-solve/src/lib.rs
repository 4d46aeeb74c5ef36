//! # brdf-solve
//!
//! Solvers for fitting any [`brdf_core::Parametric`] model (or any problem
//! implementing this crate's problem traits) to data. Every factorisation is
//! faer's.
//!
//! | module | what |
//! | --- | --- |
//! | [`linear`] | dense (weighted) least squares: pivoted QR with a rank report, SVD, normal equations as an option; leverages |
//! | [`nnls`] | Lawson-Hanson non-negative least squares |
//! | [`robust_weights`] | the eight robust weight functions with their tuning constants |
//! | [`error`] | [`SolveError`] |
//!
//! ## Crate features
//!
//! - `rayon` (default): parallel multi-start.
//! - `serde`: serialize reports.

pub mod error;
pub mod linear;
pub mod nnls;
pub mod robust_weights;

pub use error::SolveError;
pub use linear::{LstsqMethod, LstsqSolution, lstsq};
pub use nnls::{NnlsSolution, NnlsTermination, nnls};
