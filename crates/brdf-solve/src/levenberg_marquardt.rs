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
//!   [`Termination::DampingLimit`]); accepted: halve, floored at `1e-4`.
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
//! [`Termination::SingularPlateau`], not as convergence.

use faer::Mat;
use faer::linalg::solvers::{Solve, SolveLstsq};

use crate::constraints::Constraints;
use crate::problem::LeastSquaresProblem;
use crate::report::{SolverReport, Termination};
use crate::{SolveError, lsi, tall_qr};

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

/// The Jacobian at the current point, reduced to what a step needs: the
/// triangle `R` of `J = Q R`, `Q^T r`, the column norms `||J_k|| = ||R_k||`
/// and the gradient `g = J^T r = R^T Q^T r`. Every damped step is then a
/// `2n x n` problem, whatever the number of residuals.
struct Factored {
    r: Mat<f64>,
    qtr: Vec<f64>,
    colnorm: Vec<f64>,
    g: Vec<f64>,
}

impl Factored {
    /// Reduce `[J | r]` (`jac` row-major): by the guarded normal equations
    /// where they are accurate, else by QR in `ws`, the reused `m x (n+1)`
    /// workspace ([`tall_qr`]).
    fn new(jac: &[f64], r: &[f64], n: usize, ws: &mut Option<Mat<f64>>) -> Self {
        Self::by_normal_equations(jac, r, n).unwrap_or_else(|| Self::by_qr(jac, r, n, ws))
    }

    /// The guarded normal equations; `None` where they are not accurate
    /// (or `J` is not finite: a non-finite entry makes the Gram matrix
    /// non-finite, which the guard refuses).
    fn by_normal_equations(jac: &[f64], r: &[f64], n: usize) -> Option<Self> {
        let m = r.len();
        let jm = faer::MatRef::from_row_major_slice(jac, m, n);
        let rm = faer::MatRef::from_column_major_slice(r, m, 1);
        let (rr, qtr) = tall_qr::gram_triangle(jm, rm)?;
        Some(Self::from_triangle(
            rr,
            (0..n).map(|i| qtr[(i, 0)]).collect(),
        ))
    }

    /// The guarded normal equations a problem formed in its residual pass
    /// (`gram`: the `(n+1) x (n+1)` row-major Gram matrix of `[J | r]`);
    /// `None` where they are not accurate. Exactly zero columns (a
    /// parameter without influence at this point, such as a tint whose lobe
    /// is off) do not send the rest of the solve to the stored Jacobian and
    /// QR: they get zero rows and columns in `R`, as in QR's.
    fn from_gram(gram: &[f64], n: usize) -> Option<Self> {
        let w = n + 1;
        let g = Mat::from_fn(n, n, |i, k| gram[i * w + k]);
        let h = Mat::from_fn(n, 1, |i, _| gram[i * w + n]);
        let (rr, qtr) = tall_qr::triangle_from_gram_with_zero_columns(g.as_ref(), h)?;
        Some(Self::from_triangle(
            rr,
            (0..n).map(|i| qtr[(i, 0)]).collect(),
        ))
    }

    /// Householder QR of `[J | r]` in `ws` (allocated on first use).
    fn by_qr(jac: &[f64], r: &[f64], n: usize, ws: &mut Option<Mat<f64>>) -> Self {
        let m = r.len();
        let ws = ws.get_or_insert_with(|| Mat::<f64>::zeros(m, n + 1));
        for k in 0..n {
            let col = ws
                .col_mut(k)
                .try_as_col_major_mut()
                .map(|c| c.as_slice_mut());
            if let Some(col) = col {
                for (i, v) in col.iter_mut().enumerate() {
                    *v = jac[i * n + k];
                }
            }
        }
        if let Some(col) = ws.col_mut(n).try_as_col_major_mut() {
            col.as_slice_mut().copy_from_slice(r);
        }
        let raug = tall_qr::r_factor(ws.as_mut());
        let rows = raug.nrows().min(n);
        let rr = Mat::from_fn(n, n, |i, k| if i < rows { raug[(i, k)] } else { 0.0 });
        let qtr: Vec<f64> = (0..n)
            .map(|i| if i < rows { raug[(i, n)] } else { 0.0 })
            .collect();
        debug_assert!(m >= n);
        Self::from_triangle(rr, qtr)
    }

