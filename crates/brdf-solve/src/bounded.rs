//! The bounded solver in the SQP family (Ngan and Kurt fitted with MATLAB's
//! constrained SQP): every iteration solves the damped Gauss-Newton model of
//! `1/2 ||r||^2` as a quadratic programme with the box and the linear
//! inequalities as constraints (an LSI problem, [`crate::lsi`](fn@crate::lsi), solved exactly
//! by the Lawson-Hanson LDP/NNLS reduction), and accepts the step on the cost
//! as merit function with Levenberg-Marquardt control of the damping. The
//! iterates never leave the feasible set; the report says which parameters
//! sit on a bound.
//!
//! The options are [`crate::LmOptions`]; the stopping gradient is
//! the projected one (components pushing against an active bound removed).

use crate::SolveError;
use crate::constraints::Constraints;
use crate::levenberg_marquardt::{LmOptions, minimize};
use crate::problem::LeastSquaresProblem;
use crate::report::SolverReport;

/// Minimise `1/2 ||r(p)||^2` subject to `constraints`, from a feasible `p0`.
pub fn bounded_least_squares<P: LeastSquaresProblem + ?Sized>(
    problem: &P,
    p0: &[f64],
    constraints: &Constraints,
    options: &LmOptions,
) -> Result<SolverReport, SolveError> {
    minimize(problem, p0, constraints, options)
}
