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
//! Objectives ([`Objective`]) are the row scalings of `fitting.md`; the log
//! objective transforms the residual and is fitted on all parameters.

use std::time::Instant;

use brdf_core::metrics::{
    cube_root_metric, lafortune_l2, log_metric, ngan_l2, relative_metric, sopp_error,
};
use brdf_core::{MetricValue, Parametric, SampleSet};
use brdf_solve::covariance::standard_errors;
use brdf_solve::multistart::{StartBox, multistart};
use brdf_solve::robust_weights::RobustWeight;
use brdf_solve::{
    BoundStatus, Constraints, IrlsOptions, IrlsTermination, LeastSquaresProblem, LmOptions,
    ModelProblem, RowTransform, ScaleConvention, SolverReport, Termination, VarPro,
    bounded_least_squares, irls,
};
use faer::Mat;
use serde::Serialize;

use crate::FitError;

mod log_scaled;

/// The fitting objective (see `fitting.md`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Objective {
    /// Ngan's / Kurt's L2: rows `sqrt(w) cos_i (R - M)`.
    Ngan,
    /// Sopp's: rows `w cos_i (R - M) / sum w` (weighting on) or
    /// `cos_i (R - M) / n` (off).
    Sopp {
        /// Solid-angle weighting ("Gewichtung").
        weighted: bool,
    },
    /// Lafortune et al.: rows `sqrt(w) cos_i cos_o (R - M)`.
    Lafortune,
    /// Matusik's log: `ln(1 + M cos_i) - ln(1 + R cos_i)`.
    Log,
    /// Forés et al.'s cube root (2012, "BRDF parameter estimation"):
    /// `sqrt(w) (cbrt(M cos_i + d) - cbrt(R cos_i + d))`, `d = 1e-6 p99(R
    /// cos_i)` keeping the derivative finite at 0. Like lightness, the cube
    /// root compresses the highlight so the body colour weighs.
    CubeRoot,
    /// Relative error: rows `sqrt(w) (M - R) / (mean_c R + e)`, `e = 1e-2
    /// median(mean_c R)`: every sample counts by its ratio to the data, so
    /// the dim body weighs as much as the peak. A row scaling, so the linear
    /// parameters are still projected out.
    Relative,
    /// The image objective ([`crate::image_objective`]): log residuals of
    /// the sphere's pixels under the standard light sets of `brdf-render`,
    /// for data that can be evaluated at any direction pair. Fitted from
    /// the best BRDF-space fits (see [`crate::appearance`]).
    Image,
}

impl Objective {
    /// Parse `ngan|sopp|sopp-unweighted|lafortune|log`.
    pub fn parse(s: &str) -> Result<Self, FitError> {
        Ok(match s {
            "ngan" => Objective::Ngan,
            "sopp" => Objective::Sopp { weighted: true },
            "sopp-unweighted" => Objective::Sopp { weighted: false },
            "lafortune" => Objective::Lafortune,
            "log" => Objective::Log,
            "cube-root" | "cuberoot" | "cube_root" => Objective::CubeRoot,
            "relative" => Objective::Relative,
            "image" => Objective::Image,
            other => {
                return Err(FitError::Usage(format!(
                    "unknown metric `{other}`: ngan, sopp, sopp-unweighted, lafortune, log, cube-root, relative or image"
                )));
            }
        })
    }

    /// Name in reports.
    pub fn name(self) -> &'static str {
        match self {
            Objective::Ngan => "ngan",
            Objective::Sopp { weighted: true } => "sopp",
            Objective::Sopp { weighted: false } => "sopp-unweighted",
            Objective::Lafortune => "lafortune",
            Objective::Log => "log",
            Objective::CubeRoot => "cube-root",
            Objective::Relative => "relative",
            Objective::Image => "image",
        }
    }

    /// Whether the objective transforms the residual (fitted on all
    /// parameters) rather than scaling its rows.
    pub fn is_transformed(self) -> bool {
        matches!(
            self,
            Objective::Log | Objective::CubeRoot | Objective::Image
        )
    }

    /// Row scales `s_j` (the residual is `s_j (M - R)`); the log objective
    /// uses unit scales and transforms the residual instead.
    pub fn row_scales(self, s: &SampleSet) -> Vec<f64> {
        let p = s.pairs();
        let w = s.weights();
        let n = s.len();
        match self {
            Objective::Ngan => (0..n).map(|j| w[j].sqrt() * p.lz[j]).collect(),
            Objective::Lafortune => (0..n).map(|j| w[j].sqrt() * p.lz[j] * p.vz[j]).collect(),
            Objective::Sopp { weighted: true } => {
                let sw: f64 = w.iter().sum();
                (0..n).map(|j| w[j] * p.lz[j] / sw).collect()
            }
            Objective::Sopp { weighted: false } => (0..n).map(|j| p.lz[j] / n as f64).collect(),
            Objective::Relative => {
                let nc = s.channels();
                let mean: Vec<f64> = (0..n)
                    .map(|j| (0..nc).map(|c| s.channel(c)[j]).sum::<f64>() / nc as f64)
                    .collect();
                let e = relative_floor(&mean);
                (0..n)
                    .map(|j| w[j].sqrt() / (mean[j].max(0.0) + e))
                    .collect()
            }
            Objective::Log | Objective::CubeRoot | Objective::Image => vec![1.0; n],
        }
    }

    /// The objective's error of `fitted` (channel-major) on `s`.
    pub fn error(self, s: &SampleSet, fitted: &[f64]) -> Result<MetricValue, FitError> {
        let m = s.values_channel_major();
        let p = s.pairs();
        Ok(match self {
            Objective::Ngan => ngan_l2(&m, fitted, &p.lz, s.weights())?,
            Objective::Lafortune => lafortune_l2(&m, fitted, &p.lz, &p.vz, s.weights())?,
            Objective::Sopp { weighted } => sopp_error(&m, fitted, &p.lz, s.weights(), weighted)?,
            Objective::Log | Objective::Image => log_metric(&m, fitted, &p.lz, s.weights())?,
            Objective::CubeRoot => {
                cube_root_metric(&m, fitted, &p.lz, s.weights(), cube_root_offset(s))?
            }
            Objective::Relative => {
                let scales = self.row_scales(s);
                relative_metric(&m, fitted, &scales, s.weights())?
            }
        })
    }
}

