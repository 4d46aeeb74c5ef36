//! The damped LM driver shared by the unconstrained and the bounded solver,
//! as named steps over one state: [`Driver::start`] evaluates the start,
//! each iteration [`Driver::factor`]s the Jacobian, updates the scaling,
//! tests for convergence and [`Driver::search_step`]s (damped trials until
//! one is accepted, [`Driver::trial`]), and [`Driver::finish`] reports why
//! it stopped with the gradient at the final point.

use faer::Mat;

use super::factored::Factored;
use super::{
    Damping, LmOptions, NOISE, POLISH_STEPS, Scaling, all_finite, check_inputs, cost_of,
    geodesic_correction, increase_damping, plateau, scaled_gradient,
};
use crate::SolveError;
use crate::constraints::Constraints;
use crate::problem::LeastSquaresProblem;
use crate::report::{SolverReport, Termination};

/// Minimise `problem` from `p0` inside `constraints` (see the parent
/// module's doc).
pub(crate) fn minimize<P: LeastSquaresProblem + ?Sized>(
    problem: &P,
    p0: &[f64],
    constraints: &Constraints,
    options: &LmOptions,
) -> Result<SolverReport, SolveError> {
    let mut lm = match Driver::start(problem, p0, constraints, options)? {
        Ok(lm) => lm,
        Err(report) => return Ok(report),
    };
    let mut fac: Option<Factored> = None;
    let termination = loop {
        let f = match lm.factor() {
            Factor::Ready(f) => f,
            Factor::NonFiniteAtStart => {
                let ssr = 2.0 * lm.cost;
                return Ok(lm.into_report(ssr, Termination::NonFiniteStart, f64::NAN, 0.0));
            }
            Factor::NonFinite => {
                fac = None;
                break Termination::NonFiniteStart;
            }
        };
        lm.update_scaling(&f);
        let status = constraints.status(&lm.p);
        let gscaled = scaled_gradient(&f, &status, (2.0 * lm.cost).sqrt());
        let f = fac.insert(f);
        if let Some(t) = lm.converged(gscaled) {
            break t;
        }
        lm.iterations += 1;
        lm.init_damping(f);
        if let Some(t) = lm.search_step(f) {
            break t;
        }
    };
    Ok(lm.finish(termination, fac))
}

/// How [`Driver::factor`] went.
enum Factor {
    /// The Jacobian reduced.
    Ready(Factored),
    /// Not finite at the start point: nothing was solved.
    NonFiniteAtStart,
    /// Not finite, even by finite differences, at an accepted point.
    NonFinite,
}

/// How one damped trial step went.
enum Trial {
    /// Accepted: the iterate moved.
    Accepted,
    /// Rejected: raise the damping and try again.
    Rejected,
    /// Accepted, and the run ends.
    Stop(Termination),
}

/// The state between the driver's steps: the iterate, its residuals (and
/// normal equations where the problem forms them in its residual pass),
/// the scaling, the damping and the counters, with the buffers the trials
/// reuse.
struct Driver<'a, P: ?Sized> {
    problem: &'a P,
    constraints: &'a Constraints,
    options: &'a LmOptions,
    constrained: bool,
    p: Vec<f64>,
    r: Vec<f64>,
    /// Normal equations of `[J | r]` at `p` (when `have_gram`) and at the
    /// trial point.
    gram: Vec<f64>,
    gram_new: Vec<f64>,
    /// Whether the problem still forms its normal equations in the
    /// residual pass (no stored Jacobian).
    fused: bool,
    have_gram: bool,
    jac: Vec<f64>,
    ws: Option<Mat<f64>>,
    cost: f64,
    /// The scaling `D`.
    d: Vec<f64>,
    lambda: f64,
    nu: f64,
    iterations: usize,
    evaluations: usize,
    r_new: Vec<f64>,
    r_tmp: Vec<f64>,
    p_new: Vec<f64>,
    /// Consecutive accepted steps at the noise level of the cost.
    polished: usize,
}

