//! The non-linear fit (see [`crate::pipeline`]): multi-start search from
//! the starts of [`crate::starts`], by variable projection or on all
//! parameters, then the polish to the full tolerances; models whose
//! channels share nothing are fitted channel by channel, and the image
//! objective from its target's start.

use brdf_core::{Parametric, SampleSet};
use brdf_solve::multistart::{MultiStartReport, multistart};
use brdf_solve::{
    BoundStatus, Constraints, LeastSquaresProblem, LmOptions, ModelProblem, SolverReport,
    Termination, VarPro, bounded_least_squares,
};

use crate::FitError;
use crate::image_objective::{IMAGE_MAX_ITERATIONS, ImageProblem};
use crate::objective::Objective;
use crate::options::{FitOptions, Solver};
use crate::param_box::box_constraints;
use crate::starts::{
    COARSE_ABOVE, COARSE_FULL_MAX_PARAMS, FUSED_REFINE_FROM, SCREEN_ROUNDS, Screen, coarse_starts,
    screen_stages, search_stages, start_box,
};
use crate::transformed_rows::TransformedRows;

mod log_scaled;

/// A non-linear fit: the parameters, the solver's report (of the whole
/// fit: search and polish), the starts and how it was solved.
pub(crate) struct NonlinearFit {
    /// The fitted parameters.
    pub params: Vec<f64>,
    /// The solver's report.
    pub report: SolverReport,
    /// Starts tried, converged, and at the best cost.
    pub starts: (usize, usize, usize),
    /// The solver, in words.
    pub how: String,
}

/// The polish's report with the search's iterations and evaluations
/// counted in (the work of the whole fit).
fn after_search(search: &SolverReport, polish: SolverReport) -> SolverReport {
    SolverReport {
        iterations: search.iterations + polish.iterations,
        evaluations: search.evaluations + polish.evaluations,
        ..polish
    }
}

/// How the multi-start search runs.
#[derive(Clone, Copy, PartialEq)]
enum Search {
    /// On the non-linear parameters, the linear ones projected out
    /// (variable projection); `fused_refine`: the coarse optima refined
    /// on all parameters in the fused blocked pass.
    Projected { fused_refine: bool },
    /// On all parameters, coarse-to-fine on a subsample.
    CoarseFull,
    /// On all parameters, from starts screened on a subsample.
    Screened,
}

impl Search {
    /// The search for `model` on `data`. Projection needs linear
    /// parameters (the full Oren-Nayar model has none: its kd enters
    /// squared). Models without linear parameters and with few parameters
    /// (gltf) are searched on all parameters coarse-to-fine like the
    /// projected ones (starts on the subsample are already full parameter
    /// vectors). With many (principled's 12) the subsample's optimum lies
    /// in flat valleys far from the full data's: measured on the RGL
    /// files, refining it took hundreds of iterations and ended at
    /// slightly higher costs, so those keep every start on all samples.
    /// The log objective keeps the full search (its problem wraps the
    /// full-data one). On large sets the projected search refines its
    /// coarse optima on all parameters in the fused blocked pass (one pass
    /// per trial point, the normal equations formed in it), not by
    /// projection (two passes per iteration and a stored basis): the
    /// projection + polish took 1.24 s and the fused pass 0.46 s on the
    /// full MERL grid.
    fn choose(mp: &ModelProblem<'_>, data: &SampleSet, opts: &FitOptions) -> Search {
        let no_linear = mp.linear_indices().is_empty();
        let use_varpro =
            opts.solver == Solver::Sqp && !opts.objective.is_transformed() && !no_linear;
        if use_varpro {
            Search::Projected {
                fused_refine: data.len() >= FUSED_REFINE_FROM,
            }
        } else if no_linear
            && mp.nonlinear_indices().len() <= COARSE_FULL_MAX_PARAMS
            && opts.objective != Objective::Log
            && data.len() > COARSE_ABOVE
        {
            Search::CoarseFull
        } else {
            Search::Screened
        }
    }
}