/// Which solver fits the model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Solver {
    /// The default for the model: Kurt's robust IRLS (bisquare) for his
    /// polynomial, direct least squares (NNLS where the box starts at 0) for
    /// the other all-linear models, [`Solver::Sqp`] for the rest.
    Auto,
    /// Variable projection + bounded SQP-style solver + multi-start (default).
    Sqp,
    /// Bounded Levenberg-Marquardt on all parameters + multi-start.
    Lm,
    /// Sopp's two-stage procedure with his damping schedule.
    Sopp,
    /// Direct linear least squares (all-linear models).
    Ols,
    /// Robust IRLS (all-linear models), with a weight function.
    Irls(RobustWeight),
}

impl Solver {
    /// Parse `auto|sqp|lm|sopp|ols|irls[:weight]`.
    pub fn parse(s: &str) -> Result<Self, FitError> {
        Ok(match s {
            "auto" => Solver::Auto,
            "sqp" => Solver::Sqp,
            "lm" => Solver::Lm,
            "sopp" => Solver::Sopp,
            "ols" => Solver::Ols,
            "irls" => Solver::Irls(RobustWeight::Bisquare),
            other => match other.strip_prefix("irls:") {
                Some(w) => Solver::Irls(w.parse().map_err(|e| FitError::Usage(format!("{e}")))?),
                None => {
                    return Err(FitError::Usage(format!(
                        "unknown solver `{other}`: auto, sqp, lm, sopp, ols, irls or irls:WEIGHT"
                    )));
                }
            },
        })
    }
}

/// Options of [`fit`].
#[derive(Clone, Debug)]
pub struct FitOptions {
    /// Objective (default Ngan).
    pub objective: Objective,
    /// Solver (default Auto).
    pub solver: Solver,
    /// Multi-start count (default 12).
    pub starts: usize,
    /// Solver options of the non-linear stages.
    pub lm: LmOptions,
    /// Tolerance (`ftol`, `xtol`, `gtol`, never tighter than `lm`'s) of
    /// the multi-start search (default 1e-7): the starts only have to find
    /// and rank the basins; the best one is then polished to `lm`'s
    /// tolerances, so the result is the same optimum at a fraction of the
    /// iterations (issue 16: stop at the data's noise level, not at 1e-15,
    /// for every start).
    pub search_tolerance: f64,
    /// What the image objective fits to ([`Objective::Image`] only).
    pub image: Option<std::sync::Arc<crate::image_objective::ImageTarget>>,
    /// Reweighting cap of the robust (IRLS) fits (default
    /// [`IRLS_MAX_ITERATIONS`]; MATLAB's `robustfit`, Kurt's procedure,
    /// stops at 50).
    pub irls_max_iterations: usize,
    /// End a robust fit whose reweighting cycles as soon as a weighted
    /// solution recurs (default true; MATLAB's loop runs to its cap, and
    /// where it stops in the cycle sets the result).
    pub irls_stop_on_cycle: bool,
}

impl FitOptions {
    /// The solver options of the multi-start search.
    fn search_lm(&self) -> LmOptions {
        let t = self.search_tolerance;
        LmOptions {
            ftol: self.lm.ftol.max(t),
            xtol: self.lm.xtol.max(t),
            gtol: self.lm.gtol.max(t),
            ..self.lm.clone()
        }
    }
}

impl Default for FitOptions {
    fn default() -> Self {
        Self {
            objective: Objective::Ngan,
            solver: Solver::Auto,
            starts: 12,
            lm: LmOptions {
                max_iterations: 300,
                max_evaluations: 3000,
                ..LmOptions::default()
            },
            search_tolerance: 1e-7,
            image: None,
            irls_max_iterations: IRLS_MAX_ITERATIONS,
            irls_stop_on_cycle: true,
        }
    }
}

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
    pub termination: String,
    /// Starts tried, converged, and at the best cost (within 1e-6).
    pub starts: (usize, usize, usize),
    /// Wall-clock seconds.
    pub seconds: f64,
    /// Number of stored numbers (parameters).
    pub stored_numbers: usize,
}

