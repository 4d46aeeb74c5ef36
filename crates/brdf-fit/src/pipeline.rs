//! The fitting pipeline: any catalogue model, any data set, any objective,
//! from automatic starts — the user never supplies start values and the
//! result is the same from run to run.
//!
//! - [`Solver::Sqp`] (default), as Ngan et al. and Kurt fitted: the linear
//!   parameters (`kd`, `ks` per channel, ...) are projected out by
//!   non-negative least squares (variable projection), the bounded
//!   SQP-style solver optimises the non-linear ones inside their box from
//!   deterministic Halton multi-starts (exponents on a log scale; after
//!   the starts a model's catalogue entry suggests, if any), and the
//!   best result is polished by the bounded solver on all parameters (which
//!   also enforces the linear parameters' upper bounds and reports every
//!   parameter on a bound).
//! - [`Solver::Lm`]: Levenberg-Marquardt (bounded) on all parameters from
//!   the same starts, linear parameters initialised by projection.
//! - [`Solver::Sopp`]: Sopp's procedure: stage 1 fits every parameter of a
//!   one-channel model on the mean of the channels with his LM and damping
//!   schedule from the model's default parameters; stage 2 fixes the
//!   non-linear parameters and solves the per-channel linear coefficients
//!   directly, within their box (least squares with inequality
//!   constraints).
//! - All-linear models (Lambert, Koenderink, Kurt's polynomial) are solved
//!   directly: NNLS / column-pivoted QR ([`Solver::Ols`]) or robust IRLS
//!   ([`Solver::Irls`]).
//!
//! Objectives ([`Objective`](crate::Objective)) are the row scalings of `fitting.md`; the log
//!
//! The pieces: [`crate::objective`] (what is minimised),
//! [`crate::options`] (how), [`crate::linear`] and [`crate::nonlinear`]
//! (the solves, from the starts of [`crate::starts`] inside
//! [`crate::param_box`]), [`crate::summary`] (what is reported). This
//! module dispatches a fit to them.

use std::time::Instant;

use brdf_core::{Parametric, SampleSet};
use brdf_models::{LinearSolver, NonlinearSearch};
use brdf_solve::robust_weights::RobustWeight;
use brdf_solve::{LmOptions, ModelProblem, VarPro, bounded_least_squares};

use crate::FitError;
use crate::linear::fit_all_linear;
use crate::nonlinear::fit_nonlinear;
use crate::options::{FitOptions, Solver};
use crate::param_box::box_constraints;
use crate::summary::{FitSummary, summarise};
use crate::termination::Termination;

/// Fit `model` (same channel count as `data`) in place and summarise.
pub fn fit(
    model: &mut dyn Parametric,
    data: &SampleSet,
    opts: &FitOptions,
) -> Result<FitSummary, FitError> {
    let t0 = Instant::now();
    check_sizes(model, data)?;
    let all_linear = model.param_specs().iter().all(|s| s.linear);
    let scales = opts.objective.row_scales(data);
    let values = data.values_channel_major();
    let opts = &FitOptions {
        solver: resolve_solver(opts.solver, model.name(), all_linear),
        ..opts.clone()
    };
    // An iterative linear fit (IRLS) says how it ended; a direct solve
    // has nothing to report.
    let mut irls_end = None;
    let (p, solver, rep, starts_info) = if all_linear && !opts.objective.is_transformed() {
        let linear = fit_all_linear(model, data, &scales, opts)?;
        irls_end = linear.irls;
        (linear.params, linear.how, None, (1, 1, 1))
    } else {
        check_nonlinear_solver(model, opts.solver)?;
        let f = fit_nonlinear(model, data, &values, &scales, opts, false)?;
        (f.params, f.how, Some(f.report), f.starts)
    };
    model.set_params(&p)?;
    let mut summary = summarise(
        model,
        data,
        opts,
        &p,
        &scales,
        &values,
        solver,
        rep,
        starts_info,
        t0,
    )?;
    if let Some(end) = irls_end {
        summary.iterations = end.iterations.iter().sum();
        summary.termination = Termination::Irls(end.termination);
    }
    Ok(summary)
}

/// Refuse data whose channels differ from the model's, or too few values
/// for its parameters.
fn check_sizes(model: &dyn Parametric, data: &SampleSet) -> Result<(), FitError> {
    if model.channels() != data.channels() {
        return Err(FitError::ChannelMismatch {
            model: model.name().to_string(),
            model_channels: model.channels(),
            data: data.name.clone(),
            data_channels: data.channels(),
        });
    }
    let np = model.param_specs().len();
    if data.len() * data.channels() <= np {
        return Err(FitError::TooFewSamples {
            samples: data.len(),
            channels: data.channels(),
            parameters: np,
            model: model.name().to_string(),
        });
    }
    Ok(())
}

