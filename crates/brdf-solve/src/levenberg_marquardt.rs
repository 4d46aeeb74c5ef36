//! Levenberg-Marquardt (Levenberg 1944, Marquardt 1963) for any
//! [`LeastSquaresProblem`], optionally inside [`Constraints`] (then it is the
//! bounded solver of [`crate::bounded`]).
//!
//! Each iteration solves the damped Gauss-Newton problem
//! `min_d ||J d + r||^2 + lambda ||D d||^2`, i.e.
//! `(J^T J + lambda D^2) d = -J^T r`, as the stacked system
//! `[R; sqrt(lambda) D] d = [-Q^T r; 0]` by Householder QR (faer), where
//! `R` and `Q^T r` are the triangle of `[J | r]`, reduced once per Jacobian
//! ([`crate::tall_qr`]): from the normal equations when their guard shows
//! them accurate (one streaming pass, no copy of `J`; the gradient `J^T r`
//! is formed directly, so the fixed point does not depend on the path),
//! by Householder QR otherwise. Each trial damping then costs a `2n x n`
//! solve, whatever the number of residuals. With constraints the same
//! stacked problem is solved as a
//! least-squares problem with linear inequalities ([`crate::lsi`](fn@crate::lsi)) so every
//! iterate stays feasible.
//!
//! Scaling `D`: Marquardt's `D^2 = diag(J^T J)`, with MINPACK's rule of
//! keeping the largest column norm seen so far (so a column that vanishes on
//! a plateau does not make the damping vanish with it); or the identity.
//!
//! Damping schedules ([`Damping`]):
//! - Nielsen (1999) (default): gain ratio `rho = actual / predicted
//!   reduction`; accepted (`rho > 0`): `lambda *= max(1/3, 1 - (2 rho - 1)^3)`,
//!   `nu = 2`; rejected: `lambda *= nu`, `nu *= 2`.
//! - Sopp's (Sopp 2008): start `1e-3`; a step is kept only if the error
//!   falls; rejected: double, capped at 1 (no progress at 1 stops with
//!   [`Termination::DampingLimit`](crate::report::Termination::DampingLimit)); accepted: halve, floored at `1e-4`.
//!
//! Optional geodesic acceleration (Transtrum & Sethna 2012), unconstrained
//! only: a second-order correction `a` from the directional second
//! derivative `r'' ~ 2/h ((r(p + h d) - r(p))/h - J d)`, accepted when
//! `2 ||a|| / ||d|| <= 0.75`.
//!
//! Stopping (MINPACK's tests, all scaled): `max_k |g_k| / (||J_k|| ||r||) <=
//! gtol` (projected gradient under bounds); actual and predicted relative
//! reductions `<= ftol`; `||D d|| <= xtol (||D p|| + xtol)`; an exact fit;
//! iteration and evaluation caps; after a few consecutive steps at the noise
//! level of the cost (where only the Gauss-Newton step can still improve the
//! parameters). A convergence test that holds where some parameter has lost
//! its influence on the residuals is reported as
//! [`Termination::SingularPlateau`](crate::report::Termination::SingularPlateau), not as convergence.

mod driver;
mod factored;

use faer::Mat;
use faer::linalg::solvers::Solve;

use crate::SolveError;
use crate::constraints::Constraints;
use crate::problem::LeastSquaresProblem;
use crate::report::SolverReport;
pub(crate) use driver::minimize;
use factored::Factored;

/// Damping schedule.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Damping {
    /// Nielsen's gain-ratio update (default).
    #[default]
    Nielsen,
    /// Sopp's schedule: start 1e-3, x2 on rejection up to 1, /2 on acceptance
    /// down to 1e-4.
    Sopp,
}

/// Scaling matrix `D` of the damping term.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Scaling {
    /// `D^2 = diag(J^T J)`, largest column norms kept (default).
    #[default]
    Marquardt,
    /// `D = I` (Levenberg).
    Identity,
}

/// Options of [`levenberg_marquardt`] and [`crate::bounded::bounded_least_squares`].
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct LmOptions {
    /// Iteration cap (default 1000).
    pub max_iterations: usize,
    /// Residual-evaluation cap (default 10000).
    pub max_evaluations: usize,
    /// Relative cost-reduction tolerance [1e-15].
    pub ftol: f64,
    /// Relative step tolerance [1e-15].
    pub xtol: f64,
    /// Scaled gradient tolerance [1e-15].
    pub gtol: f64,
    /// Damping schedule (default Nielsen).
    pub damping: Damping,
    /// Scaling (default Marquardt).
    pub scaling: Scaling,
    /// Initial damping; `None` uses `1e-3` (times `max diag(J^T J)` with the
    /// identity scaling).
    pub initial_damping: Option<f64>,
    /// Geodesic acceleration (unconstrained problems only) (default false).
    pub geodesic_acceleration: bool,
}