/// Fit `model` (same channel count as `data`) in place and summarise.
pub fn fit(
    model: &mut dyn Parametric,
    data: &SampleSet,
    opts: &FitOptions,
) -> Result<FitSummary, FitError> {
    let t0 = Instant::now();
    if model.channels() != data.channels() {
        return Err(FitError::Usage(format!(
            "model `{}` has {} channels, data `{}` has {}",
            model.name(),
            model.channels(),
            data.name,
            data.channels()
        )));
    }
    let specs = model.param_specs().to_vec();
    let np = specs.len();
    if data.len() * data.channels() <= np {
        return Err(FitError::Usage(format!(
            "{} samples x {} channels are not more than the {np} parameters of `{}`",
            data.len(),
            data.channels(),
            model.name()
        )));
    }
    let all_linear = specs.iter().all(|s| s.linear);
    let scales = opts.objective.row_scales(data);
    let values = data.values_channel_major();
    let solver_kind = match opts.solver {
        Solver::Auto if all_linear && model.name().starts_with("polynomial") => {
            Solver::Irls(RobustWeight::Bisquare)
        }
        Solver::Auto if all_linear => Solver::Ols,
        Solver::Auto => Solver::Sqp,
        s => s,
    };
    let opts = &FitOptions {
        solver: solver_kind,
        ..opts.clone()
    };
    // An iterative linear fit (IRLS) says how it ended; a direct solve
    // has nothing to report.
    let mut irls_end = None;
    let (p, solver, rep, starts_info) = if all_linear && !opts.objective.is_transformed() {
        let linear = fit_all_linear(model, data, &scales, opts)?;
        irls_end = linear.irls;
        let (p, how) = (linear.params, linear.how);
        (p, how, None, (1, 1, 1))
    } else {
        match opts.solver {
            Solver::Ols | Solver::Irls(_) => {
                return Err(FitError::Usage(format!(
                    "--solver ols/irls need an all-linear model; `{}` has the non-linear parameter `{}`",
                    model.name(),
                    specs
                        .iter()
                        .find(|s| !s.linear)
                        .map(|s| s.name.as_str())
                        .unwrap_or("?")
                )));
            }
            Solver::Sopp => return Err(FitError::Usage(
                "Sopp's two-stage procedure needs a one-channel model for stage 1: use fit_sopp"
                    .into(),
            )),
            Solver::Sqp | Solver::Lm | Solver::Auto => {
                let (p, rep, info, how) =
                    fit_nonlinear(model, data, &values, &scales, opts, false)?;
                (p, how, Some(rep), info)
            }
        }
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
        summary.termination = format!("IRLS {}", end.termination.describe());
    }
    Ok(summary)
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

/// Box constraints of a model's parameters (open lower ends moved inside by
/// `1e-9` of the box width).
pub fn box_constraints(model: &dyn Parametric) -> Result<Constraints, FitError> {
    let specs = model.param_specs();
    let lower = specs
        .iter()
        .map(|s| {
            if s.lower_open {
                s.lower + 1e-9 * (s.upper - s.lower).min(1.0)
            } else {
                s.lower
            }
        })
        .collect();
    Ok(Constraints::boxed(
        lower,
        specs.iter().map(|s| s.upper).collect(),
    )?)
}

/// The multi-start box of the non-linear parameters: exponents (upper end
/// of 1e3 or more) on a log scale over `[max(lower, 1), min(upper, 1e4)]`,
/// roughness-like parameters (box open at 0) on a log scale over
/// `[1e-3 upper, upper]`, the rest linearly over the box (infinite ends
/// replaced by +-1).
fn start_box(model: &dyn Parametric, nonlinear: &[usize]) -> StartBox {
    let specs = model.param_specs();
    let mut b = StartBox {
        lower: Vec::new(),
        upper: Vec::new(),
        log_scale: Vec::new(),
    };
    for k in nonlinear {
        let s = &specs[*k];
        if s.upper >= 1e3 {
            b.lower.push(s.lower.max(1.0));
            b.upper.push(s.upper.min(1e4));
            b.log_scale.push(true);
        } else if s.lower_open && s.lower == 0.0 && s.upper.is_finite() {
            // Roughness-like parameters: sharp lobes need values decades
            // below the box's upper end.
            b.lower.push(1e-3 * s.upper);
            b.upper.push(s.upper);
            b.log_scale.push(true);
        } else {
            let lo = if s.lower.is_finite() { s.lower } else { -1.0 };
            let hi = if s.upper.is_finite() {
                s.upper
            } else {
                lo + 2.0
            };
            let width = hi - lo;
            let lo = if s.lower_open { lo + 1e-3 * width } else { lo };
            b.lower.push(lo);
            b.upper.push(hi);
            b.log_scale.push(false);
        }
    }
    b
}

pub(crate) type NonlinearFit = (Vec<f64>, SolverReport, (usize, usize, usize), String);

/// The polish's report with the search's iterations and evaluations
/// counted in (the work of the whole fit).
fn after_search(search: &SolverReport, polish: SolverReport) -> SolverReport {
    SolverReport {
        iterations: search.iterations + polish.iterations,
        evaluations: search.evaluations + polish.evaluations,
        ..polish
    }
}

/// The non-linear fit of `model` (see the module doc). `log_wide`: the
/// problem is one channel of a model whose channels share nothing
/// ([`fit_per_channel`]); its wide positive non-linear parameters are then
/// solved on a log scale (`log_scaled`: Bagher's shadowing valley) once
/// the coarse search has ranked the starts: the refinement on all samples
/// and the polish. Measured on the five RGL files (SGD): the polish that
/// crept to its cap of 3000 iterations per channel converges in tens;
/// the coarse search stays in the box's own scale, whose ranking finds
/// the basins the earlier fits found (on the log scale, or on a smaller
/// subsample, it ranked a worse basin first on cc_iris_purple_gem).
fn fit_nonlinear(
    model: &dyn Parametric,
    data: &SampleSet,
    values: &[f64],
    scales: &[f64],
    opts: &FitOptions,
    log_wide: bool,
) -> Result<NonlinearFit, FitError> {
    let full = box_constraints(model)?;
    if opts.objective == Objective::Image {
        return crate::image_objective::fit_image(model, opts, &full);
    }
    if !opts.objective.is_transformed()
        && let Some(blocks) = brdf_models::channel_slice::channel_blocks(model)
    {
        return fit_per_channel(model, data, opts, &blocks);
    }
    let (rows, transformed);
    let mp = ModelProblem::new(model, data.pairs(), values, scales)?;
    let nonlinear = mp.nonlinear_indices().to_vec();
    let sb = start_box(model, &nonlinear);
    // The model's own suggestions (its catalogue entry's) first, then the
    // Halton points of its box.
    let mut starts: Vec<Vec<f64>> = brdf_models::suggested_starts(model)
        .into_iter()
        .filter(|s| s.len() == model.n_params())
        .map(|s| nonlinear.iter().map(|k| s[*k]).collect())
        .collect();
    starts.extend(sb.starts(opts.starts.max(1))?);
    let nl_box = Constraints::boxed(
        nonlinear.iter().map(|k| full.lower()[*k]).collect(),
        nonlinear.iter().map(|k| full.upper()[*k]).collect(),
    )?;
    // Wide positive non-linear parameters on a log scale (`log_wide`).
    let specs = model.param_specs();
    let wide_nl = log_scaled::wide_positive(&nl_box, &vec![log_wide; nonlinear.len()]);
    let nonlinear_mask: Vec<bool> = specs.iter().map(|s| log_wide && !s.linear).collect();
    let wide_full = log_scaled::wide_positive(&full, &nonlinear_mask);
    let solve_nl = |problem: &(dyn LeastSquaresProblem + Sync), s: &[f64], lm: &LmOptions| {
        log_scaled::solve(problem, s, &nl_box, &wide_nl, lm)
    };
    // Projection needs linear parameters (the full Oren-Nayar model has
    // none: its kd enters squared).
    let use_varpro = opts.solver == Solver::Sqp
        && !opts.objective.is_transformed()
        && !mp.linear_indices().is_empty();
    let problem: &(dyn LeastSquaresProblem + Sync) = if opts.objective.is_transformed() {
        rows = TransformedRows::new(data, opts.objective);
        transformed = ModelProblem::new(model, data.pairs(), values, scales)?.with_transform(&rows);
        &transformed
    } else {
        &mp
    };
    // Full parameter vector from non-linear values: linear ones projected.
    let project = |a: &[f64]| -> Result<Vec<f64>, brdf_solve::SolveError> {
        let c = if mp.linear_indices().is_empty() {
            Vec::new()
        } else {
            VarPro::new(&mp, true).linear_coefficients(a)?
        };
        let mut p = mp.assemble(a, &c);
        full.clamp(&mut p);
        Ok(p)
    };
    let search = opts.search_lm();
    // Models without linear parameters and with few parameters (gltf) are
    // searched on all parameters coarse-to-fine like the projected ones
    // (starts on the subsample are already full parameter vectors). With
    // many (principled's 12) the subsample's optimum lies in flat valleys
    // far from the full data's: measured on the RGL files, refining it took
    // hundreds of iterations and ended at slightly higher costs, so those
    // keep every start on all samples. The log objective keeps the full
    // search (its problem wraps the full-data one).
    let coarse_full = !use_varpro
        && mp.linear_indices().is_empty()
        && nonlinear.len() <= COARSE_FULL_MAX_PARAMS
        && opts.objective != Objective::Log
        && data.len() > COARSE_ABOVE;
    // On large sets the projected search refines its coarse optima on all
    // parameters in the fused blocked pass (one pass per trial point, the
    // normal equations formed in it), not by projection (two passes per
    // iteration and a stored basis): issue 28 measured the projection +
    // polish at 1.24 s and the fused pass at 0.46 s on the full MERL grid.
    let fused_refine = use_varpro && data.len() >= FUSED_REFINE_FROM;
    let ms = if use_varpro {
        let coarse = coarse_starts(model, data, scales, &starts, |sub, s| {
            bounded_least_squares(&VarPro::new(sub, true), s, &nl_box, &search)
        })?;
        if fused_refine {
            multistart(&coarse, |s| {
                let p0 = project(s)?;
                bounded_least_squares(problem, &p0, &full, &search)
            })?
        } else {
            multistart(&coarse, |s| solve_nl(&VarPro::new(&mp, true), s, &search))?
        }
    } else if coarse_full {
        let coarse = coarse_starts(model, data, scales, &starts, |sub, s| {
            bounded_least_squares(sub, s, &full, &search)
        })?;
        multistart(&coarse, |s| {
            bounded_least_squares(problem, s, &full, &search)
        })?
    } else {
        let screened = screened_starts(data, opts.objective, model, &starts, |sub, s| {
            let p0 = project(s)?;
            bounded_least_squares(sub, &p0, &full, &search)
        })?;
        multistart(&screened, |s| {
            let p0 = project(s)?;
            bounded_least_squares(problem, &p0, &full, &search)
        })?
    };
    let info = (starts.len(), ms.n_converged, ms.n_at_best);
    // The polish's iteration cap: the model's factor of the solver's.
    let factor = brdf_models::polish_factor(model);
    let polish_lm = LmOptions {
        max_iterations: opts.lm.max_iterations * factor,
        max_evaluations: opts.lm.max_evaluations * factor,
        ..opts.lm.clone()
    };
    let (p, rep, how) = if fused_refine {
        // Already on all parameters: polish the best to the full tolerances.
        let polish = repolish(problem, &full, &polish_lm, &ms.best.params)?;
        let rep = after_search(&ms.best, polish);
        let stages = search_stages(data.len(), starts.len());
        (
            rep.params.clone(),
            rep,
            format!(
                "variable projection (NNLS) + bounded SQP-style LM on the subsample, {stages} by bounded LM on all parameters (fused blocked pass)"
            ),
        )
    } else if use_varpro {
        // Polish on all parameters (enforces the linear upper bounds and
        // reports every parameter's bound status).
        let p0 = project(&ms.best.params)?;
        let polish = log_scaled::solve(problem, &p0, &full, &wide_full, &polish_lm)?;
        let rep = after_search(&ms.best, polish);
        let stages = search_stages(data.len(), starts.len());
        (
            rep.params.clone(),
            rep,
            format!(
                "variable projection (NNLS) + bounded SQP-style LM, {stages}, polished on all parameters"
            ),
        )
    } else {
        // Polish the best start to the full tolerances.
        let polish = repolish(problem, &full, &polish_lm, &ms.best.params)?;
        let rep = after_search(&ms.best, polish);
        (
            rep.params.clone(),
            rep,
            if coarse_full {
                format!(
                    "bounded LM on all parameters, {}",
                    search_stages(data.len(), starts.len())
                )
            } else {
                format!(
                    "bounded LM on all parameters, {}",
                    screen_stages(data.len(), starts.len())
                )
            },
        )
    };
    Ok((p, rep, info, how))
}

/// A model whose channels share no parameter ([`channel_blocks`]), fitted
/// channel by channel: each channel's block is a one-channel problem
/// ([`ChannelSlice`]) with its own starts and the objective's rows of that
/// channel; the reports are summed (iterations, evaluations, cost), the
/// termination is the first channel's that did not converge, else the
/// last channel's.
///
/// [`channel_blocks`]: brdf_models::channel_slice::channel_blocks
/// [`ChannelSlice`]: brdf_models::channel_slice::ChannelSlice
fn fit_per_channel(
    model: &dyn Parametric,
    data: &SampleSet,
    opts: &FitOptions,
    blocks: &[Vec<usize>],
) -> Result<NonlinearFit, FitError> {
    use brdf_models::channel_slice::ChannelSlice;
    let mut p = model.params().to_vec();
    let mut bounds = vec![BoundStatus::Free; p.len()];
    let mut total: Option<SolverReport> = None;
    let mut info = (0, 0, 0);
    let mut how = String::new();
    for (c, block) in blocks.iter().enumerate() {
        let slice = ChannelSlice::new(model, c, block.clone())?;
        let single = data.single_channel(c);
        let scales = opts.objective.row_scales(&single);
        let values = single.values_channel_major();
        let (pc, rep, i, h) = fit_nonlinear(&slice, &single, &values, &scales, opts, true)?;
        for (j, &k) in block.iter().enumerate() {
            p[k] = pc[j];
            bounds[k] = rep.bounds.get(j).copied().unwrap_or(BoundStatus::Free);
        }
        info = (info.0 + i.0, info.1 + i.1, info.2 + i.2);
        how = h;
        total = Some(match total {
            None => rep,
            Some(t) => SolverReport {
                ssr: t.ssr + rep.ssr,
                iterations: t.iterations + rep.iterations,
                evaluations: t.evaluations + rep.evaluations,
                gradient_norm: t.gradient_norm.max(rep.gradient_norm),
                termination: if t.termination.is_converged() {
                    rep.termination
                } else {
                    t.termination
                },
                ..t
            },
        });
    }
    let mut rep = total.ok_or_else(|| FitError::Usage("a model without channels".into()))?;
    rep.params = p.clone();
    rep.bounds = bounds;
    Ok((
        p,
        rep,
        info,
        format!(
            "per channel (no parameter shared; wide positive parameters refined on a log scale): {how}"
        ),
    ))
}

/// The bounded solve from `p0` to the full tolerances; when it stops on
/// the step test, solved once more from where it stopped and kept if that
/// lowers the cost. A step below tolerance can be the damping's doing, not
/// the minimum's (principled on the RGL files: rounding-level changes of
/// the kernel moved such a stop by 1e-9 of the cost); the restart begins
/// with fresh damping. The report counts both solves and says why the
/// kept one stopped.
fn repolish(
    problem: &(dyn LeastSquaresProblem + Sync),
    full: &Constraints,
    lm: &LmOptions,
    p0: &[f64],
) -> Result<SolverReport, FitError> {
    let first = bounded_least_squares(problem, p0, full, lm)?;
    if first.termination != Termination::SmallStep {
        return Ok(first);
    }
    let again = bounded_least_squares(problem, &first.params, full, lm)?;
    let (iterations, evaluations) = (
        first.iterations + again.iterations,
        first.evaluations + again.evaluations,
    );
    let kept = if again.ssr < first.ssr { again } else { first };
    Ok(SolverReport {
        iterations,
        evaluations,
        ..kept
    })
}

/// The multi-start stages in words.
fn search_stages(samples: usize, starts: usize) -> String {
    if samples > COARSE_ABOVE {
        format!(
            "{starts} Halton starts on a {}-sample stratified subsample, the best {} refined on all samples",
            samples.div_ceil(samples.div_ceil(COARSE_SAMPLES)),
            POLISHED_STARTS.min(starts)
        )
    } else {
        format!("{starts} Halton starts")
    }
}

/// The screened search in words ([`screened_starts`]).
fn screen_stages(samples: usize, starts: usize) -> String {
    if samples > SCREEN_ABOVE && starts > POLISHED_STARTS {
        format!(
            "{starts} Halton starts screened on a {}-sample stratified subsample, the best {POLISHED_STARTS} solved on all samples",
            samples.div_ceil(samples.div_ceil(SCREEN_SAMPLES))
        )
    } else {
        format!("{starts} Halton starts")
    }
}

/// Sample sets from this size on refine the coarse optima of a projected
/// search on all parameters in the fused blocked pass.
const FUSED_REFINE_FROM: usize = 100_000;

/// Sample sets larger than this are searched coarse-to-fine.
const COARSE_ABOVE: usize = 20_000;
/// Size of the stratified subsample of the coarse search.
const COARSE_SAMPLES: usize = 8_192;
/// Most parameters of a model without linear ones searched coarse-to-fine.
const COARSE_FULL_MAX_PARAMS: usize = 8;
/// Coarse optima refined on every sample.
const POLISHED_STARTS: usize = 3;

/// The starts of the full-data search. Small sets use the Halton starts
/// themselves. On a large set every start is first solved on a
/// deterministic stratified subsample (every `k`-th sample, in the data's
/// own order, which for gridded data covers the grid evenly), and the
/// distinct best few of those optima become the starts on all samples: the
/// coarse search finds the basin, the full data only refines it.
///
/// `solve` solves one start on the subsample's problem (on the non-linear
/// parameters by projection, or on all of them).
fn coarse_starts<S>(
    model: &dyn Parametric,
    data: &SampleSet,
    scales: &[f64],
    starts: &[Vec<f64>],
    solve: S,
) -> Result<Vec<Vec<f64>>, FitError>
where
    S: Fn(&ModelProblem<'_>, &[f64]) -> Result<SolverReport, brdf_solve::SolveError> + Sync,
{
    if data.len() <= COARSE_ABOVE {
        return Ok(starts.to_vec());
    }
    let (sub, k) = stratified_subsample(data, COARSE_SAMPLES);
    let sub_scales: Vec<f64> = scales.iter().step_by(k).copied().collect();
    let values = sub.values_channel_major();
    let mp = ModelProblem::new(model, sub.pairs(), &values, &sub_scales)?;
    use rayon::prelude::*;
    let mut found: Vec<SolverReport> = starts
        .par_iter()
        .filter_map(|s| solve(&mp, s).ok())
        .filter(|r| r.ssr.is_finite())
        .collect();
    found.sort_by(|a, b| a.ssr.total_cmp(&b.ssr));
    let mut chosen: Vec<Vec<f64>> = Vec::new();
    for r in found {
        let distinct = chosen.iter().all(|c| {
            c.iter()
                .zip(&r.params)
                .any(|(x, y)| (x - y).abs() > 1e-6 * x.abs().max(y.abs()).max(1e-12))
        });
        if distinct && chosen.len() < POLISHED_STARTS {
            chosen.push(r.params);
        }
    }
    if chosen.is_empty() {
        return Ok(starts.to_vec());
    }
    Ok(chosen)
}

/// A deterministic stratified subsample of about `target` samples: every
/// `k`-th sample (`k = ceil(n / target)`), in the data's own order, which
/// for gridded data covers the grid evenly. Returns the subsample and `k`
/// (all samples and 1 when `n <= target`).
pub(crate) fn stratified_subsample(data: &SampleSet, target: usize) -> (SampleSet, usize) {
    let k = data.len().div_ceil(target.max(1)).max(1);
    let keep: Vec<bool> = (0..data.len()).map(|j| j % k == 0).collect();
    (data.select(&keep), k)
}

/// Sample sets larger than this screen the starts of a search on all
/// parameters on a subsample ([`screened_starts`]).
const SCREEN_ABOVE: usize = 8_000;
/// Size of the stratified subsample the starts are screened on.
const SCREEN_SAMPLES: usize = 2_048;
/// Relative difference of two screened costs below which they are taken
/// for the same basin.
const SAME_BASIN: f64 = 1e-5;

/// The starts of a search on all parameters, screened. Every start is
/// solved on a deterministic stratified subsample ([`SCREEN_SAMPLES`]
/// samples: every `k`-th, in the data's order) in `objective`, and the
/// starts of the [`POLISHED_STARTS`] best distinct subsample costs are
/// solved on all samples, from the starts themselves: the subsample ranks
/// the basins, the full data finds their optima (the subsample's optima of
/// a many-parameter model lie in flat valleys from which the full solve
/// creeps). Measured on the five RGL files (principled, ngan/log/cube root):
/// the same or lower final costs at a third to a half of the processor
/// time; starts a subsample puts in one basin (costs within
/// [`SAME_BASIN`]) count once, so a highlight the subsample samples
/// sparsely cannot hide the other basins.
///
/// `solve` solves one start on a problem.
fn screened_starts<S>(
    data: &SampleSet,
    objective: Objective,
    model: &dyn Parametric,
    starts: &[Vec<f64>],
    solve: S,
) -> Result<Vec<Vec<f64>>, FitError>
where
    S: Fn(
            &(dyn LeastSquaresProblem + Sync),
            &[f64],
        ) -> Result<SolverReport, brdf_solve::SolveError>
        + Sync,
{
    if data.len() <= SCREEN_ABOVE || starts.len() <= POLISHED_STARTS {
        return Ok(starts.to_vec());
    }
    let (sub, _) = stratified_subsample(data, SCREEN_SAMPLES);
    let scales = objective.row_scales(&sub);
    let values = sub.values_channel_major();
    // One problem on the subsample (the transformed one wraps it).
    let mp = ModelProblem::new(model, sub.pairs(), &values, &scales)?;
    let (rows, transformed);
    let problem: &(dyn LeastSquaresProblem + Sync) = if objective.is_transformed() {
        rows = TransformedRows::new(&sub, objective);
        transformed = mp.with_transform(&rows);
        &transformed
    } else {
        &mp
    };
    use rayon::prelude::*;
    let mut found: Vec<(f64, usize)> = starts
        .par_iter()
        .enumerate()
        .filter_map(|(i, s)| solve(problem, s).ok().map(|r| (r.ssr, i)))
        .filter(|(ssr, _)| ssr.is_finite())
        .collect();
    found.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut chosen: Vec<(f64, usize)> = Vec::new();
    for (ssr, i) in found {
        let distinct = chosen
            .iter()
            .all(|(c, _)| (c - ssr).abs() > SAME_BASIN * ssr.abs().max(f64::MIN_POSITIVE));
        if distinct && chosen.len() < POLISHED_STARTS {
            chosen.push((ssr, i));
        }
    }
    if chosen.is_empty() {
        return Ok(starts.to_vec());
    }
    Ok(chosen.into_iter().map(|(_, i)| starts[i].clone()).collect())
}

/// Default reweighting cap of the robust (IRLS) fits. MATLAB's
/// `robustfit` stops at 50 (the study keeps that cap for Kurt's tables,
/// his procedure); the degree-7 polynomial on the shared RGL files (20196
/// samples a channel) converges in 60 (paper_white's green) to 409
/// (cc_iris_purple_gem's green) iterations per channel, so with 50 every
/// one of those fits ended "NOT converged". Where the reweighting cycles (the
/// degree-3 fit of CUReT's quarry tile) no cap helps: the fit stops when
/// a weighted solution recurs ([`FitOptions::irls_stop_on_cycle`]) and
/// says so.
pub const IRLS_MAX_ITERATIONS: usize = 500;

/// An all-linear fit ([`fit_all_linear`]).
pub(crate) struct LinearFit {
    /// The parameters.
    pub params: Vec<f64>,
    /// The solver, in words.
    pub how: String,
    /// The smallest numerical rank (or number of positive NNLS
    /// coefficients) over the channels.
    pub rank: usize,
    /// How the robust fit ended, for IRLS.
    pub irls: Option<IrlsEnd>,
}

/// How a robust (IRLS) fit ended over the channels.
pub(crate) struct IrlsEnd {
    /// Reweighting iterations of each fitted channel.
    pub iterations: Vec<usize>,
    /// The termination of the first channel that did not converge, else
    /// of the last: a fit converges only if every channel does.
    pub termination: IrlsTermination,
}

impl IrlsEnd {
    fn add(end: &mut Option<IrlsEnd>, iterations: usize, termination: IrlsTermination) {
        let e = end.get_or_insert(IrlsEnd {
            iterations: Vec::new(),
            termination,
        });
        e.iterations.push(iterations);
        if e.termination.is_converged() {
            e.termination = termination;
        }
    }
}

/// Fit an all-linear model channel by channel on rows scaled by `scales`.
pub(crate) fn fit_all_linear(
    model: &dyn Parametric,
    data: &SampleSet,
    scales: &[f64],
    opts: &FitOptions,
) -> Result<LinearFit, FitError> {
    let solver = opts.solver;
    let specs = model.param_specs();
    let (n, nc, np) = (data.len(), model.channels(), specs.len());
    let zero = vec![0.0; np];
    let mut offset = vec![0.0; nc * n];
    let mut jac = vec![0.0; nc * n * np];
    model.eval_grad_batch_at(&zero, data.pairs(), &mut offset, &mut jac);
    let mut p = zero;
    let mut how = String::new();
    let mut rank = usize::MAX;
    let mut irls_end = None;
    for c in 0..nc {
        let cols: Vec<usize> = (0..np)
            .filter(|&k| (0..n).any(|j| jac[(c * n + j) * np + k] != 0.0))
            .collect();
        if cols.is_empty() {
            continue;
        }
        let y = data.channel(c);
        let a = Mat::from_fn(n, cols.len(), |j, k| {
            scales[j] * jac[(c * n + j) * np + cols[k]]
        });
        let b: Vec<f64> = (0..n)
            .map(|j| scales[j] * (y[j] - offset[c * n + j]))
            .collect();
        let x: Vec<f64> = match solver {
            Solver::Irls(weight) => {
                let s = irls(
                    a.as_ref(),
                    &b,
                    &IrlsOptions {
                        weight,
                        scale: ScaleConvention::Matlab2004,
                        max_iterations: opts.irls_max_iterations,
                        stop_on_cycle: opts.irls_stop_on_cycle,
                        ..IrlsOptions::default()
                    },
                )?;
                IrlsEnd::add(&mut irls_end, s.iterations, s.termination);
                s.coef
            }
            _ if cols.iter().all(|&k| specs[k].lower == 0.0) => {
                how = "NNLS (Lawson-Hanson)".into();
                let s = brdf_solve::nnls(a.as_ref(), &b, 3 * cols.len() + 10)?;
                rank = rank.min(s.passive.len());
                let upper: Vec<f64> = cols.iter().map(|&k| specs[k].upper).collect();
                match crate::linear_box::within_upper(a.as_ref(), &b, s.x, &upper)? {
                    (x, true) => {
                        how = "least squares within the box (LSI: NNLS exceeded an upper bound)"
                            .into();
                        x
                    }
                    (x, false) => x,
                }
            }
            _ => {
                let bm = Mat::from_fn(n, 1, |j, _| b[j]);
                let s = brdf_solve::lstsq(
                    a.as_ref(),
                    bm.as_ref(),
                    None,
                    brdf_solve::LstsqMethod::PivotedQr,
                )?;
                how = format!("least squares (column-pivoted QR, rank {})", s.rank);
                rank = rank.min(s.rank);
                (0..cols.len()).map(|k| s.x[(k, 0)]).collect()
            }
        };
        for (k, &col) in cols.iter().enumerate() {
            p[col] = x[k];
        }
    }
    if let (Solver::Irls(weight), Some(end)) = (solver, &irls_end) {
        let counts: Vec<String> = end.iterations.iter().map(|k| k.to_string()).collect();
        how = format!(
            "IRLS ({}, MATLAB 2004 scale), {} iterations{}",
            weight.name(),
            counts.join(" / "),
            if counts.len() > 1 {
                " (per channel)"
            } else {
                ""
            }
        );
    }
    Ok(LinearFit {
        params: p,
        how,
        rank: if rank == usize::MAX { 0 } else { rank },
        irls: irls_end,
    })
}

#[allow(clippy::too_many_arguments)]
fn summarise(
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
        termination: describe_termination(&mp, p, rep.as_ref(), &status, specs),
        starts,
        seconds,
        stored_numbers: specs.len(),
    })
}