/// The problems and boxes one non-linear fit solves in.
struct Problems<'a> {
    /// The model problem on all samples (unit transform).
    mp: &'a ModelProblem<'a>,
    /// The objective's problem on all parameters (`mp`, or `mp` with the
    /// objective's row transform).
    problem: &'a (dyn LeastSquaresProblem + Sync),
    /// The model's full box.
    full: &'a Constraints,
    /// The box of the non-linear parameters.
    nl_box: Constraints,
    /// Non-linear parameters solved on a log scale.
    wide_nl: Vec<bool>,
    /// Parameters of the full vector solved on a log scale.
    wide_full: Vec<bool>,
}

impl Problems<'_> {
    /// The full parameter vector from non-linear values: linear ones
    /// projected.
    fn project(&self, a: &[f64]) -> Result<Vec<f64>, brdf_solve::SolveError> {
        let c = if self.mp.linear_indices().is_empty() {
            Vec::new()
        } else {
            VarPro::new(self.mp, true).linear_coefficients(a)?
        };
        let mut p = self.mp.assemble(a, &c);
        self.full.clamp(&mut p);
        Ok(p)
    }
}

/// The non-linear fit of `model` (see the module doc). `log_wide`: the
/// problem is one channel of a model whose channels share nothing
/// ([`fit_per_channel`]); its wide positive non-linear parameters are then
/// solved on a log scale (`log_scaled`: Bagher's shadowing valley) once
/// the coarse search or the screen has ranked the starts: the solves on
/// all samples and the polish. Measured on the five RGL files (SGD): the
/// polish that crept to its cap of 3000 iterations per channel converges
/// in tens; the coarse search stays in the box's own scale, whose ranking
/// finds the basins the earlier fits found (on the log scale, or on a
/// smaller subsample, it ranked a worse basin first on
/// cc_iris_purple_gem).
pub(crate) fn fit_nonlinear(
    model: &dyn Parametric,
    data: &SampleSet,
    values: &[f64],
    scales: &[f64],
    opts: &FitOptions,
    log_wide: bool,
) -> Result<NonlinearFit, FitError> {
    let full = box_constraints(model)?;
    if opts.objective == Objective::Image {
        return fit_image(model, opts, &full);
    }
    if let Some(blocks) = brdf_models::channel_slice::channel_blocks(model) {
        return fit_per_channel(model, data, opts, &blocks);
    }
    let (rows, transformed);
    let mp = ModelProblem::new(model, data.pairs(), values, scales)?;
    let nonlinear = mp.nonlinear_indices().to_vec();
    let starts = nonlinear_starts(model, data, &nonlinear, opts)?;
    let nl_box = Constraints::boxed(
        nonlinear.iter().map(|k| full.lower()[*k]).collect(),
        nonlinear.iter().map(|k| full.upper()[*k]).collect(),
    )?;
    // Wide positive non-linear parameters on a log scale (`log_wide`).
    let wide_nl = log_scaled::wide_positive(&nl_box, &vec![log_wide; nonlinear.len()]);
    let nonlinear_mask: Vec<bool> = model
        .param_specs()
        .iter()
        .map(|s| log_wide && !s.linear)
        .collect();
    let wide_full = log_scaled::wide_positive(&full, &nonlinear_mask);
    let problem: &(dyn LeastSquaresProblem + Sync) = if opts.objective.is_transformed() {
        rows = TransformedRows::new(data, opts.objective);
        transformed = ModelProblem::new(model, data.pairs(), values, scales)?.with_transform(&rows);
        &transformed
    } else {
        &mp
    };
    let problems = Problems {
        mp: &mp,
        problem,
        full: &full,
        nl_box,
        wide_nl,
        wide_full,
    };
    let search = Search::choose(&mp, data, opts);
    let ms = search_starts(&problems, search, model, data, scales, opts, &starts)?;
    let (report, how) = polish_best(
        &problems,
        search,
        &ms.best,
        model,
        data.len(),
        starts.len(),
        opts,
    )?;
    Ok(NonlinearFit {
        params: report.params.clone(),
        report,
        starts: (starts.len(), ms.n_converged, ms.n_at_best),
        how,
    })
}