impl Default for LmOptions {
    fn default() -> Self {
        Self {
            max_iterations: 1000,
            max_evaluations: 10_000,
            ftol: 1e-15,
            xtol: 1e-15,
            gtol: 1e-15,
            damping: Damping::Nielsen,
            scaling: Scaling::Marquardt,
            initial_damping: None,
            geodesic_acceleration: false,
        }
    }
}

impl LmOptions {
    /// Sopp's configuration: his damping schedule, Marquardt scaling.
    pub fn sopp() -> Self {
        Self {
            damping: Damping::Sopp,
            ..Self::default()
        }
    }

    fn validate(&self) -> Result<(), SolveError> {
        for (name, v) in [
            ("ftol", self.ftol),
            ("xtol", self.xtol),
            ("gtol", self.gtol),
        ] {
            if !(v >= 0.0 && v.is_finite()) {
                return Err(SolveError::InvalidOption {
                    name,
                    value: v,
                    reason: "tolerances must be finite and >= 0",
                });
            }
        }
        if let Some(l) = self.initial_damping
            && !(l > 0.0 && l.is_finite())
        {
            return Err(SolveError::InvalidOption {
                name: "initial_damping",
                value: l,
                reason: "must be finite and > 0",
            });
        }
        Ok(())
    }
}

/// Minimise `1/2 ||r(p)||^2` from `p0` without constraints.
pub fn levenberg_marquardt<P: LeastSquaresProblem + ?Sized>(
    problem: &P,
    p0: &[f64],
    options: &LmOptions,
) -> Result<SolverReport, SolveError> {
    let c = Constraints::unbounded(problem.n_params());
    minimize(problem, p0, &c, options)
}

fn sum_sq(r: &[f64]) -> f64 {
    r.iter().map(|v| v * v).sum()
}

/// `1/2 ||r||^2`, infinite when some residual is not finite; from the
/// corner `r^T r` of the augmented Gram matrix when the problem formed it
/// (a non-finite residual makes that corner non-finite too).
fn cost_of(r: &[f64], gram: Option<&[f64]>) -> f64 {
    let ssr = match gram {
        Some(g) => g[g.len() - 1],
        None if all_finite(r) => sum_sq(r),
        None => f64::INFINITY,
    };
    if ssr.is_finite() {
        0.5 * ssr
    } else {
        f64::INFINITY
    }
}

fn all_finite(v: &[f64]) -> bool {
    v.iter().all(|x| x.is_finite())
}

/// Misuse of the driver: no parameters, mismatched lengths, fewer residuals
/// than parameters, a non-finite or infeasible start.
fn check_inputs(
    m: usize,
    n: usize,
    p0: &[f64],
    constraints: &Constraints,
) -> Result<(), SolveError> {
    if n == 0 {
        return Err(SolveError::Empty { what: "parameters" });
    }
    if p0.len() != n || constraints.len() != n {
        return Err(SolveError::Dimension {
            what: "start / constraints vs parameters",
            left: p0.len(),
            right: n,
        });
    }
    if m < n {
        return Err(SolveError::Dimension {
            what: "fewer residuals than parameters",
            left: m,
            right: n,
        });
    }
    if let Some(k) = p0.iter().position(|v| !v.is_finite()) {
        return Err(SolveError::NonFinite {
            what: "start",
            row: k,
            col: 0,
            value: p0[k],
        });
    }
    if !constraints.is_feasible(p0, 1e-12) {
        return Err(SolveError::InvalidOption {
            name: "start",
            value: f64::NAN,
            reason: "the start violates the bounds or inequality constraints",
        });
    }
    Ok(())
}

/// MINPACK's scaled gradient `max_k |g_k| / (||J_k|| ||r||)` over the
/// parameters not held by a bound.
fn scaled_gradient(f: &Factored, status: &[crate::BoundStatus], rnorm: f64) -> f64 {
    let mut gscaled = 0.0f64;
    for k in 0..f.g.len() {
        let g = f.g[k];
        let blocked = (status[k] == crate::BoundStatus::AtLower && g > 0.0)
            || (status[k] == crate::BoundStatus::AtUpper && g < 0.0);
        if !blocked && f.colnorm[k] > 0.0 && rnorm > 0.0 {
            gscaled = gscaled.max(g.abs() / (f.colnorm[k] * rnorm));
        }
    }
    gscaled
}