/// The termination in words. A plateau where some free parameters have no
/// influence at all (their Jacobian columns are exactly 0) while others sit
/// on bounds is a degenerate but genuine fit: a term of the model has
/// vanished (a linear `ks = 0`; principled's dielectric lobe at
/// `metallic = 1`, where `specular` no longer acts) and the parameters only
/// that term used cannot be identified. It is reported as such, naming
/// them, rather than as a failure; any other plateau stays "not converged".
fn describe_termination(
    mp: &ModelProblem<'_>,
    p: &[f64],
    rep: Option<&SolverReport>,
    status: &[BoundStatus],
    specs: &[brdf_core::ParamSpec],
) -> String {
    let Some(rep) = rep else {
        return "direct solve".into();
    };
    if rep.termination != Termination::SingularPlateau {
        return rep.termination.describe().to_string();
    }
    let zero_term = specs
        .iter()
        .zip(status)
        .any(|(s, b)| s.linear && s.lower == 0.0 && *b == BoundStatus::AtLower);
    let (m, n) = (mp.n_residuals(), p.len());
    let mut jac = vec![0.0; m * n];
    mp.jacobian(p, &mut jac);
    let lost: Vec<&str> = (0..n)
        .filter(|k| status[*k] == BoundStatus::Free)
        .filter(|k| (0..m).all(|i| jac[i * n + k] == 0.0))
        .map(|k| specs[k].name.as_str())
        .collect();
    let on_bound = status.iter().any(|b| *b != BoundStatus::Free);
    if lost.is_empty() || !on_bound {
        rep.termination.describe().to_string()
    } else if zero_term {
        format!(
            "converged to a degenerate fit: a linear term is 0, so {} have no influence",
            lost.join(", ")
        )
    } else {
        format!(
            "converged to a degenerate fit: parameters on their bounds switch off the term of {}, which then have no influence",
            lost.join(", ")
        )
    }
}