/// The starts of the search on the non-linear parameters: the model's
/// own suggestions for `data` (its catalogue entry's) first, then the
/// Halton points of its box.
fn nonlinear_starts(
    model: &dyn Parametric,
    data: &SampleSet,
    nonlinear: &[usize],
    opts: &FitOptions,
) -> Result<Vec<Vec<f64>>, FitError> {
    let mut starts: Vec<Vec<f64>> = brdf_models::suggested_starts(model, data)
        .into_iter()
        .filter(|s| s.len() == model.n_params())
        .map(|s| nonlinear.iter().map(|k| s[*k]).collect())
        .collect();
    starts.extend(start_box(model, nonlinear).starts(opts.starts.max(1))?);
    Ok(starts)
}

/// The multi-start search from `starts` (non-linear parameter values),
/// to the search's tolerances.
fn search_starts(
    pr: &Problems<'_>,
    search: Search,
    model: &dyn Parametric,
    data: &SampleSet,
    scales: &[f64],
    opts: &FitOptions,
    starts: &[Vec<f64>],
) -> Result<MultiStartReport, FitError> {
    let lm = opts.search_lm();
    let (problem, full, nl_box) = (pr.problem, pr.full, &pr.nl_box);
    Ok(match search {
        Search::Projected { fused_refine } => {
            let coarse = coarse_starts(model, data, scales, starts, |sub, s| {
                bounded_least_squares(&VarPro::new(sub, true), s, nl_box, &lm)
            })?;
            if fused_refine {
                multistart(&coarse, |s| {
                    let p0 = pr.project(s)?;
                    bounded_least_squares(problem, &p0, full, &lm)
                })?
            } else {
                multistart(&coarse, |s| {
                    log_scaled::solve(&VarPro::new(pr.mp, true), s, nl_box, &pr.wide_nl, &lm)
                })?
            }
        }
        Search::CoarseFull => {
            let coarse = coarse_starts(model, data, scales, starts, |sub, s| {
                bounded_least_squares(sub, s, full, &lm)
            })?;
            multistart(&coarse, |s| bounded_least_squares(problem, s, full, &lm))?
        }
        Search::Screened => {
            let screen = Screen {
                data,
                objective: opts.objective,
                model,
                starts,
                lm: &lm,
            };
            let screened = screen.run(
                &SCREEN_ROUNDS,
                |s| pr.project(s),
                |sub, p0, lm| bounded_least_squares(sub, p0, full, lm),
            )?;
            multistart(&screened, |s| {
                let p0 = pr.project(s)?;
                // Without wide parameters this is the bounded solve itself.
                log_scaled::solve(problem, &p0, full, &pr.wide_full, &lm)
            })?
        }
    })
}

