//! # brdf-solve
//!
//! Solvers for fitting any [`brdf_core::Parametric`] model (or any problem
//! implementing this crate's problem traits) to data: dense linear least
//! squares, non-negative least squares, robust IRLS, Levenberg-Marquardt, a
//! bounded SQP-style solver, variable projection and deterministic
//! multi-start. Every factorisation is faer's.