impl<'a, P: LeastSquaresProblem + ?Sized> Driver<'a, P> {
    /// The state at `p0`, or the report of a start whose cost is not finite.
    ///
    /// A problem that forms its normal equations in the residual pass gets
    /// them at every trial point (one pass per trial, the Jacobian never
    /// stored): a rejected trial wastes its derivatives, an accepted one
    /// needs no second pass. Not with the geodesic correction, which needs
    /// `J` itself.
    fn start(
        problem: &'a P,
        p0: &[f64],
        constraints: &'a Constraints,
        options: &'a LmOptions,
    ) -> Result<Result<Self, SolverReport>, SolveError> {
        options.validate()?;
        let (m, n) = (problem.n_residuals(), problem.n_params());
        check_inputs(m, n, p0, constraints)?;
        let p = p0.to_vec();
        let mut r = vec![0.0; m];
        let mut gram = vec![0.0; (n + 1) * (n + 1)];
        let fused =
            !options.geodesic_acceleration && problem.residuals_and_gram(&p, &mut r, &mut gram);
        if !fused {
            problem.residuals(&p, &mut r);
        }
        let cost = cost_of(&r, fused.then_some(gram.as_slice()));
        let lm = Driver {
            problem,
            constraints,
            options,
            constrained: !constraints.is_unconstrained(),
            p,
            r,
            gram_new: gram.clone(),
            gram,
            fused,
            have_gram: fused,
            jac: vec![0.0; m * n],
            ws: None,
            cost,
            d: vec![0.0; n],
            lambda: f64::NAN,
            nu: 2.0,
            iterations: 0,
            evaluations: 1,
            r_new: vec![0.0; m],
            r_tmp: vec![0.0; m],
            p_new: vec![0.0; n],
            polished: 0,
        };
        if !cost.is_finite() {
            return Ok(Err(lm.into_report(
                f64::NAN,
                Termination::NonFiniteStart,
                f64::NAN,
                0.0,
            )));
        }
        Ok(Ok(lm))
    }

    /// `R`, `Q^T r`, the column norms and the gradient at `p`: from the
    /// fused normal equations while their guard accepts them, else from
    /// the Jacobian (normal equations or QR); a non-finite Jacobian at an
    /// accepted point is replaced by finite differences.
    fn factor(&mut self) -> Factor {
        let n = self.p.len();
        let mut by_gram = if self.have_gram {
            Factored::from_gram(&self.gram, n)
        } else {
            None
        };
        if by_gram.is_none() {
            // The fused normal equations failed their guard: QR of the
            // Jacobian from here on, without further speculation.
            self.fused = false;
            self.problem.jacobian(&self.p, &mut self.jac);
            by_gram = Factored::by_normal_equations(&self.jac, &self.r, n);
        }
        // The Gram path succeeds only for a finite Jacobian, so the scan for
        // non-finite entries is needed only when it does not.
        if by_gram.is_none() && !all_finite(&self.jac) {
            if self.iterations == 0 {
                return Factor::NonFiniteAtStart;
            }
            crate::problem::fd_jacobian(self.problem, &self.p, &mut self.jac);
            self.evaluations += 2 * n;
            if !all_finite(&self.jac) {
                return Factor::NonFinite;
            }
        }
        Factor::Ready(match by_gram {
            Some(f) => f,
            None => Factored::by_qr(&self.jac, &self.r, n, &mut self.ws),
        })
    }

    /// Marquardt's scaling keeps the largest column norm seen so far (a
    /// column that vanishes on a plateau does not make the damping vanish
    /// with it); a zero column is scaled by 1.
    fn update_scaling(&mut self, f: &Factored) {
        for (k, d) in self.d.iter_mut().enumerate() {
            *d = match self.options.scaling {
                Scaling::Marquardt => d.max(f.colnorm[k]),
                Scaling::Identity => 1.0,
            };
            if *d == 0.0 {
                *d = 1.0;
            }
        }
    }