/// Offset `d` of the cube-root objective: `1e-6 p99(R cos_i)` (1e-300 for
/// all-zero data), so `cbrt'` stays finite at 0.
fn cube_root_offset(s: &SampleSet) -> f64 {
    let n = s.len();
    let mut v: Vec<f64> = (0..s.channels())
        .flat_map(|c| (0..n).map(move |j| (c, j)))
        .map(|(c, j)| (s.channel(c)[j] * s.pairs().lz[j]).abs())
        .filter(|x| x.is_finite())
        .collect();
    v.sort_by(f64::total_cmp);
    let p99 = v
        .get((v.len().saturating_sub(1) * 99) / 100)
        .copied()
        .unwrap_or(0.0);
    (1e-6 * p99).max(1e-300)
}

/// Floor `e` of the relative objective: `1e-2 median(mean_c R)` (1e-300
/// for all-zero data).
fn relative_floor(mean: &[f64]) -> f64 {
    let mut v: Vec<f64> = mean
        .iter()
        .map(|x| x.abs())
        .filter(|x| x.is_finite())
        .collect();
    v.sort_by(f64::total_cmp);
    (1e-2 * v.get(v.len() / 2).copied().unwrap_or(0.0)).max(1e-300)
}

/// A residual transform `T`: the objective's residual is `T(M cos_i) -
/// T(R cos_i)`.
#[derive(Clone, Copy)]
enum Transform {
    /// `ln(1 + x)` (Matusik's log; arguments clamped at `-1 + 1e-12`).
    Log,
    /// `sqrt(w_j) cbrt(x + d)` (Forés' cube root).
    CubeRoot(f64),
}

