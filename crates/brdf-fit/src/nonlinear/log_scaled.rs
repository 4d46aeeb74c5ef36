//! A bounded solve with some parameters on a log scale: `x_k = exp(u_k)`
//! for the positive parameters of a wide box (upper end at least 100 times
//! the lower, or from 0), the solver working on `u`.
//!
//! Why: the shadowing term of Bagher's SGD, `1 + Lambda (1 - exp(c x^k))`,
//! depends for small `c x^k` on `Lambda c` alone, and the fits of the RGL
//! materials end in that valley (`Lambda c` about 1, the cost still falling
//! slowly as `Lambda` grows and `c` shrinks, until `Lambda` meets its upper
//! bound). In `(Lambda, c)` the valley floor is a hyperbola: a linearised
//! step along it leaves it quadratically, so the damping holds the steps
//! small and the solver creeps for thousands of iterations (the polish of
//! each channel reaches its cap of 3000). In `(ln Lambda, ln c)` the
//! floor is a straight line and the Gauss-Newton step follows it.
//!
//! The problem's residuals are unchanged (the cost is the same function);
//! the Jacobian's column `k` is scaled by `dx_k / du_k = x_k`. The `u` box
//! is `[ln max(lower, 1e-15 upper), ln upper]`, `x` clamped into the
//! original box (so `exp(ln upper)` lands on the bound exactly). A
//! parameter at 0 at the start stays linear.

use brdf_solve::{
    Constraints, LeastSquaresProblem, LmOptions, SolveError, SolverReport, bounded_least_squares,
};

/// Which parameters of the box `full` a log scale suits (positive box at
/// least two decades wide; `eligible` further restricts, e.g. to the
/// non-linear parameters).
pub(super) fn wide_positive(full: &Constraints, eligible: &[bool]) -> Vec<bool> {
    full.lower()
        .iter()
        .zip(full.upper())
        .zip(eligible)
        .map(|((&lo, &hi), &e)| e && lo >= 0.0 && hi.is_finite() && hi >= 100.0 * lo.max(1.0))
        .collect()
}

/// `problem` over `u` (see the module doc).
struct LogScaled<'a> {
    inner: &'a (dyn LeastSquaresProblem + Sync),
    log: &'a [bool],
    lower: &'a [f64],
    upper: &'a [f64],
}

impl LogScaled<'_> {
    fn to_x(&self, u: &[f64]) -> Vec<f64> {
        (0..u.len())
            .map(|k| {
                if self.log[k] {
                    u[k].exp().clamp(self.lower[k], self.upper[k])
                } else {
                    u[k]
                }
            })
            .collect()
    }
}

impl LeastSquaresProblem for LogScaled<'_> {
    fn n_params(&self) -> usize {
        self.inner.n_params()
    }
    fn n_residuals(&self) -> usize {
        self.inner.n_residuals()
    }
    fn residuals(&self, u: &[f64], out: &mut [f64]) {
        self.inner.residuals(&self.to_x(u), out)
    }
    fn jacobian(&self, u: &[f64], jac: &mut [f64]) {
        let x = self.to_x(u);
        self.inner.jacobian(&x, jac);
        let n = x.len();
        for row in jac.chunks_exact_mut(n) {
            for k in 0..n {
                if self.log[k] {
                    row[k] *= x[k];
                }
            }
        }
    }
    fn residuals_and_gram(&self, u: &[f64], out: &mut [f64], gram: &mut [f64]) -> bool {
        let x = self.to_x(u);
        if !self.inner.residuals_and_gram(&x, out, gram) {
            return false;
        }
        // [J D | r]^T [J D | r]: rows and columns k < n scaled by d_k.
        let n = x.len();
        let d: Vec<f64> = (0..=n)
            .map(|k| if k < n && self.log[k] { x[k] } else { 1.0 })
            .collect();
        for i in 0..=n {
            for j in 0..=n {
                gram[i * (n + 1) + j] *= d[i] * d[j];
            }
        }
        true
    }
}

/// The bounded solve of `problem` from `x0` in `full`, the parameters
/// `wide` marks (and positive at `x0`) on a log scale; the report in the
/// original parameters (bounds judged there).
pub(super) fn solve(
    problem: &(dyn LeastSquaresProblem + Sync),
    x0: &[f64],
    full: &Constraints,
    wide: &[bool],
    lm: &LmOptions,
) -> Result<SolverReport, SolveError> {
    let log: Vec<bool> = wide.iter().zip(x0).map(|(&w, &x)| w && x > 0.0).collect();
    if !log.contains(&true) {
        return bounded_least_squares(problem, x0, full, lm);
    }
    let (lower, upper) = (full.lower(), full.upper());
    let ulo: Vec<f64> = (0..x0.len())
        .map(|k| match log[k] {
            true => lower[k].max(1e-15 * upper[k]).ln(),
            false => lower[k],
        })
        .collect();
    let uhi: Vec<f64> = (0..x0.len())
        .map(|k| if log[k] { upper[k].ln() } else { upper[k] })
        .collect();
    let u0: Vec<f64> = (0..x0.len())
        .map(|k| match log[k] {
            true => x0[k].ln().clamp(ulo[k], uhi[k]),
            false => x0[k],
        })
        .collect();
    let ubox = Constraints::boxed(ulo, uhi)?;
    let scaled = LogScaled {
        inner: problem,
        log: &log,
        lower,
        upper,
    };
    let rep = bounded_least_squares(&scaled, &u0, &ubox, lm)?;
    let params = scaled.to_x(&rep.params);
    Ok(SolverReport {
        bounds: full.status(&params),
        params,
        ..rep
    })
}