/// The solver `asked` means for model `name`: [`Solver::Auto`] resolved by
/// the catalogue entry's facts (robust IRLS or direct least squares for an
/// all-linear model, Levenberg-Marquardt on every parameter or the
/// projected bounded search otherwise).
fn resolve_solver(asked: Solver, name: &str, all_linear: bool) -> Solver {
    let entry = brdf_models::entry(name);
    let fact = |f: fn(&brdf_models::ModelEntry) -> bool| entry.as_ref().is_some_and(f);
    match asked {
        Solver::Auto if all_linear && fact(|e| e.linear_solver == LinearSolver::RobustIrls) => {
            Solver::Irls(RobustWeight::Bisquare)
        }
        Solver::Auto if all_linear => Solver::Ols,
        Solver::Auto if fact(|e| e.nonlinear_search == NonlinearSearch::AllParameters) => {
            Solver::Lm
        }
        Solver::Auto => Solver::Sqp,
        s => s,
    }
}

/// Refuse a linear-only solver for a model with non-linear parameters (or
/// a fit in a transformed objective), and Sopp's procedure, which needs
/// the grey model of [`fit_sopp`].
fn check_nonlinear_solver(model: &dyn Parametric, solver: Solver) -> Result<(), FitError> {
    match solver {
        Solver::Ols | Solver::Irls(_) => Err(FitError::NeedsAllLinear {
            model: model.name().to_string(),
            parameter: model
                .param_specs()
                .iter()
                .find(|s| !s.linear)
                .map_or_else(|| "?".to_string(), |s| s.name.clone()),
        }),
        Solver::Sopp => Err(FitError::SoppNeedsGreyModel),
        Solver::Sqp | Solver::Lm | Solver::Auto => Ok(()),
    }
}

/// Sopp's two-stage procedure: `grey` is a one-channel instance of the same
/// model (stage 1 on the mean of the channels), `model` the full one.
pub fn fit_sopp(
    grey: &mut dyn Parametric,
    model: &mut dyn Parametric,
    data: &SampleSet,
    opts: &FitOptions,
) -> Result<FitSummary, FitError> {
    let t0 = Instant::now();
    let mean = data.mean_channel();
    let scales = opts.objective.row_scales(&mean);
    let lm = LmOptions {
        damping: brdf_solve::Damping::Sopp,
        ..opts.lm.clone()
    };
    let gp = ModelProblem::new(&*grey, mean.pairs(), &mean.values_channel_major(), &scales)?;
    let c = box_constraints(grey)?;
    let start = grey.params().to_vec();
    let rep1 = bounded_least_squares(&gp, &start, &c, &lm)?;
    // Stage 2: the non-linear parameters by name, the linear ones solved.
    let gspecs = grey.param_specs().to_vec();
    let mut p = model.params().to_vec();
    for (k, s) in model.param_specs().iter().enumerate() {
        if !s.linear
            && let Some(g) = gspecs.iter().position(|g| g.name == s.name)
        {
            p[k] = rep1.params[g];
        }
    }
    model.set_params(&p)?;
    let scales = opts.objective.row_scales(data);
    let values = data.values_channel_major();
    let mp = ModelProblem::new(&*model, data.pairs(), &values, &scales)?;
    let nl: Vec<f64> = mp.nonlinear_indices().iter().map(|k| p[*k]).collect();
    // The linear parameters within their box (NNLS alone would let, e.g.,
    // a specular coefficient exceed its upper bound); rounding-level
    // violations of the box by the constrained solution are clamped.
    let full = box_constraints(model)?;
    let lin = mp.coefficient_indices();
    let lower: Vec<f64> = lin.iter().map(|k| full.lower()[*k]).collect();
    let upper: Vec<f64> = lin.iter().map(|k| full.upper()[*k]).collect();
    let coef = VarPro::new(&mp, true).linear_coefficients_in_box(&nl, &lower, &upper)?;
    let mut p = mp.assemble(&nl, &coef);
    full.clamp(&mut p);
    drop(mp);
    model.set_params(&p)?;
    summarise(
        model,
        data,
        opts,
        &p,
        &scales,
        &values,
        "Sopp two-stage: LM (Sopp damping) on the channel mean, then the linear parameters by least squares within their box (LSI)"
            .into(),
        Some(rep1),
        (1, 1, 1),
        t0,
    )
}