    /// The stopping tests before a step: an exact fit, a small scaled
    /// gradient, the iteration cap.
    fn converged(&self, gscaled: f64) -> Option<Termination> {
        if self.cost <= f64::MIN_POSITIVE {
            Some(Termination::ZeroResidual)
        } else if gscaled <= self.options.gtol {
            Some(Termination::SmallGradient)
        } else if self.iterations >= self.options.max_iterations {
            Some(Termination::MaxIterations)
        } else {
            None
        }
    }

    /// The first damping: the option's, else `1e-3` (times the largest
    /// squared column norm without Marquardt's scaling).
    fn init_damping(&mut self, f: &Factored) {
        if !self.lambda.is_nan() {
            return;
        }
        self.lambda = self
            .options
            .initial_damping
            .unwrap_or(match self.options.scaling {
                Scaling::Marquardt => 1e-3,
                Scaling::Identity => 1e-3 * f.colnorm.iter().fold(0.0f64, |a, c| a.max(c * c)),
            });
        if self.lambda <= 0.0 {
            self.lambda = 1e-3;
        }
    }

    /// Damped trials from `p` until one is accepted (`None`: iterate again)
    /// or the run ends (its termination).
    fn search_step(&mut self, f: &Factored) -> Option<Termination> {
        let n = self.p.len();
        let (grows, hrows) = if self.constrained {
            self.constraints.step_rows(&self.p)
        } else {
            (Vec::new(), Vec::new())
        };
        let gmat = Mat::from_fn(grows.len(), n, |i, k| grows[i][k]);
        loop {
            if self.evaluations >= self.options.max_evaluations {
                return Some(Termination::MaxEvaluations);
            }
            let sub = self.constrained.then_some((&gmat, hrows.as_slice()));
            let Some((mut delta, pred)) = f.step(&self.d, self.lambda, sub) else {
                // A failed subproblem is treated as a rejected step.
                if !increase_damping(self.options.damping, &mut self.lambda, &mut self.nu) {
                    return Some(Termination::DampingLimit);
                }
                continue;
            };
            if self.options.geodesic_acceleration && !self.constrained {
                self.evaluations += geodesic_correction(
                    self.problem,
                    (&self.p, &self.r, &self.jac),
                    f,
                    (&self.d, self.lambda),
                    &mut delta,
                    (&mut self.p_new, &mut self.r_tmp),
                );
            }
            if self.small_step(&delta) {
                return Some(Termination::SmallStep);
            }
            match self.trial(pred) {
                Trial::Accepted => return None,
                Trial::Stop(t) => return Some(t),
                Trial::Rejected => {
                    if !increase_damping(self.options.damping, &mut self.lambda, &mut self.nu) {
                        return Some(Termination::DampingLimit);
                    }
                }
            }
        }
    }

    /// The trial point `p + delta` (clamped into the box) into `p_new`, and
    /// whether the step is below `xtol` (MINPACK's scaled test).
    fn small_step(&mut self, delta: &[f64]) -> bool {
        let (d, p) = (&self.d, &self.p);
        let n = p.len();
        let dnorm = (0..n)
            .map(|k| (d[k] * delta[k]).powi(2))
            .sum::<f64>()
            .sqrt();
        let pnorm = (0..n).map(|k| (d[k] * p[k]).powi(2)).sum::<f64>().sqrt();
        for k in 0..n {
            self.p_new[k] = p[k] + delta[k];
        }
        if self.constrained {
            self.constraints.clamp(&mut self.p_new);
        }
        dnorm <= self.options.xtol * (pnorm + self.options.xtol)
    }

