//! What a fit reports ([`FitSummary`]) and how the pipeline forms it from
//! the fitted parameters: errors, standard errors, bound status and why
//! the solve stopped.

use std::time::Instant;

use brdf_core::metrics::ngan_l2;
use brdf_core::{Parametric, SampleSet};
use brdf_solve::covariance::standard_errors;
use brdf_solve::{BoundStatus, LeastSquaresProblem, ModelProblem, SolverReport};
use serde::Serialize;

use crate::FitError;
use crate::options::{FitOptions, Solver};
use crate::param_box::box_constraints;
use crate::termination::{Termination, VanishedTerm};

/// One fitted parameter: name, value, standard error, bound status and
/// whether it was projected out (the saved-model schema's parameter).
pub type FittedParam = brdf_models::saved_model::SavedParam;

/// What a fit reports.
#[derive(Clone, Debug, Serialize)]
pub struct FitSummary {
    /// Model name.
    pub model: String,
    /// Data set name.
    pub data: String,
    /// Samples used.
    pub samples: usize,
    /// Parameters.
    pub parameters: Vec<FittedParam>,
    /// Objective name.
    pub objective: &'static str,
    /// Error in the objective's metric (total, per channel).
    pub error: f64,
    /// Per-channel error in the objective's metric.
    pub error_per_channel: Vec<f64>,
    /// Ngan's L2 (total).
    pub ngan_l2: f64,
    /// Ngan's L2 per channel.
    pub ngan_l2_per_channel: Vec<f64>,
    /// Solver description.
    pub solver: String,
    /// Iterations of the solve that produced the result.
    pub iterations: usize,
    /// Why it stopped.
    pub termination: Termination,
    /// Starts tried, converged, and at the best cost (within 1e-6).
    pub starts: (usize, usize, usize),
    /// Wall-clock seconds.
    pub seconds: f64,
    /// Number of stored numbers (parameters).
    pub stored_numbers: usize,
    /// Non-linear parameters the fitted model does not depend on at the
    /// samples used (their Jacobian columns are exactly 0): the shape of a
    /// lobe whose strength is 0, `specular` at `metallic = 1`.
    pub inert: Vec<String>,
}

#[allow(clippy::too_many_arguments)]
pub(crate) fn summarise(
    model: &dyn Parametric,
    data: &SampleSet,
    opts: &FitOptions,
    p: &[f64],
    scales: &[f64],
    values: &[f64],
    solver: String,
    rep: Option<SolverReport>,
    starts: (usize, usize, usize),
    t0: Instant,
) -> Result<FitSummary, FitError> {
    let seconds = t0.elapsed().as_secs_f64();
    let n = data.len();
    let mut fitted = vec![0.0; n * model.channels()];
    model.eval_batch_at(p, data.pairs(), &mut fitted);
    let err = opts.objective.error(data, &fitted)?;
    let ngan = ngan_l2(values, &fitted, &data.pairs().lz, data.weights())?;
    let mp = ModelProblem::new(model, data.pairs(), values, scales)?;
    let se = standard_errors(&mp, p).ok();
    let status = box_constraints(model)?.status(p);
    let specs = model.param_specs();
    let plateau = rep
        .as_ref()
        .is_some_and(|r| r.termination == brdf_solve::Termination::SingularPlateau);
    let inert_columns = if plateau || specs.iter().any(|s| !s.linear) {
        inert_columns(&mp, p)
    } else {
        Vec::new()
    };
    let parameters = specs
        .iter()
        .enumerate()
        .map(|(k, s)| FittedParam {
            name: s.name.clone(),
            value: p[k],
            std_error: se.as_ref().map(|v| v[k]).filter(|v| v.is_finite()),
            at_bound: match status[k] {
                BoundStatus::Free => None,
                BoundStatus::AtLower => Some("lower".to_string()),
                BoundStatus::AtUpper => Some("upper".to_string()),
            },
            projected: s.linear && matches!(opts.solver, Solver::Sqp),
        })
        .collect();
    Ok(FitSummary {
        model: model.name().to_string(),
        data: data.name.clone(),
        samples: n,
        parameters,
        objective: opts.objective.name(),
        error: err.total,
        error_per_channel: err.per_channel,
        ngan_l2: ngan.total,
        ngan_l2_per_channel: ngan.per_channel,
        solver,
        iterations: rep.as_ref().map(|r| r.iterations).unwrap_or(0),
        termination: describe_termination(rep.as_ref(), &status, specs, &inert_columns),
        starts,
        seconds,
        stored_numbers: specs.len(),
        inert: inert_columns
            .iter()
            .filter(|k| !specs[**k].linear)
            .map(|k| specs[*k].name.clone())
            .collect(),
    })
}

/// Indices of the parameters whose Jacobian columns are exactly 0 at `p`.
/// Asked only where it can matter (a non-linear parameter, or a plateau to
/// explain): the Jacobians of all-linear models are the largest (Kurt's
/// polynomials), and a linear strength at 0 is a bound, not a lost shape.
fn inert_columns(mp: &ModelProblem<'_>, p: &[f64]) -> Vec<usize> {
    let (m, n) = (mp.n_residuals(), p.len());
    let mut jac = vec![0.0; m * n];
    mp.jacobian(p, &mut jac);
    (0..n)
        .filter(|k| (0..m).all(|i| jac[i * n + k] == 0.0))
        .collect()
}

/// Why the fit stopped. A plateau where some free parameters have no
/// influence at all (their Jacobian columns are exactly 0) while others sit
/// on bounds is a degenerate but genuine fit: a term of the model has
/// vanished (a linear `ks = 0`; principled's dielectric lobe at
/// `metallic = 1`, where `specular` no longer acts) and the parameters only
/// that term used cannot be identified. It is reported as such, naming
/// them, rather than as a failure; any other plateau stays "not converged".
fn describe_termination(
    rep: Option<&SolverReport>,
    status: &[BoundStatus],
    specs: &[brdf_core::ParamSpec],
    inert_columns: &[usize],
) -> Termination {
    let Some(rep) = rep else {
        return Termination::DirectSolve;
    };
    if rep.termination != brdf_solve::Termination::SingularPlateau {
        return Termination::Solver(rep.termination);
    }
    let zero_term = specs
        .iter()
        .zip(status)
        .any(|(s, b)| s.linear && s.lower == 0.0 && *b == BoundStatus::AtLower);
    let lost: Vec<String> = inert_columns
        .iter()
        .filter(|k| status[**k] == BoundStatus::Free)
        .map(|k| specs[*k].name.clone())
        .collect();
    let on_bound = status.iter().any(|b| *b != BoundStatus::Free);
    if lost.is_empty() || !on_bound {
        Termination::Solver(rep.termination)
    } else if zero_term {
        Termination::Degenerate {
            cause: VanishedTerm::LinearTermZero,
            lost,
        }
    } else {
        Termination::Degenerate {
            cause: VanishedTerm::SwitchedOffByBounds,
            lost,
        }
    }
}