/// The search's best result polished on all parameters to the full
/// tolerances (the polish enforces the linear upper bounds and reports
/// every parameter's bound status), its iteration cap the model's factor
/// of the solver's; the report and the solver in words.
fn polish_best(
    pr: &Problems<'_>,
    search: Search,
    best: &SolverReport,
    model: &dyn Parametric,
    samples: usize,
    starts: usize,
    opts: &FitOptions,
) -> Result<(SolverReport, String), FitError> {
    let factor = brdf_models::polish_factor(model);
    let polish_lm = LmOptions {
        max_iterations: opts.lm.max_iterations * factor,
        max_evaluations: opts.lm.max_evaluations * factor,
        ..opts.lm.clone()
    };
    let stages = search_stages(samples, starts);
    Ok(match search {
        Search::Projected { fused_refine: true } => {
            // Already on all parameters: polish the best.
            let polish = repolish(pr.problem, pr.full, &polish_lm, &best.params)?;
            (
                after_search(best, polish),
                format!(
                    "variable projection (NNLS) + bounded SQP-style LM on the subsample, {stages} by bounded LM on all parameters (fused blocked pass)"
                ),
            )
        }
        Search::Projected {
            fused_refine: false,
        } => {
            let p0 = pr.project(&best.params)?;
            let polish = log_scaled::solve(pr.problem, &p0, pr.full, &pr.wide_full, &polish_lm)?;
            (
                after_search(best, polish),
                format!(
                    "variable projection (NNLS) + bounded SQP-style LM, {stages}, polished on all parameters"
                ),
            )
        }
        Search::CoarseFull | Search::Screened => {
            let polish = if pr.wide_full.contains(&true) {
                log_scaled::solve(pr.problem, &best.params, pr.full, &pr.wide_full, &polish_lm)?
            } else {
                repolish(pr.problem, pr.full, &polish_lm, &best.params)?
            };
            let stages = if search == Search::CoarseFull {
                stages
            } else {
                screen_stages(samples, starts)
            };
            (
                after_search(best, polish),
                format!("bounded LM on all parameters, {stages}"),
            )
        }
    })
}

/// The fit in the image objective: the bounded solver on all parameters
/// from the target's start.
fn fit_image(
    model: &dyn Parametric,
    opts: &FitOptions,
    full: &Constraints,
) -> Result<NonlinearFit, FitError> {
    let target = opts.image.as_ref().ok_or(FitError::NeedsDenseData)?;
    if target.start.len() != model.param_specs().len() {
        return Err(FitError::StartLength {
            given: target.start.len(),
            model: model.name().to_string(),
            parameters: model.param_specs().len(),
        });
    }
    let problem = ImageProblem::new(model, &target.terms, &target.reference, &target.exposures)?;
    let mut p0 = target.start.clone();
    full.clamp(&mut p0);
    let lm = LmOptions {
        max_iterations: opts.lm.max_iterations.min(IMAGE_MAX_ITERATIONS),
        ..opts.lm.clone()
    };
    let report = bounded_least_squares(&problem, &p0, full, &lm)?;
    let how = format!(
        "bounded LM on all parameters in the image objective ({} pixels of {} images, {} shading terms; at most {IMAGE_MAX_ITERATIONS} iterations), from the best BRDF-space fit",
        target.terms.pixels(),
        target.terms.images(),
        target.terms.len()
    );
    Ok(NonlinearFit {
        params: report.params.clone(),
        report,
        starts: (1, 1, 1),
        how,
    })
}

/// A model whose channels share no parameter ([`channel_blocks`]), fitted
/// channel by channel: each channel's block is a one-channel problem
/// ([`ChannelSlice`]) with its own starts and the objective's rows of that
/// channel; the reports are summed (iterations, evaluations, cost), the
/// termination is the first channel's that did not converge, else the
/// last channel's. Every BRDF-space objective is a sum over channels of
/// the rows of each, so its optimum is the channels' own optima; the
/// transformed ones (log, cube root) too, each channel's cube-root offset
/// taken from its own values (it only keeps the root's slope finite at
/// 0). Measured (SGD, cc_iris_purple_gem): the cube-root fit of all
/// channels at once took 875 iterations and 22 s, channel by channel 806
/// and 12 s, to a slightly lower cost.
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
        let NonlinearFit {
            params: pc,
            report: rep,
            starts: i,
            how: h,
        } = fit_nonlinear(&slice, &single, &values, &scales, opts, true)?;
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
    let mut rep = total.ok_or(FitError::NoChannels)?;
    rep.params.clone_from(&p);
    rep.bounds = bounds;
    Ok(NonlinearFit {
        params: p,
        report: rep,
        starts: info,
        how: format!(
            "per channel (no parameter shared; wide positive parameters refined on a log scale): {how}"
        ),
    })
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
