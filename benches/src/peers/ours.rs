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

/// The bounded solver on all parameters.
pub fn bounded(prob: &PeerProblem) -> Result<Outcome, PeerError> {
    let mp = prob.model_problem()?;
    let c = prob.constraints()?;
    let opts = fit_options();
    let (seconds, cpu_seconds, repeats, rep) =
        timed(|| Ok(bounded_least_squares(&mp, &prob.start, &c, &opts)?))?;
    Ok(outcome(
        "rust bounded (all parameters)",
        prob,
        (seconds, cpu_seconds, repeats),
        None,
        &rep,
    ))
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
    let (seconds, cpu_seconds, repeats, (stage, polish)) = timed(|| {
        let vp = VarPro::new(&mp, true);
        let stage = bounded_least_squares(&vp, &a0, &nl_box, &opts)?;
        let c = vp.linear_coefficients(&stage.params)?;
        let mut p0 = mp.assemble(&stage.params, &c);
        full.clamp(&mut p0);
        let polish = bounded_least_squares(&mp, &p0, &full, &opts)?;
        Ok((stage, polish))
    })?;
    Ok(outcome(
        "rust varpro (NNLS) + polish",
        prob,
        (seconds, cpu_seconds, repeats),
        Some(&stage),
        &polish,
    ))
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