    /// The column norms and gradient from `R` and `Q^T r`.
    fn from_triangle(rr: Mat<f64>, qtr: Vec<f64>) -> Self {
        let n = qtr.len();
        let colnorm = (0..n)
            .map(|k| (0..=k).map(|i| rr[(i, k)].powi(2)).sum::<f64>().sqrt())
            .collect();
        let g = (0..n)
            .map(|k| (0..=k).map(|i| rr[(i, k)] * qtr[i]).sum())
            .collect();
        Factored {
            r: rr,
            qtr,
            colnorm,
            g,
        }
    }

    /// The damped step `min ||R d + Q^T r||^2 + lambda ||D d||^2` (subject to
    /// `G d >= h` when constrained) and its predicted cost reduction.
    fn step(
        &self,
        d: &[f64],
        lambda: f64,
        constrained: Option<(&Mat<f64>, &[f64])>,
    ) -> Option<(Vec<f64>, f64)> {
        let n = d.len();
        let sl = lambda.sqrt();
        let e = Mat::from_fn(2 * n, n, |i, k| {
            if i < n {
                self.r[(i, k)]
            } else if i - n == k {
                sl * d[k]
            } else {
                0.0
            }
        });
        let f: Vec<f64> = (0..2 * n)
            .map(|i| if i < n { -self.qtr[i] } else { 0.0 })
            .collect();
        let delta = match constrained {
            Some((gmat, h)) => lsi::lsi(e.as_ref(), &f, gmat.as_ref(), h).ok()?,
            None => {
                let fm = Mat::from_fn(2 * n, 1, |i, _| f[i]);
                let s = e.qr().solve_lstsq(&fm);
                (0..n).map(|k| s[(k, 0)]).collect()
            }
        };
        if !all_finite(&delta) {
            return None;
        }
        Some((delta.clone(), self.predicted_reduction(&delta)))
    }

    /// `cost - 1/2 ||r + J d||^2 = 1/2 (||Q^T r||^2 - ||R d + Q^T r||^2)`.
    fn predicted_reduction(&self, delta: &[f64]) -> f64 {
        let n = delta.len();
        let mut before = 0.0;
        let mut after = 0.0;
        for i in 0..n {
            let rd: f64 = (i..n).map(|k| self.r[(i, k)] * delta[k]).sum();
            before += self.qtr[i] * self.qtr[i];
            after += (rd + self.qtr[i]).powi(2);
        }
        0.5 * (before - after)
    }
}

