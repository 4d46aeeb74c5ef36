//! This workspace's solvers on a peer problem, called through their public
//! interfaces only (so the harness measures whatever they do today):
//!
//! - `bounded`: [`bounded_least_squares`] on every parameter from the start;
//! - `varpro+polish`: the `brdf fit` path for one start: [`VarPro`] over the
//!   non-linear parameters (linear ones projected by NNLS) with the bounded
//!   solver in their box, then the linear ones projected at its result and
//!   the bounded solver polishing every parameter.
//!
//! The options are those of `brdf fit` (300 iterations, 3000 evaluations,
//! the solver's default tolerances).

use std::sync::atomic::{AtomicUsize, Ordering};

use brdf_solve::{
    Constraints, LeastSquaresProblem, LmOptions, SolverReport, VarPro, bounded_least_squares,
};

use super::{Outcome, PeerError, PeerProblem, timed};

/// The options `brdf fit` passes to its non-linear stages.
pub fn fit_options() -> LmOptions {
    LmOptions {
        max_iterations: 300,
        max_evaluations: 3000,
        ..LmOptions::default()
    }
}

/// A problem that counts its passes over the samples by kind (the solver
/// report counts evaluations, not which of them also formed derivatives).
struct Counted<'a, P: LeastSquaresProblem> {
    inner: &'a P,
    residuals: AtomicUsize,
    jacobians: AtomicUsize,
    fused: AtomicUsize,
}

impl<'a, P: LeastSquaresProblem> Counted<'a, P> {
    fn new(inner: &'a P) -> Self {
        Self {
            inner,
            residuals: AtomicUsize::new(0),
            jacobians: AtomicUsize::new(0),
            fused: AtomicUsize::new(0),
        }
    }

    /// (residual-only, Jacobian-only, fused) passes so far.
    fn counts(&self) -> (usize, usize, usize) {
        (
            self.residuals.load(Ordering::Relaxed),
            self.jacobians.load(Ordering::Relaxed),
            self.fused.load(Ordering::Relaxed),
        )
    }
}

impl<P: LeastSquaresProblem> LeastSquaresProblem for Counted<'_, P> {
    fn n_params(&self) -> usize {
        self.inner.n_params()
    }
    fn n_residuals(&self) -> usize {
        self.inner.n_residuals()
    }
    fn residuals(&self, p: &[f64], out: &mut [f64]) {
        self.residuals.fetch_add(1, Ordering::Relaxed);
        self.inner.residuals(p, out)
    }
    fn jacobian(&self, p: &[f64], jac: &mut [f64]) {
        self.jacobians.fetch_add(1, Ordering::Relaxed);
        self.inner.jacobian(p, jac)
    }
    fn residuals_and_gram(&self, p: &[f64], out: &mut [f64], gram: &mut [f64]) -> bool {
        let done = self.inner.residuals_and_gram(p, out, gram);
        if done {
            self.fused.fetch_add(1, Ordering::Relaxed);
        }
        done
    }
}

/// Evaluation counts of one fit from the counting wrapper: (residual
/// evaluations, Jacobian evaluations, passes), a fused pass counting as
/// both evaluations and as one pass.
fn pass_counts(counts: (usize, usize, usize)) -> (usize, usize, usize) {
    let (r, j, f) = counts;
    (r + f, j + f, r + j + f)
}

/// The bounded solver on all parameters.
pub fn bounded(prob: &PeerProblem) -> Result<Outcome, PeerError> {
    let mp = prob.model_problem()?;
    let c = prob.constraints()?;
    let opts = fit_options();
    let mut counts = (0, 0, 0);
    let (seconds, cpu_seconds, repeats, rep) = timed(|| {
        let counted = Counted::new(&mp);
        let rep = bounded_least_squares(&counted, &prob.start, &c, &opts)?;
        counts = counted.counts();
        Ok(rep)
    })?;
    let mut o = outcome(
        "rust bounded (all parameters)",
        prob,
        (seconds, cpu_seconds, repeats),
        None,
        &rep,
    );
    (o.residual_evals, o.jacobian_evals, o.passes) = {
        let (r, j, p) = pass_counts(counts);
        (r, Some(j), Some(p))
    };
    Ok(o)
}

/// Variable projection + bounded solver, then the polish on all parameters.
pub fn varpro_polish(prob: &PeerProblem) -> Result<Outcome, PeerError> {
    let mp = prob.model_problem()?;
    let full = prob.constraints()?;
    let nl = mp.nonlinear_indices().to_vec();
    let nl_box = Constraints::boxed(
        nl.iter().map(|k| prob.lower[*k]).collect(),
        nl.iter().map(|k| prob.upper[*k]).collect(),
    )?;
    let a0: Vec<f64> = nl.iter().map(|k| prob.start[*k]).collect();
    let opts = fit_options();
    let mut counts = (0, 0, 0);
    let (seconds, cpu_seconds, repeats, (stage, polish)) = timed(|| {
        let vp = VarPro::new(&mp, true);
        let counted_vp = Counted::new(&vp);
        let stage = bounded_least_squares(&counted_vp, &a0, &nl_box, &opts)?;
        let c = vp.linear_coefficients(&stage.params)?;
        let mut p0 = mp.assemble(&stage.params, &c);
        full.clamp(&mut p0);
        let counted = Counted::new(&mp);
        let polish = bounded_least_squares(&counted, &p0, &full, &opts)?;
        let (a, b) = (counted_vp.counts(), counted.counts());
        // The projection of the linear coefficients at the stage's result
        // is one more basis pass.
        counts = (a.0 + b.0 + 1, a.1 + b.1, a.2 + b.2);
        Ok((stage, polish))
    })?;
    let mut o = outcome(
        "rust varpro (NNLS) + polish",
        prob,
        (seconds, cpu_seconds, repeats),
        Some(&stage),
        &polish,
    );
    (o.residual_evals, o.jacobian_evals, o.passes) = {
        let (r, j, p) = pass_counts(counts);
        (r, Some(j), Some(p))
    };
    Ok(o)
}

/// The outcome of a solve (`stage`: the first of two stages, if any;
/// `last` holds the result); `time` is (wall s, processor s, runs).
fn outcome(
    solver: &str,
    prob: &PeerProblem,
    time: (f64, f64, usize),
    stage: Option<&SolverReport>,
    last: &SolverReport,
) -> Outcome {
    let (seconds, cpu_seconds, repeats) = time;
    let (re, je, termination) = match stage {
        Some(first) => (
            first.evaluations + last.evaluations,
            first.iterations + last.iterations,
            format!(
                "{} / polish: {}",
                first.termination.describe(),
                last.termination.describe()
            ),
        ),
        None => (
            last.evaluations,
            last.iterations,
            last.termination.describe().to_string(),
        ),
    };
    Outcome {
        solver: solver.into(),
        params: last.params.clone(),
        seconds,
        cpu_seconds,
        repeats,
        residual_evals: re,
        jacobian_evals: Some(je),
        termination,
        inside_box: prob.inside_box(&last.params),
        own_cost: 0.5 * last.ssr,
        passes: None,
    }
}

/// `0.5 ||r(p)||^2` of the full problem (for the Rust-side check of the
/// Python cost).
pub fn cost(prob: &PeerProblem, p: &[f64]) -> Result<f64, PeerError> {
    let mp = prob.model_problem()?;
    let mut r = vec![0.0; mp.n_residuals()];
    mp.residuals(p, &mut r);
    Ok(0.5 * r.iter().map(|x| x * x).sum::<f64>())
}
