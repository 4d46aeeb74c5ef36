//! # brdf-solve
//!
//! Solvers for fitting any [`brdf_core::Parametric`] model (or any problem
//! implementing this crate's problem traits) to data. Every factorisation is
//! faer's.
//!
//! | module | what |
//! | --- | --- |
//! | [`linear`] | dense (weighted) least squares: pivoted QR with a rank report, SVD, normal equations as an option; leverages |
//! | [`nnls`](mod@nnls) | Lawson-Hanson non-negative least squares |
//! | [`lsi`](mod@lsi) | least squares with linear inequality constraints (LDP through NNLS) |
//! | [`robust_weights`] | the eight robust weight functions with their tuning constants |
//! | [`irls`](mod@irls) | robust regression by IRLS (MATLAB `robustfit`; three scale conventions) |
//! | [`problem`] | [`LeastSquaresProblem`]: what a non-linear solver needs from a problem |
//! | [`levenberg_marquardt`](mod@levenberg_marquardt) | Levenberg-Marquardt: stacked-QR steps, Marquardt scaling, Nielsen's or Sopp's damping, geodesic acceleration |
//! | [`compass`] | compass search: derivative-free, in a box, for a scalar objective without a Jacobian (an image metric) |
//! | [`covariance`] | parameter covariance and standard errors (SVD of `J`) |
//! | [`constraints`] | box bounds and linear inequalities |
//! | [`bounded`] | the bounded SQP-style solver (LSI subproblem per iteration) |
//! | [`report`] | [`SolverReport`], [`Termination`], [`BoundStatus`] |
//! | [`varpro`] | variable projection: linear coefficients (NNLS) projected out, Golub-Pereyra Jacobian |
//! | [`model_problem`] | least-squares problems from any `Parametric` model and samples (full and separable) |
//! | [`multistart`](mod@multistart) | deterministic Halton multi-start, best result and spread |
//! | [`rounds`] | multi-start in two rounds: the starts still going after a few iterations solved again only when they can win |
//! | [`tall_qr`] | the triangular factor of tall, skinny matrices (row-block TSQR on faer's kernels) |
//! | [`scratch`] | reusable buffers for problems shared between threads |
//! | [`strd`] | the 27 NIST StRD model functions with analytic gradients, LRE |
//! | [`error`] | [`SolveError`] |
//!
//! ## Crate features
//!
//! - `rayon` (default): parallel multi-start.
//! - `serde`: serialize reports.
//!
//! ## Layering
//!
//! `brdf-solve` depends on `brdf-core` only (the `ModelProblem` adaptor
//! uses its `Parametric` trait); it knows no data format and no model
//! catalogue. `brdf-fit` drives it; `brdf-study` certifies it on NIST StRD.

pub mod bounded;
pub mod compass;
pub mod constraints;
pub mod covariance;
pub mod error;
pub mod irls;
pub mod levenberg_marquardt;
pub mod linear;
pub mod lsi;
pub mod model_problem;
pub mod multistart;
pub mod nnls;
pub mod problem;
pub mod report;
pub mod robust_weights;
pub mod rounds;
pub mod scratch;
mod small_qr;
pub mod strd;
pub mod tall_qr;
pub mod varpro;

pub use bounded::bounded_least_squares;
pub use compass::{CompassOptions, CompassReport, CompassTermination, compass_search};
pub use constraints::Constraints;
pub use error::SolveError;
pub use irls::{IrlsOptions, IrlsSolution, IrlsTermination, ScaleConvention, StoppingTest, irls};
pub use levenberg_marquardt::{Damping, LmOptions, Scaling, levenberg_marquardt};
pub use linear::{LstsqMethod, LstsqSolution, lstsq};
pub use lsi::lsi;
pub use model_problem::{ModelProblem, RowTransform};
pub use multistart::{MultiStartReport, StartBox, multistart};
pub use nnls::{NnlsSolution, NnlsTermination, nnls};
pub use problem::{LeastSquaresProblem, fd_jacobian};
pub use report::{BoundStatus, SolverReport, Termination};
/// Make faer's dense factorisations (the pivoted QR and SVD of [`lstsq`])
/// sequential for the whole process (faer's global parallelism). By
/// default faer splits their blocks by the thread count of the rayon pool
/// they run in, so the same solve can differ in its last bits between 1
/// and 2 threads (Koenderink's coefficients in `brdf select` did). Callers
/// parallelise over starts, candidates and materials instead, so nothing is
/// lost; an application that wants the same results for any thread count
/// calls this once at start, as the `brdf` command and the Python module do.
pub fn sequential_factorisations() {
    faer::set_global_parallelism(faer::Par::Seq);
}

pub use varpro::{SeparableProblem, VarPro};