/// The damped LM driver shared by the unconstrained and the bounded solver.
pub(crate) fn minimize<P: LeastSquaresProblem + ?Sized>(
    problem: &P,
    p0: &[f64],
    constraints: &Constraints,
    options: &LmOptions,
) -> Result<SolverReport, SolveError> {
    options.validate()?;
    let (m, n) = (problem.n_residuals(), problem.n_params());
    check_inputs(m, n, p0, constraints)?;
    let constrained = !constraints.is_unconstrained();
    let mut p = p0.to_vec();
    let mut r = vec![0.0; m];
    // A problem that forms its normal equations in the residual pass gets
    // them at every trial point (one pass per trial, the Jacobian never
    // stored): a rejected trial wastes its derivatives, an accepted one
    // needs no second pass. Not with the geodesic correction, which needs
    // `J` itself.
    let mut gram = vec![0.0; (n + 1) * (n + 1)];
    let mut gram_new = gram.clone();
    let mut fused =
        !options.geodesic_acceleration && problem.residuals_and_gram(&p, &mut r, &mut gram);
    if !fused {
        problem.residuals(&p, &mut r);
    }
    // Whether `gram` holds the normal equations at `p`.
    let mut have_gram = fused;
    let mut evaluations = 1;
    let mut jac = vec![0.0; m * n];
    let mut ws = None;
    let report = |p: Vec<f64>, ssr: f64, t, it, ev, g, l| SolverReport {
        bounds: constraints.status(&p),
        params: p,
        ssr,
        termination: t,
        iterations: it,
        evaluations: ev,
        gradient_norm: g,
        damping: l,
    };
    if !cost_of(&r, have_gram.then_some(gram.as_slice())).is_finite() {
        return Ok(report(
            p,
            f64::NAN,
            Termination::NonFiniteStart,
            0,
            1,
            f64::NAN,
            0.0,
        ));
    }
    let mut cost = cost_of(&r, have_gram.then_some(gram.as_slice()));
    let mut d = vec![0.0f64; n];

    let mut lambda = f64::NAN;
    let mut nu = 2.0;
    let mut iterations = 0;
    let mut r_new = vec![0.0; m];
    let mut r_tmp = vec![0.0; m];
    let mut p_new = vec![0.0; n];
    let mut polished = 0;
    let mut fac;
    let termination = 'outer: loop {
        let mut by_gram = if have_gram {
            Factored::from_gram(&gram, n)
        } else {
            None
        };
        if by_gram.is_none() {
            // The fused normal equations failed their guard: QR of the
            // Jacobian from here on, without further speculation.
            fused = false;
            problem.jacobian(&p, &mut jac);
            by_gram = Factored::by_normal_equations(&jac, &r, n);
        }
        // The Gram path succeeds only for a finite Jacobian, so the scan for
        // non-finite entries is needed only when it does not.
        if by_gram.is_none() && !all_finite(&jac) {
            if iterations == 0 {
                return Ok(report(
                    p,
                    2.0 * cost,
                    Termination::NonFiniteStart,
                    0,
                    evaluations,
                    f64::NAN,
                    0.0,
                ));
            }
            // A non-finite Jacobian at an accepted point: fall back to the
            // finite-difference one, and stop if that fails too.
            crate::problem::fd_jacobian(problem, &p, &mut jac);
            evaluations += 2 * n;
            if !all_finite(&jac) {
                fac = None;
                break Termination::NonFiniteStart;
            }
        }
        let f = match by_gram {
            Some(f) => f,
            None => Factored::by_qr(&jac, &r, n, &mut ws),
        };
        for k in 0..n {
            d[k] = match options.scaling {
                Scaling::Marquardt => d[k].max(f.colnorm[k]),
                Scaling::Identity => 1.0,
            };
            if d[k] == 0.0 {
                d[k] = 1.0;
            }
        }
        let gscaled = scaled_gradient(&f, &constraints.status(&p), (2.0 * cost).sqrt());
        fac = Some(f);
        let f = fac.as_ref().expect("just set");
        if cost <= f64::MIN_POSITIVE {
            break Termination::ZeroResidual;
        }
        if gscaled <= options.gtol {
            break Termination::SmallGradient;
        }
        if iterations >= options.max_iterations {
            break Termination::MaxIterations;
        }
        iterations += 1;
        if lambda.is_nan() {
            lambda = options.initial_damping.unwrap_or(match options.scaling {
                Scaling::Marquardt => 1e-3,
                Scaling::Identity => 1e-3 * f.colnorm.iter().fold(0.0f64, |a, c| a.max(c * c)),
            });
            if lambda <= 0.0 {
                lambda = 1e-3;
            }
        }
        let (grows, hrows) = if constrained {
            constraints.step_rows(&p)
        } else {
            (Vec::new(), Vec::new())
        };
        let gmat = Mat::from_fn(grows.len(), n, |i, k| grows[i][k]);
        // Inner loop: find an acceptable damping.
        loop {
            if evaluations >= options.max_evaluations {
                break 'outer Termination::MaxEvaluations;
            }
            let sub = constrained.then_some((&gmat, hrows.as_slice()));
            let Some((mut delta, pred)) = f.step(&d, lambda, sub) else {
                // A failed subproblem is treated as a rejected step.
                if !increase_damping(options.damping, &mut lambda, &mut nu) {
                    break 'outer Termination::DampingLimit;
                }
                continue;
            };
            if options.geodesic_acceleration && !constrained {
                evaluations += geodesic_correction(
                    problem,
                    (&p, &r, &jac),
                    f,
                    (&d, lambda),
                    &mut delta,
                    (&mut p_new, &mut r_tmp),
                );
            }
            let dnorm = (0..n)
                .map(|k| (d[k] * delta[k]).powi(2))
                .sum::<f64>()
                .sqrt();
            let pnorm = (0..n).map(|k| (d[k] * p[k]).powi(2)).sum::<f64>().sqrt();
            for k in 0..n {
                p_new[k] = p[k] + delta[k];
            }
            if constrained {
                constraints.clamp(&mut p_new);
            }
            if dnorm <= options.xtol * (pnorm + options.xtol) {
                break 'outer Termination::SmallStep;
            }
            let fused_new = fused && problem.residuals_and_gram(&p_new, &mut r_new, &mut gram_new);
            if !fused_new {
                problem.residuals(&p_new, &mut r_new);
            }
            evaluations += 1;
            let cost_new = cost_of(&r_new, fused_new.then_some(gram_new.as_slice()));
            let actual = cost - cost_new;
            // At the noise level of the cost (reductions of a few ulps) the
            // cost can no longer rank steps, but the Gauss-Newton step is
            // still accurate: accept it if the cost does not rise beyond
            // rounding, and stop after a few consecutive polishing steps
            // (Gauss-Newton converges quadratically, so by then the
            // parameters no longer change beyond rounding). A cost test
            // alone certifies only half the digits of the parameters.
            let noise = NOISE * cost;
            let polishing = pred.abs() <= noise && cost_new <= cost + noise;
            let accept = polishing
                || match options.damping {
                    Damping::Nielsen => pred > 0.0 && actual > 0.0,
                    Damping::Sopp => actual > 0.0,
                };
            if accept {
                let rho = actual / pred;
                std::mem::swap(&mut p, &mut p_new);
                std::mem::swap(&mut r, &mut r_new);
                std::mem::swap(&mut gram, &mut gram_new);
                have_gram = fused_new;
                let old = cost;
                cost = cost_new;
                match options.damping {
                    Damping::Nielsen => {
                        lambda *= (1.0 - (2.0 * rho - 1.0).powi(3)).max(1.0 / 3.0);
                        lambda = lambda.max(1e-300);
                        nu = 2.0;
                    }
                    Damping::Sopp => lambda = (lambda / 2.0).max(1e-4),
                }
                if polishing {
                    polished += 1;
                    if polished >= POLISH_STEPS {
                        break 'outer Termination::SmallReduction;
                    }
                } else {
                    polished = 0;
                }
                if actual <= options.ftol * old && pred.abs() <= options.ftol * old {
                    break 'outer Termination::SmallReduction;
                }
                continue 'outer;
            }
            if !increase_damping(options.damping, &mut lambda, &mut nu) {
                break 'outer Termination::DampingLimit;
            }
        }
    };
    // The factorisation is at the final `p` unless the last step was
    // accepted and ended the run (the relative-reduction test): only then
    // evaluate the Jacobian again.
    if termination == Termination::SmallReduction || fac.is_none() {
        fac = have_gram.then(|| Factored::from_gram(&gram, n)).flatten();
        if fac.is_none() {
            problem.jacobian(&p, &mut jac);
            fac = all_finite(&jac).then(|| Factored::new(&jac, &r, n, &mut ws));
        }
    }
    let (termination, gn) = match &fac {
        Some(f) => {
            let t = if termination.is_converged()
                && termination != Termination::ZeroResidual
                && plateau(&f.colnorm, &r, &p, &constraints.status(&p))
            {
                Termination::SingularPlateau
            } else {
                termination
            };
            (t, f.g.iter().fold(0.0f64, |a, v| a.max(v.abs())))
        }
        None => (termination, f64::NAN),
    };
    Ok(report(
        p,
        2.0 * cost,
        termination,
        iterations,
        evaluations,
        gn,
        lambda,
    ))
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