impl Transform {
    fn value(self, x: f64) -> f64 {
        match self {
            Transform::Log => x.max(-1.0 + 1e-12).ln_1p(),
            Transform::CubeRoot(d) => (x.max(0.0) + d).cbrt(),
        }
    }

    /// `T(x)` and `T'(x)`, the cube root taken once for both (it was
    /// 4% of a default appearance fit's profile when taken twice).
    fn value_and_derivative(self, x: f64) -> (f64, f64) {
        match self {
            Transform::Log => (self.value(x), 1.0 / (1.0 + x).max(1e-12)),
            Transform::CubeRoot(d) => {
                let t = (x.max(0.0) + d).cbrt();
                (t, 1.0 / (3.0 * t * t))
            }
        }
    }
}

/// A transformed objective (log, cube root) as the row transform of a
/// least-squares problem over all parameters: residual `s_j (T(M cos_i) -
/// T(R cos_i))` with `s_j = 1` (log) or `sqrt(w_j / mean w)` (cube root),
/// so the model problem forms it in its fused blocked pass.
struct TransformedRows {
    transform: Transform,
    /// `cos_i` of each sample (`n` of them; row `i` is sample `i % n`).
    cos_i: Vec<f64>,
    row: Vec<f64>,
    target: Vec<f64>,
    /// The measured values (channel-major).
    values: Vec<f64>,
}