/// Geodesic acceleration (unconstrained): add `a/2`, where `a` solves the
/// damped system for the directional second derivative
/// `r'' ~ 2/h ((r(p + h d) - r(p))/h - J d)`, when `2 ||D a|| <= 0.75
/// ||D d||`. Returns the residual evaluations used.
fn geodesic_correction<P: LeastSquaresProblem + ?Sized>(
    problem: &P,
    (p, r, jac): (&[f64], &[f64], &[f64]),
    f: &Factored,
    (d, lambda): (&[f64], f64),
    delta: &mut [f64],
    (p_tmp, r_tmp): (&mut [f64], &mut [f64]),
) -> usize {
    let (m, n) = (r.len(), delta.len());
    let h = 0.1;
    for k in 0..n {
        p_tmp[k] = p[k] + h * delta[k];
    }
    problem.residuals(p_tmp, r_tmp);
    if !all_finite(r_tmp) {
        return 1;
    }
    // Right-hand side rows and J^T of them; then the damped normal
    // equations of the small system (R^T R + lambda D^2) a = J^T rhs.
    let mut jtb = vec![0.0; n];
    for i in 0..m {
        let row = &jac[i * n..(i + 1) * n];
        let jd: f64 = (0..n).map(|k| row[k] * delta[k]).sum();
        let rhs = -(2.0 / h) * ((r_tmp[i] - r[i]) / h - jd);
        for k in 0..n {
            jtb[k] += row[k] * rhs;
        }
    }
    let a = Mat::from_fn(n, n, |i, k| {
        (0..n).map(|t| f.r[(t, i)] * f.r[(t, k)]).sum::<f64>()
            + if i == k { lambda * d[k] * d[k] } else { 0.0 }
    });
    let Ok(chol) = a.llt(faer::Side::Lower) else {
        return 1;
    };
    let acc = chol.solve(Mat::from_fn(n, 1, |k, _| jtb[k]));
    let an = (0..n)
        .map(|k| (d[k] * acc[(k, 0)]).powi(2))
        .sum::<f64>()
        .sqrt();
    let dn = (0..n)
        .map(|k| (d[k] * delta[k]).powi(2))
        .sum::<f64>()
        .sqrt();
    if an.is_finite() && 2.0 * an <= 0.75 * dn {
        for k in 0..n {
            delta[k] += 0.5 * acc[(k, 0)];
        }
    }
    1
}

/// Raise the damping after a rejected step; false when the schedule is
/// exhausted.
fn increase_damping(schedule: Damping, lambda: &mut f64, nu: &mut f64) -> bool {
    match schedule {
        Damping::Nielsen => {
            *lambda *= *nu;
            *nu *= 2.0;
            lambda.is_finite() && *lambda < 1e300
        }
        Damping::Sopp => {
            if *lambda >= 1.0 {
                return false;
            }
            *lambda = (*lambda * 2.0).min(1.0);
            true
        }
    }
}

/// Whether some free parameter has lost its influence: a 100% change of
/// `p_k` would change the residual by less than `PLATEAU_RCOND ||r||`
/// (`||J_k|| max(|p_k|, 1e-300) <= PLATEAU_RCOND ||r||`). There a stationary
/// point is a plateau, not a certified minimum (BoxBOD from start 1 ends
/// with `exp(-b2 x) ~ 0`).
fn plateau(colnorm: &[f64], r: &[f64], p: &[f64], status: &[crate::BoundStatus]) -> bool {
    let rnorm = r.iter().map(|v| v * v).sum::<f64>().sqrt();
    if rnorm == 0.0 {
        return false;
    }
    (0..p.len())
        .filter(|k| status[*k] == crate::BoundStatus::Free)
        .any(|k| colnorm[k] * p[k].abs().max(1e-300) <= PLATEAU_RCOND * rnorm)
}

/// Relative size of a cost change that rounding can produce.
const NOISE: f64 = 64.0 * f64::EPSILON;

/// Consecutive noise-level steps after which the solver stops.
const POLISH_STEPS: usize = 4;

/// Relative influence below which a parameter is considered lost.
const PLATEAU_RCOND: f64 = 1e-6;