    /// Evaluate `p_new` (whose step predicted the reduction `pred`) and
    /// accept or reject it, updating the damping.
    ///
    /// At the noise level of the cost (reductions of a few ulps) the cost
    /// can no longer rank steps, but the Gauss-Newton step is still
    /// accurate: accept it if the cost does not rise beyond rounding, and
    /// stop after a few consecutive polishing steps (Gauss-Newton converges
    /// quadratically, so by then the parameters no longer change beyond
    /// rounding). A cost test alone certifies only half the digits of the
    /// parameters.
    fn trial(&mut self, pred: f64) -> Trial {
        let fused_new = self.fused
            && self
                .problem
                .residuals_and_gram(&self.p_new, &mut self.r_new, &mut self.gram_new);
        if !fused_new {
            self.problem.residuals(&self.p_new, &mut self.r_new);
        }
        self.evaluations += 1;
        let cost_new = cost_of(&self.r_new, fused_new.then_some(self.gram_new.as_slice()));
        let actual = self.cost - cost_new;
        let noise = NOISE * self.cost;
        let polishing = pred.abs() <= noise && cost_new <= self.cost + noise;
        let accept = polishing
            || match self.options.damping {
                Damping::Nielsen => pred > 0.0 && actual > 0.0,
                Damping::Sopp => actual > 0.0,
            };
        if !accept {
            return Trial::Rejected;
        }
        let rho = actual / pred;
        std::mem::swap(&mut self.p, &mut self.p_new);
        std::mem::swap(&mut self.r, &mut self.r_new);
        std::mem::swap(&mut self.gram, &mut self.gram_new);
        self.have_gram = fused_new;
        let old = self.cost;
        self.cost = cost_new;
        match self.options.damping {
            Damping::Nielsen => {
                self.lambda *= (1.0 - (2.0 * rho - 1.0).powi(3)).max(1.0 / 3.0);
                self.lambda = self.lambda.max(1e-300);
                self.nu = 2.0;
            }
            Damping::Sopp => self.lambda = (self.lambda / 2.0).max(1e-4),
        }
        if polishing {
            self.polished += 1;
            if self.polished >= POLISH_STEPS {
                return Trial::Stop(Termination::SmallReduction);
            }
        } else {
            self.polished = 0;
        }
        if actual <= self.options.ftol * old && pred.abs() <= self.options.ftol * old {
            return Trial::Stop(Termination::SmallReduction);
        }
        Trial::Accepted
    }

    /// The report: the factorisation is at the final `p` unless the last
    /// step was accepted and ended the run (the relative-reduction test):
    /// only then is the Jacobian evaluated again. A convergence test that
    /// holds where a free parameter has lost its influence is a plateau.
    fn finish(mut self, termination: Termination, mut fac: Option<Factored>) -> SolverReport {
        let n = self.p.len();
        if termination == Termination::SmallReduction || fac.is_none() {
            fac = self
                .have_gram
                .then(|| Factored::from_gram(&self.gram, n))
                .flatten();
            if fac.is_none() {
                self.problem.jacobian(&self.p, &mut self.jac);
                fac = all_finite(&self.jac)
                    .then(|| Factored::new(&self.jac, &self.r, n, &mut self.ws));
            }
        }
        let (termination, gn) = match &fac {
            Some(f) => {
                let t = if termination.is_converged()
                    && termination != Termination::ZeroResidual
                    && plateau(
                        &f.colnorm,
                        &self.r,
                        &self.p,
                        &self.constraints.status(&self.p),
                    ) {
                    Termination::SingularPlateau
                } else {
                    termination
                };
                (t, f.g.iter().fold(0.0f64, |a, v| a.max(v.abs())))
            }
            None => (termination, f64::NAN),
        };
        let (ssr, lambda) = (2.0 * self.cost, self.lambda);
        self.into_report(ssr, termination, gn, lambda)
    }

    /// The solver's report at `p`.
    fn into_report(
        self,
        ssr: f64,
        termination: Termination,
        gradient_norm: f64,
        damping: f64,
    ) -> SolverReport {
        SolverReport {
            bounds: self.constraints.status(&self.p),
            params: self.p,
            ssr,
            termination,
            iterations: self.iterations,
            evaluations: self.evaluations,
            gradient_norm,
            damping,
        }
    }
}