impl TransformedRows {
    fn new(data: &SampleSet, objective: Objective) -> Self {
        let n = data.len();
        let values = data.values_channel_major();
        let cos_i = data.pairs().lz.clone();
        let (transform, row) = match objective {
            Objective::CubeRoot => {
                let w = data.weights();
                let mean = w.iter().sum::<f64>() / n as f64;
                let row = (0..values.len())
                    .map(|i| (w[i % n] / mean).sqrt())
                    .collect();
                (Transform::CubeRoot(cube_root_offset(data)), row)
            }
            _ => (Transform::Log, vec![1.0; values.len()]),
        };
        let target = values
            .iter()
            .enumerate()
            .map(|(i, r)| row[i] * transform.value(r * cos_i[i % n]))
            .collect();
        Self {
            transform,
            cos_i,
            row,
            target,
            values,
        }
    }
}

impl RowTransform for TransformedRows {
    fn apply(&self, i: usize, m: f64) -> (f64, f64) {
        let c = self.cos_i[i % self.cos_i.len()];
        // The model value as the unit-scale residual `M - R` plus `R`, as
        // the transformed objective has always formed it (at data near
        // 1e300 the difference is what the fit has seen).
        let v = self.values[i];
        let x = ((m - v) + v) * c;
        let (t, dt) = self.transform.value_and_derivative(x);
        (self.row[i] * t - self.target[i], self.row[i] * c * dt)
    }
}
